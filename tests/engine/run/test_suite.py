"""Suite statistics: verdict fractions and approx/exact percentiles, against hand computations."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from audit.engine.shared.schemas import SUITE_COLUMNS, verdict_column
from audit.engine.run.suite import suite_statistics, suite_summary
from audit.engine.shared.verdicts import VERDICTS


def _results(rows):
    return pd.DataFrame(rows, columns=["record", "procedure", "alpha_deg", "size_s", "verdict",
                                       "ratio"])


@pytest.fixture
def synthetic():
    """One procedure, α = 15°, two sizes, four records; a second procedure at one size."""
    return _results([
        # size 1.0 s: ratios 0.5 (unconservative), 1.0 (agrees), 2.0 (conservative), overturned
        ("A", "p", 15.0, 1.0, "unconservative", 0.5),
        ("B", "p", 15.0, 1.0, "agrees", 1.0),
        ("C", "p", 15.0, 1.0, "conservative", 2.0),
        ("D", "p", 15.0, 1.0, "missed-overturn", np.nan),
        # size 2.0 s: one ratio only
        ("A", "p", 15.0, 2.0, "no-uplift", np.nan),
        ("B", "p", 15.0, 2.0, "both-overturn", np.nan),
        ("C", "p", 15.0, 2.0, "agrees", 0.95),
        ("D", "p", 15.0, 2.0, "not-converged", np.nan),
        ("A", "q", 15.0, 1.0, "false-overturn", np.nan),
        ("B", "q", 15.0, 1.0, "false-overturn", np.nan),
    ])


def test_columns_and_one_row_per_procedure_alpha_size(synthetic):
    suite = suite_statistics(synthetic)
    assert list(suite.columns) == SUITE_COLUMNS
    assert list(zip(suite["procedure"], suite["size_s"])) == [("p", 1.0), ("p", 2.0), ("q", 1.0)]
    assert suite["records"].tolist() == [4, 4, 2]


def test_fractions_by_hand(synthetic):
    suite = suite_statistics(synthetic).set_index(["procedure", "size_s"])
    first = suite.loc[("p", 1.0)]
    assert first["frac_unconservative"] == 0.25 and first["frac_agrees"] == 0.25
    assert first["frac_conservative"] == 0.25 and first["frac_missed_overturn"] == 0.25
    assert first["frac_unsafe"] == 0.5          # missed-overturn + unconservative
    second = suite.loc[("p", 2.0)]
    assert second["frac_no_uplift"] == second["frac_both_overturn"] == 0.25
    assert second["frac_not_converged"] == second["frac_agrees"] == 0.25
    assert second["frac_unsafe"] == 0.0
    assert suite.loc[("q", 1.0), "frac_false_overturn"] == 1.0


def test_fractions_sum_to_one(synthetic):
    suite = suite_statistics(synthetic)
    total = suite[[verdict_column(v) for v in VERDICTS]].sum(axis=1)
    np.testing.assert_allclose(total, 1.0, rtol=0, atol=1e-15)


def test_ratio_percentiles_by_hand(synthetic):
    suite = suite_statistics(synthetic).set_index(["procedure", "size_s"])
    # ratios 0.5, 1.0, 2.0: linear between order statistics at positions q·(n − 1)
    # p16 → 0.32 → 0.5 + 0.32·0.5 = 0.66; p50 → 1.0; p84 → 1.68 → 1.0 + 0.68·1.0 = 1.68
    first = suite.loc[("p", 1.0)]
    assert first["ratio_p16"] == pytest.approx(0.66, abs=1e-12)
    assert first["ratio_p50"] == pytest.approx(1.0, abs=1e-12)
    assert first["ratio_p84"] == pytest.approx(1.68, abs=1e-12)
    second = suite.loc[("p", 2.0)]      # a single ratio is every percentile
    assert second["ratio_p16"] == second["ratio_p50"] == second["ratio_p84"] == 0.95
    assert np.isnan(suite.loc[("q", 1.0), "ratio_p50"])   # no block where both survive


def test_summary_mean_unsafe_worst_size_and_sentence(synthetic):
    summary = suite_summary(suite_statistics(synthetic), {"p": "FEMA 356"})
    p, q = summary
    # 2 unsafe blocks (A and D at 1.0 s) out of 8 record × size blocks
    assert p["mean_unsafe"] == 0.25 and p["blocks"] == 8 and p["records"] == 4
    assert p["worst_size_s"] == 1.0 and p["worst_unsafe"] == 0.5
    assert p["sentence"] == ("over 4 records, FEMA 356 is unsafe for 25 % of blocks with "
                             "α = 15°, worst at 2π/p ≈ 1 s (50 % of records)")
    assert q["worst_size_s"] is None and q["mean_unsafe"] == 0.0
    assert q["sentence"] == "over 2 records, q is never unsafe for blocks with α = 15° (2π/p = 1–1 s)"


def test_unknown_verdict_is_refused(synthetic):
    synthetic.loc[0, "verdict"] = "maybe"
    with pytest.raises(ValueError, match="maybe"):
        suite_statistics(synthetic)


def test_empty_results_give_an_empty_table_with_the_columns():
    suite = suite_statistics(_results([]))
    assert suite.empty and list(suite.columns) == SUITE_COLUMNS


def test_ratio_takes_each_rotation_as_at_least_the_rocking_floor():
    from audit.engine.shared.verdicts import ROCKING_FLOOR, classify, reported_ratio, rotation_ratio
    alpha = 0.2
    floor = ROCKING_FLOOR * alpha  # 2e-4 rad
    approx = np.array([0.05, 1e-14, 1e-14, 0.01, np.nan, 0.05])
    exact = np.array([1e-14, 0.05, 2e-14, 0.02, 0.01, np.nan])
    np.testing.assert_allclose(rotation_ratio(approx, exact, alpha),
                               [0.05 / floor, floor / 0.05, 1.0, 0.5, np.nan, np.nan],
                               rtol=1e-12)
    outcome = np.array(["converged"] * 6, dtype=object)
    verdicts = classify(exact, np.zeros(6, bool), np.ones(6, bool), approx, outcome, alpha, 0.1)
    # 2e-14 against 1e-14 is no rocking against no rocking: agrees, not "conservative"
    assert list(verdicts[:4]) == ["conservative", "unconservative", "agrees", "unconservative"]
    # results.csv gives a ratio only where the exact block rocks
    np.testing.assert_allclose(reported_ratio(verdicts, approx, exact, alpha),
                               [np.nan, floor / 0.05, np.nan, 0.5, np.nan, np.nan], rtol=1e-12)


def test_an_exact_rotation_of_1e_14_rad_gives_no_ratio_of_1e12():
    """A one-cosine pulse whose amplitude exceeds g tan α by 1e-6: the exact block rocks by
    ~5e-14 rad (θ grows with the excess), Priestley's iteration to ~0.04 rad: the ratio was
    ~8e11."""
    import math
    from audit.engine.run.pipeline import audit_in_memory
    from audit.engine.shared.verdicts import ROCKING_FLOOR
    from procedures import get_procedures
    from records import RecordEntry, RecordSuite, one_pulse
    from reports.outcome_words import describe_exact
    alpha = math.radians(10.0)
    edge = one_pulse("cosine", math.tan(alpha) * (1 + 1e-6), 1.0, record_id="edge")
    run = audit_in_memory(get_procedures("priestley1978"),
                    RecordSuite((RecordEntry("edge", edge, None, "edge"),), "edge"),
                    alpha_deg=(10.0,), size_s=np.array([4.0]), robustness=0.0)
    row = run.results.iloc[0]
    assert row["exact_uplifted"] and row["exact_theta_rad"] < 1e-12 < row["approx_theta_rad"]
    assert row["exact_theta_rad"] < ROCKING_FLOOR * alpha
    # the guideline rocks, the block does not: conservative, and no ratio in any band
    assert row["verdict"] == "conservative" and np.isnan(row["ratio"])
    assert np.isnan(run.suite.iloc[0]["ratio_p50"])
    assert describe_exact(row).startswith("no rocking (θ/α = ")


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.sampled_from([0.5, 1.0, 2.0, -0.0, 0.0, np.inf, np.nan]),
                          st.sampled_from([True, False, np.nan])), max_size=12),
       st.sampled_from(["ratio", "approx_theta_rad"]), st.booleans())
def test_ranking_is_pandas_stable_sort_robust_first_nan_last(rows, column, largest):
    """The worst-first ranking equals pandas' stable two-key sort it replaced (robust blocks
    before fragile ones, then the column, NaN last, ties in the rows' order), index and all."""
    from audit.engine.run.ranking import rank_worst
    frame = pd.DataFrame({column: [value for value, _ in rows],
                          "exact_fragile": pd.Series([fragile for _, fragile in rows],
                                                     dtype=object),
                          "label": range(len(rows))}, index=np.arange(len(rows))[::-1] * 10)
    expected = frame.assign(_fragile=frame["exact_fragile"].eq(True)).sort_values(
        ["_fragile", column], ascending=[True, not largest], kind="stable").drop(
        columns="_fragile")
    pd.testing.assert_frame_equal(rank_worst(frame, column, largest), expected)
