"""Suite statistics: verdict fractions and approx/exact percentiles, against hand computations."""

import numpy as np
import pandas as pd
import pytest

from audit.engine.schemas import SUITE_COLUMNS, verdict_column
from audit.engine.suite import suite_statistics, suite_summary
from audit.engine.verdicts import VERDICTS


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
