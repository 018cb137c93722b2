"""P at the site (#59): the fixed stripe lattice, the exact binomial bands against their
closed forms, the headline rule, a fragility that is the object's (not the site's), and P that
rises with the site's intensity."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import binom, binomtest

import audit
from audit.engine.check.pipeline import check_levels, fitted_stripes
from audit.engine.design.site_probability import (clopper_pearson, one_sided_bound,
                                                  site_probability)
from audit.engine.shared.defaults import DEFAULT_STRIPES
from audit.engine.shared.lattice import on_lattice, stripe_lattice
from tests.engine.check.pulses import eight_pulses


def test_the_lattice_is_two_to_the_quarter_powers_from_a_sixteenth_to_5_66_g():
    levels = stripe_lattice()
    assert levels.size == DEFAULT_STRIPES == 27
    assert levels[0] == 0.0625 and levels[4] == 0.125 and levels[16] == 1.0
    assert levels[-1] == pytest.approx(4.0 * math.sqrt(2.0), rel=1e-15)
    np.testing.assert_allclose(levels[1:] / levels[:-1], 2.0 ** 0.25, rtol=1e-14)
    # a check solves every other level (√2 apart) and the site's own
    every_other = stripe_lattice(2)
    np.testing.assert_array_equal(every_other, levels[::2])
    np.testing.assert_allclose(every_other[1:] / every_other[:-1], math.sqrt(2.0), rtol=1e-14)
    levels = check_levels(0.6)
    assert levels.size == 15 and 0.6 in levels.tolist() and np.all(np.diff(levels) > 0)
    np.testing.assert_array_equal(levels[fitted_stripes(levels)], every_other)
    # a site on the lattice adds no stripe; one on an odd level is not fitted
    np.testing.assert_array_equal(check_levels(0.5), every_other)
    odd = 2.0 ** (-1 / 4)
    assert on_lattice([odd]).all() and not on_lattice([odd], 2).any()
    assert check_levels(odd).size == 15


@pytest.mark.parametrize("k, n", [(0, 44), (1, 44), (7, 44), (22, 44), (43, 44), (44, 44),
                                  (3, 8)])
def test_clopper_pearson_solves_the_binomial_tails_and_agrees_with_scipy(k, n):
    low, high = clopper_pearson(k, n, 0.90)
    # the exact band's ends: P(X ≥ k | low) = 5 %, P(X ≤ k | high) = 5 % (0 and 1 at the ends)
    if k > 0:
        assert binom.sf(k - 1, n, low) == pytest.approx(0.05, rel=1e-8)
    else:
        assert low == 0.0
    if k < n:
        assert binom.cdf(k, n, high) == pytest.approx(0.05, rel=1e-8)
    else:
        assert high == 1.0
    ci = binomtest(k, n).proportion_ci(confidence_level=0.90, method="exact")
    assert (low, high) == pytest.approx((ci.low, ci.high), abs=1e-12)


def test_the_one_sided_bound_is_the_closed_form_and_the_exact_band_at_zero():
    for n in (8, 44, 100):
        bound = one_sided_bound(n)
        assert bound == pytest.approx(1.0 - 0.05 ** (1.0 / n), rel=1e-14)
        assert binom.pmf(0, n, bound) == pytest.approx(0.05, rel=1e-12)  # (1 − x)^n = 5 %
        assert clopper_pearson(0, n, 0.90)[1] == pytest.approx(bound, rel=1e-10)
    assert one_sided_bound(44) == pytest.approx(0.0658, abs=5e-5)  # the "< 6.6 %" of 44 records


def test_the_headline_is_the_model_unless_the_records_at_the_site_reject_it():
    inside = site_probability(0.10, (0.05, 0.16), 5, 44)
    assert inside.estimator == "lognormal" and inside.p == 0.10 and inside.band == (0.05, 0.16)
    assert inside.words() == "10 % [5–16 %]"
    # a count outside the model's band is not a rejection: 1 of 44 where the model says 6.9 %
    # happens with probability 0.19, so the exact binomial test keeps the lognormal
    near = site_probability(0.0686, (0.024, 0.1176), 1, 44)
    assert binom.cdf(1, 44, 0.0686) == pytest.approx(0.19, abs=0.01)
    assert near.estimator == "lognormal" and near.p == 0.0686
    # 43 of 44 where the model says 80 %: P(X ≥ 43 | 0.8) = 0.1 %, rejected
    rejected = site_probability(0.80, (0.70, 0.88), 43, 44)
    assert binom.sf(42, 44, 0.80) < 0.005
    assert rejected.estimator == "count" and rejected.p == pytest.approx(43 / 44)
    assert rejected.band == clopper_pearson(43, 44)
    assert rejected.model_p == 0.80 and "reject" in rejected.reason
    # the issue's roof: 90.3 % against 43/44 is inside the count's band, kept
    assert site_probability(0.903, (0.839, 0.966), 43, 44).estimator == "lognormal"
    none = site_probability(1e-8, (0.0, 2e-7), 0, 44)  # "0 % [0–0 %]" before
    assert none.bound == {"side": "upper", "value": one_sided_bound(44), "confidence": 0.95}
    assert none.words() == "< 6.6 %" and none.band[1] == pytest.approx(one_sided_bound(44))
    every = site_probability(0.99999, (0.9999, 1.0), 44, 44)
    assert every.bound["side"] == "lower" and every.words() == "> 93 %"
    assert site_probability(None, None, 3, 44).estimator == "count"


@pytest.fixture(scope="module")
def two_sites():
    """One object checked at two sites (PGA 0.6 g and 0.4 g)."""
    return [audit.check(["0.6x1.8"], site, procedures=["fema356"], records=eight_pulses(),
                        im="pga", solver=audit.Solver(free_motion_s=5.0)
                        ).document["objects"][0]["exact"]
            for site in ((1.5, 0.9), (1.0, 0.6))]


def test_two_sites_give_one_fragility_and_p_rises_with_the_site(two_sites):
    high, low = two_sites
    assert high["site_im_g"] == pytest.approx(0.6) and low["site_im_g"] == pytest.approx(0.4)
    assert high["median_g"] is not None
    assert high["median_g"] == pytest.approx(low["median_g"], rel=1e-6)
    assert high["beta"] == pytest.approx(low["beta"], rel=1e-6)
    # the lattice's counts are the same records at the same levels
    fitted_high = np.asarray(high["stripes"]["overturned"])[high["stripes"]["fitted"]]
    fitted_low = np.asarray(low["stripes"]["overturned"])[low["stripes"]["fitted"]]
    np.testing.assert_array_equal(fitted_high, fitted_low)
    assert low["p_at_site"]["model"]["p"] <= high["p_at_site"]["model"]["p"]
    for exact in two_sites:
        at = exact["p_at_site"]
        low_end, high_end = at["count"]["band"]
        assert low_end <= exact["p_overturn_at_site"] <= high_end  # the records don't reject it
        assert at["count"]["records"] == 8


def test_the_roof_cabinet_of_the_issue_has_a_band_that_holds_its_43_of_44():
    """#59: a 0.6 × 1.8 m cabinet on the roof of a 10-storey shear building (T1 = 1 s, ζ = 5 %)
    at S_X1 = 0.6 g; 43 of the 44 far-field records overturn it at the site's intensity. The
    lognormal fitted on stripes around the site said 90 % [84–97 %], below the count."""
    exact = audit.check(["0.6x1.8"], (1.0, 0.6), procedures=["fema356"], records="p695-far-field",
                        floor=audit.Floor(1.0, audit.Building(1.0, "shear:10"))
                        ).document["objects"][0]["exact"]
    count = exact["p_at_site"]["count"]
    assert (count["overturned"], count["records"]) == (43, 44)
    low, high = exact["p_band"]
    assert low <= 43 / 44 <= high
    assert count["band"][0] <= exact["p_overturn_at_site"] <= count["band"][1]
    assert exact["p_at_site"]["bound"] is None
