"""A displacement spectrum tabulated on periods, linear in T in between: a function of T that
also shows its table, so the iteration can read it compiled
(:func:`procedures.iteration.iterate_tabulated`) and many of them at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class TabulatedDisplacement:
    """Sd(T) [m], linear in T between ``period_s`` [s], the end values held beyond them.

    Attributes
    ----------
    period_s : numpy.ndarray
        Ascending periods [s].
    sd_m : numpy.ndarray
        Sd at those periods [m].
    """

    period_s: np.ndarray
    sd_m: np.ndarray

    def __call__(self, period_s):
        return np.interp(period_s, self.period_s, self.sd_m)


__all__ = ["TabulatedDisplacement"]
