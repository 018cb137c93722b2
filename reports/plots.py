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


def _json_objects(values: np.ndarray) -> np.ndarray:
    """Rounded floats as JSON-ready objects: an int where integral (a lighter page), None for
    NaN; sorted by masks, not value by value."""
    out = values.astype(object)
    with np.errstate(invalid="ignore"):
        whole = (values == np.trunc(values)) & (np.abs(values) < 1e15)
    out[whole] = values[whole].astype(np.int64)
    out[np.isnan(values)] = None
    return out


#: Types orjson writes as they are (no rounding).
_AS_IS = frozenset((str, int, bool, type(None)))
#: Types of a list that is numbers to round, None written as null.
_NUMBERS = frozenset((float, np.float64, type(None)))


class _Numbers:
    """The floats of one spec, rounded together once the spec has been walked: one numpy pass
    per figure, not one per array or per lone float (a figure holds hundreds of short arrays
    and thousands of hover numbers, where numpy's per-call cost would be most of the work)."""

    def __init__(self):
        self.arrays = []  # (list to fill, the float array it stands for)
        self.places = []  # (dict or list, key) of a lone float
        self.alone = []  # the lone floats, in the order of places

    def place(self, container, key, item):
        """Put ``item`` JSON-ready at ``container[key]`` (a lone float: once rounded)."""
        if type(item) is float or isinstance(item, np.floating) or (
                isinstance(item, np.ndarray) and item.ndim == 0 and item.dtype.kind == "f"):
            container[key] = None  # holds the key's place in a dict's order
            self.places.append((container, key))
            self.alone.append(item)
        else:
            container[key] = self.clean(item)

    def clean(self, value):
        """``value`` (not a lone float) JSON-ready, its floats left for :meth:`fill`."""
        kind = type(value)
        if kind is dict:
            out = dict(value)
            for key, item in value.items():
                if type(item) not in _AS_IS:
                    self.place(out, key, item)
            return out
        if kind is list or kind is tuple:
            kinds = set(map(type, value))
            if kinds <= _AS_IS:
                return value
            if kinds <= _NUMBERS:  # None becomes NaN, written as null as a lone None is
                return self._later(np.array(value, dtype=float))
            out = list(value)
            for i, item in enumerate(value):
                if type(item) not in _AS_IS:
                    self.place(out, i, item)
            return out
        if isinstance(value, (np.ndarray, pd.Series, pd.Index)):
            value = np.asarray(value)
            if value.dtype.kind == "f":
                return self._later(value)
            return value if value.dtype.kind in "biu" else self.clean(value.tolist())
        return value

    def _later(self, values: np.ndarray) -> list:
        slot = []
        self.arrays.append((slot, values))
        return slot

    def fill(self):
        """Round every float at once and put each where it belongs."""
        flat = _json_objects(rounded(np.concatenate(
            [values.ravel() for _, values in self.arrays] + [np.array(self.alone, dtype=float)])))
        start = 0
        for slot, values in self.arrays:
            slot.extend(flat[start:start + values.size].reshape(values.shape).tolist())
            start += values.size
        for (container, key), number in zip(self.places, flat[start:].tolist()):
            container[key] = number


def to_json(spec) -> str:
    """The spec as compact JSON, numbers rounded, NaN/inf as null, safe inside ``<script>``.

    Every float of the spec (arrays, lists and lone hover numbers) is rounded in one vectorised
    step, and the result serialised by orjson; lists of text pass untouched.
    """
    numbers = _Numbers()
    holder = [None]
    numbers.place(holder, 0, spec)
    numbers.fill()
    text = orjson.dumps(holder[0], option=orjson.OPT_SERIALIZE_NUMPY).decode()
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
