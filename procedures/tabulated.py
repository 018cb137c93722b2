"""A displacement spectrum tabulated on periods, linear in T in between: a function of T that
also shows its table, so the iteration can read it compiled
(:func:`procedures.iteration.iterate_tabulated`) and many of them at once; and one whose table
is computed where it is read (:class:`TabulatedOnDemand`).
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


class TabulatedOnDemand:
    """A record's Sd(T) × ``factor`` [m], linear in T between ``period_s`` [s] as
    :class:`TabulatedDisplacement`, whose tabulated values are computed only where they are read
    (``source``, an :class:`audit.physics.response_spectra.DisplacementOnDemand` of the unscaled
    record, keeps them for every reader). Each value read is the source's × ``factor``, as the
    whole table scaled would hold it, so every reading equals that table's bit for bit.

    Attributes
    ----------
    period_s : numpy.ndarray
        Ascending periods [s].
    sd_m : numpy.ndarray
        Sd × factor [m] where ``known``, NaN elsewhere.
    known : numpy.ndarray of bool
    factor : float
    source : audit.physics.response_spectra.DisplacementOnDemand
    """

    def __init__(self, source, factor: float):
        self.source, self.factor = source, float(factor)
        self.period_s = source.period_s
        self.sd_m = source.sd_m * self.factor
        self.known = source.known.copy()

    def __call__(self, period_s):
        period_s = np.asarray(period_s, dtype=float)
        left = np.searchsorted(self.period_s, period_s.ravel(), side="right") - 1
        # the nodes numpy.interp reads: either side of each T, the end ones beyond the table
        self.read(np.clip(np.concatenate((left, left + 1)), 0, self.period_s.size - 1))
        return np.interp(period_s, self.period_s, self.sd_m)

    def read(self, index) -> None:
        """Make the table known at the indices ``index``."""
        index = np.asarray(index, dtype=np.intp)
        new = index[~self.known[index]]
        if new.size:
            self.source.fill(new)
            self.sd_m[new] = self.source.sd_m[new] * self.factor
            self.known[new] = True

    def kernel_arguments(self) -> tuple:
        """What :func:`procedures.iteration_kernels.iterate_on_demand` reads the table through:
        (known, factor, then the source's
        :meth:`~audit.physics.response_spectra.DisplacementOnDemand.kernel_arguments`)."""
        return (self.known, self.factor) + self.source.kernel_arguments()


__all__ = ["TabulatedDisplacement", "TabulatedOnDemand"]
