"""The audit grid: block sizes 2π/p (light: numpy only when a grid is made, so the API's front
door can import it)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np


def size_grid(start: float, stop: float, step: float) -> np.ndarray:
    """Sizes 2π/p from ``start`` to ``stop`` inclusive [s], rounded to the step's decimals.

    Parameters
    ----------
    start, stop, step : float
        First and last size 2π/p, and the step [s].
    """
    import numpy as np
    count = int(math.floor((stop - start) / step + 1e-9)) + 1
    return np.round(start + step * np.arange(count), 10)
