"""Shahi & Baker (2014) pulse identification: the legacy continuous transform against a direct
sum, and the whole algorithm against the authors' MATLAB result for their El Centro #4 example."""

from __future__ import annotations

import gzip
from pathlib import Path

import numpy as np
import pytest
import pywt

from audit.physics.pulses.legacy_cwt import legacy_cwt
from audit.physics.pulses.shahi_baker_2014 import (centre_frequency, pulse_indicator,
                                                   shahi_baker_2014, velocity_cm_s)
from records import read_at2

DATA = Path(__file__).parent / "data"

#: classification_result.mat of shreyshahi/PulseClassification, commit 2000226 (MATLAB, legacy
#: cwt): per candidate, rotation angle [rad], column (1-based sample), pulse scale, T_p [s], PI,
#: PGV of the rotated record [cm/s], late.
MATLAB_EL_CENTRO_4 = [
    (1.5599600995132608, 1261, 684, 4.788, 20.061014605130545, 80.83335130333052, False),
    (1.5686061316975186, 828, 767, 5.369, 17.813802629589887, 80.50678950305678, False),
    (-1.4154282992995335, 1656, 540, 3.780, -2.5459843493581005, 81.35463733951451, False),
    (1.297798964939051, 521, 1291, 9.037, 4.93888786373576, 87.92445194357406, False),
    (1.2760193995283573, 1877, 794, 5.558, 1.087951348970277, 88.25265322325788, False),
]


def direct_transform(signal, scale):
    """(1/√a) Σ_k s_k ψ(x_k) with ψ interpolated on its cascade, x_k the legacy transform's
    alignment: x = (7a − ½ − b − ⌊(7a − 1)/2⌋ + k)/a on db4's support [0, 7]."""
    _, psi, x = pywt.Wavelet("db4").wavefun(level=10)
    k = np.arange(signal.size)
    first = (7 * scale - 1) // 2
    return np.array([np.dot(signal, np.interp((7 * scale - 0.5 - b - first + k) / scale, x, psi,
                                              left=0.0, right=0.0)) / np.sqrt(scale)
                     for b in range(signal.size)])


@pytest.mark.parametrize("scale", [30, 31, 200, 201])
def test_legacy_transform_is_the_direct_sum(scale):
    signal = np.cumsum(np.random.default_rng(1).normal(size=1500))
    fast, direct = legacy_cwt(signal, [scale])[0], direct_transform(signal, scale)
    # the legacy transform integrates ψ over each sample (Riemann sum error ~ 1/a² of the peak)
    assert np.max(np.abs(fast - direct)) < 0.005 * np.max(np.abs(direct))


def test_legacy_transform_of_a_spike_is_the_wavelet():
    """A unit spike at sample 500: C(a, b) = ψ(x_b)/√a, with ψ(3.5 − ...) peaking where ψ does."""
    signal = np.zeros(1001)
    signal[500] = 1.0
    scale = 64
    coefficients = legacy_cwt(signal, [scale])[0]
    _, psi, x = pywt.Wavelet("db4").wavefun(level=10)
    assert np.max(np.abs(coefficients)) == pytest.approx(np.max(np.abs(psi)) / 8.0, rel=0.01)


def test_db4_centre_frequency_is_matlabs():
    assert centre_frequency() == pytest.approx(0.7143, abs=5e-5)
    assert centre_frequency() == pytest.approx(5.0 / 7.0, rel=1e-12)


def test_pulse_indicator_boundary():
    """PI of the MATLAB's centred form at P = V = 0 is the intercept, and grows with PGV at a
    low PGV ratio (a strong pulse)."""
    assert pulse_indicator(11.58861, 1.0, (1.208421 - 0.63) / 0.777) == pytest.approx(-7.817)
    assert pulse_indicator(80.0, 0.4, 0.2) > pulse_indicator(40.0, 0.4, 0.2) > 0.0


@pytest.fixture(scope="module")
def el_centro_4(tmp_path_factory):
    folder = tmp_path_factory.mktemp("el_centro_4")
    motions = []
    for name in ("el_centro_4_140.AT2", "el_centro_4_230.AT2"):
        path = folder / name
        path.write_bytes(gzip.decompress((DATA / f"{name}.gz").read_bytes()))
        motions.append(read_at2(path))
    first, second = motions
    return shahi_baker_2014(velocity_cm_s(first.acceleration, first.dt),
                            velocity_cm_s(second.acceleration, second.dt), first.dt)


@pytest.mark.parametrize("index", range(5))
def test_el_centro_4_reproduces_the_matlab_result(el_centro_4, index):
    angle, column, scale, tp_s, pi, pgv, late = MATLAB_EL_CENTRO_4[index]
    candidate = el_centro_4.candidates[index]
    assert candidate.direction_rad == pytest.approx(angle, abs=1e-9)
    assert candidate.sample + 1 == column
    assert candidate.scale == scale
    assert candidate.tp_s == pytest.approx(tp_s, abs=1e-3)
    assert candidate.pulse_indicator == pytest.approx(pi, abs=1e-3)
    assert candidate.pgv_cm_s == pytest.approx(pgv, abs=1e-6)
    assert candidate.late == late


def test_el_centro_4_is_pulse_like_with_the_first_candidates_period(el_centro_4):
    assert el_centro_4.pulse_like
    assert el_centro_4.pulse is el_centro_4.candidates[0]
    assert el_centro_4.pulse.tp_s == pytest.approx(4.788, abs=1e-3)
    assert [c.is_pulse for c in el_centro_4.candidates] == [True, True, False, True, True]
