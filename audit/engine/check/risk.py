"""``audit check`` with the site's hazard curve: each object's annual rate of overturning, the
risk of the object as each guideline would size it, and the exact width for a risk target.

The object's fragility is the one the check fitted on the fixed lattice's stripes
(:mod:`audit.engine.shared.lattice`, 0.0625–5.66 g; not the site's own stripe, so the integrand
is the object's fragility whatever the site); outside them the risk integral (:func:`~audit.engine.design.risk.risk_integral`) reads the
fitted lognormal, and the counted stripe shares beside it show what the fit adds. A family
member (the object at another width) gets the same treatment from its own outcomes at the
stripes; where no lognormal fits (no stripe overturns it, or every record at every stripe does)
its counted shares stand in. How much of the rate comes from intensities outside the stripes,
where the fit is extrapolated, is reported beside it (:func:`shares_outside`).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from audit.engine.design.lognormal_fit import lognormal_fits
from audit.engine.design.margins_risk import hazard_summary
from audit.engine.design.risk import LognormalFragility, StripeFragility, risk_integral
from audit.errors import InputWarning


def fragilities(overturned, levels):
    """The fitted (None where no lognormal fits) and counted fragility of one block from its
    outcomes shaped (record, stripe).

    Parameters
    ----------
    overturned : numpy.ndarray of bool
        Whether each record overturns the block at each stripe, shaped (record, stripe).
    levels : array_like of float
        The stripes' intensities [g].

    Returns
    -------
    tuple of (LognormalFragility or None, StripeFragility)
    """
    levels = np.asarray(levels, dtype=float)
    counted = StripeFragility(levels, np.asarray(overturned, dtype=float).mean(axis=0))
    (median,), (beta,) = lognormal_fits(levels, overturned.shape[0],
                                        np.asarray(overturned).sum(axis=0)[None, :])
    fitted = (LognormalFragility(float(median), float(beta))
              if math.isfinite(median) and median > 0 and math.isfinite(beta) and beta > 0
              else None)
    return fitted, counted


def quiet_risk(fragility, curve):
    """:func:`~audit.engine.design.risk.risk_integral` without its truncation warning (the caller says
    it once, for all the blocks it concerns).

    Parameters
    ----------
    fragility : LognormalFragility or StripeFragility
        The block's fragility.
    curve : records.hazard.HazardCurve
        The site's hazard curve.

    Returns
    -------
    OverturningRisk
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputWarning)
        return risk_integral(fragility, curve)


def p50_of_blocks(overturned, levels, curve) -> np.ndarray:
    """P of overturning in 50 years of each block, outcomes shaped (record, stripe, block): the
    fitted fragility's, the counted one's where none fits.

    Parameters
    ----------
    overturned : numpy.ndarray of bool
        Outcomes shaped (record, stripe, block).
    levels : array_like of float
        The stripes' intensities [g].
    curve : records.hazard.HazardCurve
        The site's hazard curve.
    """
    out = np.empty(overturned.shape[2])
    for b in range(out.size):
        fitted, counted = fragilities(overturned[:, :, b], levels)
        out[b] = quiet_risk(fitted or counted, curve).p50
    return out


def shares_outside(risk, low_g: float, high_g: float) -> tuple[float, float]:
    """Shares of λ_ov from intensities below ``low_g`` and above ``high_g`` (the stripes'
    range, outside which a fitted fragility is extrapolated), the tail above the curve's last
    level counted above.

    Parameters
    ----------
    risk : OverturningRisk
        The block's risk, with its deaggregation.
    low_g, high_g : float
        The lowest and highest stripe [g].
    """
    if not risk.annual_rate > 0:
        return 0.0, 0.0
    x, density = np.log(risk.density_im_g), risk.density
    order = np.argsort(x, kind="stable")
    x, density = x[order], density[order]

    def integral(mask):
        return float(np.trapezoid(np.where(mask, density, 0.0), x))

    tail = float(risk.deaggregation["annual_rate"].iloc[-1])
    below = integral(x <= math.log(low_g))
    above = integral(x >= math.log(high_g)) + tail
    return below / risk.annual_rate, above / risk.annual_rate


def object_risk(fitted, counted, curve, target_p50: float, width_m: float | None) -> dict:
    """The ``risk`` entry of ``check.json`` for one object: its fitted fragility (None where
    none fits) and its counted one; ``width_m`` is the exact width for the target (None where
    no width up to 0.95 × the height meets it).

    Parameters
    ----------
    fitted : LognormalFragility or None
        The lognormal fitted to the stripes, None where none fits.
    counted : StripeFragility
        The fractions overturning at the stripes.
    curve : records.hazard.HazardCurve
        The site's hazard curve.
    target_p50 : float
        The target P of overturning in 50 years [-].
    width_m : float or None
        The exact width meeting the target [m].
    """
    risk = quiet_risk(fitted or counted, curve)
    by_stripes = quiet_risk(counted, curve)
    below, above = shares_outside(risk, float(counted.levels_g[0]), float(counted.levels_g[-1]))
    return {**risk.as_dict(), "fragility": risk.fragility,
            "annual_rate_upper": risk.annual_rate_upper,
            "return_period_years": 1.0 / risk.annual_rate if risk.annual_rate > 0 else None,
            "im_range_90_g": [v if math.isfinite(v) else None for v in risk.im_range_90_g],
            "truncated": risk.truncated, "p_at_first_level": risk.p_at_first_level,
            "share_below_stripes": below, "share_above_stripes": above,
            "annual_rate_stripes": by_stripes.annual_rate, "p50_stripes": by_stripes.p50,
            "target_p50": target_p50, "meets_target": bool(risk.p50 <= target_p50),
            "required_width_m": width_m}


def hazard_document(curve, target_p50: float) -> dict:
    """What ``check.json`` says of the site's hazard curve: what a margins run's summary says
    (:func:`~audit.engine.design.margins_risk.hazard_summary`) and the curve itself, for the
    page.

    Parameters
    ----------
    curve : records.hazard.HazardCurve
        The site's hazard curve.
    target_p50 : float
        The target P of overturning in 50 years [-].
    """
    return {**hazard_summary(curve, target_p50),
            "curve": {"im_g": np.asarray(curve.im_g, dtype=float).tolist(),
                      "annual_rate": np.asarray(curve.annual_rate, dtype=float).tolist()}}


__all__ = ["fragilities", "p50_of_blocks", "object_risk", "hazard_document", "quiet_risk",
           "shares_outside"]
