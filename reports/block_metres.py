"""A block of size 2π/p in metres: the words that name it and the secondary axes that give a
2π/p axis in metres.

A block of size 2π/p has R = 3g/(4p²) (its half-diagonal) whatever its slenderness α; its
full width is 2R sin α and its full height 2R cos α.
"""

from __future__ import annotations

import math

import numpy as np

from audit import G
from audit.physics.block import RigidBlock


def describe_block(alpha_deg: float, size_s: float) -> str:
    """The object a grid cell is, in metres: ``a 0.38 m × 1.15 m block`` (full width × full
    height, 2R sin α × 2R cos α with R = 3g/(4p²), p = 2π/size)."""
    block = RigidBlock.from_size(float(size_s), math.radians(float(alpha_deg)))
    return f"a {2 * block.half_width:.2f} m × {2 * block.half_height:.2f} m block"


#: Heights of the ticks of a metres axis [m].
METRE_TICKS = (0.1, 0.2, 0.3, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0, 30.0, 50.0)


def metres_axis(alpha_deg: float, span, overlaying: str, anchor: str) -> dict:
    """A secondary x axis, on top of a 2π/p axis spanning ``span`` [s], labelled with the
    height [m] of the block of each size at slenderness α: h = 2R cos α, R = 3g/(4p²),
    p = 2π/size, so size = 2π √(2R/(3g)) with R = h/(2 cos α)."""
    radius = np.array(METRE_TICKS) / (2.0 * math.cos(math.radians(alpha_deg)))
    sizes = 2.0 * np.pi * np.sqrt(4.0 * radius / (3.0 * G))
    kept, last = [], -math.inf
    for height, size in zip(METRE_TICKS, sizes):  # a tick an eighth of the span from the last
        if span[0] <= size <= span[1] and size - last >= (span[1] - span[0]) / 8.0:
            kept.append((height, size))
            last = size
    return {"overlaying": overlaying, "anchor": anchor, "side": "top", "range": list(span),
            "tickvals": [size for _, size in kept],
            "ticktext": [f"{height:g} m" for height, _ in kept], "tickangle": 0,
            "tickfont": {"size": 9, "color": "#666"}, "showgrid": False, "ticks": "outside",
            "zeroline": False}
