"""The page of ``audit check`` (``check.html``), rendered from its saved ``check.json`` only.

Per object: the sentence for a calculation note; each guideline's verdict and the numbers it
compares; the object drawn to scale beside outlines of the width each guideline requires at its
height and the exact widths for P(overturn) ≤ 10 % and ≤ 50 % at the site; its exact fragility
(stripe shares, the lognormal fit, the bootstrap band over records) with the site's intensity
and each guideline's line; the records that overturn it at the site's level. With a hazard
curve: the risk of each guideline's width, the exact width for the risk target, and the
hazard × fragility figure (:func:`reports.risk_figure.risk_figure`, the integral recomputed
from the curve and the fragility the JSON holds).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from scipy.special import ndtr

from audit.engine.check.risk import quiet_risk
from audit.engine.check.spectrum_read import reading_words
from audit.engine.check.words import anchorage_words, exact_width_words, metres
from audit.engine.design.risk import LognormalFragility, StripeFragility
from records.hazard import HazardCurve
from records.suite import counted_records
from reports.floor_section import floor_spectra_figure
from reports.html_parts import PAGE_STYLE, number, page_templates
from reports.margins_figures import fragility_axes, vertical_line
from reports.palette import _EXTRA_COLOURS
from reports.plots import _axis, _layout, to_json
from reports.risk_figure import risk_figure

CHECK_JSON = "check.json"
#: Colours of the procedures, in the order of the run (the exact answer is black).
PROCEDURE_COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd", *_EXTRA_COLOURS)
SITE_COLOUR = "#b58900"


def _colours(document) -> dict:
    return {p["name"]: PROCEDURE_COLOURS[i % len(PROCEDURE_COLOURS)]
            for i, p in enumerate(document["procedures"])}


def im_name(name: str) -> str:
    """An intensity measure in words, e.g. ``S_a(1 s)`` for ``sa:1``, ``PGA`` for ``pga``."""
    return f"S_a({float(name[3:]):g} s)" if name.startswith("sa:") else name.upper()


def _outline(x0, width, height, colour, dash, fill=None) -> dict:
    return {"type": "rect", "x0": x0, "x1": x0 + width, "y0": 0, "y1": height,
            "line": {"color": colour, "dash": dash, "width": 2},
            "fillcolor": fill or "rgba(0,0,0,0)"}


def _drawing(obj, colours) -> dict:
    """The object to scale (grey), then outlines of the required widths at its height."""
    height = obj["height_m"]
    exact = obj["exact"]
    columns = [("this object", obj["width_m"], "#444", "solid", "#bbbbbb")]
    for target, dash in (("10", "solid"), ("50", "dot")):
        width = exact[f"required_width_m_{target}pct"]
        if width is not None:
            columns.append((f"exact, P ≤ {target} %", width, "#000", dash, None))
    risk = obj["risk"]
    if risk and risk["required_width_m"] is not None:
        columns.append((f"exact, {risk['target_p50']:.0%} in 50 yr", risk["required_width_m"],
                        SITE_COLOUR, "solid", None))
    for proc in obj["procedures"]:
        if proc["required_width_m"] is not None:
            label = (proc["procedure"] if proc["limit_state"] == "overturning"
                     else f"{proc['procedure']} {proc['limit_state']}")
            columns.append((label, proc["required_width_m"], colours[proc["key"]], "dash", None))
    gap = 0.35 * height
    shapes, notes, x = [], [], 0.0
    for label, width, colour, dash, fill in columns:
        shapes.append(_outline(x, width, height, colour, dash, fill))
        notes.append({"x": x + width / 2, "y": -0.04 * height, "yanchor": "top",
                      "showarrow": False, "textangle": -30 if len(columns) > 4 else 0,
                      "text": f"{label}<br>{metres(width)}", "font": {"size": 11, "color": colour}})
        x += width + gap
    layout = _layout(460, shapes=shapes, annotations=notes)
    layout["xaxis"] = _axis("width [m]", range=[-0.1 * height, x], zeroline=False)
    layout["yaxis"] = _axis("height [m]", range=[-0.45 * height, 1.08 * height],
                            scaleanchor="x", scaleratio=1)
    layout["margin"]["b"] = 30
    # an invisible point so plotly draws the axes
    return {"data": [{"type": "scatter", "x": [0], "y": [0], "mode": "markers",
                      "marker": {"opacity": 0}, "hoverinfo": "skip", "showlegend": False}],
            "layout": layout}


def _fragility(obj, document, colours) -> dict:
    exact = obj["exact"]
    unit, im = exact["im_unit"], exact["im"]
    stripes = exact["stripes"]
    levels = np.asarray(stripes["im"])
    band = exact["band_curve"]
    data = [{"type": "scatter", "mode": "lines", "x": band["im"], "y": band["high"],
             "line": {"width": 0}, "hoverinfo": "skip", "showlegend": False},
            {"type": "scatter", "mode": "lines", "x": band["im"], "y": band["low"],
             "fill": "tonexty", "fillcolor": "rgba(0,0,0,0.12)", "line": {"width": 0},
             "name": "exact, bootstrap band over records (90 %)", "hoverinfo": "skip"},
            {"type": "scatter", "mode": "markers", "x": levels.tolist(),
             "y": (np.asarray(stripes["overturned"]) / stripes["records"]).tolist(),
             "name": "exact, share of records at each stripe", "marker": {
                 "color": "#000", "symbol": ["circle" if on else "circle-open"
                                             for on in stripes.get("fitted",
                                                                   [True] * levels.size)]},
             "hovertemplate": (f"{im_name(im)} = %{{x:.3g}} {unit}: %{{y:.0%}} overturn"
                               "<extra></extra>")}]
    if exact["median_g"]:
        x = np.asarray(band["im"])
        data.append({"type": "scatter", "mode": "lines", "x": x.tolist(),
                     "y": ndtr(np.log(x / exact["median_g"]) / exact["beta"]).tolist(),
                     "name": f"exact, lognormal fit (median {exact['median_g']:.3g} {unit}, "
                             f"β {exact['beta']:.2f})", "line": {"color": "#000", "width": 2}})
    site = exact["site_im_g"]
    at = exact["p_at_site"]
    p, (low, high) = exact["p_overturn_at_site"], exact["p_band"]
    data.append({"type": "scatter", "mode": "markers", "x": [site], "y": [p],
                 "error_y": {"type": "data", "symmetric": False, "array": [high - p],
                             "arrayminus": [p - low], "color": SITE_COLOUR},
                 "marker": {"color": SITE_COLOUR, "size": 12, "symbol": "star"},
                 "name": f"at the site, {im_name(im)} = {site:.3g} {unit}: P "
                         f"{'' if at['bound'] else '= '}{at['headline']} ({'lognormal' if at['estimator'] == 'lognormal' else 'count at the site'})"
                         + (f", {exact['atlas']['text']}" if exact.get("atlas") else "")})
    shapes = [vertical_line(site, SITE_COLOUR, "dot")]
    drawn = set()
    for proc in obj["procedures"]:
        line = proc["guideline_im"]
        if line is None or proc["key"] in drawn:
            continue
        drawn.add(proc["key"])
        shapes.append(vertical_line(line, colours[proc["key"]], "dash"))
        data.append({"type": "scatter", "mode": "lines", "x": [line, line], "y": [0, 1],
                     "line": {"color": colours[proc["key"]], "dash": "dash"},
                     "name": f"{proc['procedure']}: predicts overturning for half the records "
                             f"from {line:.3g} {unit}"})
    layout = _layout(470, shapes=shapes)
    fragility_axes(layout, f"{im_name(im)} [{unit}]", min(band["im"]), max(band["im"]), 170, 560)
    return {"data": data, "layout": layout}


def _risk(obj, document) -> dict:
    """The site's hazard curve, the object's fragility and their product (the deaggregation)."""
    hazard, exact, risk = document["hazard"], obj["exact"], obj["risk"]
    curve = HazardCurve.checked(hazard["im"], hazard["curve"]["im_g"],
                                hazard["curve"]["annual_rate"], hazard["source"],
                                tuple(hazard["site"] or ()) or None)
    counted = StripeFragility(np.array(exact["stripes"]["im"]),
                              np.array(exact["stripes"]["overturned"])
                              / exact["stripes"]["records"])
    fitted = (LognormalFragility(exact["median_g"], exact["beta"])
              if exact["median_g"] and exact["beta"] else None)
    low, high = risk["im_range_90_g"]
    return risk_figure(curve, fitted or counted, quiet_risk(fitted or counted, curve),
                       counted if fitted else None,
                       f"{obj['name']}: λ_ov = {risk['annual_rate']:.3g}/yr, P in 50 years "
                       f"{risk['p50']:.2%}; 90 % of it from {number(low)} to "
                       f"{number(high)} g (shaded)")


def render_check_page(folder) -> str:
    """The HTML page of the check saved in ``folder`` (its ``check.json``), plotly.js inlined."""
    from plotly.offline import get_plotlyjs
    document = json.loads((Path(folder) / CHECK_JSON).read_text(encoding="utf-8"))
    colours = _colours(document)
    objects = [{**obj, "drawing": to_json(_drawing(obj, colours)),
                "fragility": to_json(_fragility(obj, document, colours)),
                "risk_figure": to_json(_risk(obj, document)) if obj["risk"] else None,
                "width_10": exact_width_words(obj["exact"], "10"),
                "width_50": exact_width_words(obj["exact"], "50"),
                "other_im_name": (im_name(obj["exact"]["other_im"]["im"])
                                  if obj["exact"].get("other_im") else None),
                "spectrum_notes": [reading_words(p) for p in obj["procedures"]
                                   if p.get("other_spectrum")]}
               for obj in document["objects"]]
    return page_templates().get_template("check.html.j2").render(
        document=document, objects=objects, plotly=get_plotlyjs(),
        floor_figure=floor_spectra_figure(document.get("floor") or {}),
        im_words=im_name(document["im"]), page_style=PAGE_STYLE, anchorage_words=anchorage_words,
        records_words=counted_records(len(document["records"]), document["records_source"]))


__all__ = ["render_check_page", "im_name", "CHECK_JSON"]
