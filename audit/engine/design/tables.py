"""The tables of the design-level audit (:mod:`audit.engine.design.margins`) from its records' parts:
``stripes.csv`` (every record × stripe × block), ``fragility.csv`` (each block's exact fit, its
CMR and bootstrap bands) and ``capacity.csv`` (where each procedure draws its line against it).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from audit.engine.shared.blocks import BlockList
from audit.engine.design.fragility import overturning_pattern
from audit.engine.design.bootstrap import bootstrap_lognormal
from audit.engine.design.lognormal_fit import fit_lognormal, lognormal_estimate
from audit.engine.design.site_probability import MODEL, site_probability


#: How a procedure meets the stripes, by whether it reads the records (the report says it).
READINGS = {True: "each record scaled to the level: a fragility, the share of records for "
                  "which it predicts overturning",
            False: "the site's design spectrum scaled to the level: a step, one answer for "
                   "every record"}


def reading(procedure, entries) -> str:
    """Which reading of the stripes a procedure gets, over the records it can evaluate.

    Parameters
    ----------
    procedure : procedures.base.Procedure
        The procedure.
    entries : iterable of records.RecordEntry
        The records.
    """
    readings = {procedure.reads_record(e) for e in entries
                if procedure.unmet_requirements(e) is None}
    if not readings:
        return "none: it can evaluate no record of the suite"
    return "; ".join(READINGS[reading] for reading in sorted(readings, reverse=True))


def _block_columns(blocks: BlockList, index) -> dict:
    return {"alpha_deg": blocks.alpha_deg[index], "size_s": blocks.size_s[index],
            "width_m": blocks.width_m[index], "height_m": blocks.height_m[index]}


def site_factor(suite, record_id: str) -> float:
    """The factor by which the suite's scaling to a site (FEMA P695) scaled a record, 1 where
    it was not scaled.

    Parameters
    ----------
    suite : records.RecordSuite
        The records, with their scaling.
    record_id : str
        The record.
    """
    scaled = (suite.scaling or {}).get("records", {}).get(record_id)
    return float(scaled["scale_factor"]) if scaled else 1.0


def stripe_rows(run, site_factors) -> pd.DataFrame:
    """One row per record × stripe × block (``stripes.csv``).

    Parameters
    ----------
    run : audit.engine.design.margins.MarginsStripes
        Every record's part of the audit: its records, stripes, blocks and intensity measure
        (``run.settings``), each record's intensity [unit of the measure], and the exact and
        predicted overturning, shaped (record, stripe, block).
    site_factors : numpy.ndarray
        Each record's scale factor to the design site [-], 1 where none.
    """
    entries, blocks, im = run.entries, run.settings.blocks, run.settings.im
    levels, intensities = np.asarray(run.settings.levels), run.intensities
    exact_over, exact_theta = run.exact_overturned, run.exact_theta_rad
    record, level, block = np.indices(exact_over.shape).reshape(3, -1)
    frame = pd.DataFrame({
        "record": np.array([e.id for e in entries])[record], **_block_columns(blocks, block),
        "im": im.name, "im_level": levels[level],
        "scale_factor": levels[level] / intensities[record] * site_factors[record],
        "site_factor": site_factors[record],
        "exact_overturned": exact_over.reshape(-1), "exact_theta_rad": exact_theta.reshape(-1)})
    for name, over in run.predicted.items():
        frame[f"{name}_overturns"] = over.reshape(-1)
    return frame


def exact_fit(levels, overturned, bands: bool = True):
    """The lognormal fragility of one block's exact outcomes (record, stripe), None where the
    counts fix no median (no overturning, or every record at every stripe); without ``bands``
    only its θ and β (:class:`~audit.engine.design.lognormal_fit.LognormalEstimate`).

    Parameters
    ----------
    levels : numpy.ndarray
        The stripes (e.g. [g]).
    overturned : numpy.ndarray of bool
        The block's outcomes, shaped (record, stripe).
    bands : bool
        Whether to compute the confidence bands.
    """
    fit = fit_lognormal if bands else lognormal_estimate
    try:
        return fit(levels, np.full(levels.size, overturned.shape[0]), overturned.sum(axis=0))
    except ValueError:
        return None


def collapse_margin(fit, levels, mce) -> tuple[float, str]:
    """The collapse margin ratio and how far it is known: a median beyond the stripes is an
    extrapolation of the fit, so the CMR is only bounded by the outermost stripe there.

    Parameters
    ----------
    fit : LognormalFit or None
        The block's fit.
    levels : numpy.ndarray
        The stripes, ascending (e.g. [g]).
    mce : float or None
        The MCE intensity, in the same unit.

    Returns
    -------
    cmr : float
        The collapse margin ratio median/MCE [-] (NaN without a fit or an MCE).
    bound : str
        ``""``, ``"at least"`` or ``"at most"``.
    """
    if fit is None or not mce:
        return math.nan, ""
    if fit.median > levels[-1]:
        return levels[-1] / mce, "at least"
    if fit.median < levels[0]:
        return levels[0] / mce, "at most"
    return fit.median / mce, ""


def _percentile_band(values, confidence: float = 0.90) -> tuple[float, float]:
    """The two-sided percentile band of resampled values that may be ±inf (a resample with no
    overturning has θ = inf): read at the order statistics, without interpolating."""
    tail = 50.0 * (1.0 - confidence)
    return (float(np.percentile(values, tail, method="lower")),
            float(np.percentile(values, 100.0 - tail, method="higher")))


def fragility_rows(levels, blocks, im, exact_over, mce):
    """``fragility.csv`` and, per block, its lognormal fit and its bootstrap over records
    (records are reused across the stripes, so the binomial band is too narrow).

    Parameters
    ----------
    levels : numpy.ndarray
        The stripes (e.g. [g]).
    blocks : BlockList
        The blocks.
    im : IntensityMeasure
        The intensity measure.
    exact_over : numpy.ndarray of bool or float
        Exact outcomes, shaped (record, stripe, block) (or an atlas's per-record
        probabilities: no islands are counted then).
    mce : float or None
        The MCE intensity, in the unit of the stripes.

    Returns
    -------
    rows : pandas.DataFrame
        ``fragility.csv``.
    fits : list of LognormalFit or None
        Each block's fit.
    boots : list of BootstrapFits or None
        Each block's bootstrap over records.
    """
    rows, fits, boots = [], [], []
    n_records = exact_over.shape[0]
    nan = math.nan
    # islands are read from whole outcomes; an atlas's between its nodes are probabilities
    whole = exact_over.dtype == bool
    for b in range(len(blocks)):
        pattern = overturning_pattern(exact_over[:, :, b]) if whole else None
        fit = exact_fit(levels, exact_over[:, :, b])
        boot = bootstrap_lognormal(levels, exact_over[:, :, b]) if fit else None
        fits.append(fit)
        boots.append(boot)
        cmr, bound = collapse_margin(fit, levels, mce)
        median_band = _percentile_band(boot.medians) if boot else (nan, nan)
        beta_band = _percentile_band(boot.betas[np.isfinite(boot.betas)]) \
            if boot and np.isfinite(boot.betas).any() else (nan, nan)
        rows.append({
            **_block_columns(blocks, b), "im": im.name, "records": n_records,
            "stripes": levels.size, "median": fit.median if fit else nan,
            "beta": fit.beta if fit else nan,
            "median_low": fit.median_band[0] if fit else nan,
            "median_high": fit.median_band[1] if fit else nan,
            "beta_low": fit.beta_band[0] if fit else nan,
            "beta_high": fit.beta_band[1] if fit else nan,
            "median_boot_low": median_band[0], "median_boot_high": median_band[1],
            "beta_boot_low": beta_band[0], "beta_boot_high": beta_band[1],
            "median_extrapolated": fit is not None and not levels[0] <= fit.median <= levels[-1],
            "cmr": cmr, "cmr_bound": bound,
            "cmr_boot_low": median_band[0] / mce if mce else nan,
            "cmr_boot_high": median_band[1] / mce if mce else nan,
            "records_with_islands": int(pattern.islands.sum()) if whole else nan,
            "island_share": float(pattern.islands.mean()) if whole else nan})
    return pd.DataFrame(rows), fits, boots


def capacity_rows(procedures, run, fits, boots, lines) -> pd.DataFrame:
    """One row per procedure × block: where the procedure draws its line against the exact
    fragility (``capacity.csv``).

    Parameters
    ----------
    procedures : list of procedures.Procedure
    run : audit.engine.design.margins.MarginsStripes
        The stripes and blocks (``run.settings``) and the exact overturning.
    fits, boots : list
        Per block, the exact lognormal fit (None where none) and its bootstrap.
    lines : dict
        Procedure name → its line for each block [unit of the measure]
        (:func:`~audit.engine.design.guideline_lines.guideline_lines`).
    """
    levels, blocks = np.asarray(run.settings.levels), run.settings.blocks
    rows = []
    exact_fraction = run.exact_overturned.mean(axis=0)  # (stripe, block)
    for proc in procedures:
        for b in range(len(blocks)):
            line = float(lines[proc.name][b])
            fit = fits[b]
            known = fit is not None and math.isfinite(line)
            nearest = int(np.argmin(np.abs(np.log(levels / line)))) if math.isfinite(line) \
                else None
            band = boots[b].probability_band(line) if known else (math.nan, math.nan)
            achieved = (_achieved(fit, boots[b], levels[nearest], line,
                                  run.exact_overturned[:, nearest, b]) if nearest is not None
                        else {name: math.nan for name in ACHIEVED_COLUMNS})
            rows.append({
                "procedure": proc.name, **_block_columns(blocks, b), "guideline_im": line,
                "ratio_to_exact_median": line / fit.median if known else math.nan,
                "achieved_p_fit": float(fit.probability(line)) if known else math.nan,
                "achieved_p_boot_low": float(band[0]), "achieved_p_boot_high": float(band[1]),
                "achieved_p_stripe": float(exact_fraction[nearest, b])
                if nearest is not None else math.nan, **achieved})
    return pd.DataFrame(rows)


#: The achieved P as the headline rule gives it (:func:`_achieved`).
ACHIEVED_COLUMNS = ("achieved_p", "achieved_p_low", "achieved_p_high", "achieved_p_from")


def _achieved(fit, boot, stripe: float, line: float, overturned) -> dict:
    """The achieved P at a guideline's line by the rule of P at a site
    (:mod:`audit.engine.design.site_probability`): the lognormal's at the line unless the count at
    the nearest stripe rejects the lognormal's P there (it lies outside the count's exact band),
    then that count with its exact
    band (a one-sided 95 % bound where it is 0 or every record)."""
    model = float(fit.probability(stripe)) if fit is not None else None
    at = site_probability(model, boot.probability_band(stripe) if fit is not None else None,
                          int(np.rint(np.sum(overturned))), len(overturned))
    if at.estimator == MODEL:
        low, high = boot.probability_band(line)
        return dict(zip(ACHIEVED_COLUMNS, (float(fit.probability(line)), float(low),
                                           float(high), MODEL)))
    return dict(zip(ACHIEVED_COLUMNS, (at.p, *at.band, at.words())))


__all__ = ["stripe_rows", "fragility_rows", "exact_fit", "collapse_margin",
           "capacity_rows", "reading", "site_factor", "READINGS"]
