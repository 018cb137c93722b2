"""Displacement spectra tabulated on periods, linear in T in between: one read as a function,
or many read at once, each block on its own row.

:func:`interp_rows` reads row ``rows[i]`` at ``period_s[i]`` with the same arithmetic as
:func:`numpy.interp` (slope·(T − Tⱼ) + Sdⱼ, the node's value at a node, the end values held
beyond the table), so the iteration gives the same iterates bit for bit whether a record's
stripes and slendernesses are iterated one spectrum at a time or all at once.
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


def interp_rows(x, xp, tables, rows):
    """``numpy.interp(x[i], xp, tables[rows[i]])`` for every i at once, bit for bit.

    Parameters
    ----------
    x : numpy.ndarray
        Where to read, 1-D.
    xp : numpy.ndarray
        Ascending abscissae of the tables, distinct.
    tables : numpy.ndarray
        Ordinates, shaped (table, len(xp)).
    rows : numpy.ndarray of int
        The table each ``x`` reads.
    """
    n = xp.size
    # numpy.interp's bracket: xp[j] ≤ x < xp[j + 1]; j = n − 1 at and beyond the last node
    j = np.searchsorted(xp, x, side="right") - 1
    left = np.clip(j, 0, n - 2)
    low, high = tables[rows, left], tables[rows, left + 1]
    slope = (high - low) / (xp[left + 1] - xp[left])
    with np.errstate(invalid="ignore"):
        out = slope * (x - xp[left]) + low
        # numpy.interp's retry from the right node where the left one gives NaN (an infinite
        # slope), and a flat piece's value where both do
        retry = np.isnan(out)
        if retry.any():
            out[retry] = slope[retry] * (x[retry] - xp[left + 1][retry]) + high[retry]
            flat = np.isnan(out) & (low == high)
            out[flat] = low[flat]
    out = np.where(x == xp[left], low, out)
    out = np.where(j >= n - 1, tables[rows, n - 1], out)
    out = np.where(j < 0, tables[rows, 0], out)
    return np.where(np.isnan(x), x, out)


__all__ = ["TabulatedDisplacement", "interp_rows"]
