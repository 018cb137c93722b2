"""The risk of one object at a site in one figure: the site's hazard curve, the object's
overturning fragility, and their product, the deaggregation of the annual rate of overturning
over intensity. A plotly spec (a dict), for any page that embeds it.
"""

from __future__ import annotations

import math

import numpy as np

from reports.plots import _axis, _domains, _layout

#: Tick labels of the shared logarithmic intensity axis [g].
LOG_TICKS = (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5)
_BAND = "rgba(181,137,0,0.15)"


def risk_figure(curve, fragility, risk, counted=None, title: str | None = None) -> dict:
    """Three panels over one intensity axis: λ(im) of the hazard curve (log–log, as
    integrated), P(overturn | im), and dλ_ov/d ln im with the central 90 % shaded.

    Parameters
    ----------
    curve : records.hazard.HazardCurve
    fragility : audit.engine.design.risk.LognormalFragility or StripeFragility
        The fragility ``risk`` integrated.
    risk : audit.engine.design.risk.OverturningRisk
    counted : audit.engine.design.risk.StripeFragility, optional
        The stripe shares, drawn as dots beside a fitted ``fragility``.
    title : str, optional
    """
    positive = curve.annual_rate > 0
    im = curve.im_g[positive]
    x = np.geomspace(im.min(), im.max(), 300)
    unit = f"{risk.im} [g]"
    low, high = risk.im_range_90_g
    data = [
        {"type": "scatter", "mode": "lines+markers", "x": im, "y": curve.annual_rate[positive],
         "name": "hazard curve λ(im)", "line": {"color": "#2166ac", "width": 2},
         "marker": {"size": 5}, "xaxis": "x", "yaxis": "y",
         "hovertemplate": f"{risk.im} = %{{x:.3g}} g: exceeded %{{y:.3g}} times a year"
                          "<extra></extra>"},
        {"type": "scatter", "mode": "lines", "x": x, "y": fragility.probability(x),
         "name": f"fragility: {fragility.describe()}", "line": {"color": "#000", "width": 2},
         "xaxis": "x", "yaxis": "y2",
         "hovertemplate": f"{risk.im} = %{{x:.3g}} g: P(overturn) %{{y:.0%}}<extra></extra>"}]
    if counted is not None:
        data.append({"type": "scatter", "mode": "markers", "x": counted.levels_g,
                     "y": counted.shares, "name": "share of records overturning at a stripe",
                     "marker": {"color": "#000", "size": 6, "symbol": "circle-open"},
                     "xaxis": "x", "yaxis": "y2"})
    share = risk.density / risk.annual_rate if risk.annual_rate > 0 else risk.density
    data.append({"type": "scatter", "mode": "lines", "x": risk.density_im_g, "y": share,
                 "name": "deaggregation: share of λ_ov per unit ln im", "fill": "tozeroy",
                 "line": {"color": "#b58900", "width": 2}, "xaxis": "x", "yaxis": "y3",
                 "hovertemplate": f"{risk.im} = %{{x:.3g}} g<extra></extra>"})
    top, middle, bottom = _domains(3, 0.07)
    shapes = []
    if math.isfinite(low):
        shapes.append({"type": "rect", "xref": "x", "yref": "paper", "x0": low,
                       "x1": high if math.isfinite(high) else im.max(), "y0": bottom[0],
                       "y1": top[1], "fillcolor": _BAND, "line": {"width": 0},
                       "layer": "below"})
    layout = _layout(640, shapes=shapes)
    ticks = [t for t in LOG_TICKS if im.min() / 1.5 <= t <= im.max() * 1.5]
    layout["xaxis"] = _axis(unit, anchor="y3", type="log", tickvals=ticks,
                            ticktext=[f"{t:g}" for t in ticks])
    layout["yaxis"] = _axis("λ [1/yr]", top, "x", type="log", exponentformat="power")
    layout["yaxis2"] = _axis("P(overturn)", middle, "x", range=[-0.02, 1.02], tickformat=".0%")
    layout["yaxis3"] = _axis("share of λ_ov / ln im", bottom, "x", rangemode="tozero")
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.1, "yanchor": "top",
                        "font": {"size": 11}}
    layout["margin"]["b"] = 110
    layout["title"] = {"font": {"size": 13}, "text": title or (
        f"λ_ov = {risk.annual_rate:.3g}/yr, P in 50 years {risk.p50:.2%}; 90 % of it from "
        f"{low:.3g} to {high:.3g} g (shaded)")}
    return {"data": data, "layout": layout}


__all__ = ["risk_figure"]
