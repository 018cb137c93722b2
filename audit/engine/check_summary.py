"""The answer of ``audit check`` in words and files: per object the fields of ``check.json``,
one sentence for a calculation note, the table of ``check.csv`` (one row per object ×
procedure) and the summary printed on standard output.

Every probability is conditional on the site's intensity at the hazard level of the S_XS, S_X1
given, except ``risk`` (per object: the annual rate of overturning from the site's hazard curve,
P in 50 years, the exact width for the risk target) and ``risk_p50`` (per procedure: P in 50
years of the object at the width the guideline requires), null without a hazard curve.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd

from audit.engine.csv_text import csv_bytes
from audit.engine.schemas import GUIDE

#: What the site's numbers stand for, said in every output.
HAZARD_LEVEL = ("the hazard level of the S_XS, S_X1 given (e.g. ASCE 41's BSE-1E or BSE-2E): "
                "every verdict and probability is at the site's intensity at that level")
CHECK_JSON, CHECK_CSV, CHECK_HTML = "check.json", "check.csv", "check.html"
#: Share of an annual rate from outside the stripes above which the sentence warns of it.
EXTRAPOLATED_SHARE = 0.10
#: Columns of ``check.csv`` (their units and meanings in :mod:`audit.engine.schemas`).
CSV_COLUMNS = list(GUIDE[CHECK_CSV])


def _number(value) -> float | None:
    """A finite float, else None (JSON null)."""
    return float(value) if value is not None and math.isfinite(value) else None


def im_words(im, site_im: float) -> str:
    """The site's intensity in words, e.g. ``S_a(1 s) = S_X1 = 0.9 g``."""
    if im.kind == "sa":
        design = " = S_X1" if im.period_s == 1.0 else " of the design spectrum"
        return f"S_a({im.period_s:g} s){design} = {site_im:.3g} g"
    return f"PGA = 0.4 S_XS = {site_im:.3g} g"


def _procedure_answer(proc, judgements, line, width, b: int, first_entry,
                      risk_p50: float | None) -> dict:
    answer = {"name": proc.name, "title": proc.title, "verdict": None, "compares": None,
              "demand": None, "capacity": None, "unit": None, "share_predicting_overturn": None,
              "records_judged": len(judgements), "required_width_m": None,
              "guideline_im": _number(line), "reason": None, "risk_p50": risk_p50}
    if not judgements:
        answer["reason"] = (proc.unmet_requirements(first_entry)
                            or "it can evaluate no record of the suite")
        return answer
    share = float(np.mean([j.overturns[b] for j in judgements]))
    # over the records where it gives a number (a rotation iteration may settle on none)
    demands = np.array([j.demand[b] for j in judgements])
    demand = float(np.median(demands[~np.isnan(demands)])) if (~np.isnan(demands)).any() \
        else math.nan
    reasons = []
    if math.isinf(demand):
        reasons.append("its rotation estimate reaches α (overturning)"
                       + (" for most records" if len(judgements) > 1 else "")
                       + ": no rotation to compare")
    elif math.isnan(demand):
        reasons.append("its iteration settles on no rotation for any record")
    if math.isinf(width):
        reasons.append("no width up to 0.99 × the height passes it (restrain the object)")
    answer.update(verdict="passes" if share <= 0.5 else "fails",
                  compares=judgements[0].quantity[b], unit=judgements[0].unit[b],
                  demand=_number(demand),
                  capacity=_number(float(np.median([j.capacity[b] for j in judgements]))),
                  share_predicting_overturn=share, required_width_m=_number(width),
                  reason="; ".join(reasons) or None)
    return answer


def object_answer(obj, b: int, levels, site_im: float, im, fit, boot, overturned, record_ids,
                  widths, judged, first_entry, risk: dict | None = None,
                  guideline_p50: dict | None = None) -> dict:
    """The entry of ``check.json`` for one object (see the module): ``risk`` its entry of
    :func:`~audit.engine.check_risk.object_risk`, ``guideline_p50`` P in 50 years at each
    guideline's width by procedure name (both with a hazard curve)."""
    site = int(np.argmin(np.abs(levels - site_im)))
    if fit is not None:
        p_site = float(fit.probability(site_im))
    else:  # no stripe overturns it, or every record at every stripe does
        p_site = 1.0 if overturned.all() else 0.0
    low, high = boot.probability_band(site_im)
    curve = site_im * np.geomspace(0.2, 5.0, 61)
    curve_low, curve_high = boot.probability_band(curve)
    answer = {
        "name": obj.name, "width_m": obj.width_m, "height_m": obj.height_m,
        "alpha_deg": obj.alpha_deg, "size_s": obj.size_s,
        "exact": {"im": im.name, "im_unit": im.unit,
                  "median_g": fit.median if fit else None, "beta": fit.beta if fit else None,
                  "p_overturn_at_site": p_site, "p_band": [float(low), float(high)],
                  "p_band_method": f"bootstrap over records, {len(boot.medians)} resamples, "
                                   f"{boot.confidence:.0%} percentile band",
                  "site_im_g": site_im,
                  "required_width_m_10pct": _number(widths[0]),
                  "required_width_m_50pct": _number(widths[1]),
                  "records_overturning_at_site": [r for r, o in zip(record_ids,
                                                                    overturned[:, site]) if o],
                  "stripes": {"im": levels.tolist(),
                              "overturned": overturned.sum(axis=0).tolist(),
                              "records": int(overturned.shape[0])},
                  "band_curve": {"im": curve.tolist(), "low": curve_low.tolist(),
                                 "high": curve_high.tolist()}},
        "procedures": [_procedure_answer(proc, mine, line, width, b, first_entry,
                                         (guideline_p50 or {}).get(proc.name))
                       for proc, mine, line, width in judged],
        "risk": risk}
    answer["sentence"] = sentence(answer, im)
    return answer


def _names(titles) -> str:
    return titles[0] if len(titles) == 1 else ", ".join(titles[:-1]) + " and " + titles[-1]


def sentence(answer: dict, im) -> str:
    """One sentence for a calculation note: the guidelines' verdicts, the exact P(overturn) at
    the site with its band, the exact widths."""
    by = {v: [p["title"] for p in answer["procedures"] if p["verdict"] == v]
          for v in ("passes", "fails", None)}
    parts = []
    if by["passes"]:
        parts.append(f"{_names(by['passes'])} accept{'s' if len(by['passes']) == 1 else ''} it")
    if by["fails"]:
        parts.append(f"{_names(by['fails'])} reject{'s' if len(by['fails']) == 1 else ''} it")
    if by[None]:
        parts.append(f"{_names(by[None])} cannot judge it")
    exact = answer["exact"]
    low, high = exact["p_band"]
    text = (f"{answer['name']} ({answer['width_m']:.3g} m wide × {answer['height_m']:.3g} m "
            f"tall): " + "; ".join(parts) + f"; the exact P(overturn) at "
            f"{im_words(im, exact['site_im_g'])} is {100 * exact['p_overturn_at_site']:.0f} % "
            f"[{100 * low:.0f}–{100 * high:.0f} %]")
    w10, w50 = exact["required_width_m_10pct"], exact["required_width_m_50pct"]
    if w10 is None:
        text += "; no width up to 0.95 × its height brings it to 10 % (restrain it)"
    else:
        text += (f"; it needs {w10:.2f} m of base width for 10 %"
                 + (f" ({w50:.2f} m for 50 %)" if w50 is not None else ""))
    risk = answer["risk"]
    if risk is None:
        return text + "."
    width = risk["required_width_m"]
    rate = risk["annual_rate"]
    outside = risk["share_below_stripes"] + risk["share_above_stripes"]
    return (text + f". From the site's hazard curve it overturns at {rate:.2g}/yr"
            + (f" (once in {1 / rate:,.0f} years)" if rate > 0 else "")
            + f", P = {100 * risk['p50']:.2g} % in 50 years "
            f"({'within' if risk['meets_target'] else 'above'} the "
            f"{100 * risk['target_p50']:g} % target"
            + (f"; {width:.2f} m of base width meets it)" if width is not None else
               "; no width up to 0.95 × its height meets it)")
            + (f"; {100 * outside:.0f} % of that rate comes from intensities outside the stripes, "
               "where the fitted fragility is extrapolated." if outside > EXTRAPOLATED_SHARE
               else "."))


def run_summary(suite, entries, im, levels, site_im, procedures, restitution, where) -> dict:
    """The part of ``check.json`` that describes the run."""
    from audit import __version__
    site = suite.design_site or {}
    return {"version": __version__,
            "site": {"sxs_g": site.get("sxs_g"), "sx1_g": site.get("sx1_g"),
                     "hazard_level": HAZARD_LEVEL},
            "im": im.name, "im_unit": im.unit, "site_im": site_im, "levels": levels.tolist(),
            "records": [e.id for e in entries], "records_source": suite.description,
            "restitution": str(restitution), "scheduler": where,
            "procedures": [{"name": p.name, "title": p.title} for p in procedures]}


def check_table(objects: list) -> pd.DataFrame:
    """One row per object × procedure (the columns of ``check.csv``)."""
    rows = []
    for obj in objects:
        exact, risk = obj["exact"], obj["risk"]
        for proc in obj["procedures"]:
            rows.append({
                "object": obj["name"], "width_m": obj["width_m"], "height_m": obj["height_m"],
                "alpha_deg": obj["alpha_deg"], "size_s": obj["size_s"],
                "procedure": proc["name"], "verdict": proc["verdict"] or "",
                "compares": proc["compares"] or "", "demand": proc["demand"],
                "capacity": proc["capacity"], "unit": proc["unit"] or "",
                "share_predicting_overturn": proc["share_predicting_overturn"],
                "required_width_m": proc["required_width_m"],
                "guideline_im": proc["guideline_im"], "reason": proc["reason"] or "",
                "im": exact["im"], "site_im": exact["site_im_g"],
                "p_overturn_at_site": exact["p_overturn_at_site"],
                "p_band_low": exact["p_band"][0], "p_band_high": exact["p_band"][1],
                "exact_median": exact["median_g"], "exact_beta": exact["beta"],
                "exact_required_width_m_10pct": exact["required_width_m_10pct"],
                "exact_required_width_m_50pct": exact["required_width_m_50pct"],
                "risk_p50": proc["risk_p50"],
                "p50": risk["p50"] if risk else None,
                "annual_rate": risk["annual_rate"] if risk else None,
                "exact_required_width_m_risk": risk["required_width_m"] if risk else None})
    return pd.DataFrame(rows, columns=CSV_COLUMNS).astype(
        {c: float for c in CSV_COLUMNS if c not in ("object", "procedure", "verdict", "compares",
                                                     "unit", "reason", "im")})


def check_data_files(run) -> dict[str, bytes]:
    """``check.json`` and ``check.csv`` of a :class:`~audit.engine.check.CheckRun`."""
    document = {**run.summary, "objects": run.objects}
    return {CHECK_JSON: json.dumps(document, indent=1, ensure_ascii=False).encode(),
            CHECK_CSV: csv_bytes(check_table(run.objects), "%.6g")}


def _compared(proc: dict) -> str:
    if proc["verdict"] is None:
        return proc["reason"] or ""
    unit = proc["unit"]
    demand = "≥ α" if proc["demand"] is None and unit == "deg" else (
        "—" if proc["demand"] is None else f"{proc['demand']:.3g}")
    if unit == "deg":
        return f"θ {demand}{'°' if proc['demand'] is not None else ''} vs α {proc['capacity']:.3g}°"
    return f"demand {demand} vs capacity {proc['capacity']:.3g} {unit}"


def _percent(p: float | None) -> str:
    return "—" if p is None else f"{100 * p:.2g} %"


def _intensity(name: str):
    from audit.engine.intensity import IntensityMeasure
    return IntensityMeasure.parse(name)


def summary_text(document: dict) -> str:
    """The summary on standard output: one paragraph, then per object its sentence and table."""
    site = document["site"]
    lines = [f"Site S_XS = {site['sxs_g']:g} g, S_X1 = {site['sx1_g']:g} g, at the hazard level "
             f"these values are for (as given); {len(document['records'])} records of "
             f"{document['records_source'].split(':')[0]}, each scaled "
             f"to {im_words(_intensity(document['im']), document['site_im'])} and to "
             f"{len(document['levels'])} stripes {min(document['levels']):.3g}–"
             f"{max(document['levels']):.3g} {document['im_unit']} for the exact fragility.", ""]
    hazard = document.get("hazard")
    if hazard:
        lines[-1:-1] = [f"Risk from the hazard curve {hazard['source']}: target P ≤ "
                        f"{100 * hazard['target_p50']:g} % of overturning in 50 years; "
                        "'P in 50 yr' is of the object at the width each row requires."]
    for obj in document["objects"]:
        lines += [obj["sentence"], ""]
        rows = [("procedure", "verdict", "compares", "width needed")
                + (("P in 50 yr",) if hazard else ())]
        for proc in obj["procedures"]:
            width = proc["required_width_m"]
            rows.append((proc["title"], proc["verdict"] or "—",
                         _compared(proc) if proc["verdict"] else "cannot judge",
                         f"{width:.2f} m" if width is not None else "—")
                        + ((_percent(proc["risk_p50"]),) if hazard else ()))
        exact = obj["exact"]
        for target in ("10", "50"):
            width = exact[f"required_width_m_{target}pct"]
            rows.append((f"exact, P(overturn) ≤ {target} %", "", "",
                         f"{width:.2f} m" if width is not None else "none ≤ 0.95 h")
                        + (("",) if hazard else ()))
        if hazard:
            width = obj["risk"]["required_width_m"]
            rows.append((f"exact, P in 50 years ≤ {100 * hazard['target_p50']:g} %", "", "",
                         f"{width:.2f} m" if width is not None else "none ≤ 0.95 h",
                         f"≤ {_percent(hazard['target_p50'])}" if width is not None else ""))
        sizes = [max(len(row[k]) for row in rows) for k in range(len(rows[0]))]
        lines += ["  " + "  ".join(cell.ljust(size) for cell, size in zip(row, sizes)).rstrip()
                  for row in rows]
        lines += [f"  (object width {obj['width_m']:.3g} m; exact fragility: median "
                  + (f"{exact['median_g']:.3g}" if exact["median_g"] else "—")
                  + f" {exact['im_unit']}, β = "
                  + (f"{exact['beta']:.2f}" if exact["beta"] else "—") + ")", ""]
    return "\n".join(lines).rstrip() + "\n"


__all__ = ["object_answer", "run_summary", "sentence", "check_table", "check_data_files",
           "summary_text", "im_words", "HAZARD_LEVEL", "CHECK_JSON", "CHECK_CSV", "CHECK_HTML",
           "CSV_COLUMNS"]
