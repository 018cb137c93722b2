"""Figures against time: one block's rocking history with the guidelines' estimates, the pulse
sensitivity of Figure 4.1 vs 7.2, and the plain line plot."""

from __future__ import annotations

import numpy as np
import pandas as pd

from reports.plots import _axis, _layout

#: Samples of a time history drawn in the page (decimated by a stride).
HISTORY_SAMPLES = 900


def history_figure(history: pd.DataFrame, meta: dict, estimates: list) -> dict:
    """θ/α and θ' of one block against time: full rocking cycles shaded (duration on hover and
    as a label where wide enough), each guideline's estimate ±θ/α dashed, its T(θ) in the legend.

    ``estimates`` are ``(label, theta_ratio or None, period_s or None, colour)``.
    """
    time = history["time_s"].to_numpy()
    start, stop = time[0], time[-1]
    if meta.get("first_impact_s") is not None:
        start = max(start, meta["first_impact_s"] - 2.0)
        stop = min(stop, meta["last_impact_s"] + 3.0)
    if meta.get("overturn_time_s") is not None:
        stop = min(time[-1], meta["overturn_time_s"] + 1.0)
    window = np.flatnonzero((time >= start) & (time <= stop))
    window = window[::max(1, window.size // HISTORY_SAMPLES)]
    time_s = time[window]
    theta = history["theta_ratio"].to_numpy(dtype=float)[window]
    omega = history["omega_rad_s"].to_numpy(dtype=float)[window]
    peak = np.nanmax(np.abs(theta)) if np.isfinite(theta).any() else 1.0
    drawn = [abs(ratio) for _, ratio, _, _ in estimates if ratio is not None]
    limit = 1.1 if meta.get("overturned") else min(1.1, max(0.25, 1.3 * peak,
                                                             1.15 * max(drawn, default=0)))
    data = [{"type": "scatter", "mode": "lines", "x": time_s, "y": theta,
             "line": {"color": "#333333", "width": 1.2}, "name": "exact θ/α",
             "hovertemplate": "t = %{x:.3f} s<br>θ/α = %{y:.4f}<extra></extra>"},
            {"type": "scatter", "mode": "lines", "x": time_s,
             "y": omega, "xaxis": "x2", "yaxis": "y2",
             "line": {"color": "#666666", "width": 1}, "name": "exact θ'", "showlegend": False,
             "hovertemplate": "t = %{x:.3f} s<br>θ' = %{y:.4g} rad/s<extra></extra>"}]
    shapes, mid_x, mid_text = [], [], []
    for k, (begin, duration) in enumerate(zip(meta["cycle_starts_s"], meta["cycle_durations_s"])):
        if begin + duration < start or begin > stop:
            continue
        shapes.append({"type": "rect", "xref": "x", "yref": "y domain", "x0": begin,
                       "x1": begin + duration, "y0": 0, "y1": 1, "line": {"width": 0},
                       "fillcolor": "#1f77b4" if k % 2 else "#9ecae1", "opacity": 0.18,
                       "layer": "below"})
        mid_x.append(begin + duration / 2)
        mid_text.append(f"{duration:.2f} s" if duration > 0.07 * (stop - start) else "")
    if mid_x:
        data.append({"type": "scatter", "mode": "markers+text", "x": mid_x,
                     "y": [0.93 * limit] * len(mid_x), "text": mid_text,
                     "textposition": "middle right", "textfont": {"size": 10, "color": "#1f4e79"},
                     "marker": {"symbol": "square", "size": 9, "color": "#9ecae1"},
                     "name": "full rocking cycle (shaded; hover for its duration)",
                     "customdata": [d for b, d in zip(meta["cycle_starts_s"],
                                                       meta["cycle_durations_s"])
                                    if not (b + d < start or b > stop)],
                     "hovertemplate": "full rocking cycle: %{customdata:.3f} s<extra></extra>"})
    if meta.get("excitation_end_s") is not None and start < meta["excitation_end_s"] < stop:
        for yref in ("y domain", "y2 domain"):
            shapes.append({"type": "line", "xref": "x" if yref[1] == " " else "x2",
                           "yref": yref, "x0": meta["excitation_end_s"],
                           "x1": meta["excitation_end_s"], "y0": 0, "y1": 1,
                           "line": {"color": "#999999", "width": 1, "dash": "dash"}})
    for label, ratio, period, colour in estimates:
        if ratio is None:
            continue
        name = f"{label}: θ/α = {ratio:.3f}" + (f", T(θ) = {period:.2f} s" if period else "")
        data.append({"type": "scatter", "mode": "lines", "x": [start, stop, None, start, stop],
                     "y": [ratio, ratio, None, -ratio, -ratio],
                     "line": {"color": colour, "width": 1.2, "dash": "dash"}, "name": name,
                     "hovertemplate": name + "<extra></extra>"})
    if limit >= 1.0:
        data.append({"type": "scatter", "mode": "lines", "x": [start, stop, None, start, stop],
                     "y": [1, 1, None, -1, -1], "line": {"color": "#b2182b", "width": 1,
                                                         "dash": "dot"},
                     "name": "θ = ±α (overturning)", "hoverinfo": "skip"})
    layout = _layout(430, shapes=shapes, margin={"l": 70, "r": 20, "t": 10, "b": 45})
    layout["xaxis"] = _axis("", anchor="y", range=[start, stop], showticklabels=False)
    layout["xaxis2"] = _axis("t [s]", anchor="y2", matches="x")
    layout["yaxis"] = _axis("θ/α [-]", domain=[0.42, 1], range=[-limit, limit])
    layout["yaxis2"] = _axis("θ' [rad/s]", domain=[0, 0.36])
    layout["legend"] = {"orientation": "h", "x": 0, "y": 1.02, "yanchor": "bottom",
                        "font": {"size": 11}}
    layout["margin"]["t"] = 60
    return {"data": data, "layout": layout}


def lines_figure(series, x_title, y_title, height=420, y_range=None, legend_below=False):
    """Plain line plot: ``series`` are dicts with ``x, y, name`` and optional ``colour``,
    ``dash``, ``width``, ``showlegend``."""
    data = [{"type": "scatter", "mode": "lines", "x": s["x"], "y": s["y"], "name": s["name"],
             "line": {"color": s.get("colour"), "width": s.get("width", 1.3),
                      "dash": s.get("dash", "solid")},
             "showlegend": s.get("showlegend", True), "legendgroup": s.get("group", s["name"]),
             "hovertemplate": f"{s['name']}<br>%{{x:.4g}}, %{{y:.4g}}<extra></extra>"}
            for s in series]
    layout = _layout(height)
    layout["xaxis"] = _axis(x_title)
    layout["yaxis"] = _axis(y_title, **({"range": y_range} if y_range else {}))
    if legend_below:
        layout["margin"]["b"] = 190
        layout["height"] = height + 140
        layout["legend"] = {"orientation": "h", "x": 0, "yanchor": "top", "font": {"size": 11},
                            "y": -60 / (layout["height"] - 230)}
    return {"data": data, "layout": layout}


def sensitivity_figure(rocking: dict, oscillator: dict, title_rocking, title_oscillator) -> dict:
    """Figure 4.1 vs 7.2: block θ/α (left) and the 'equivalent' oscillator u (right)."""
    colours = ("#1f77b4", "#ff7f0e", "#d62728")
    data = []
    for colour, (label, (t, value)) in zip(colours, rocking.items()):
        data.append({"type": "scatter", "mode": "lines", "x": t, "y": value, "name": label,
                     "line": {"color": colour, "width": 1.3}, "legendgroup": label.split(" (")[0],
                     "hovertemplate": f"{label}<br>t = %{{x:.3f}} s<br>θ/α = %{{y:.4f}}"
                                      "<extra></extra>"})
    for colour, (label, (t, value)) in zip(colours, oscillator.items()):
        data.append({"type": "scatter", "mode": "lines", "x": t, "y": 100 * np.asarray(value),
                     "name": label, "xaxis": "x2", "yaxis": "y2", "showlegend": False,
                     "line": {"color": colour, "width": 1.3}, "legendgroup": label.split(" (")[0],
                     "hovertemplate": f"{label}<br>t = %{{x:.3f}} s<br>u = %{{y:.4g}} cm"
                                      "<extra></extra>"})
    layout = _layout(430, margin={"l": 70, "r": 20, "t": 50, "b": 100})
    layout["xaxis"] = _axis("t [s]", domain=[0, 0.45])
    layout["xaxis2"] = _axis("t [s]", domain=[0.55, 1], anchor="y2")
    layout["yaxis"] = _axis("θ/α [-]", range=[-1.1, 1.1])
    layout["yaxis2"] = _axis("u [cm]", anchor="x2")
    layout["annotations"] = [
        {"text": title_rocking, "xref": "x domain", "yref": "paper", "x": 0, "y": 1.02,
         "xanchor": "left", "yanchor": "bottom", "showarrow": False, "font": {"size": 11}},
        {"text": title_oscillator, "xref": "x2 domain", "yref": "paper", "x": 0, "y": 1.02,
         "xanchor": "left", "yanchor": "bottom", "showarrow": False, "font": {"size": 11}}]
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.2, "yanchor": "top"}
    return {"data": data, "layout": layout}
