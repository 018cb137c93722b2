"""A block of size 2π/p in metres: the words that name it and the secondary axes that give a
2π/p axis in metres.

A block of size 2π/p has R = 3g/(4p²) (its half-diagonal) whatever its slenderness α; its
full width is 2R sin α and its full height 2R cos α.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from audit import G
from audit.engine.shared.blocks import Block


def describe_block(alpha_deg: float, size_s: float) -> str:
    """The object a grid cell is, in metres: ``a 0.38 m × 1.15 m block`` (full width × full
    height, 2R sin α × 2R cos α with R = 3g/(4p²), p = 2π/size)."""
    block = Block(alpha_deg=float(alpha_deg), size_s=float(size_s))
    return f"a {block.width_m:.2f} m × {block.height_m:.2f} m block"


def block_size_m(alpha_deg: float, size_s: float) -> tuple[float, float]:
    """(full width, full height) [m] of the block of slenderness α and size 2π/p, to the
    centimetre: a map's hover data per cell (:func:`block_hover`), two short numbers where
    :func:`describe_block` would be a string, so that a page of many maps stays light."""
    return _block_size_m(float(alpha_deg), float(size_s))


@functools.lru_cache(maxsize=4096)
def _block_size_m(alpha_deg: float, size_s: float) -> tuple[float, float]:
    # the page's maps ask for the same few hundred cells of the grid tens of thousands of times
    block = Block(alpha_deg=alpha_deg, size_s=size_s)
    return round(block.width_m, 2), round(block.height_m, 2)


def block_sizes_m(alphas_deg, sizes_s) -> np.ndarray:
    """:func:`block_size_m` of every cell of a grid, α down and 2π/p across [m] (shape
    ``(len(alphas_deg), len(sizes_s), 2)``; read-only: shared by the maps of the same grid)."""
    return _block_sizes_m(tuple(float(a) for a in alphas_deg), tuple(float(s) for s in sizes_s))


@functools.lru_cache(maxsize=64)
def _block_sizes_m(alphas_deg: tuple, sizes_s: tuple) -> np.ndarray:
    # the checks' maps repeat one grid tens of times
    grid = np.array([[_block_size_m(a, s) for s in sizes_s] for a in alphas_deg], dtype=float)
    grid.flags.writeable = False
    return grid


def block_hover(first: int) -> str:
    """The words of :func:`describe_block` in a hover template, from a cell's
    :func:`block_size_m` at ``customdata[first]`` and ``customdata[first + 1]``."""
    return f"a %{{customdata[{first}]:.2f}} m × %{{customdata[{first + 1}]:.2f}} m block"


#: Lengths at the ticks of a metres axis [m]: round numbers, 1–2–5 in each decade.
METRE_TICKS = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0)
#: Title of a metres axis over several α: the diagonal does not depend on α, the height does.
DIAGONAL_TITLE = "block diagonal 2R [m] (height = 2R cos α)"
#: Room [px] above a plot for a titled metres axis: its tick labels and its title.
METRES_ROOM_PX = 40


def metres_axis(alpha_deg: float | None, span, overlaying: str, anchor: str,
                log: bool = False) -> dict:
    """A secondary x axis on top of the 2π/p axis ``overlaying`` spanning ``span`` [s], with the
    same range, ticked at the sizes of blocks of round lengths [m].

    The length is the block's height h = 2R cos α at slenderness ``alpha_deg`` [°], or, with
    ``alpha_deg=None`` (a figure over several α), its diagonal 2R, the same at every α (titled
    :data:`DIAGONAL_TITLE`). R = 3g/(4p²) with p = 2π/size, so size = 2π √(4R/(3g)): a
    monotone map, so the ticks sit exactly where the 2π/p axis has those sizes. ``log``: the
    2π/p axis is logarithmic; this one is too, its range in decades as plotly reads it.
    """
    cos_alpha = 1.0 if alpha_deg is None else math.cos(math.radians(alpha_deg))
    radius = np.array(METRE_TICKS) / (2.0 * cos_alpha)
    sizes = 2.0 * np.pi * np.sqrt(4.0 * radius / (3.0 * G))
    scale = np.log10 if log else np.asarray
    low, high = (float(v) for v in scale(np.asarray(span, dtype=float)))
    kept, last = [], -math.inf
    for length, size in zip(METRE_TICKS, sizes):  # a tick an eighth of the span from the last
        at = float(scale(size))
        if low <= at <= high and at - last >= (high - low) / 8.0:
            kept.append((length, size))
            last = at
    axis = {"overlaying": overlaying, "anchor": anchor, "side": "top", "range": [low, high],
            "tickvals": [size for _, size in kept],
            "ticktext": [f"{length:g} m" for length, _ in kept], "tickangle": 0,
            "tickfont": {"size": 9, "color": "#666"}, "showgrid": False, "ticks": "outside",
            "zeroline": False}
    if log:
        axis["type"] = "log"
    if alpha_deg is None:
        axis["title"] = {"text": DIAGONAL_TITLE, "font": {"size": 11, "color": "#666"},
                         "standoff": 4}
    return axis


def add_metres_axis(figure: dict, span, axis: str = "xaxis", alpha_deg: float | None = None,
                    room_px: int = 0) -> str:
    """Put a :func:`metres_axis` on top of the 2π/p axis ``axis`` (a layout key) of ``figure``
    (a plotly spec), giving both the range ``span`` [s] so that they align; the layout key of
    the new axis. Plotly draws an axis only under a trace: an empty one is added. ``room_px``
    is added to the top margin and to the height (the plot keeps its size): room above the
    plot for the axis' ticks and title (:data:`METRES_ROOM_PX`)."""
    layout = figure["layout"]
    layout["margin"]["t"] += room_px
    layout["height"] += room_px
    primary = layout[axis]
    anchor = primary.get("anchor", "y")
    number = 1 + max(int(key[5:] or 1) for key in layout if key.startswith("xaxis"))
    overlay = metres_axis(alpha_deg, span, "x" + axis[5:], anchor, primary.get("type") == "log")
    primary["range"] = list(overlay["range"])
    layout[f"xaxis{number}"] = overlay
    figure["data"].append({"type": "scatter", "x": list(span), "y": [None, None],
                           "xaxis": f"x{number}", "yaxis": anchor, "showlegend": False,
                           "hoverinfo": "skip"})
    return f"xaxis{number}"
