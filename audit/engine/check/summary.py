"""The answer of ``audit check`` as files: per object the fields of ``check.json`` (with its
sentence, :mod:`audit.engine.check.words`) and the table of ``check.csv`` (one row per object ×
procedure).

Every probability is conditional on the site's intensity at the hazard level of the S_XS, S_X1
given, except ``risk`` (per object: the annual rate of overturning from the site's hazard curve,
P in 50 years, the exact width for the risk target) and ``risk_p50`` (per procedure: P in 50
years of the object at the width the guideline requires), null without a hazard curve.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from audit.engine.check.entries import ExactRotations, procedure_entries
from audit.engine.check.words import sentence
from audit.engine.design.site_probability import MODEL, site_probability
from audit.engine.shared.csv_text import csv_bytes
from audit.engine.shared.floors import suite_floor
from audit.engine.shared.schemas import GUIDE

#: What the site's numbers stand for, said in every output.
HAZARD_LEVEL = ("the hazard level of the S_XS, S_X1 given (e.g. ASCE 41's BSE-1E or BSE-2E): "
                "every verdict and probability is at the site's intensity at that level")
CHECK_JSON, CHECK_CSV, CHECK_HTML = "check.json", "check.csv", "check.html"
#: Columns of ``check.csv`` (their units and meanings in :mod:`audit.engine.shared.schemas`).
CSV_COLUMNS = list(GUIDE[CHECK_CSV])
TEXT_COLUMNS = ("object", "procedure", "limit_state", "verdict", "compares", "unit", "basis",
                "reason", "im", "building_model", "p_estimator", "exact_source")


def _number(value) -> float | None:
    """A finite float, else None (JSON null)."""
    return float(value) if value is not None and math.isfinite(value) else None


def _family_widths(family, searched, height_m: float) -> dict:
    """The 10 % and 50 % widths read from the fragility family with their bands (null beyond
    0.95 × the height, where the family is not fitted), its curve, and the widths the search
    found on the counted P(w) (which is not monotone: its jumps are the records')."""
    out = {"required_width_m_10pct_searched": _number(searched[0]),
           "required_width_m_50pct_searched": _number(searched[1])}
    if family is None:
        return {**out, "required_width_m_10pct": _number(searched[0]),
                "required_width_m_50pct": _number(searched[1]), "width_curve": None,
                "required_width_m_10pct_band": None, "required_width_m_50pct_band": None}
    out["width_curve"] = family.curve
    out["width_family"] = {"median_intercept": family.family.intercept,
                           "median_width_exponent": family.family.slope,
                           "beta": family.family.beta,
                           "model": "P = Φ((ln im − a − c ln w)/β), fitted on every width "
                                    "solved at this height"}
    for target, name in ((0.10, "10pct"), (0.50, "50pct")):
        width = family.widths[target]
        inside = math.isfinite(width) and width <= 0.95 * height_m
        out[f"required_width_m_{name}"] = width if inside else None
        out[f"required_width_m_{name}_band"] = family.bands[target] if inside else None
    return out


@dataclass(frozen=True)
class CheckFrame:
    """What every object of a check shares: the stripes [unit of ``im``], the site's intensity
    (one of them), the intensity measure, the records' ids, the first record (whose unmet
    requirements say why a procedure judged none), the limit state asked for (SLV, SLC or
    both), and which stripes the fragility is fitted on (the lattice's; every one when None)."""

    levels: np.ndarray
    site_im: float
    im: object
    record_ids: list
    first_entry: object
    limit_state: str = "both"
    fitted: np.ndarray | None = None


@dataclass
class ObjectFindings:
    """What a check found for one object.

    Attributes
    ----------
    obj : audit.engine.shared.blocks.Block
    index : int
        Its column in the stripes' outcomes and the judgements.
    fit : audit.engine.design.lognormal_fit.LognormalFit or None
        Its exact fragility, fitted on the lattice's stripes (None where no lognormal fits).
    boot : audit.engine.design.bootstrap.BootstrapFits
        Its bootstrap over records, on the same stripes.
    overturned : numpy.ndarray
        Exact outcomes at every stripe (the site's too), shaped (record, stripe).
    widths : numpy.ndarray
        Exact widths for P(overturn) ≤ 10 % and ≤ 50 % at the site [m], then for the risk target
        with a hazard curve.
    judged : list of audit.engine.check.entries.GuidelineJudgement
        Per procedure, its judgement of the object (its judgements, its line on the stripes,
        its required widths, whether it reads only the site).
    risk : dict or None
        :func:`~audit.engine.check.risk.object_risk`, with a hazard curve.
    guideline_p50 : dict
        P in 50 years at each guideline's width, by procedure name (with a hazard curve).
    theta_rad : numpy.ndarray or None
        Exact peak rotations, shaped (record, stripe) [rad].
    other_im : dict or None
        Its exact P(overturn) at the site at the other standard IM
        (:mod:`audit.engine.check.other_im`).
    family : audit.engine.check.width_family.WidthAnswer or None
        The object's height as one fragility family: P(width) at the site, the 10 % and 50 %
        widths read from it with their bootstrap bands.
    solved_overturned : numpy.ndarray or None
        Where ``overturned`` is an atlas's (per-record probabilities), the outcomes solved
        (record, stripe), which ``theta_rad`` goes with: the limits' P(exceed) and the records
        overturning at the site read them. None: ``overturned`` is solved, or, where it is an
        atlas's, nothing is (no chosen guideline reads a limit short of overturning: each
        limit's P(exceed) is P(overturn), the records overturning at the site are not given).
    source : dict or None
        ``exact.atlas`` (:meth:`~audit.engine.check.atlas_side.AtlasSide.source`) where the
        exact side is an atlas's; None where it is solved.
    """

    obj: object
    index: int
    fit: object
    boot: object
    overturned: np.ndarray
    widths: np.ndarray
    judged: list
    risk: dict | None = None
    guideline_p50: dict = field(default_factory=dict)
    theta_rad: np.ndarray | None = None
    family: object = None
    other_im: dict | None = None
    solved_overturned: np.ndarray | None = None
    source: dict | None = None


def object_answer(found: ObjectFindings, frame: CheckFrame) -> dict:
    """The entry of ``check.json`` for one object (see the module).

    Parameters
    ----------
    found : ObjectFindings
        What the check found of the object.
    frame : CheckFrame
        What every object shares: stripes, site intensity, IM, records.
    """
    obj, b, fit, boot, overturned = found.obj, found.index, found.fit, found.boot, found.overturned
    levels, site_im, im = frame.levels, frame.site_im, frame.im
    fitted = frame.fitted if frame.fitted is not None else np.ones(levels.size, dtype=bool)
    site = int(np.argmin(np.abs(levels - site_im)))  # the site's own stripe
    # an atlas's count at the site is a sum of per-record probabilities: to a whole record
    at_site = site_probability(float(fit.probability(site_im)) if fit is not None else None,
                               [float(v) for v in boot.probability_band(site_im)]
                               if fit is not None else None,
                               int(np.rint(overturned[:, site].sum())), overturned.shape[0])
    unsolved = found.source is not None and found.solved_overturned is None
    solved = found.solved_overturned if found.solved_overturned is not None else overturned
    p_site = at_site.p
    curve = np.geomspace(levels.min(), levels.max(), 61)  # the band over every stripe
    theta = found.theta_rad if found.theta_rad is not None else np.zeros(overturned.shape)
    exact = (ExactRotations(None, None, levels, site_im, p_site, fitted,
                            alpha_rad=math.radians(obj.alpha_deg)) if unsolved else
             ExactRotations(theta, solved, levels, site_im, p_site, fitted))
    curve_low, curve_high = boot.probability_band(curve)
    answer = {
        "name": obj.name, "width_m": obj.width_m, "height_m": obj.height_m,
        "alpha_deg": obj.alpha_deg, "size_s": obj.size_s,
        "exact": {"im": im.name, "im_unit": im.unit,
                  "median_g": fit.median if fit else None, "beta": fit.beta if fit else None,
                  "p_overturn_at_site": p_site, "p_band": [float(v) for v in at_site.band],
                  "p_band_method": (f"bootstrap over records, {len(boot.medians)} resamples, "
                                    f"{boot.confidence:.0%} percentile band"
                                    if at_site.estimator == MODEL else
                                    at_site.as_dict()["count"]["band_method"]),
                  "p_at_site": {**at_site.as_dict(), "stripe_im": float(levels[site]),
                                "model_band_method": f"bootstrap over records, "
                                                     f"{len(boot.medians)} resamples, "
                                                     f"{boot.confidence:.0%} percentile band"},
                  "fitted_on": "the lattice's stripes (not the site's): "
                               f"{int(fitted.sum())} of {levels.size}",
                  "site_im_g": site_im,
                  **_family_widths(found.family, found.widths, obj.height_m),
                  "other_im": found.other_im,
                  "source": "direct" if found.source is None else "atlas",
                  "atlas": found.source,
                  "records_overturning_at_site": None if unsolved else [
                      r for r, o in zip(frame.record_ids, solved[:, site]) if o],
                  "stripes": {"im": levels.tolist(),
                              "overturned": (overturned.sum(axis=0).tolist()
                                             if found.source is None else
                                             np.round(overturned.sum(axis=0), 3).tolist()),
                              "records": int(overturned.shape[0]),
                              "fitted": fitted.tolist()},
                  "band_curve": {"im": curve.tolist(), "low": curve_low.tolist(),
                                 "high": curve_high.tolist()}},
        "procedures": [entry for guideline in found.judged
                       for entry in procedure_entries(
                           guideline, b, exact, frame.limit_state, frame.first_entry,
                           found.guideline_p50.get(guideline.proc.name))],
        "risk": found.risk}
    answer["sentence"] = sentence(answer, im)
    return answer




def run_summary(suite, entries, im, levels, site_im, procedures, restitution, where) -> dict:
    """The part of ``check.json`` that describes the run.

    Parameters
    ----------
    suite : records.RecordSuite
        The records, with their design site and floor.
    entries : sequence of records.RecordEntry
        The records used.
    im : IntensityMeasure
        The check's intensity measure.
    levels : numpy.ndarray
        The stripes (in the IM's unit, e.g. [g]).
    site_im : float
        The site's intensity, in the same unit.
    procedures : sequence of procedures.base.Procedure
        The guidelines checked.
    restitution : Restitution
        The impact model.
    where : str
        Where the records were solved (the scheduler).
    """
    from audit import __version__
    site = suite.design_site or {}
    return {"version": __version__,
            "site": {"sxs_g": site.get("sxs_g"), "sx1_g": site.get("sx1_g"),
                     "hazard_level": HAZARD_LEVEL},
            "im": im.name, "im_unit": im.unit, "site_im": site_im, "levels": levels.tolist(),
            "records": [e.id for e in entries], "records_source": suite.description,
            "floor": suite_floor(suite),
            "restitution": str(restitution), "scheduler": where,
            "procedures": [{"name": p.name, "title": p.title} for p in procedures]}


def check_table(objects: list, floor: dict | None = None) -> pd.DataFrame:
    """One row per object × procedure (the columns of ``check.csv``), on ``floor`` (the run's
    ``floor``; the ground when None).

    Parameters
    ----------
    objects : list of dict
        The objects' entries of ``check.json`` (:func:`object_answer`).
    floor : dict, optional
        The run's ``floor`` (:func:`~audit.engine.shared.floors.floor_document`).
    """
    floor = floor or {}
    where = {"floor_z_over_h": floor.get("z_over_h", 0.0),
             "building_period_s": floor.get("building_period_s"),
             "building_model": floor.get("building_model") or ""}
    rows = []
    for obj in objects:
        exact, risk = obj["exact"], obj["risk"]
        for proc in obj["procedures"]:
            rows.append({
                "object": obj["name"], "width_m": obj["width_m"], "height_m": obj["height_m"],
                "alpha_deg": obj["alpha_deg"], "size_s": obj["size_s"], **where,
                "procedure": proc["key"], "limit_state": proc["limit_state"],
                "verdict": proc["verdict"], "compares": proc["quantity"] or "",
                "demand": proc["demand"], "capacity": proc["capacity"],
                "unit": proc["unit"] or "", "basis": proc["basis"] or "",
                "share_of_records_overturning": proc["share_of_records_overturning"],
                "exact_p_exceed": proc["exact_p_exceed"],
                "required_width_m": proc["required_width_m"],
                "guideline_im": proc["guideline_im"], "reason": proc["reason"] or "",
                "im": exact["im"], "site_im": exact["site_im_g"],
                "p_overturn_at_site": exact["p_overturn_at_site"],
                "p_band_low": exact["p_band"][0], "p_band_high": exact["p_band"][1],
                "p_estimator": exact["p_at_site"]["estimator"],
                "exact_median": exact["median_g"], "exact_beta": exact["beta"],
                "exact_required_width_m_10pct": exact["required_width_m_10pct"],
                "exact_required_width_m_50pct": exact["required_width_m_50pct"],
                "risk_p50": proc["risk_p50"],
                "p50": risk["p50"] if risk else None,
                "annual_rate": risk["annual_rate"] if risk else None,
                "exact_required_width_m_risk": risk["required_width_m"] if risk else None,
                "exact_source": exact.get("source", "direct"),
                "exact_p_error": (exact["atlas"] or {}).get("p_error")})
    return pd.DataFrame(rows, columns=CSV_COLUMNS).astype(
        {c: float for c in CSV_COLUMNS if c not in TEXT_COLUMNS})


def check_data_files(run) -> dict[str, bytes]:
    """``check.json`` and ``check.csv`` of a :class:`~audit.engine.check.pipeline.CheckRun`.

    Parameters
    ----------
    run : CheckRun
        The finished check.

    Returns
    -------
    dict of str to bytes
        File name → contents.
    """
    document = {**run.summary, "objects": run.objects}
    return {CHECK_JSON: json.dumps(document, indent=1, ensure_ascii=False).encode(),
            CHECK_CSV: csv_bytes(check_table(run.objects, run.summary.get("floor")), "%.6g")}


__all__ = ["object_answer", "ObjectFindings", "CheckFrame", "run_summary", "check_table",
           "check_data_files", "HAZARD_LEVEL", "CHECK_JSON", "CHECK_CSV", "CHECK_HTML",
           "CSV_COLUMNS"]
