"""The audit grid: slendernesses and block sizes (light: numpy only, so the CLI can parse it)."""

from __future__ import annotations

import math

import numpy as np

DEFAULT_ALPHA_DEG = (10.0, 15.0, 20.0)
#: Block sizes 2π/p: START, STOP (inclusive), STEP [s].
DEFAULT_SIZES = (0.5, 8.0, 0.05)


def size_grid(start: float, stop: float, step: float) -> np.ndarray:
    """Sizes 2π/p from ``start`` to ``stop`` inclusive [s], rounded to the step's decimals."""
    count = int(math.floor((stop - start) / step + 1e-9)) + 1
    return np.round(start + step * np.arange(count), 10)
