"""The fixed-point scan's signs, found compiled (a tabulated spectrum) or chunk by chunk (a
nondecreasing design spectrum), equal those of the array expression they replace,
``Sd(4v/p)·scale − θ/α > 0`` at every grid point, bit for bit; and the design spectra that
declare Sd nondecreasing have it so."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from audit.physics.design_spectra import DesignDisplacement, FEMA356Spectrum
from procedures.rotation_map import SCAN_STEP_LOG_PERIOD, SCAN_V_RANGE, _excess_positive
from procedures.tabulated import TabulatedDisplacement

V = np.exp(np.arange(np.log(SCAN_V_RANGE[0]), np.log(SCAN_V_RANGE[1]), SCAN_STEP_LOG_PERIOD))
GRID = 1.0 - 1.0 / np.cosh(V)


def _array_expression(displacement, p, scale):
    return (displacement(4.0 * V / p[:, None]) * scale[:, None] - GRID) > 0.0


def _crossings(signs):
    return int((signs[:, 1:] != signs[:, :-1]).sum())


@settings(max_examples=60, deadline=None)
@given(steps=st.lists(st.floats(1e-3, 2.0), min_size=1, max_size=40),
       start=st.floats(1e-3, 3.0),
       levels=st.data(),
       p=st.lists(st.floats(0.3, 30.0), min_size=1, max_size=4),
       scale=st.floats(0.2, 50.0))
def test_tabulated_signs_equal_the_array_expression(steps, start, levels, p, scale):
    period_s = start + np.concatenate([[0.0], np.cumsum(steps)])
    period_s = np.unique(period_s)
    # values that cross θ/α often: plateaus (repeated values), zeros and peaks above α
    sd_m = np.array(levels.draw(st.lists(st.sampled_from([0.0, 0.004, 0.01, 0.02, 0.05])
                                         | st.floats(0.0, 0.08), min_size=period_s.size,
                                         max_size=period_s.size)))
    p, scale = np.array(p), np.full(len(p), scale)
    displacement = TabulatedDisplacement(period_s, sd_m)
    found = _excess_positive(displacement, V, GRID, p, scale)
    np.testing.assert_array_equal(found, _array_expression(displacement, p, scale))


def test_tabulated_signs_on_a_record_spectrum(seed_suite):
    from procedures.context import RecordContext
    table = RecordContext(seed_suite.get("pacoima_dam_1971")).true_displacement(0.05)
    p = 2 * np.pi / np.arange(0.5, 8.01, 0.05)
    scale = 1.0 / (3 * 9.80665 / (4 * p ** 2) * np.cos(0.2) * 0.2)
    expected = _array_expression(table, p, scale)
    assert _crossings(expected) > 50  # a real test: many fixed points
    np.testing.assert_array_equal(_excess_positive(table, V, GRID, p, scale), expected)


@pytest.mark.parametrize("damping", [0.02, 0.05, 0.12, 0.3, 0.5])
@pytest.mark.parametrize("sxs_g, sx1_g", [(1.5, 0.9), (0.4, 0.6), (2.5, 0.2)])
def test_design_signs_equal_the_array_expression(sxs_g, sx1_g, damping):
    displacement = DesignDisplacement(FEMA356Spectrum(sxs_g, sx1_g), damping)
    assert displacement.nondecreasing
    p = 2 * np.pi / np.arange(0.5, 8.01, 0.05)
    for alpha in (0.05, 0.2, 0.45):
        scale = 1.0 / (3 * 9.80665 / (4 * p ** 2) * np.cos(alpha) * alpha)
        expected = _array_expression(displacement, p, scale)
        np.testing.assert_array_equal(_excess_positive(displacement, V, GRID, p, scale),
                                      expected)


def test_the_signs_checked_hold_crossings():
    """The design cases above cross θ/α: a scan that skipped every chunk would fail them."""
    displacement = DesignDisplacement(FEMA356Spectrum(0.4, 0.6), 0.12)
    p = 2 * np.pi / np.arange(0.5, 8.01, 0.05)
    scale = 1.0 / (3 * 9.80665 / (4 * p ** 2) * np.cos(0.2) * 0.2)
    assert _crossings(_array_expression(displacement, p, scale)) > 100


@pytest.mark.parametrize("sxs_g, sx1_g", [(1.5, 0.9), (0.3, 1.2), (2.5, 0.2)])
def test_fema_356_displacement_never_falls(sxs_g, sx1_g):
    """FEMA 356 declares Sd nondecreasing (the scan bounds a chunk by its ends): so it is, on a
    dense grid of periods, at dampings across and beyond Table 1-6, to the rounding."""
    spectrum = FEMA356Spectrum(sxs_g, sx1_g)
    assert spectrum.displacement_nondecreasing
    period = np.geomspace(1e-5, 500.0, 200_001)
    for damping in (0.01, 0.02, 0.05, 0.1, 0.25, 0.4, 0.5, 0.6):
        sd = spectrum.displacement(period, damping)
        assert np.all(np.diff(sd) >= -1e-13 * sd[1:]), damping


@pytest.mark.parametrize("period_s, sd_m", [
    ([2.0], [0.03]),  # one node: Sd held everywhere
    ([0.0, 0.5, 1.0, 3.0], [0.0, 0.01, np.nan, 0.04]),  # a NaN node: every value read
    ([0.0, 1.0, 1.0, 2.0, 6.0], [0.0, 0.02, 0.05, 0.01, 0.08]),  # a repeated period
    ([0.0, 0.3, 0.31, 9.0], [0.0, 1e-9, 0.06, 0.06]),  # a jump of ~10⁷ between two nodes
])
def test_tabulated_signs_on_edge_tables(period_s, sd_m):
    displacement = TabulatedDisplacement(np.array(period_s), np.array(sd_m))
    p = 2 * np.pi / np.array([0.7, 2.0, 5.5])
    scale = 1.0 / (3 * 9.80665 / (4 * p ** 2) * np.cos(0.25) * 0.25)
    np.testing.assert_array_equal(_excess_positive(displacement, V, GRID, p, scale),
                                  _array_expression(displacement, p, scale))
