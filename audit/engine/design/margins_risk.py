"""The design-level audit at a site: every block's mean annual rate of overturning, from its
exact fragility and the site's hazard curve (:mod:`audit.engine.design.risk`), and the slenderness
each size needs for a risk target, beside the one each guideline accepts.

The risk-targeted exact curve is read on the grid's slendernesses (``--alpha``): per size,
the smallest α above which P in 50 years stays within the target, ln P interpolated linearly
in α at the last crossing (as :func:`~audit.engine.design.required_alpha.interpolated_alpha` does for
shares). A guideline's α (``required_alpha.csv``) gets the P in 50 years of the grid's blocks
of its size, ln P interpolated in α; none outside the grid's α. Give ``--alpha`` finely for a
fine curve.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd

from audit.engine.design.required_alpha import interpolated_alpha
from audit.engine.design.risk import (YEARS, annual_rate_for, block_fragilities, check_same_im,
                               risk_integral)
from audit.engine.design.risk_schema import RISK_GUIDE
from audit.engine.shared.schemas import block_labels
from audit.errors import InputWarning

#: The exact risk-targeted curve's name in ``risk_alpha.csv``.
EXACT_RISK = "exact@risk"
#: Smallest P in 50 years kept in logarithms (a block that never overturns at any stripe).
FLOOR_P = 1e-12

def _keys(frame: pd.DataFrame) -> pd.Series:
    return (frame["alpha_deg"].map("{:.9g}".format) + "|" + frame["size_s"].map("{:.9g}".format)
            + "|" + block_labels(frame))


def margins_risk(run, curve, target_p50: float = 0.01) -> tuple[pd.DataFrame, pd.DataFrame]:
    """``risk.csv`` and ``risk_alpha.csv`` of a design-level audit at the site of ``curve``.

    Parameters
    ----------
    run : audit.engine.design.margins.MarginsRun
        Its ``required_alpha`` gives the guidelines' curves (none when it is None).
    curve : records.hazard.HazardCurve
        Of the run's intensity measure (InputError otherwise).
    target_p50 : float
        The risk target: P of overturning in 50 years [-].
    """
    check_same_im(curve, run.summary["im"], "design-level audit")
    annual_rate_for(target_p50)  # checks the target
    by_block = dict(tuple(run.stripes.groupby(_keys(run.stripes), sort=False)))
    rows, truncated = [], 0
    for key, block in zip(_keys(run.fragility), run.fragility.to_dict("records")):
        fitted, counted = block_fragilities(block, by_block[key])
        with warnings.catch_warnings():  # one warning for the grid, below
            warnings.simplefilter("ignore", InputWarning)
            fit = risk_integral(fitted, curve) if fitted else None
            stripe = risk_integral(counted, curve)
        truncated += bool(fit and fit.truncated)
        nan = math.nan
        rows.append({"alpha_deg": block["alpha_deg"], "size_s": block["size_s"],
                     "width_m": block["width_m"], "height_m": block["height_m"],
                     "im": curve.im_name,
                     "annual_rate_fit": fit.annual_rate if fit else nan,
                     "annual_rate_fit_upper": fit.annual_rate_upper if fit else nan,
                     "p50_fit": fit.p50 if fit else nan,
                     "im_low_90_g": fit.im_range_90_g[0] if fit else nan,
                     "im_high_90_g": fit.im_range_90_g[1] if fit else nan,
                     "annual_rate_stripes": stripe.annual_rate, "p50_stripes": stripe.p50,
                     "truncated": bool(fit and fit.truncated)})
    if truncated:
        warnings.warn(f"hazard: {curve.source}: the curve stops below the fragility's median "
                      f"for {truncated} of {len(rows)} blocks: their λ_ov is a lower bound "
                      "(risk.csv annual_rate_fit_upper bounds it)", InputWarning, stacklevel=2)
    risk = pd.DataFrame(rows, columns=list(RISK_GUIDE["risk.csv"]))
    return risk, _risk_alpha(risk, run.required_alpha, target_p50)


def _grid_p50(risk: pd.DataFrame) -> pd.DataFrame:
    """P in 50 years of the grid's blocks, (α × size): the fit's, the stripes' where no fit."""
    grid = risk[risk["width_m"].isna()]
    p50 = grid["p50_fit"].where(np.isfinite(grid["p50_fit"]), grid["p50_stripes"])
    return grid.assign(p50=p50).pivot_table(index="alpha_deg", columns="size_s", values="p50",
                                            aggfunc="first")


def _risk_alpha(risk, required, target_p50) -> pd.DataFrame:
    grid = _grid_p50(risk)
    alphas = grid.index.to_numpy(dtype=float)
    ln_p = np.log(np.clip(grid.to_numpy(dtype=float), FLOOR_P, None))  # (α, size)
    rows = []
    for s, size in enumerate(grid.columns):
        alpha = (interpolated_alpha(alphas, ln_p[:, s], math.log(target_p50))
                 if alphas.size > 1 else math.nan)
        rows.append({"procedure": EXACT_RISK, "size_s": float(size), "required_alpha_deg": alpha,
                     "p50": _p50_at(alphas, ln_p[:, s], alpha)})
    if required is not None:
        sizes = grid.columns.to_numpy(dtype=float)
        for row in required[~required["procedure"].str.startswith("exact@")].itertuples():
            s = np.flatnonzero(np.isclose(sizes, row.size_s))
            p50 = _p50_at(alphas, ln_p[:, s[0]], row.required_alpha_deg) if s.size else math.nan
            rows.append({"procedure": row.procedure, "size_s": float(row.size_s),
                         "required_alpha_deg": row.required_alpha_deg, "p50": p50})
    return pd.DataFrame(rows, columns=list(RISK_GUIDE["risk_alpha.csv"]))


def _p50_at(alphas, ln_p, alpha) -> float:
    """P in 50 years at ``alpha``, ln P interpolated on the grid; NaN outside it."""
    if not (math.isfinite(alpha) and alphas.size and alphas[0] <= alpha <= alphas[-1]):
        return math.nan
    return float(np.exp(np.interp(alpha, alphas, ln_p)))


def hazard_summary(curve, target_p50: float) -> dict:
    """What ``summary.json`` says of the site's hazard.

    Parameters
    ----------
    curve : records.hazard.HazardCurve
        The site's hazard curve.
    target_p50 : float
        The target P of overturning in 50 years [-].
    """
    return {"source": curve.source, "im": curve.im_name, "site": curve.site,
            "target_p50": target_p50, "years": YEARS,
            "target_annual_rate": annual_rate_for(target_p50)}


def hazard_table(curve) -> pd.DataFrame:
    """``hazard.csv``: the curve as read (the page draws it from the saved files).

    Parameters
    ----------
    curve : records.hazard.HazardCurve
        The site's hazard curve.
    """
    return pd.DataFrame({"im_g": curve.im_g, "annual_rate": curve.annual_rate})


__all__ = ["margins_risk", "hazard_summary", "hazard_table", "EXACT_RISK"]
