"""What every figure of the pages is built from: plotly.js specifications (``{"data", "layout"}``
dicts), their layout and axes, and their JSON.

The browser draws the figures from the embedded data (plotly.js is inlined once in the page), so
hovering a block shows its values and spectra can be zoomed; nothing is drawn on the server.
Every ``*_figure`` function (:mod:`reports.grid_figures`, :mod:`reports.spectra_figures`,
:mod:`reports.history_figures`) takes plain frames and returns a JSON-ready dict; floats are
rounded to :data:`SIGNIFICANT_DIGITS` when the page is written (:func:`to_json`). Units on every
axis; the same colour for the same slenderness α, damping ratio and verdict everywhere.
"""

from __future__ import annotations

import math

import numpy as np
import orjson
import pandas as pd

from reports.block_metres import METRES_ROOM_PX, add_metres_axis


#: Significant digits of the numbers embedded in the page.
SIGNIFICANT_DIGITS = 4
_FONT = {"family": "DejaVu Sans, Helvetica, Arial, sans-serif", "size": 12}


def rounded(values) -> np.ndarray:
    """Floats rounded to :data:`SIGNIFICANT_DIGITS` [same unit], all at once; NaN stays NaN,
    ±inf (and a value next to the largest double that rounds past it) becomes NaN: JSON has
    neither, both are written as null.

    Each value is the integer n = rint(x·10^k), with k making n hold the significant digits,
    over 10^k: n and 10^k are exact doubles, so the quotient is the double nearest the decimal
    n·10^(−k), the one the shortest representation writes back as those digits. 10^k is exact
    for |k| ≤ 22 only, so magnitudes outside 1e-18 … 1e24 (none in a figure of this tool) take
    the formatted digits one by one.
    """
    values = np.array(values, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        magnitude = np.abs(values)
        ordinary = (magnitude >= 1e-18) & (magnitude < 1e24)
        x = values[ordinary]
        k = SIGNIFICANT_DIGITS - 1 - np.floor(np.log10(np.abs(x))).astype(int)
        n = np.rint(x * 10.0 ** k)
        values[ordinary] = np.where(k >= 0, n / 10.0 ** np.maximum(k, 0),
                                    n * 10.0 ** np.maximum(-k, 0))
        extreme = np.isfinite(values) & ~ordinary & (values != 0.0)
        values[extreme] = [float(f"{v:.{SIGNIFICANT_DIGITS}g}") for v in values[extreme]]
        values[~np.isfinite(values)] = np.nan
    return values


def _rounded_scalar(value: float):
    """One float as :func:`rounded` and :func:`_json_numbers` give it inside an array (the same
    rint(x·10^k)/10^k in IEEE doubles), without numpy's per-call cost: figures carry thousands
    of lone floats in their hover data."""
    magnitude = abs(value)
    if not 1e-18 <= magnitude < 1e24:
        return _json_numbers(rounded([value]))[0]
    k = SIGNIFICANT_DIGITS - 1 - math.floor(math.log10(magnitude))
    n = float(round(value * 10.0 ** k))
    x = n / 10.0 ** k if k >= 0 else n * 10.0 ** -k
    if x != x or x in (math.inf, -math.inf):
        return None
    return int(x) if x.is_integer() and abs(x) < 1e15 else x


def _json_numbers(values: np.ndarray):
    """Rounded floats as JSON-ready nested lists: an int where integral (a lighter page), None
    for NaN; sorted by masks, not value by value."""
    out = values.astype(object)
    with np.errstate(invalid="ignore"):
        whole = (values == np.trunc(values)) & (np.abs(values) < 1e15)
    out[whole] = values[whole].astype(np.int64)
    out[np.isnan(values)] = None
    return out.tolist()


def to_json(spec) -> str:
    """The spec as compact JSON, numbers rounded, NaN/inf as null, safe inside ``<script>``.

    Arrays and lists of numbers (the bulk of every figure) are rounded in one vectorised step
    and serialised by orjson.
    """
    def clean(value):
        kind = type(value)
        if kind is dict:
            return {k: clean(v) for k, v in value.items()}
        if kind in (list, tuple):
            if value and all(type(v) is float for v in value):
                return _json_numbers(rounded(value))
            return [clean(v) for v in value]
        if kind in (str, int, bool) or value is None:
            return value
        if isinstance(value, (np.ndarray, pd.Series, pd.Index)):
            value = np.asarray(value)
            if value.dtype.kind == "f":
                return _json_numbers(rounded(value))
            return value if value.dtype.kind in "biu" else clean(value.tolist())
        if isinstance(value, (float, np.floating)):
            return _rounded_scalar(float(value))
        return value
    text = orjson.dumps(clean(spec), option=orjson.OPT_SERIALIZE_NUMPY).decode()
    return text.replace("</", "<\\/")


def _layout(height, **extra):
    layout = {"height": height, "margin": {"l": 70, "r": 20, "t": 40, "b": 50}, "font": _FONT,
              "plot_bgcolor": "#ffffff", "hovermode": "closest",
              "legend": {"orientation": "v", "x": 1.02, "xanchor": "left", "y": 1.0,
                         "font": {"size": 11}}}
    layout.update(extra)
    return layout


def _axis(title, domain=None, anchor=None, **extra):
    axis = {"title": {"text": title, "font": {"size": 12}}, "gridcolor": "#e5e5e5",
            "zeroline": False, "linecolor": "#888888", "mirror": True, "ticks": "outside"}
    if domain is not None:
        axis["domain"] = domain
    if anchor is not None:
        axis["anchor"] = anchor
    axis.update(extra)
    return axis


def required_alpha_layout() -> dict:
    """The layout of a required-slenderness chart: α against the block size 2π/p, the legend
    below, the top margin left for a metres axis to add (``reports.block_metres``)."""
    layout = _layout(440)
    layout["margin"]["t"] = 20
    layout["xaxis"] = _axis("block size 2π/p [s]")
    layout["yaxis"] = _axis("required α [°]")
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.18, "yanchor": "top"}
    layout["margin"]["b"] = 120
    return layout


def cell_span(centres) -> list[float]:
    """The extent [same unit] of a heatmap's cells along an axis of their ``centres``, as
    plotly draws them: half a step beyond the first and the last centre (a lone cell is 1
    wide)."""
    x = np.unique(np.asarray(centres, dtype=float))
    if x.size == 1:
        return [float(x[0]) - 0.5, float(x[0]) + 0.5]
    return [float(x[0] - (x[1] - x[0]) / 2), float(x[-1] + (x[-1] - x[-2]) / 2)]


def alpha_size_map(data: list, alphas, sizes) -> dict:
    """A heatmap figure over α (rows, one tick per α) and 2π/p (columns) of ``data``, with the
    blocks' diagonal in metres on a top axis."""
    layout = _layout(120 + 50 * max(len(alphas), 1))
    layout["margin"]["t"] = 20
    layout["xaxis"] = _axis("block size 2π/p [s]")
    layout["yaxis"] = _axis("α [°]", tickvals=alphas, ticktext=[f"{a:g}°" for a in alphas])
    figure = {"data": data, "layout": layout}
    add_metres_axis(figure, cell_span(sizes), room_px=METRES_ROOM_PX)
    return figure


def padded_span(values, fraction: float = 0.03) -> list[float]:
    """The extent of ``values`` [same unit] with ``fraction`` of it added on each side (0.1
    where all are equal), room for the markers at the ends; NaN ignored."""
    x = np.asarray(values, dtype=float)
    low, high = float(np.nanmin(x)), float(np.nanmax(x))
    pad = fraction * (high - low) or 0.1
    return [low - pad, high + pad]


def _domains(count, gap):
    """``count`` equal [bottom, top] paper domains from the top down, ``gap`` apart."""
    height = (1.0 - gap * (count - 1)) / count
    return [[1.0 - (i + 1) * height - i * gap, 1.0 - i * height - i * gap] for i in range(count)]


def _stacked(count, panel_px=78, gap_px=26, margins_px=70):
    """Height [px] of a figure of ``count`` stacked map panels and the gap between them as a
    fraction of the plot area (room for each panel's title)."""
    height = margins_px + count * panel_px + (count - 1) * gap_px
    return height, gap_px / (height - margins_px)


def _ref(n):
    return "" if n == 1 else str(n)


def _note(text, xref, yref, y=0.5):
    return {"text": text, "xref": f"{xref} domain", "yref": f"{yref} domain", "x": 0.5, "y": y,
            "showarrow": False, "font": {"size": 12, "color": "#555555"}}


def _literal(text: str) -> str:
    """``text`` shown as it is inside a plotly hover template (no ``%{...}`` substitution)."""
    return str(text).replace("%{", "%\u200b{")
