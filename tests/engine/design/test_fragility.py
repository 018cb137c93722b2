"""Multiple-stripe fragility: the binomial maximum-likelihood lognormal fit against known
lognormals, its bands against the Fisher information worked by hand, the overturning pattern,
and the exact stripes of the one-cosine pulse of Figure 4.1 (an island of survival)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.stats import norm

from audit.engine.design.fragility import overturning_pattern, stripe_outcomes
from audit.engine.design.lognormal_fit import fit_lognormal
from records import one_pulse


def _expected_counts(levels, trials, median, beta):
    return trials * norm.cdf(np.log(levels / median) / beta)


def test_fit_recovers_a_lognormal_from_its_expected_counts():
    levels = np.geomspace(0.1, 3.0, 20)
    trials = np.full(20, 1e6)
    fit = fit_lognormal(levels, trials, _expected_counts(levels, trials, 0.8, 0.45))
    assert fit.median == pytest.approx(0.8, rel=1e-5)
    assert fit.beta == pytest.approx(0.45, rel=1e-5)


def test_covariance_is_the_inverse_fisher_information():
    # at the truth with expected counts, the observed information equals the expected one:
    # I = Σ n φ(z)²/(Φ(1 − Φ)) g gᵀ, g = ∂z/∂(ln θ, ln β) = (−1/β, −z)
    levels, median, beta = np.geomspace(0.2, 5.0, 12), 1.1, 0.5
    trials = np.full(12, 400.0)
    fit = fit_lognormal(levels, trials, _expected_counts(levels, trials, median, beta))
    z = np.log(levels / median) / beta
    p = norm.cdf(z)
    weight = trials * norm.pdf(z) ** 2 / (p * (1 - p))
    gradient = np.stack([-np.ones_like(z) / beta, -z])
    information = (gradient * weight) @ gradient.T
    np.testing.assert_allclose(fit.covariance, np.linalg.inv(information), rtol=2e-3)
    low, high = fit.median_band
    k = norm.ppf(0.95)
    spread = math.sqrt(fit.covariance[0, 0])
    assert low == pytest.approx(fit.median * math.exp(-k * spread), rel=1e-12)
    assert high == pytest.approx(fit.median * math.exp(k * spread), rel=1e-12)
    assert fit.median == pytest.approx(median, rel=1e-5)


def test_counts_that_do_not_fix_beta_claim_no_band_and_warn_nothing():
    # one of two records overturns at the top stripe, none below: P = 1/2 there fixes the median
    # at that stripe, while any small β fits the zeros below equally well
    levels = np.geomspace(0.05, 2.0, 5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit = fit_lognormal(levels, [2] * 5, [0, 0, 0, 0, 1])
    assert fit.median == pytest.approx(2.0, rel=1e-3)
    # no bounded band on β is claimed: NaN (information not positive definite) or (≈0, ≫1)
    assert not (0.05 <= fit.beta_band[0] and fit.beta_band[1] <= 10.0)


def test_fit_of_sampled_counts_brackets_the_truth():
    # 44 records a stripe, as the FEMA P695 far-field set: the truth lies in the 99 % bands
    rng = np.random.default_rng(20)
    levels, trials = np.geomspace(0.2, 5.0, 24), np.full(24, 44)
    counts = rng.binomial(trials, norm.cdf(np.log(levels / 1.3) / 0.5))
    fit = fit_lognormal(levels, trials, counts, confidence=0.99)
    assert fit.median_band[0] < 1.3 < fit.median_band[1]
    assert fit.beta_band[0] < 0.5 < fit.beta_band[1]
    lower, upper = fit.probability_band(levels)
    assert np.all(lower <= fit.probability(levels)) and np.all(fit.probability(levels) <= upper)
    with pytest.raises(ValueError):
        fit_lognormal(levels, trials, np.zeros(24))


def test_overturning_pattern_names_first_stripe_and_islands():
    pattern = overturning_pattern([[0, 1, 1, 0, 1], [0, 0, 0, 0, 0], [0, 0, 1, 1, 1]])
    assert list(pattern.first_stripe) == [1, -1, 2]
    assert list(pattern.islands) == [True, False, False]


def test_one_cosine_pulse_stripes_in_pga():
    # p = 2 rad/s, α = 15°, T_p = 2 s: survives 0.3148 g, overturns from 0.31503 g on, and
    # survives again in a narrow island around 0.330 g (0.328 and 0.332 g overturn)
    pga_g = [0.3148, 0.3152, 0.328, 0.330, 0.332]
    overturned, theta = stripe_outcomes(one_pulse("cosine", 1.0, 2.0), pga_g, [math.pi],
                                        [math.radians(15.0)], 9.81, 8.0)
    assert list(overturned[:, 0, 0]) == [False, True, True, False, True]
    pattern = overturning_pattern(overturned[:, 0, 0][None, :])
    assert pattern.first_stripe[0] == 1 and pattern.islands[0]
    assert theta[0, 0, 0] < math.radians(15.0) and theta[1, 0, 0] == pytest.approx(
        math.radians(15.0))


def test_fits_of_many_count_sets_equal_those_of_every_row_scored_together():
    """lognormal_fits scores each distinct row once: the numbers of scoring every row of a
    bootstrap together (from the same pooled start), bit for bit, step fits included."""
    from audit.engine.design import lognormal_fit as lf
    rng = np.random.default_rng(7)
    levels = np.geomspace(0.2, 3.6, 24)
    for records in (1, 3, 8, 44):
        capacity = np.exp(rng.normal(0.0, 0.5, records))
        over = (levels[None, :] >= capacity[:, None]) ^ (rng.random((records, 24)) < 0.05)
        counts = over[rng.integers(0, records, size=(1000, records))].sum(axis=1).astype(float)
        medians, betas = lf.lognormal_fits(levels, records, counts)
        total = counts.sum(axis=1)
        fitted = (total > 0) & (total < records * 24)
        rows = counts[fitted]
        if records <= 3:  # a few records' resamples repeat (one record's: all alike)
            assert len(np.unique(rows, axis=0)) < len(rows) / 2
        every = lf._steps_where_unsettled(levels, records, rows, *lf._probit_fits(
            np.log(levels), records, rows, rows.sum(axis=0) / (records * len(rows))))
        np.testing.assert_array_equal(medians[fitted], every[0])
        np.testing.assert_array_equal(betas[fitted], every[1])
        assert np.all(np.isinf(medians[total == 0])) and np.all(medians[total == records * 24] == 0)
