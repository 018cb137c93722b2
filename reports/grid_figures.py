"""Figures over the grid of blocks (2π/p across, α up): the verdict map of a procedure, maps of
suite statistics and limit-state checks, and the suite's approx/exact band per α."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pandas as pd

from reports.block_metres import METRES_ROOM_PX, add_metres_axis, block_hover, block_size_m, \
    block_sizes_m
from reports.frame_rows import row_dicts
from reports.outcome_words import describe_exact, describe_guideline
from reports.palette import VERDICT_COLOURS, alpha_colour
from reports.plots import _axis, _domains, _layout, _literal, _ref, _stacked, cell_span, \
    padded_span

#: What a cell of a verdict map says on hover (``describe_exact``, ``describe_guideline``).
CELL_COLUMNS = ("alpha_deg", "size_s", "verdict", "exact_overturned", "exact_fragile",
                "exact_theta_rad", "approx_outcome", "approx_theta_rad", "approx_period_s",
                "approx_cycle")


def _metres_on_top(figure: dict, sizes) -> dict:
    """The block diagonal over the top panel of a stack of maps (its x axis ``xaxis``, which
    the others match), the top panel's name lifted above the axis' title."""
    add_metres_axis(figure, cell_span(sizes), room_px=METRES_ROOM_PX)
    figure["layout"]["annotations"][0]["yshift"] = METRES_ROOM_PX - 4
    return figure


def verdict_map_figure(results: pd.DataFrame, records: list, names: dict, verdicts) -> dict:
    """Verdict of every block of one procedure: 2π/p across, α up, one panel per record.

    Hovering a cell shows record, α, 2π/p, the exact and the guideline's values and the verdict
    (``customdata``); blocks whose exact overturning is fragile are marked ×.
    """
    codes = {v: i for i, v in enumerate(verdicts)}
    colourscale = []
    for i, verdict in enumerate(verdicts):
        colour = VERDICT_COLOURS[verdict]
        colourscale += [[i / len(verdicts), colour], [(i + 1) / len(verdicts), colour]]
    height, gap = _stacked(len(records))
    domains = _domains(len(records), gap)
    data, layout = [], _layout(height, margin={"l": 60, "r": 20, "t": 20, "b": 50})
    present = set()
    results = results[["record", *CELL_COLUMNS]]  # each selection below copies these only
    for n, record in enumerate(records, start=1):
        rows = results[results["record"] == record].sort_values(["alpha_deg", "size_s"])
        alphas = sorted(rows["alpha_deg"].unique())
        sizes = np.sort(rows["size_s"].unique())
        # each row's cell: the α and sizes are the rows' own, so each is found exactly
        cells_i = np.searchsorted(np.array(alphas), rows["alpha_deg"].to_numpy())
        cells_j = np.searchsorted(sizes, rows["size_s"].to_numpy())
        z = np.full((len(alphas), sizes.size), np.nan)
        custom = [[None] * sizes.size for _ in alphas]
        fragile_x, fragile_y = [], []
        for i, j, row in zip(cells_i.tolist(), cells_j.tolist(), row_dicts(rows, CELL_COLUMNS)):
            z[i, j] = codes[row["verdict"]]
            present.add(row["verdict"])
            custom[i][j] = [describe_exact(row), describe_guideline(row), row["verdict"],
                            *block_size_m(row["alpha_deg"], row["size_s"])]
            if row["exact_fragile"] is True:
                fragile_x.append(row["size_s"])
                fragile_y.append(row["alpha_deg"])
        data.append({
            "type": "heatmap", "x": sizes, "y": alphas, "z": z, "customdata": custom,
            "zmin": -0.5, "zmax": len(verdicts) - 0.5, "colorscale": colourscale,
            "showscale": False, "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}",
            "xgap": 0, "ygap": 1,
            # the record's name once per panel, not once per cell: it keeps the page light
            "hovertemplate": f"{_literal(names.get(record, record))}<br>"
                             f"α = %{{y:~g}}°, 2π/p = %{{x:.2f}} s: {block_hover(3)}<br>"
                             "exact: %{customdata[0]}<br>guideline: %{customdata[1]}<br>"
                             "<b>%{customdata[2]}</b><extra></extra>"})
        if fragile_x:
            data.append({"type": "scatter", "mode": "markers", "x": fragile_x, "y": fragile_y,
                         "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}", "hoverinfo": "skip",
                         "marker": {"symbol": "x", "size": 7, "color": "#ffffff",
                                    "line": {"width": 1, "color": "#000000"}},
                         "name": "fragile overturning (×)", "showlegend": False,
                         "legendgroup": "fragile"})
        layout[f"xaxis{_ref(n)}"] = _axis("2π/p [s]" if n == len(records) else "",
                                          anchor=f"y{_ref(n)}", matches="x" if n > 1 else None,
                                          showticklabels=n == len(records))
        layout[f"yaxis{_ref(n)}"] = _axis("α [°]", domain=domains[n - 1], anchor=f"x{_ref(n)}",
                                          tickvals=alphas, ticktext=[f"{a:g}°" for a in alphas],
                                          fixedrange=True)
        layout.setdefault("annotations", []).append({
            "text": f"<b>{names.get(record, record)}</b>", "xref": "paper",
            "yref": "paper", "x": 0, "y": domains[n - 1][1], "yanchor": "bottom",
            "xanchor": "left", "showarrow": False, "font": {"size": 11}})
    for key in list(layout):
        if key.startswith("xaxis") and layout[key].get("matches") is None:
            layout[key].pop("matches", None)
    layout["showlegend"] = False
    figure = _metres_on_top({"data": data, "layout": layout}, results["size_s"])
    return dict(figure, present=[v for v in verdicts if v in present])


def _pivot(rows: pd.DataFrame, value: str):
    """``value`` over (α, size): the α and sizes that have a value, and the first value of each
    cell (NaN where none), as ``pivot_table(aggfunc="first")`` gives it, without its cost."""
    values = rows[value].to_numpy(dtype=float)
    keep = ~np.isnan(values)
    alphas, i = np.unique(rows["alpha_deg"].to_numpy(dtype=float)[keep], return_inverse=True)
    sizes, j = np.unique(rows["size_s"].to_numpy(dtype=float)[keep], return_inverse=True)
    z = np.full((alphas.size, sizes.size), np.nan)
    _, first = np.unique(i * sizes.size + j, return_index=True)  # each cell's first row
    z[i[first], j[first]] = values[keep][first]
    return alphas, sizes, z


class MapColours(NamedTuple):
    """How :func:`grid_map_figure` colours its cells: the plotly colour scale from ``low`` to
    ``high``, the colour bar's title (no bar when None), and the words of the integer codes of
    the value (``labels[z]``), if it holds codes."""

    scale: list
    low: float
    high: float
    bar: str | None = None
    labels: list | None = None


def grid_map_figure(frame: pd.DataFrame, value: str, panels: list, title_of, hover: str,
                    colours: MapColours) -> dict:
    """A map of ``value`` over (2π/p across, α up), one panel per key of ``panels``
    (``frame`` rows selected by ``panels[i][1]``, a boolean mask); for suite statistics and
    limit-state checks. ``hover`` is the hover template, where ``{title}`` stands for the
    panel's title, ``{block}`` for the block the cell is, in metres
    (:func:`~reports.block_metres.block_hover`), and ``%{text}`` for ``labels[z]`` when
    ``colours.labels`` name the integer codes of ``value``."""
    colourscale, zmin, zmax, colourbar, labels = colours
    height, gap = _stacked(len(panels))
    domains = _domains(len(panels), gap)
    data, annotations, drawn = [], [], []
    layout = _layout(height, margin={"l": 60, "r": 90 if colourbar else 20, "t": 20, "b": 50})
    for n, (key, mask) in enumerate(panels, start=1):
        alphas, sizes, z = _pivot(frame[mask], value)
        drawn.append(sizes)
        title = title_of(key)
        data.append({"type": "heatmap", "x": sizes, "y": alphas, "z": z,
                     # one float array: its numbers are rounded for the page all at once
                     "customdata": block_sizes_m(alphas, sizes),
                     "colorscale": colourscale, "zmin": zmin, "zmax": zmax,
                     "showscale": bool(colourbar) and n == 1, "ygap": 1,
                     "colorbar": {"title": {"text": colourbar or ""}, "len": 1, "x": 1.01,
                                  "thickness": 12, "tickformat": ".0%"},
                     "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}",
                     "hovertemplate": hover.replace("{title}", _literal(title)).replace(
                         "{block}", block_hover(0))})
        if labels is not None:  # "" where no value: the index past the labels
            words = np.array([*labels, ""], dtype=object)
            data[-1]["text"] = words[np.where(np.isfinite(z), z, len(labels)).astype(int)].tolist()
        layout[f"xaxis{_ref(n)}"] = _axis("2π/p [s]" if n == len(panels) else "",
                                          anchor=f"y{_ref(n)}", showticklabels=n == len(panels))
        if n > 1:
            layout[f"xaxis{_ref(n)}"]["matches"] = "x"
        layout[f"yaxis{_ref(n)}"] = _axis("α [°]", domain=domains[n - 1], anchor=f"x{_ref(n)}",
                                          tickvals=alphas, ticktext=[f"{a:g}°" for a in alphas],
                                          fixedrange=True)
        annotations.append({"text": f"<b>{title}</b>", "xref": "paper", "yref": "paper", "x": 0,
                            "y": domains[n - 1][1], "yanchor": "bottom", "xanchor": "left",
                            "showarrow": False, "font": {"size": 11}})
    layout["annotations"] = annotations
    layout["showlegend"] = False
    return _metres_on_top({"data": data, "layout": layout}, np.concatenate(drawn))


def ratio_band_figure(suite: pd.DataFrame) -> dict:
    """Suite statistics: median approx/exact against 2π/p per α with the 16–84 % band."""
    data = []
    for alpha, group in suite.groupby("alpha_deg"):
        group = group.sort_values("size_s")
        colour = alpha_colour(alpha)
        x = group["size_s"].to_numpy(dtype=float)
        data.append({"type": "scatter", "mode": "lines", "x": np.concatenate([x, x[::-1]]),
                     "y": np.concatenate([group["ratio_p84"].to_numpy(dtype=float),
                                          group["ratio_p16"].to_numpy(dtype=float)[::-1]]),
                     "fill": "toself", "fillcolor": colour, "opacity": 0.2,
                     "line": {"width": 0}, "hoverinfo": "skip", "legendgroup": f"a{alpha}",
                     "name": f"α = {alpha:g}°: 16–84 %"})
        data.append({"type": "scatter", "mode": "lines", "x": x, "y": group["ratio_p50"],
                     "line": {"color": colour, "width": 1.5}, "legendgroup": f"a{alpha}",
                     "name": f"α = {alpha:g}°: median",
                     "hovertemplate": f"α = {alpha:g}°, 2π/p = %{{x:.2f}} s<br>"
                                      "median approx/exact = %{y:.3f}<extra></extra>"})
    layout = _layout(380)
    layout["margin"]["t"] = 20
    layout["xaxis"] = _axis("2π/p [s]")
    # whole numbers on the log axis: plotly's default minor labels read "3" for 30
    ticks = [0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100]
    layout["yaxis"] = _axis("approx/exact [-] where both survive", type="log", tickvals=ticks,
                            ticktext=[f"{t:g}" for t in ticks])
    layout["shapes"] = [{"type": "line", "xref": "x domain", "x0": 0, "x1": 1, "yref": "y",
                         "y0": 1, "y1": 1, "line": {"color": "#888888", "dash": "dot"}}]
    figure = {"data": data, "layout": layout}
    add_metres_axis(figure, padded_span(suite["size_s"], 0.0), room_px=METRES_ROOM_PX)
    return figure
