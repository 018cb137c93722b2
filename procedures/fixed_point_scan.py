"""The sign scan of :func:`procedures.rotation_map.fixed_points` over a tabulated spectrum,
compiled.

Apart from :mod:`procedures.rotation_map` so that reading a run back and rendering its report
(which imports the procedures' declarations) never loads numba.
"""

from __future__ import annotations

import numba
import numpy as np

from procedures.iteration_kernels import interp_between


@numba.njit(cache=True, nogil=True)
def _exact(v, grid, p, scale, period_s, sd_m, first, stop, low, out):
    """The signs of grid points ``first`` … ``stop − 1``, each in the array expression's
    operations; ``low`` is the node the first period reads, or before it. Returns the node the
    last one reads."""
    last = period_s.size - 1
    for i in range(first, stop):
        period = 4.0 * v[i] / p
        if period < period_s[0]:
            sd = sd_m[0]
        elif period >= period_s[last]:
            sd = sd_m[last]
        else:
            while period_s[low + 1] <= period:  # period_s[low] ≤ period < period_s[low + 1]
                low += 1
            sd = interp_between(period, period_s, sd_m, low, low + 1)
        out[i] = sd * scale - grid[i] > 0.0
    return low


@numba.njit(cache=True, nogil=True)
def _node_after(period, period_s, low):
    """The highest node numpy.interp reads for ``period``, walking up from node ``low``."""
    last = period_s.size - 1
    if period < period_s[0]:
        return 0
    if period >= period_s[last]:
        return last
    while period_s[low + 1] <= period:
        low += 1
    return low + 1


@numba.njit(cache=True, nogil=True)
def tabulated_excess(v, grid, p, scale, period_s, sd_m, chunk, room):
    """Whether F(θ) > θ at every point of the scan's grid, block by block: ``Sd(4v/p)·scale −
    grid > 0``, Sd read as ``numpy.interp(T, period_s, sd_m)`` reads it: the values of the
    array expression it replaces (:func:`procedures.rotation_map.fixed_points`).

    T grows along the grid (v ascending, p > 0), and Sd between two periods lies within the
    tabulated values of the nodes read between them. A chunk of ``chunk`` grid points whose
    θ/α all lie above that range's top, or all below its bottom, by more than the rounding of
    the values inside (``room``, relative), takes its sign without reading a value;
    only the chunks that hold a crossing are evaluated, each element in the array expression's
    operations. numpy's array expression read all ~10⁶ periods of a call.

    Parameters
    ----------
    v, grid : numpy.ndarray
        The grid's pT/4 ascending and θ/α at each [-].
    p, scale : numpy.ndarray
        Each block's frequency parameter [rad/s] and 1/(R cos α α) [1/m].
    period_s, sd_m : numpy.ndarray
        The spectrum's ascending periods [s] and Sd there [m].
    chunk : int
        Grid points per chunk (:data:`~procedures.rotation_map.SCAN_CHUNK`).
    room : float
        :data:`~procedures.rotation_map.ROUNDING_ROOM`.

    Returns
    -------
    numpy.ndarray of bool, shape (blocks, grid points)
    """
    size = v.size
    chunks = (size + chunk - 1) // chunk
    lowest, highest = np.empty(chunks), np.empty(chunks)
    for c in range(chunks):
        part = grid[c * chunk:min(size, (c + 1) * chunk)]
        lowest[c], highest[c] = part.min(), part.max()
    out = np.empty((p.size, size), dtype=np.bool_)
    for b in range(p.size):
        low = 0  # the node the chunk's first period reads
        for c in range(chunks):
            first, stop = c * chunk, min(size, (c + 1) * chunk)
            while low < period_s.size - 1 and period_s[low + 1] <= 4.0 * v[first] / p[b]:
                low += 1
            high = _node_after(4.0 * v[stop - 1] / p[b], period_s, low)
            top, bottom = -np.inf, np.inf
            for j in range(low, high + 1):
                if sd_m[j] != sd_m[j]:  # NaN: no bound, every value read
                    top, bottom = np.inf, -np.inf
                    break
                top, bottom = max(top, sd_m[j]), min(bottom, sd_m[j])
            top, bottom = top * scale[b], bottom * scale[b]
            if top + room * abs(top) < lowest[c]:
                out[b, first:stop] = False
            elif bottom - room * abs(bottom) > highest[c]:
                out[b, first:stop] = True
            else:
                _exact(v, grid, p[b], scale[b], period_s, sd_m, first, stop, low, out[b])
    return out


__all__ = ["tabulated_excess"]
