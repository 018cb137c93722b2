"""The design-level audit against an independent slow path: every record × stripe solved and
evaluated afresh, the margins worked by hand from those counts."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from audit.cli import main
from audit.engine.fragility import fit_lognormal
from audit.engine.margins import IntensityMeasure, run_margins
from audit.engine.sites import with_design_site
from audit.errors import InputError
from audit.physics.block import RigidBlock, coefficient_of_restitution
from audit.physics.rocking import simulate
from procedures import get_procedures
from procedures.context import RecordContext
from records import RecordEntry, RecordSuite, one_pulse

PERIODS_S = (1.0, 2.0, 3.0)
LEVELS_G = np.geomspace(0.15, 1.2, 9)
SIZE_S, ALPHA_DEG = 3.0, 15.0


def _suite():
    entries = tuple(RecordEntry(f"cosine_{t:g}s", one_pulse("cosine", 0.5, t, record_id=f"c{t:g}"))
                    for t in PERIODS_S)
    return with_design_site(RecordSuite(entries, "three one-cosine pulses"), 1.5, 0.9,
                            override=True)


def test_margins_of_three_pulses_by_hand():
    suite = _suite()
    priestley = get_procedures("priestley1978")[0]
    run = run_margins([priestley], suite, IntensityMeasure.parse("pga"), LEVELS_G, (ALPHA_DEG,),
                      [SIZE_S], free_motion_s=8.0)
    block = RigidBlock.from_size(SIZE_S, math.radians(ALPHA_DEG))
    alpha = math.radians(ALPHA_DEG)
    exact = np.zeros((3, LEVELS_G.size), dtype=bool)
    guideline = np.zeros((3, LEVELS_G.size), dtype=bool)
    for k, period in enumerate(PERIODS_S):
        for j, level in enumerate(LEVELS_G):
            pulse = one_pulse("cosine", level, period)  # the record scaled to the level, afresh
            exact[k, j] = simulate(block, pulse, 8.0).overturned
            entry = RecordEntry("x", pulse)
            evaluation = priestley.evaluate(entry, np.array([block.p]), alpha,
                                            float(coefficient_of_restitution(alpha)),
                                            RecordContext(entry, 8.0))
            guideline[k, j] = evaluation.estimate.outcome[0] == "overturn"
    stripes = run.stripes
    assert list(stripes["exact_overturned"]) == list(exact.reshape(-1))
    assert list(stripes["priestley1978_overturns"]) == list(guideline.reshape(-1))
    np.testing.assert_allclose(stripes["scale_factor"], np.tile(LEVELS_G / 0.5, 3))
    fit = fit_lognormal(LEVELS_G, np.full(LEVELS_G.size, 3), exact.sum(axis=0))
    row = run.fragility.iloc[0]
    assert row["median"] == pytest.approx(fit.median, rel=1e-9)
    # CMR: median over the design PGA, 0.4 S_XS = 0.6 g (FEMA 356 §1.6)
    assert row["cmr"] == pytest.approx(fit.median / 0.6, rel=1e-9)
    # the guideline's line: where its share first reaches one half, ln-interpolated
    share = guideline.mean(axis=0)
    j = int(np.argmax(share >= 0.5))
    t = (0.5 - share[j - 1]) / (share[j] - share[j - 1])
    line = math.exp(math.log(LEVELS_G[j - 1]) + t * math.log(LEVELS_G[j] / LEVELS_G[j - 1]))
    capacity = run.capacity.iloc[0]
    assert capacity["guideline_im"] == pytest.approx(line, rel=1e-12)
    assert capacity["achieved_p_fit"] == pytest.approx(
        norm.cdf(math.log(line / fit.median) / fit.beta), rel=1e-9)
    nearest = int(np.argmin(np.abs(np.log(LEVELS_G / line))))
    assert capacity["achieved_p_stripe"] == pytest.approx(exact[:, nearest].mean())


def test_site_based_procedure_reads_the_design_spectrum_scaled_to_each_level():
    # FEMA 356 reads only the site: at a stripe, every record gives the same answer (a step)
    run = run_margins(get_procedures("fema356"), _suite(), IntensityMeasure.parse("pga"),
                      LEVELS_G, (ALPHA_DEG,), [SIZE_S], free_motion_s=8.0)
    over = run.stripes["fema356_overturns"].to_numpy().reshape(3, LEVELS_G.size)
    assert np.all(over == over[0]) and over[0].any() and not over[0].all()
    assert np.all(np.diff(over[0].astype(int)) >= 0)  # one step up


def test_intensity_measures_and_bad_input(tmp_path, capsys):
    assert IntensityMeasure.parse("SA:0.5") == IntensityMeasure("sa", 0.5)
    assert IntensityMeasure.parse("pgv").unit == "m/s"
    design = IntensityMeasure.parse("sa:1.0").of_design_site({"sxs_g": 1.5, "sx1_g": 0.9})
    assert design == pytest.approx(0.9)  # S_X1/T at T = 1 s
    for bad in ("sa:", "sa:-1", "pgd"):
        with pytest.raises(InputError, match="--im"):
            IntensityMeasure.parse(bad)
    assert main(["margins", "all", "--stripes", "0.2,x", "--out", str(tmp_path / "m")]) == 2
    assert "--stripes" in capsys.readouterr().err
    assert not (tmp_path / "m").exists()


def test_margins_from_python(tmp_path):
    import audit
    result = audit.margins("fema356", _suite(), im="pga", stripes=LEVELS_G, alpha_deg=[15],
                           sizes_s=[SIZE_S], free_motion_s=8.0)
    assert len(result.fragility) == 1 and "fema356" in result._repr_html_()
    written = sorted(p.name for p in result.write(tmp_path / "m").iterdir())
    assert written == ["capacity.csv", "columns.json", "fragility.csv", "required_alpha.csv",
                       "stripes.csv", "summary.json"]


def test_required_alpha_is_where_the_share_stays_below_the_target():
    from audit.engine.margins import _smallest_alpha_staying_below
    alpha = np.array([2.0, 3.0, 4.0, 5.0, 6.0])
    # not monotonic: below 10 % at 3°, above again at 4°, below for good from 5°
    share = np.array([0.5, 0.05, 0.3, 0.08, 0.0])
    assert _smallest_alpha_staying_below(alpha, share, 0.10) == pytest.approx(4 + 0.2 / 0.22)
    assert _smallest_alpha_staying_below(alpha, np.zeros(5), 0.10) == 2.0
    assert math.isnan(_smallest_alpha_staying_below(alpha, np.full(5, 0.5), 0.10))


def test_required_alpha_against_brute_force():
    from audit.engine.margins import required_alpha
    grid = np.arange(6.0, 30.1, 4.0)
    table = required_alpha(get_procedures("priestley1978"), _suite(), [2.0], grid,
                           free_motion_s=8.0).set_index("procedure")["required_alpha_deg"]
    share = np.array([np.mean([simulate(RigidBlock.from_size(2.0, math.radians(a)),
                                        entry.motion, 8.0).overturned for entry in _suite()])
                      for a in grid])
    over = np.flatnonzero(share > 0.10)
    j = over[-1]
    expected = grid[j] + (share[j] - 0.10) / (share[j] - share[j + 1]) * (grid[j + 1] - grid[j])
    assert table["exact@0.10"] == pytest.approx(expected)
    assert 6.0 <= table["priestley1978"] <= 30.0
