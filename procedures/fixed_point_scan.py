"""The sign scan of :func:`procedures.rotation_map.fixed_points` over a tabulated spectrum,
compiled.

Apart from :mod:`procedures.rotation_map` so that reading a run back and rendering its report
(which imports the procedures' declarations) never loads numba.
"""

from __future__ import annotations

import numpy as np

from audit.physics.kernel_cache import kernel
from procedures.iteration_kernels import interp_between


@kernel()
def _read(period, period_s, sd_m, low):
    """``numpy.interp(period, period_s, sd_m)``, the node it reads found by walking up from node
    ``low`` (at or before it: periods are read in ascending order). Returns (Sd, that node)."""
    last = period_s.size - 1
    if period < period_s[0]:
        return sd_m[0], low
    if period >= period_s[last]:
        return sd_m[last], last
    while period_s[low + 1] <= period:  # period_s[low] ≤ period < period_s[low + 1]
        low += 1
    return interp_between(period, period_s, sd_m, low, low + 1), low


@kernel()
def tabulated_excess(v, grid, p, scale, period_s, sd_m, chunk, room):
    """Whether F(θ) > θ at every point of the scan's grid, block by block: ``Sd(4v/p)·scale −
    grid > 0``, Sd read as ``numpy.interp(T, period_s, sd_m)`` reads it: the values of the
    array expression it replaces (:func:`procedures.rotation_map.fixed_points`).

    T grows along the grid (v ascending, p > 0), and Sd, linear between nodes, lies between its
    values at two periods and at the nodes between them. A chunk of ``chunk`` grid points
    whose θ/α all lie above that range's top, or all below its bottom, by more than the
    rounding of the values inside (``room`` of the range's largest magnitude), takes its sign
    from the two ends; only
    the chunks that hold a crossing are read point by point, each element in the array
    expression's operations, the nodes found by walking up with the periods rather than by a
    binary search. numpy's array expression read all ~10⁶ periods of a call.

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
        low = 0  # the node the chunk's first period reads, or one before it
        for c in range(chunks):
            first, stop = c * chunk, min(size, (c + 1) * chunk)
            # Sd is linear between nodes: over the chunk's periods it lies between its values
            # at both ends and at the nodes inside
            start_sd, low = _read(4.0 * v[first] / p[b], period_s, sd_m, low)
            end_period = 4.0 * v[stop - 1] / p[b]
            end_sd, _ = _read(end_period, period_s, sd_m, low)
            top, bottom = max(start_sd, end_sd), min(start_sd, end_sd)
            unknown = start_sd != start_sd or end_sd != end_sd  # NaN: every value is read
            j = low + 1
            while j < period_s.size and period_s[j] < end_period:
                top, bottom = max(top, sd_m[j]), min(bottom, sd_m[j])
                unknown = unknown or sd_m[j] != sd_m[j]
                j += 1
            top, bottom = top * scale[b], bottom * scale[b]
            # a value between two nodes is rounded to a few ulps of the larger node, whichever
            # bound it is compared with
            margin = room * max(abs(top), abs(bottom))
            if not unknown and top + margin < lowest[c]:
                out[b, first:stop] = False
            elif not unknown and bottom - margin > highest[c]:
                out[b, first:stop] = True
            else:
                inner = low
                for i in range(first, stop):
                    sd, inner = _read(4.0 * v[i] / p[b], period_s, sd_m, inner)
                    out[b, i] = sd * scale[b] - grid[i] > 0.0
    return out


__all__ = ["tabulated_excess"]
