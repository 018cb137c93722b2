"""The design-level audit against an independent slow path: every record × stripe solved and
evaluated afresh, the margins worked by hand from those counts."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm

from audit.cli import main
from audit.engine.shared.blocks import Block, BlockList
from audit.engine.design.lognormal_fit import fit_lognormal
from audit.engine.shared.intensity import IntensityMeasure
from audit.engine.design.margins import margins_tables
from audit.engine.design.tables import fragility_rows
from audit.engine.design.settings import MarginsSettings
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.solver import Solver
from audit.engine.shared.sites import scale_to_site, with_design_site
from audit.errors import InputError
from audit.physics.block import RigidBlock, coefficient_of_restitution
from audit.physics.rocking import simulate
from procedures import get_procedures
from procedures.context import RecordContext
from records import RecordEntry, RecordSuite, one_pulse

PERIODS_S = (1.0, 2.0, 3.0)
LEVELS_G = np.geomspace(0.15, 1.2, 9)
SIZE_S, ALPHA_DEG = 3.0, 15.0


def _settings(restitution="housner", **values):
    """The settings of these tests: PGA stripes LEVELS_G, the block (ALPHA_DEG, SIZE_S), 8 s of
    free motion; ``values`` replace them."""
    return MarginsSettings.parse(**{"im": "pga", "stripes": LEVELS_G, "alpha_deg": (ALPHA_DEG,),
                                    "size_s": [SIZE_S],
                                    "solver": Solver(restitution, free_motion_s=8.0), **values})


def _suite():
    entries = tuple(RecordEntry(f"cosine_{t:g}s", one_pulse("cosine", 0.5, t, record_id=f"c{t:g}"))
                    for t in PERIODS_S)
    return with_design_site(RecordSuite(entries, "three one-cosine pulses"), 1.5, 0.9,
                            override=True)


def test_margins_of_three_pulses_by_hand():
    suite = _suite()
    priestley = get_procedures("priestley1978")[0]
    run = margins_tables([priestley], suite, _settings(), Runtime())
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
    run = margins_tables(get_procedures("fema356"), _suite(), _settings(), Runtime())
    over = run.stripes["fema356_overturns"].to_numpy().reshape(3, LEVELS_G.size)
    assert np.all(over == over[0]) and over[0].any() and not over[0].all()
    assert np.all(np.diff(over[0].astype(int)) >= 0)  # one step up


def test_a_site_based_step_is_placed_at_its_level_not_between_stripes():
    """FEMA 356 sees the 0.8 m × 2.0 m block (tan α = 0.4) overturn once its design spectrum,
    scaled by level / S_X1, has 0.4·S_XS·level/S_X1 ≥ tan α: with S_XS = 1.5 g, S_X1 = 0.9 g,
    at Sa(1 s) = 0.4 × 0.9 / 0.6 = 0.600 g, whatever the stripes around it."""
    levels = np.geomspace(0.2, 1.6, 8)  # 0.566 and 0.749 g around the step
    run = margins_tables(get_procedures("fema356"), _suite(),
                      _settings(im="sa:1.0", stripes=levels, alpha_deg=(), size_s=(),
                                blocks=[Block.of_dimensions(0.8, 2.0)]), Runtime())
    step = 0.4 * 0.9 / (0.4 * 1.5)
    capacity = run.capacity.iloc[0]
    assert capacity["guideline_im"] == pytest.approx(step, rel=1e-6)
    fragility = run.fragility.iloc[0]
    assert capacity["achieved_p_fit"] == pytest.approx(
        norm.cdf(math.log(step / fragility["median"]) / fragility["beta"]), rel=1e-6)


def test_the_cmr_is_over_the_mce_and_a_bound_beyond_the_stripes():
    """P695's CMR is over the MCE intensity: the --site values as given (mce), or 1.5 × them
    (design). Stripes that stop below the median leave the CMR only bounded below."""
    suite = _suite()
    mce = margins_tables([], suite, _settings(), Runtime())
    design = margins_tables([], suite, _settings(site_level="design"), Runtime())
    median = mce.fragility["median"].iloc[0]
    assert mce.fragility["cmr"].iloc[0] == pytest.approx(median / 0.6, rel=1e-12)
    assert design.fragility["cmr"].iloc[0] == pytest.approx(median / (1.5 * 0.6), rel=1e-12)
    assert design.summary["mce_im"] == pytest.approx(0.9)
    assert not mce.fragility["median_extrapolated"].iloc[0]
    # ten records, the top stripe overturning two: the median lies above the stripes
    levels = np.array([0.1, 0.2, 0.3])
    over = np.zeros((10, 3, 1), dtype=bool)
    over[0, 1:, 0] = over[1, 2, 0] = True
    rows, _, _ = fragility_rows(levels, BlockList.of([ALPHA_DEG], [SIZE_S]),
                                 IntensityMeasure.parse("pga"), over, 0.6)
    row = rows.iloc[0]
    assert row["median"] > 0.3 and row["median_extrapolated"]
    assert row["cmr_bound"] == "at least" and row["cmr"] == pytest.approx(0.3 / 0.6)
    with pytest.raises(InputError, match="^site.level"):
        _settings(site_level="maximum")


def test_bootstrap_bands_see_that_records_are_reused_across_stripes():
    """Twelve records, each overturning the block from its own stripe on (as a real record
    does, more or less): the stripes' counts are one suite's, not independent binomials, so the
    band from resampling whole records is wider than the binomial likelihood's and holds the
    fit."""
    levels = np.geomspace(0.1, 1.0, 10)
    over = np.zeros((12, 10, 1), dtype=bool)
    for record, first in enumerate([1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 8, 9]):
        over[record, first:, 0] = True
    rows, fits, _ = fragility_rows(levels, BlockList.of([ALPHA_DEG], [SIZE_S]),
                                    IntensityMeasure.parse("pga"), over, 0.3)
    row = rows.iloc[0]
    assert row["median_boot_low"] < fits[0].median < row["median_boot_high"]
    assert (row["median_boot_high"] - row["median_boot_low"]
            > row["median_high"] - row["median_low"])
    assert row["cmr_boot_low"] == pytest.approx(row["median_boot_low"] / 0.3)


def test_stripe_scale_factors_are_on_the_record_as_read():
    """With the suite scaled to the site, a stripe's factor on the record as read is the site
    factor × the factor from the site-scaled record to the level."""
    suite = scale_to_site(_suite(), 1.5, 0.9)
    run = margins_tables([], suite, _settings(), Runtime())
    site = {k: v["scale_factor"] for k, v in suite.scaling["records"].items()}
    stripes = run.stripes
    # the pulses as read have a PGA of 0.5 g: level / 0.5 takes each to its stripe
    np.testing.assert_allclose(stripes["scale_factor"], stripes["im_level"] / 0.5, rtol=1e-12)
    np.testing.assert_allclose(stripes["site_factor"], stripes["record"].map(site))


def test_intensity_measures_and_bad_input(tmp_path, capsys):
    assert IntensityMeasure.parse("SA:0.5") == IntensityMeasure("sa", 0.5)
    assert IntensityMeasure.parse("pgv").unit == "m/s"
    design = IntensityMeasure.parse("sa:1.0").of_design_site({"sxs_g": 1.5, "sx1_g": 0.9})
    assert design == pytest.approx(0.9)  # S_X1/T at T = 1 s
    for bad in ("sa:", "sa:-1", "pgd"):
        with pytest.raises(InputError, match="^im: "):
            IntensityMeasure.parse(bad)
    assert main(["margins", "all", "--stripes", "0.2,x", "--out", str(tmp_path / "m")]) == 2
    assert "--stripes" in capsys.readouterr().err
    assert not (tmp_path / "m").exists()


def test_margins_from_python(tmp_path):
    import audit
    result = audit.margins("fema356", _suite(), im="pga", stripes=LEVELS_G, alpha_deg=[15],
                           size_s=[SIZE_S], required=False, solver=audit.Solver(free_motion_s=8.0))
    assert len(result.fragility) == 1 and "fema356" in result._repr_html_()
    written = sorted(p.name for p in result.write(tmp_path / "m").iterdir())
    assert written == ["capacity.csv", "columns.json", "fragility.csv", "margins.html",
                       "scan.csv", "stripes.csv", "summary.json"]


def test_block_by_its_dimensions():
    from audit.engine.shared.blocks import parse_blocks
    (block,) = parse_blocks(["0.4x2.0"])
    # α = atan(b/h) = atan(0.2/1.0); p = √(3g/(4R)), R = √(0.2² + 1²) (Eq. 4.2)
    assert block.alpha_deg == pytest.approx(math.degrees(math.atan(0.2)), rel=1e-12)
    p = math.sqrt(3 * 9.81 / (4 * math.hypot(0.2, 1.0)))
    assert block.size_s == pytest.approx(2 * math.pi / p, rel=1e-12)
    assert [b.label for b in parse_blocks(["0.4x2,0.8x2.4", "1x3"])] == ["0.4x2", "0.8x2.4", "1x3"]
    for bad in ("0.4", "2x0.4", "0x1", "axb"):
        with pytest.raises(InputError, match=f"^blocks {bad}: "):
            parse_blocks([bad])


def test_a_named_block_is_audited_beside_the_grid_as_its_grid_twin():
    block = Block.of_dimensions(0.8, 4.0)
    procedures = get_procedures("priestley1978")
    named = margins_tables(procedures, _suite(), _settings(blocks=[block]), Runtime())
    twin = margins_tables(procedures, _suite(),
                       _settings(alpha_deg=(block.alpha_deg,), size_s=[block.size_s]), Runtime())
    rows = named.stripes[(named.stripes["width_m"] == 0.8) & (named.stripes["height_m"] == 4.0)].reset_index(drop=True)
    assert len(rows) == 3 * LEVELS_G.size
    for column in ("exact_overturned", "exact_theta_rad", "priestley1978_overturns"):
        assert list(rows[column]) == list(twin.stripes[column])
    assert named.fragility.iloc[-1]["median"] == twin.fragility.iloc[0]["median"]


def test_required_alpha_bisects_the_last_crossing_against_brute_force():
    from audit.engine.design.required_alpha import required_alpha
    grid = np.arange(6.0, 30.1, 4.0)
    table = required_alpha(get_procedures("priestley1978"), _suite(), _settings(size_s=[2.0]),
                           Runtime(), grid, targets=(0.10,), bisections=3)
    table = table.set_index("procedure")

    def share(alpha_deg):  # every record solved afresh, one block at a time
        return np.mean([simulate(RigidBlock.from_size(2.0, math.radians(alpha_deg)),
                                 entry.motion, 8.0).overturned for entry in _suite()])
    shares = np.array([share(a) for a in grid])
    j = np.flatnonzero(shares > 0.10)[-1]
    low, high = grid[j], grid[j + 1]
    for _ in range(3):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if share(middle) > 0.10 else (low, middle)
    assert table.loc["exact@0.10", "required_alpha_deg"] == pytest.approx(high, abs=1e-12)
    assert table.loc["exact@0.10", "exact_overturning_share"] == pytest.approx(share(high))
    assert 6.0 <= table.loc["priestley1978", "required_alpha_deg"] <= 30.0


def test_required_alpha_is_where_the_share_stays_below_the_target():
    from audit.engine.design.required_alpha import interpolated_alpha
    alpha = np.array([2.0, 3.0, 4.0, 5.0, 6.0])
    # not monotonic: below 10 % at 3°, above again at 4°, below for good from 5°
    share = np.array([0.5, 0.05, 0.3, 0.08, 0.0])
    assert interpolated_alpha(alpha, share, 0.10) == pytest.approx(4 + 0.2 / 0.22)
    assert interpolated_alpha(alpha, np.zeros(5), 0.10) == 2.0
    assert math.isnan(interpolated_alpha(alpha, np.full(5, 0.5), 0.10))


def test_resumed_and_dask_margins_are_identical(tmp_path):
    pytest.importorskip("distributed")
    import audit
    from audit.engine.shared.partial import kept_parts
    common = dict(im="pga", stripes=LEVELS_G, alpha_deg=[15], size_s=[SIZE_S],
                  solver=audit.Solver(free_motion_s=8.0), required=False)
    local = audit.margins("priestley1978", _suite(), **common)
    partial = tmp_path / ".partial"
    audit.margins("priestley1978", _suite(), runtime=audit.Runtime(partial_dir=partial), **common)
    assert len(kept_parts(partial)) == 3  # one part per record, kept for a resume
    resumed = audit.margins("priestley1978", _suite(),
                            runtime=audit.Runtime(partial_dir=partial, resume=True), **common)
    assert resumed.summary["resumed"] == [e.id for e in _suite()]
    on_dask = audit.margins("priestley1978", _suite(),
                            runtime=audit.Runtime(jobs=2, scheduler="dask"), **common)
    for other in (resumed, on_dask):
        assert other.stripes.equals(local.stripes)
        assert other.fragility.equals(local.fragility)


def test_margins_page_from_the_files(tmp_path):
    import audit
    result = audit.margins(["priestley1978", "fema356"], _suite(), im="pga", stripes=LEVELS_G,
                           alpha_deg=[15], size_s=[SIZE_S], blocks=["0.8x4"],
                           solver=audit.Solver(free_motion_s=8.0))
    page = (result.write(tmp_path / "m") / "margins.html").read_text()
    share = result.required_alpha.set_index("procedure").loc["fema356", "exact_overturning_share"]
    assert ("Blocks sized by FEMA 356 (2000) for S_XS = 1.5 g, S_X1 = 0.9 g" in page
            and f"overturn in a median {share:.0%}" in page)
    assert "0.8x4 m (α = " in page and 'id="scan0"' in page and 'id="required"' in page
    assert result.summary["blocks"][0]["alpha_deg"] == Block.of_dimensions(0.8, 4.0).alpha_deg


def test_margins_command_names_the_block_option(tmp_path, capsys):
    assert main(["margins", "all", "--block", "2x1", "--out", str(tmp_path / "m")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--block" in err[0]
    assert not (tmp_path / "m").exists()


def test_p695_acceptance_of_the_blocks_a_guideline_sizes():
    """The block a guideline sizes gets the fragility its grid twin gets; β_MDL is measured from
    the exact medians with r × 0.9 and × 0.8; ACMRxx = exp(−Φ⁻¹(xx)·β_TOT) (FEMA P695 §7.4)."""
    from audit.engine.design.p695_acceptance import p695_acceptance
    suite = _suite()
    required = pd.DataFrame({"procedure": ["priestley1978", "exact@0.10"], "size_s": [SIZE_S] * 2,
                             "required_alpha_deg": [ALPHA_DEG] * 2,
                             "exact_overturning_share": [0.0, 0.0]})
    table, verdicts = p695_acceptance(suite, _settings(), Runtime(), required)
    assert list(table["procedure"]) == ["priestley1978"]  # the exact curves are no guideline
    row = table.iloc[0]
    medians = {v: margins_tables([], suite, _settings(restitution=v), Runtime()).fragility.iloc[0]
               for v in ("housner", "x0.9", "x0.8")}
    twin = medians["housner"]
    assert row["median"] == pytest.approx(twin["median"], rel=1e-6)
    assert row["cmr"] == pytest.approx(twin["median"] / 0.6, rel=1e-6)  # PGA MCE: 0.4 S_XS
    log_ratios = [math.log(medians[v]["median"] / twin["median"]) for v in ("x0.9", "x0.8")]
    assert row["beta_mdl"] == pytest.approx(math.sqrt(np.mean(np.square(log_ratios))), rel=1e-6)
    beta_total = math.hypot(twin["beta"], row["beta_mdl"])
    assert row["acmr20"] == pytest.approx(math.exp(-norm.ppf(0.2) * beta_total), rel=1e-6)
    assert row["meets_acmr20"] == (row["cmr"] >= row["acmr20"])
    verdict = verdicts[0]
    assert verdict["acmr10"] == pytest.approx(math.exp(-norm.ppf(0.1) * beta_total), rel=1e-6)
    assert verdict["passes"] == (row["meets_acmr20"] and row["cmr"] >= verdict["acmr10"])
