"""The fragility family of one height: P(width) at the site monotone by construction, and the
band of its 10 % width against an independent count of the records."""

from __future__ import annotations

import math

import numpy as np

from audit.engine.check.width_family import quoted, width_answer


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
