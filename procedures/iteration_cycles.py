"""The cycles the fixed-point iteration of Priestley, Evison & Carr (1978) may settle in
(:mod:`procedures.iteration`): when one has settled, of what length, and how it is described.
"""

from __future__ import annotations

import numpy as np

from procedures.rotation_map import ratios_text

#: Longest cycle of the iteration that is recognised as such.
MAX_CYCLE_LENGTH = 8
#: A cycle of length L has settled when the last L iterates repeat the L before them to this
#: fraction of the cycle's spread (max − min). Relative, because cycles settle geometrically at
#: their own rate and amplitude; a contracting alternation towards a fixed point (slope −0.99)
#: differs by ~1 % of its spread between every other iterate, far above this.
CYCLE_TOLERANCE_RATIO = 1e-6
#: A settled cycle of length L is read as one of length d | L when its iterates repeat after d
#: steps to this fraction of its spread (see :func:`cycle_length`).
SUBCYCLE_TOLERANCE_RATIO = 1e-3


# All cycle lengths L are tested at once: row L − 2 of _PERIOD_INDEX picks the last L iterates
# of ``recent`` (its oldest repeated up to MAX_CYCLE_LENGTH columns, harmless for max, min and
# the comparison), and _PERIOD_INDEX − L the L iterates before them.
_CYCLE_SIZES = np.arange(2, MAX_CYCLE_LENGTH + 1)[:, None]
_PERIOD_INDEX = -1 - np.minimum(np.arange(MAX_CYCLE_LENGTH), _CYCLE_SIZES - 1)


def cycle_length(recent: np.ndarray) -> np.ndarray:
    """Length L ≤ :data:`MAX_CYCLE_LENGTH` of the cycle the rows of ``recent`` settled in, or 0.

    ``recent`` holds the last 2·MAX_CYCLE_LENGTH iterates θ/α of each block, newest last (NaN
    before the first). A cycle of length L has settled when a whole period, the last L iterates,
    repeats the L before it to :data:`CYCLE_TOLERANCE_RATIO` of its spread; the shortest such L
    counts. A cycle that settles from alternate sides (multiplier of F∘F near −1) repeats at 2L
    before it does at L, so the period found is reduced to its shortest divisor whose iterates
    already repeat to :data:`SUBCYCLE_TOLERANCE_RATIO` of the spread.
    """
    period, before = recent[:, _PERIOD_INDEX], recent[:, _PERIOD_INDEX - _CYCLE_SIZES]
    spread = period.max(axis=2) - period.min(axis=2)
    repeats = (np.all(np.abs(period - before) <= CYCLE_TOLERANCE_RATIO * spread[..., None], axis=2)
               & (spread > 0.0))
    length = np.where(repeats.any(axis=1), _CYCLE_SIZES[np.argmax(repeats, axis=1), 0], 0)
    for row in np.flatnonzero(length):
        window = recent[row, -length[row]:]
        bound = SUBCYCLE_TOLERANCE_RATIO * np.ptp(window)
        length[row] = next(size for size in range(2, length[row] + 1)
                           if length[row] % size == 0
                           and np.all(np.abs(window[size:] - window[:-size]) <= bound))
    return length


def cycle_text(recent, length: int, initial_ratio: float) -> tuple[str, str]:
    """The cycle of the last ``length`` iterates of ``recent`` and what the iteration did."""
    values = np.sort(recent[-length:])
    return ratios_text(values), (
        f"iterates settle in a {length}-cycle between θ/α = {values[0]:.4f} and "
        f"{values[-1]:.4f} (no fixed point reached from θ₀/α = {initial_ratio:g})")


def unsettled_text(recent, max_iterations: int) -> str:
    """What an iteration that settled in nothing within ``max_iterations`` did."""
    return (f"no settled value or cycle after {max_iterations} iterations "
            f"(last iterates θ/α = {recent[-2]:.4f}, {recent[-1]:.4f})")


__all__ = ["CYCLE_TOLERANCE_RATIO", "MAX_CYCLE_LENGTH", "SUBCYCLE_TOLERANCE_RATIO", "cycle_length",
           "cycle_text", "unsettled_text"]
