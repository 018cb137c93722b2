"""The risk integral against the Cornell et al. (2002) closed form, on power-law hazard curves
written in OpenQuake's export layout and read back; the deaggregation, the ends of a curve, and
the intensity measures that must agree."""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate, stats

from audit.engine.design.risk import (LognormalFragility, StripeFragility, annual_rate_for,
                               risk_integral)
from audit.errors import InputError, InputWarning
from records.hazard import read_openquake_curve

YEARS = 50.0


def _power_law_export(path, k0, k, levels, imt="SA(1.0)"):
    """λ(s) = k0 s^−k written as the engine writes it: poe = 1 − exp(−λ T) in T = 50 years."""
    poes = -np.expm1(-YEARS * k0 * levels ** -k)
    meta = f"generated_by='test', kind='mean', investigation_time={YEARS}, imt='{imt}'"
    lines = ["#" + "," * (levels.size + 2) + f'"{meta}"',
             "lon,lat,depth," + ",".join(f"poe-{x:.7f}" for x in levels),
             "0.00000,-0.30000,0.00000," + ",".join(f"{p:.6E}" for p in poes)]
    path.write_text("\n".join(lines) + "\n")
    return path


def _cornell(k0, k, theta, beta):
    """Cornell et al. (2002), Eq. 11 with a lognormal fragility: k0 θ^−k exp(k² β² / 2)."""
    return k0 * theta ** -k * math.exp(0.5 * k * k * beta * beta)


@pytest.mark.parametrize("k", [2.0, 3.0, 4.0])
@pytest.mark.parametrize("beta", [0.2, 0.4, 0.6])
def test_cornell_closed_form(tmp_path, k, beta):
    theta = 0.5
    # the levels span the integrand (a Gaussian in ln s about ln θ − kβ², sd β) and more;
    # k0 keeps the rate at the lowest level below 0.05/yr, so poe stays clear of 1
    low = theta * math.exp(-k * beta ** 2 - 7 * beta)
    levels = np.geomspace(low, theta * math.exp(7 * beta + 2), 40)
    k0 = 0.05 * low ** k
    curve = read_openquake_curve(_power_law_export(tmp_path / "oq.csv", k0, k, levels))
    risk = risk_integral(LognormalFragility(theta, beta), curve)
    expected = _cornell(k0, k, theta, beta)
    assert risk.annual_rate == pytest.approx(expected, rel=1e-3)  # the issue asks 1 %
    assert risk.p50 == pytest.approx(1 - math.exp(-50 * expected), rel=0.01)
    assert not risk.truncated


def test_central_range_of_the_deaggregation(tmp_path):
    # an independent slow path: the density P(s) k λ(s) in ln s integrated by quad, and its 5 %
    # and 95 % points found by root finding
    k, beta, theta = 3.0, 0.4, 0.5
    levels = np.geomspace(0.01, 20.0, 30)
    k0 = 1e-5
    curve = read_openquake_curve(_power_law_export(tmp_path / "oq.csv", k0, k, levels))
    risk = risk_integral(LognormalFragility(theta, beta), curve)

    def density(x):
        return stats.norm.cdf((x - math.log(theta)) / beta) * k * k0 * math.exp(-k * x)

    total = integrate.quad(density, -30, 30, points=[math.log(theta)])[0]
    points = []
    for share in (0.05, 0.95):
        points.append(math.exp(_root(lambda x: integrate.quad(density, -30, x)[0]
                                     - share * total, math.log(1e-3), math.log(50.0))))
    assert risk.im_range_90_g[0] == pytest.approx(points[0], rel=0.01)
    assert risk.im_range_90_g[1] == pytest.approx(points[1], rel=0.01)
    assert risk.deaggregation["share"].sum() == pytest.approx(1.0, rel=1e-12)
    assert risk.deaggregation["annual_rate"].sum() == pytest.approx(risk.annual_rate, rel=1e-12)


def _root(function, low, high):
    from scipy.optimize import brentq
    return brentq(function, low, high, xtol=1e-10)


def test_stripe_shares_of_a_lognormal_give_its_rate(tmp_path):
    # the counted fragility sampled finely from the lognormal: the same λ_ov within 1 %
    k, beta, theta = 2.5, 0.45, 0.4
    levels = np.geomspace(0.01, 10.0, 30)
    k0 = 1e-4
    curve = read_openquake_curve(_power_law_export(tmp_path / "oq.csv", k0, k, levels))
    stripes = np.geomspace(0.01, 10.0, 120)
    counted = StripeFragility(stripes, stats.norm.cdf(np.log(stripes / theta) / beta))
    assert risk_integral(counted, curve).annual_rate == pytest.approx(
        _cornell(k0, k, theta, beta), rel=0.01)


def test_a_curve_that_stops_below_the_median_warns_with_its_bound(tmp_path):
    k, beta, theta = 3.0, 0.4, 2.0
    levels = np.geomspace(0.05, 1.0, 15)  # stops at half the median
    k0 = 1e-4
    curve = read_openquake_curve(_power_law_export(tmp_path / "oq.csv", k0, k, levels))
    fragility = LognormalFragility(theta, beta)
    with pytest.warns(InputWarning, match="stops at 1 g, below the fragility's median 2 g"):
        risk = risk_integral(fragility, curve)
    assert risk.truncated
    # the whole-curve rate lies between what is counted and the bound: λ(1 g) k0 above 1 g
    # counted at P(1 g) at least, at P = 1 at most
    exact = _cornell(k0, k, theta, beta)
    assert risk.annual_rate <= exact <= risk.annual_rate_upper
    assert risk.annual_rate_upper - risk.annual_rate == pytest.approx(
        k0 * (1 - fragility.probability(1.0)), rel=1e-4)
    assert math.isinf(risk.im_range_90_g[1])


def test_exact_zeros_bound_the_tail(tmp_path):
    # rates 0 from 1.6 g up: the exceedances of the last positive level lie below 1.6 g
    levels = np.array([0.1, 0.2, 0.4, 0.8, 1.6, 3.2])
    poes = [0.5, 0.2, 0.05, 0.01, 0.0, 0.0]
    meta = "investigation_time=50.0, imt='PGA'"
    text = ("#,,,,,,,,\"" + meta + "\"\nlon,lat,depth," + ",".join(f"poe-{x}" for x in levels)
            + "\n0,0,0," + ",".join(map(str, poes)) + "\n")
    (tmp_path / "oq.csv").write_text(text)
    curve = read_openquake_curve(tmp_path / "oq.csv")
    fragility = LognormalFragility(0.5, 0.4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # 0.8 g is above the median: no warning
        risk = risk_integral(fragility, curve)
    top_rate = -math.log(1 - 0.01) / 50
    assert risk.annual_rate_upper - risk.annual_rate == pytest.approx(
        top_rate * (fragility.probability(1.6) - fragility.probability(0.8)), rel=1e-9)
    assert risk.im_range_90_g[1] <= 1.6


def test_intensity_measures_must_agree(tmp_path):
    levels = np.geomspace(0.05, 3.0, 10)
    curve = read_openquake_curve(_power_law_export(tmp_path / "oq.csv", 1e-4, 2.0, levels))
    with pytest.raises(InputError, match=r"imt: the curve is of SA\(1.0\) .* fragility is of pga"):
        risk_integral(LognormalFragility(0.5, 0.4, im="pga"), curve)
    with pytest.raises(InputError, match="sa:0.3"):
        risk_integral(LognormalFragility(0.5, 0.4, im="sa:0.3"), curve)
    assert risk_integral(LognormalFragility(0.5, 0.4, im="sa:1.0"), curve).im == "SA(1.0)"


def test_risk_target_rate():
    # 1 % in 50 years: λ = −ln(0.99)/50 = 2.0101e-4 per year
    assert annual_rate_for(0.01) == pytest.approx(2.0101e-4, rel=1e-4)


def test_real_demo_curve_against_a_slow_path(hazard_dir):
    # the OpenQuake demo's SA(1.0) at (0.0, −0.3) through the API, against quad on the
    # log-log interpolant differentiated numerically, plus its tail at P(3 g)
    import audit
    path = hazard_dir / "openquake-demo/hazard_curve-mean-SA(1.0)_2.csv"
    risk = audit.risk((0.9, 0.35), path, site=(0.0, -0.3))
    curve = audit.read_hazard(path, site=(0.0, -0.3))
    ln_s, ln_rate = np.log(curve.im_g), np.log(curve.annual_rate)

    def rate(x):
        return math.exp(np.interp(x, ln_s, ln_rate))

    def density(x, h=1e-6):
        return stats.norm.cdf(math.log(math.exp(x) / 0.9) / 0.35) * (
            rate(x - h) - rate(x + h)) / (2 * h)

    slow = sum(integrate.quad(density, a + 1e-9, b - 1e-9, epsabs=0, epsrel=1e-10)[0]
               for a, b in zip(ln_s[:-1], ln_s[1:]))
    slow += curve.annual_rate[-1] * stats.norm.cdf(math.log(3.0 / 0.9) / 0.35)
    assert risk.annual_rate == pytest.approx(slow, rel=1e-4)
    assert risk.im == "SA(1.0)" and "hazard_curve-mean-SA(1.0)_2.csv" in risk.hazard_source


def test_the_figure_of_one_object(tmp_path):
    from reports.risk_figure import risk_figure
    levels = np.geomspace(0.01, 20.0, 30)
    curve = read_openquake_curve(_power_law_export(tmp_path / "oq.csv", 1e-5, 3.0, levels))
    fragility = LognormalFragility(0.5, 0.4)
    risk = risk_integral(fragility, curve)
    spec = risk_figure(curve, fragility, risk)
    hazard, fitted, deaggregation = spec["data"]
    assert np.allclose(hazard["y"], curve.annual_rate)
    assert (hazard["yaxis"], fitted["yaxis"], deaggregation["yaxis"]) == ("y", "y2", "y3")
    # the drawn shares per unit ln im integrate to the share below the curve's top
    x = np.log(deaggregation["x"])
    drawn = np.sum(0.5 * (deaggregation["y"][1:] + deaggregation["y"][:-1]) * np.diff(x))
    assert drawn == pytest.approx(1 - risk.deaggregation["share"].iloc[-1], rel=1e-6)
    band = spec["layout"]["shapes"][0]
    assert (band["x0"], band["x1"]) == pytest.approx(risk.im_range_90_g)


def test_the_api_names_a_bad_fragility(tmp_path):
    import audit
    levels = np.geomspace(0.05, 3.0, 10)
    path = _power_law_export(tmp_path / "oq.csv", 1e-4, 2.0, levels)
    for bad in ("x", (0.5,), (0.5, -0.1), (float("nan"), 0.3)):
        with pytest.raises(InputError, match="fragility"):
            audit.risk(bad, path)
    row = {"median": 0.5, "beta": 0.4, "im": "pga"}  # a fragility.csv row of another IM
    with pytest.raises(InputError, match="imt"):
        audit.risk(row, path)
    assert audit.risk((0.5, 0.4), path).annual_rate == pytest.approx(
        _cornell(1e-4, 2.0, 0.5, 0.4), rel=1e-3)
