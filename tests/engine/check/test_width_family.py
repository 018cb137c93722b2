"""The fragility family of one height: P(width) at the site monotone by construction, and the
band of its 10 % width against an independent count of the records."""

from __future__ import annotations

import math

import numpy as np
import pytest

from scipy.stats import norm

from audit.engine.check.width_family import (WidthFamily, fit_width_families, fit_width_family,
                                             quoted, width_answer)


def test_the_band_of_the_10pct_width_holds_the_width_a_count_of_records_gives():
    # each record i overturns the block w wide at intensity im exactly when im > k_i·w (its
    # capacity proportional to the width): at the site, record i overturns every width below
    # site/k_i, so the width at which 10 % of the records overturn is, by counting, the 90th
    # percentile of site/k_i
    rng = np.random.default_rng(11)
    records, site, height = 44, 0.6, 1.5
    k = np.exp(rng.normal(math.log(1.2), 0.45, records))
    levels = site * math.sqrt(2.0) ** np.arange(-4, 5)
    widths = height * np.geomspace(0.03, 0.95, 12)
    overturned = levels[None, :, None] > k[:, None, None] * widths[None, None, :]
    answer = width_answer(widths, levels, overturned, site, (0.10, 0.50), height,
                          resamples=200)
    counted_10 = float(np.quantile(site / k, 0.90))
    counted_50 = float(np.median(site / k))
    low, high = answer.bands[0.10]
    assert low <= counted_10 <= high
    low, high = answer.bands[0.50]
    assert low <= counted_50 <= high
    p = np.array([p for _, p in answer.curve])
    assert np.all(np.diff(p) <= 0.0)  # wider is never likelier to overturn


def test_a_width_is_quoted_to_the_precision_its_band_supports():
    assert quoted(0.5634, [0.51, 0.63]) == "0.56 m [0.51–0.63]"
    assert quoted(0.5634, [0.30, 0.90]) == "0.6 m [0.3–0.9]"


def _capacity_outcomes(seed: int, records: int = 44):
    # record i overturns the block w wide at intensity im exactly when im > k_i·w
    rng = np.random.default_rng(seed)
    k = np.exp(rng.normal(math.log(1.2), 0.45, records))
    levels = 0.6 * math.sqrt(2.0) ** np.arange(-4, 5)
    widths = 1.5 * np.geomspace(0.03, 0.95, 12)
    return widths, levels, levels[None, :, None] > k[:, None, None] * widths[None, None, :]


def test_newton_finds_the_maximum_nelder_mead_finds_for_every_resample():
    # the slow path (Nelder–Mead on the likelihood itself) as referee, on the suite and on
    # bootstrap resamples of it: the same maximum to Nelder–Mead's own tolerance
    widths, levels, overturned = _capacity_outcomes(3)
    rng = np.random.default_rng(5)
    resamples = [overturned] + [overturned[rng.integers(0, 44, 44)] for _ in range(12)]
    fast = fit_width_families(widths, levels, np.stack([o.sum(axis=0) for o in resamples]), 44)
    for outcomes, newton in zip(resamples, fast):
        slow = fit_width_family(widths, levels, outcomes)
        assert newton.beta == pytest.approx(slow.beta, rel=1e-5)
        assert newton.slope == pytest.approx(slow.slope, rel=1e-5)
        assert newton.width_for(0.1, 0.6) == pytest.approx(slow.width_for(0.1, 0.6), rel=1e-5)


def test_newton_recovers_the_family_that_made_the_counts():
    # counts of a million records each, drawn as the family's expected counts rounded: the
    # maximum-likelihood family is the one that made them, to the rounding's 1e-6
    truth = WidthFamily(intercept=0.3, slope=1.4, beta=0.45)
    levels = 0.6 * math.sqrt(2.0) ** np.arange(-4, 5)
    widths = 2.0 * np.geomspace(0.03, 0.95, 12)
    records = 1_000_000
    p = norm.cdf((np.log(levels)[:, None] - truth.intercept
                  - truth.slope * np.log(widths)[None, :]) / truth.beta)
    fit, = fit_width_families(widths, levels, np.round(records * p)[None], records)
    assert fit.intercept == pytest.approx(truth.intercept, abs=1e-4)
    assert fit.slope == pytest.approx(truth.slope, rel=1e-4)
    assert fit.beta == pytest.approx(truth.beta, rel=1e-4)


def test_outcomes_a_line_separates_are_left_to_nelder_mead():
    # every record alike: the outcomes flip on one line of (ln im, ln w), the likelihood has
    # no interior maximum (β → 0), and the answer is the slow path's
    levels = 0.6 * math.sqrt(2.0) ** np.arange(-4, 5)
    widths = 1.5 * np.geomspace(0.03, 0.95, 12)
    overturned = np.broadcast_to(levels[None, :, None] > 1.2 * widths[None, None, :],
                                 (44, levels.size, widths.size))
    fit, = fit_width_families(widths, levels, overturned.sum(axis=0)[None], 44)
    assert fit == fit_width_family(widths, levels, overturned,
                                   (float(np.mean(np.log(levels)) - np.mean(np.log(widths))),
                                    0.0, math.log(0.4)))
