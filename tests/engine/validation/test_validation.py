"""``validate``: the campaign reader, the slenderness link, the fit, the folds, the baselines and
the command, on synthetic campaigns whose truth is known; and the reader on the shared granite
campaign (``ROCKING_AUDIT_CAMPAIGN``; skipped without it, failed where .ci/run requires the
development data)."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.special import ndtr

from audit.cli import main
from conftest import REQUIRE_RECORDS, unavailable
from audit.engine.validation.baselines import ThresholdFragility, VectorLogistic, scores
from audit.engine.validation.cross_validation import folds_by_record
from audit.engine.validation.fit import fit_block
from audit.engine.validation.link import overturning_probability, slenderness_weights
from audit.engine.validation.profile import profile_interval
from audit.engine.validation.grid import band_passed, overturning_grid
from audit.engine.validation.settings import ValidationSettings
from audit.engine.validation.pipeline import fitted_restitution, methods_statement
from audit.errors import InputError
from audit.physics.block import Restitution
from audit.physics.rocking import RockingOptions, rocking_blocks
from records.campaign import read_campaign
from records.motion import GroundMotion

CAMPAIGN_VARIABLE = "ROCKING_AUDIT_CAMPAIGN"
DT = 0.01
#: The synthetic specimen: median α, test-to-test σ of ln α, p, restitution factor.
TRUE_ALPHA_DEG, TRUE_SIGMA, TRUE_P, TRUE_FACTOR = 8.0, 0.1, 4.0, 0.85
#: A small grid holding the truth (p and f on it, α between nodes).
SMALL = ValidationSettings(alpha_deg=tuple(np.geomspace(3.0, 20.0, 15)), p_rad_s=(2.5, 4.0, 6.4),
                           restitution_factors=(0.7, 0.85, 1.0), folds=4, free_motion_s=5.0)


def _record(kind: int, period_s: float) -> np.ndarray:
    """A pulse-like record [in g, unit peak]: one sine, one cosine, or a three-cycle burst."""
    t = np.arange(0.0, 3 * period_s + 2.0, DT)
    phase = 2 * np.pi * t / period_s
    cycles = (1, 1, 3)[kind]
    wave = (np.sin(phase), np.cos(phase), np.sin(phase) * np.sin(phase / 6))[kind]
    acc = np.where(t <= cycles * period_s, wave, 0.0)
    return acc / np.max(np.abs(acc))


def _campaign(folder: Path, seed: int = 1, unknown: int = 6, periods=(0.4, 0.7, 1.0, 1.5, 2.2),
              scales: int = 9) -> dict:
    """Write a synthetic campaign drawn from the true specimen (records of 3 kinds × ``periods``
    [s], each at ``scales`` scales); returns the truths."""
    rng = np.random.default_rng(seed)
    (folder / "motions").mkdir(parents=True)
    rows, motions = [], []
    for i, (kind, period) in enumerate([(k, T) for k in range(3) for T in periods]):
        base = _record(kind, period)
        for scale in np.geomspace(0.1, 1.2, scales):
            test = f"T{len(rows):03d}"
            acc = np.round(base * scale, 5)
            pd.DataFrame({"time_s": np.round(np.arange(acc.size) * DT, 2), "acc_g": acc}).to_csv(
                folder / "motions" / f"{test}.csv.gz", index=False)
            rows.append({"test": test, "ground_motion": f"rec{i}",
                         "motion_file": f"motions/{test}.csv.gz"})
            motions.append(GroundMotion(test, acc * 9.81, DT))
    alpha = np.radians(TRUE_ALPHA_DEG) * np.exp(TRUE_SIGMA * rng.standard_normal(len(rows)))
    outcome = np.array([rocking_blocks(m, [2 * np.pi / TRUE_P], [a],
                                       Restitution(factor=TRUE_FACTOR),
                                       RockingOptions(free_motion_s=5.0)).overturned[0]
                        for m, a in zip(motions, alpha)])
    frame = pd.DataFrame(rows)
    frame["spec_overturned"] = outcome.astype(int).astype(object)
    hidden = rng.choice(len(rows), unknown, replace=False)
    frame.loc[hidden, "spec_overturned"] = ""
    frame["numerical_spec_always"] = 1
    frame.to_csv(folder / "tests.csv", index=False)
    return {"outcome": outcome, "hidden": hidden}


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    folder = tmp_path_factory.mktemp("campaign")
    truth = _campaign(folder)
    return folder, truth


def test_weights_are_the_expectation_of_the_interpolated_outcome():
    """Σ w_k O_k equals E[O(α)] by quadrature of O read linearly in ln α (an independent path)."""
    nodes = np.log(np.radians(np.geomspace(2.0, 30.0, 12)))
    outcome = np.array([1, 1, 1, 0, 1, 1, 0, 0, 0, 1, 0, 0], dtype=float)  # not monotonic
    for mu, sigma in ((np.log(np.radians(6.0)), 0.3), (nodes[4] + 0.01, 0.05), (nodes[0], 1.2)):
        u = np.linspace(mu - 12 * sigma, mu + 12 * sigma, 400_001)
        density = np.exp(-0.5 * ((u - mu) / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))
        expected = np.trapezoid(np.interp(u, nodes, outcome) * density, u)
        weights = slenderness_weights(nodes, mu, sigma)
        assert weights.sum() == pytest.approx(1.0, abs=1e-12)
        assert weights @ outcome == pytest.approx(expected, abs=1e-7)


def test_weights_collapse_to_interpolation_as_sigma_vanishes():
    nodes = np.log([0.05, 0.1, 0.2])
    mu = np.log(0.08)
    weights = slenderness_weights(nodes, mu, 1e-6)
    share = (mu - nodes[0]) / (nodes[1] - nodes[0])
    assert weights == pytest.approx([1 - share, share, 0.0], abs=1e-6)


def test_vectorised_weights_are_the_scalar_ones_column_by_column():
    nodes = np.log(np.radians(np.geomspace(2.0, 30.0, 9)))
    mu = np.log(np.radians([3.0, 7.5, 29.0]))
    sigma = np.array([0.01, 0.3, 1.1])
    columns = slenderness_weights(nodes, mu, sigma)
    for c in range(3):
        assert columns[:, c] == pytest.approx(slenderness_weights(nodes, mu[c], sigma[c]),
                                              abs=1e-15)


def test_profile_interval_is_the_set_within_1_92_widened_by_a_step():
    values = np.arange(1.0, 11.0)
    profile = -0.5 * (values - 5.0) ** 2  # within 1.92 of 0 for |v − 5| ≤ 1.96: 4, 5, 6
    interval = profile_interval(values, profile, 0.0)
    assert (interval.low, interval.high, interval.identified) == (3.0, 7.0, True)
    flat = profile_interval(values, np.zeros(10) - 1.0, 0.0)  # a ridge: the whole range
    assert (flat.low, flat.high, flat.identified) == (1.0, 10.0, False)


def test_profile_is_the_maximum_over_the_other_parameters_not_a_slice(synthetic):
    """On the synthetic campaign, the α profile at a median is the lattice's best over
    (f, p, σ), and that value is the likelihood recomputed from the link at its point."""
    folder, _ = synthetic
    campaign = read_campaign(folder)
    observed = campaign.outcomes["spec"]
    known = ~np.isnan(observed)
    grid = overturning_grid([m for m, k in zip(campaign.motions, known) if k], SMALL)
    fit = fit_block(grid.overturned, observed[known], grid.blocks, SMALL.lapse)
    values = fit.surface.log_likelihood
    m = values.shape[2] // 3
    j, k, s = np.unravel_index(np.argmax(values[:, :, m, :]), values[:, :, m, :].shape)
    p = overturning_probability(grid.overturned[:, j, k, :].astype(float),
                                fit.surface.log_nodes(j, k), fit.surface.log_medians[m],
                                fit.surface.sigma[s], SMALL.lapse)
    y = observed[known]
    direct = np.sum(y * np.log(p) + (1 - y) * np.log1p(-p))
    assert values.max(axis=(0, 1, 3))[m] == pytest.approx(direct, abs=1e-9)


def test_band_pass_removes_the_offset_and_keeps_the_rocking_band():
    """A 0.05 g offset goes; a 1 Hz sine keeps its amplitude; 40 Hz noise goes (0.1–25 Hz)."""
    t = np.arange(0.0, 120.0, DT)
    sine = 0.3 * np.sin(2 * np.pi * t)
    motion = GroundMotion("m", 9.81 * (0.05 + sine + 0.05 * np.sin(2 * np.pi * 40 * t)), DT)
    kept = band_passed(motion, ValidationSettings()).acceleration / 9.81
    middle = slice(2000, -2000)  # 20 s from the ends: past the 0.1 Hz filter's transients
    assert np.max(np.abs(kept[middle] - sine[middle])) < 0.002


def test_folds_keep_each_ground_motion_whole_and_balanced():
    rng = np.random.default_rng(3)
    groups = np.repeat([f"g{i}" for i in range(40)], rng.integers(1, 15, 40))
    rng.shuffle(groups)
    fold = folds_by_record(groups, 5)
    for name in np.unique(groups):
        assert np.unique(fold[groups == name]).size == 1
    sizes = np.bincount(fold, minlength=5)
    assert sizes.max() - sizes.min() <= 14  # at most one ground motion's tests apart
    assert np.array_equal(folds_by_record(groups, 5), fold)


def test_scores_against_hand_computed_values():
    s = scores([0.9, 0.2, 0.6, 0.4], [1, 0, 0, 1])
    assert s.accuracy == 0.5
    assert s.brier == pytest.approx((0.01 + 0.04 + 0.36 + 0.36) / 4)
    assert s.log_loss == pytest.approx(-(np.log(0.9) + np.log(0.8) + 2 * np.log(0.4)) / 4)
    assert (s.true_positive, s.false_positive, s.true_negative, s.false_negative) == (1, 1, 1, 1)


def test_threshold_fragility_is_the_likelihood_maximum():
    """The fitted (threshold, β) beats every point of a brute-force grid of the likelihood."""
    rng = np.random.default_rng(5)
    x = np.exp(rng.normal(0.0, 0.8, 300))
    y = (rng.random(300) < ndtr(np.log(x / 1.3) / 0.4)).astype(float)
    fit = ThresholdFragility.fit(x, y, 0.005)

    def loglik(threshold, beta):
        p = 0.005 + 0.99 * ndtr(np.log(x / threshold) / beta)
        return np.sum(y * np.log(p) + (1 - y) * np.log1p(-p))
    best = max(loglik(t, b) for t in np.geomspace(0.5, 3.0, 120)
               for b in np.geomspace(0.1, 1.5, 80))
    assert loglik(fit.threshold, fit.beta) >= best - 1e-6
    assert fit.threshold == pytest.approx(1.3, rel=0.15)


def test_vector_logistic_solves_the_likelihood_equations():
    """At the maximum of a logistic likelihood Σ (y − P) x = 0 for every regressor x."""
    rng = np.random.default_rng(7)
    pga_g = np.exp(rng.normal(-1.5, 0.7, 400))
    ratio = np.exp(rng.normal(-2.5, 0.6, 400))
    truth = 1.0 / (1.0 + np.exp(-(4.0 + 1.5 * np.log(pga_g) + 1.0 * np.log(ratio))))
    y = (rng.random(400) < truth).astype(float)
    fit = VectorLogistic.fit(pga_g, ratio, y, 1e-12)
    residual = y - fit.probability(pga_g, ratio)
    for regressor in (np.ones(400), np.log(pga_g), np.log(ratio)):
        assert abs(residual @ regressor) < 1e-3


def test_reader_reads_outcomes_peers_and_motions(synthetic):
    folder, truth = synthetic
    campaign = read_campaign(folder)
    assert campaign.specimens == ("spec",)
    observed = campaign.outcomes["spec"]
    assert np.isnan(observed).sum() == len(truth["hidden"])
    known = ~np.isnan(observed)
    assert np.array_equal(observed[known], truth["outcome"][known])
    assert list(campaign.peers["spec"]) == ["numerical_spec_always"]
    assert campaign.motions[0].dt == pytest.approx(DT)


def test_fit_recovers_the_block_that_made_the_outcomes(synthetic):
    folder, _ = synthetic
    campaign = read_campaign(folder)
    observed = campaign.outcomes["spec"]
    known = ~np.isnan(observed)
    grid = overturning_grid([m for m, k in zip(campaign.motions, known) if k], SMALL)
    assert grid.solves == known.sum() * 15 * 3 * 3
    fit = fit_block(grid.overturned, observed[known], grid.blocks, SMALL.lapse)
    assert fit.p_rad_s == TRUE_P
    assert fit.alpha_deg == pytest.approx(TRUE_ALPHA_DEG, rel=0.1)
    assert fit.alpha.low < TRUE_ALPHA_DEG < fit.alpha.high and fit.alpha.identified
    assert fit.restitution.low <= TRUE_FACTOR <= fit.restitution.high
    assert fit.sigma < 0.3


def test_api_and_command_write_predictions_for_the_unknown_tests(synthetic, tmp_path):
    import audit
    folder, truth = synthetic
    result = audit.validate(folder, settings=SMALL)
    predicted = result.predictions
    assert sorted(predicted["test"]) == sorted(f"T{i:03d}" for i in truth["hidden"])
    assert set(predicted["predicted_overturned"]) <= {0, 1}
    assert np.array_equal(predicted["predicted_overturned"], predicted["p_overturn"] >= 0.5)
    methods = set(result.scores["method"])
    assert {"rocking model", "PGA threshold", "PGV threshold", "logistic (PGA, PGV/PGA)",
            "numerical_spec_always"} <= methods
    always = result.scores.set_index("method").loc["numerical_spec_always"]
    known = np.delete(truth["outcome"], truth["hidden"])
    assert always.accuracy == pytest.approx(known.mean())  # predicts 1 everywhere
    # every test is scored once, by a fold that did not see its ground motion
    tests = result.tests.dropna(subset=["observed"])
    assert (tests.groupby("ground_motion")["fold"].nunique() == 1).all()
    assert result.scores.set_index("method").loc["rocking model"].n == len(tests)


@pytest.mark.slow  # end to end: the validation command on the campaign
def test_command_writes_every_file(tmp_path):
    folder = tmp_path / "small"
    _campaign(folder, unknown=2, periods=(1.0,), scales=4)  # the default grid: keep it small
    out = tmp_path / "out"
    geometry = tmp_path / "geometry.csv"
    geometry.write_text("specimen,alpha_deg,p_rad_s,note\nspec,8,4,known\n")
    assert main(["validate", str(folder), "--out", str(out), "--folds", "3",
                 "--geometry", str(geometry), "--free-motion", "5"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"predictions.csv", "validation-fits.csv", "validation-scores.csv",
            "validation-tests.csv", "validation-ridge.csv", "validation.html"} <= names
    predicted = pd.read_csv(out / "predictions.csv")
    assert (predicted["p_overturn_low"] <= predicted["p_overturn"]).all()
    assert (predicted["p_overturn"] <= predicted["p_overturn_high"]).all()
    ridge = pd.read_csv(out / "validation-ridge.csv")
    assert ridge["inside_95"].any() and set(ridge["specimen"]) == {"spec"}
    fits = pd.read_csv(out / "validation-fits.csv")
    assert fits["geometry_alpha_deg"].iloc[0] == 8
    page = (out / "validation.html").read_text()
    assert "<script>" in page and "PGV threshold" in page and "one laboratory" in page
    assert "Predictions of the tests without an outcome" in page and "ridge" in page


@pytest.mark.parametrize("edit, field", [
    (lambda f: f.drop(columns="motion_file"), "motion_file"),
    (lambda f: f.assign(spec_overturned="2"), "spec_overturned"),
    (lambda f: f.assign(spec_peak_rotation_rad=0.1), "spec_peak_rotation_rad"),
    (lambda f: f.assign(motion_file="motions/none.csv"), "motion_file"),
])
def test_bad_campaign_names_the_field_and_writes_nothing(synthetic, tmp_path, capsys, edit, field):
    folder, _ = synthetic
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "motions").symlink_to(folder / "motions")
    edit(pd.read_csv(folder / "tests.csv", dtype=str)).to_csv(bad / "tests.csv", index=False)
    with pytest.raises(InputError, match=field):
        read_campaign(bad)
    out = tmp_path / "out"
    assert main(["validate", str(bad), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and field in err[0]
    assert not out.exists() or not any(out.iterdir())


@pytest.fixture(scope="module")
def granite():
    value = os.environ.get(CAMPAIGN_VARIABLE)
    if not value:
        unavailable(REQUIRE_RECORDS, f"{CAMPAIGN_VARIABLE} is not set: the shake-table campaign "
                                     "tests need it")
    return read_campaign(value)


def test_granite_campaign_counts_match_its_readme(granite):
    """490 readable tests, 163 held out; 126 and 104 public overturnings; 5 and 8 peer columns."""
    assert len(granite.motions) == 490
    one, two = granite.outcomes["specimen1"], granite.outcomes["specimen2"]
    assert np.isnan(one).sum() == np.isnan(two).sum() == 163
    assert np.nansum(one) == 126 and np.nansum(two) == 104
    assert len(granite.peers["specimen1"]) == 5 and len(granite.peers["specimen2"]) == 8
    folds = folds_by_record(granite.tests["ground_motion"], 5)
    assert (pd.Series(folds).groupby(granite.tests["ground_motion"]).nunique() == 1).all()


def test_granite_motions_hold_the_measured_pga(granite):
    table = pd.read_csv(granite.folder / "tests.csv")
    measured = np.array([m.pga_g for m in granite.motions])
    assert measured == pytest.approx(table["measured_pga_g"].to_numpy(), abs=1e-4)


def test_fitted_restitution_is_an_option_the_audit_accepts():
    fits = pd.DataFrame({"specimen": ["a", "b"], "restitution_factor": [0.6, 0.8]})
    assert fitted_restitution(fits) is None  # the specimens differ: no one value
    assert Restitution.parse(fitted_restitution(fits, "b")).factor == 0.8
    assert fitted_restitution(fits.iloc[:1]) == "x0.6"


def test_methods_statement_gives_the_fit_the_score_and_the_limits():
    fits = pd.DataFrame({"specimen": ["a"], "alpha_deg": [3.5], "alpha_deg_low": [3.3],
                         "alpha_deg_high": [3.7], "p_rad_s": [4.9], "restitution_factor": [0.6]})
    scores_table = pd.DataFrame({"specimen": ["a"], "method": ["rocking model"], "n": [327],
                                 "accuracy": [0.924], "brier": [0.0623]})
    text = methods_statement(fits, scores_table)
    for part in ("α = 3.5° (95 % 3.3–3.7°)", "p = 4.90 rad/s", "0.6 × Eq. 4.8", "accuracy 92%",
                 "Brier 0.062 over 327 tests", "one laboratory", "3-D"):
        assert part in text


@pytest.mark.parametrize("field, value", [("band_pass", "yes"), ("band_pass", 1),
                                          ("refined_solves", -1), ("refined_solves", 2.5)])
def test_settings_refuse_a_bad_processing_or_budget(field, value):
    with pytest.raises(InputError, match=field):
        ValidationSettings(**{field: value})

