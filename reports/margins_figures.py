"""The figures of the design-level audit's page (``margins.html``): the required-slenderness
chart, the collapse margin ratio over the grid, a block's fragility with each guideline's line,
and the fine amplitude scan; the intensity axis and marker lines the check page shares.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from scipy.special import ndtr

from reports.block_metres import (METRES_ROOM_PX, add_metres_axis, block_hover, block_size_m,
                                   describe_block)
from reports.palette import _EXTRA_COLOURS
from reports.plots import _axis, _layout, alpha_size_map, padded_span, required_alpha_layout

#: Tick labels of a logarithmic intensity axis.
LOG_TICKS = (0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 1, 2, 3, 5, 10, 20)
_EXACT_COLOURS = {"exact@0.10": "#000000", "exact@0.50": "#7f7f7f"}


def procedure_colour(names: list, name: str) -> str:
    return _EXTRA_COLOURS[names.index(name) % len(_EXTRA_COLOURS)] if name in names else "#000"


def block_label(row) -> str:
    if pd.notna(row.get("width_m")):  # a named block
        return (f"{row['width_m']:g}x{row['height_m']:g} m (α = {row['alpha_deg']:.3g}°, "
                f"2π/p = {row['size_s']:.3g} s)")
    return (f"α = {row['alpha_deg']:g}°, 2π/p = {row['size_s']:g} s "
            f"({describe_block(row['alpha_deg'], row['size_s'])})")


def required_figure(required: pd.DataFrame, names: list, titles) -> dict:
    data = []
    for name, rows in required.groupby("procedure", sort=False):
        exact = name.startswith("exact@")
        colour = _EXACT_COLOURS.get(name) or procedure_colour(names, name)
        label = (f"exact: ≤ {float(name[6:]):.0%} of records overturn" if exact
                 else titles.get(name, name))
        data.append({"type": "scatter", "mode": "lines+markers", "x": rows["size_s"],
                     "y": rows["required_alpha_deg"], "name": label,
                     "customdata": rows["exact_overturning_share"],
                     "line": {"color": colour, "width": 2.5 if exact else 1.5,
                              "dash": "solid" if name == "exact@0.10" else
                              "dot" if exact else "dash"},
                     "marker": {"size": 4},
                     # the object each point is: the most slender block accepted at that size
                     "text": [describe_block(a, s) if math.isfinite(a) else ""
                              for a, s in zip(rows["required_alpha_deg"], rows["size_s"])],
                     "hovertemplate": f"{label}<br>2π/p = %{{x:.3g}} s: α ≥ %{{y:.3g}}° "
                                      "(%{text})<br>"
                                      "exact share overturning there: %{customdata:.0%}"
                                      "<extra></extra>"})
    figure = {"data": data, "layout": required_alpha_layout()}
    add_metres_axis(figure, padded_span(required["size_s"]), room_px=METRES_ROOM_PX)
    return figure


def cmr_figure(fragility: pd.DataFrame) -> dict:
    grid = fragility[fragility["width_m"].isna()]
    pivot = grid.pivot_table(index="alpha_deg", columns="size_s", values="cmr", aggfunc="first")
    bounds = grid.assign(bound=grid["cmr_bound"].map(
        {"": "", "at least": " (at least: median above the stripes)",
         "at most": " (at most: median below the stripes)"})).pivot(
        index="alpha_deg", columns="size_s", values="bound")
    alphas = pivot.index.to_numpy(dtype=float)
    sizes = pivot.columns.to_numpy(dtype=float)
    data = [{"type": "heatmap", "x": sizes, "y": alphas,
             "z": pivot.to_numpy(dtype=float), "zmin": 0, "zmid": 1, "zmax": 4,
             "colorscale": [[0, "#b2182b"], [0.25, "#f7f7f7"], [1, "#2166ac"]], "ygap": 2,
             "colorbar": {"title": {"text": "CMR"}, "thickness": 12},
             "customdata": [[[*block_size_m(a, s), bound] for s, bound in zip(sizes, row)]
                            for a, row in zip(alphas, bounds.to_numpy(dtype=object))],
             "hovertemplate": f"α = %{{y:~g}}°, 2π/p = %{{x:~g}} s: {block_hover(0)}<br>"
                              "CMR = %{z:.3g}%{customdata[2]}<extra></extra>"}]
    return alpha_size_map(data, alphas, sizes)


def fragility_figure(block, stripes, capacity, names, titles, summary) -> dict:
    im, unit = summary["im"], summary["im_unit"]
    rows = stripes.groupby("im_level")["exact_overturned"].mean()
    levels = rows.index.to_numpy(dtype=float)
    x = np.geomspace(levels.min(), levels.max(), 200)
    data = [{"type": "scatter", "mode": "markers", "x": levels, "y": rows.to_numpy(),
             "name": "exact, share of records", "marker": {"color": "#000", "size": 7},
             "hovertemplate": f"{im} = %{{x:.3g}} {unit}: %{{y:.0%}} overturn<extra></extra>"}]
    if math.isfinite(block["median"]):
        z = np.log(x / block["median"]) / block["beta"]
        data.append({"type": "scatter", "mode": "lines", "x": x, "y": ndtr(z),
                     "name": f"exact, lognormal fit (median {block['median']:.3g} {unit}, "
                             f"β {block['beta']:.2f})", "line": {"color": "#000", "width": 2}})
    shapes, notes = [], []
    if summary.get("design_im"):
        shapes.append(vertical_line(summary["design_im"], "#b58900", "dot"))
        notes.append(_top_note(summary["design_im"], "design", "#b58900"))
    for row in capacity.itertuples():
        if not math.isfinite(row.guideline_im):
            continue
        colour = procedure_colour(names, row.procedure)
        shapes.append(vertical_line(row.guideline_im, colour, "dash"))
        data.append({"type": "scatter", "mode": "markers", "x": [row.guideline_im],
                     "y": [row.achieved_p_fit], "name": f"{titles.get(row.procedure, row.procedure)}"
                     f": line at {row.guideline_im:.3g} {unit}, exact P there "
                     f"{row.achieved_p_fit:.0%}",
                     "marker": {"color": colour, "size": 11, "symbol": "diamond"}})
    layout = _layout(380, shapes=shapes, annotations=notes)
    layout["title"] = {"text": block_label(block), "font": {"size": 13}}
    fragility_axes(layout, f"{im} [{unit}]", levels.min() / 1.5, levels.max() * 1.5, 150, 480)
    return {"data": data, "layout": layout}


def fragility_axes(layout: dict, title: str, low: float, high: float, legend_room: int,
                   height: int) -> None:
    """A fragility figure's axes: intensity on a log axis with whole labels between ``low`` and
    ``high`` (plotly's minor labels read "2" for 0.2), P(overturn) in %, the legend below."""
    ticks = [t for t in LOG_TICKS if low <= t <= high]
    layout["xaxis"] = _axis(title, type="log", tickvals=ticks, ticktext=[f"{t:g}" for t in ticks])
    layout["yaxis"] = _axis("P(overturn)", range=[-0.02, 1.02], tickformat=".0%")
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.2, "yanchor": "top",
                        "font": {"size": 11}}
    layout["margin"]["b"] = legend_room
    layout["height"] = height


def vertical_line(x, colour, dash) -> dict:
    """A vertical line at ``x`` across the plot (a plotly shape)."""
    return {"type": "line", "xref": "x", "x0": x, "x1": x, "yref": "y domain", "y0": 0, "y1": 1,
            "line": {"color": colour, "dash": dash, "width": 1.5}}


def _top_note(x, text, colour) -> dict:
    return {"text": text, "x": math.log10(x), "xref": "x", "yref": "y domain", "y": 1.0,
            "yanchor": "bottom", "showarrow": False, "font": {"size": 11, "color": colour}}


def scan_figure(scan: pd.DataFrame, summary) -> dict:
    unit = summary["im_unit"]
    first = scan.loc[scan["exact_overturned"], "im_level"].min()
    survives = scan[~scan["exact_overturned"] & (scan["im_level"] > first)]
    theta_ratio = scan["exact_theta_rad"] / np.radians(scan["alpha_deg"])
    data = [{"type": "scatter", "mode": "markers", "x": scan["im_level"], "y": theta_ratio,
             "marker": {"size": 5, "color": np.where(scan["exact_overturned"], "#d62728",
                                                     "#1f77b4").tolist()},
             "name": "each scaled record (red: overturns)",
             "hovertemplate": f"{summary['im']} = %{{x:.5g}} {unit}<br>peak θ/α = %{{y:.3f}}"
                              "<extra></extra>"}]
    row = scan.iloc[0]
    layout = _layout(330, shapes=[vertical_line(first, "#d62728", "dot")])
    layout["title"] = {"text": f"{row['record']}, {block_label(row)}: overturns first at "
                               f"{first:.4g} {unit}; survives {len(survives)} higher levels "
                               "of the scan", "font": {"size": 12}}
    layout["xaxis"] = _axis(f"{summary['im']} of the scaled record [{unit}] (0.2 % steps)")
    layout["yaxis"] = _axis("peak θ/α [-]", range=[0, 1.05])
    layout["showlegend"] = False
    return {"data": data, "layout": layout}



__all__ = ["required_figure", "cmr_figure", "fragility_figure", "scan_figure", "fragility_axes",
           "vertical_line", "procedure_colour", "block_label", "LOG_TICKS"]
