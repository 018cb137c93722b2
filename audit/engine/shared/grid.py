"""The audit grid: block sizes 2π/p (light: numpy only, so the CLI can parse it)."""

from __future__ import annotations

import math

import numpy as np


def size_grid(start: float, stop: float, step: float) -> np.ndarray:
    """Sizes 2π/p from ``start`` to ``stop`` inclusive [s], rounded to the step's decimals.

    Parameters
    ----------
    start, stop, step : float
        First and last size 2π/p, and the step [s].
    """
    count = int(math.floor((stop - start) / step + 1e-9)) + 1
    return np.round(start + step * np.arange(count), 10)
