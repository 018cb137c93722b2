"""The risk integral against the Cornell et al. (2002) closed form, on power-law hazard curves
written in OpenQuake's export layout and read back; the deaggregation, the ends of a curve, and
the intensity measures that must agree."""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate, stats

from audit.engine.risk import (LognormalFragility, StripeFragility, annual_rate_for,
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
