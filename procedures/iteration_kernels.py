"""The fixed-point iteration's per-step bookkeeping, compiled (see
:func:`procedures.iteration.iterate_rotation`).

Apart from :mod:`procedures.iteration` so that reading a run back and rendering its report (which
imports the procedures' declarations) never loads numba.
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def may_repeat(window: np.ndarray, cycle_tolerance: float, max_length: int) -> bool:
    """Whether the iterates ``window`` (newest last) may hold a settled cycle (see
    :func:`procedures.iteration._cycle_length`).

    A necessary condition, cheap enough for every iteration: the newest iterate repeats the one
    L before it, for some L ≤ ``max_length``, to ``cycle_tolerance`` of the whole window's
    spread (which bounds the spread of the last L iterates); NaN (before the first iterates)
    is left out of the spread and repeats nothing.
    """
    high, low = -np.inf, np.inf
    for value in window:
        if value == value:
            high, low = max(high, value), min(low, value)
    bound = cycle_tolerance * (high - low) if high >= low else np.nan
    newest = window[-1]
    for length in range(2, max_length + 1):
        if abs(newest - window[-1 - length]) <= bound:
            return True
    return False


@numba.njit(cache=True, nogil=True)
def advance(recent: np.ndarray, new: np.ndarray, tolerance: float, cycle_tolerance: float,
            max_length: int):
    """One step of the iteration's bookkeeping for every block still iterating: ``new``
    overturns (θ/α ≥ 1) or has converged (|Δθ|/α ≤ ``tolerance``), is pushed into the window
    ``recent`` (1 for an overturning one), and the others may have settled in a cycle
    (:func:`may_repeat`, with cycles up to ``max_length`` iterates).

    Compiled, with :func:`may_repeat`: it runs at every iteration, where a dozen small array
    operations cost several times the map itself (a chaotic block iterates 2000 times).

    Returns
    -------
    over, done, maybe : numpy.ndarray of bool
    """
    rows, width = recent.shape
    over = np.zeros(rows, dtype=np.bool_)
    done = np.zeros(rows, dtype=np.bool_)
    maybe = np.zeros(rows, dtype=np.bool_)
    for row in range(rows):
        over[row] = new[row] >= 1.0
        done[row] = not over[row] and abs(new[row] - recent[row, width - 1]) <= tolerance
        recent[row, :width - 1] = recent[row, 1:].copy()
        recent[row, width - 1] = 1.0 if over[row] else new[row]
        maybe[row] = (not (over[row] or done[row])
                      and may_repeat(recent[row], cycle_tolerance, max_length))
    return over, done, maybe


__all__ = ["advance", "may_repeat"]
