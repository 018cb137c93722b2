"""The fixed-point iteration's per-step bookkeeping, compiled (see
:func:`procedures.iteration.iterate_rotation`).

Apart from :mod:`procedures.iteration` so that reading a run back and rendering its report (which
imports the procedures' declarations) never loads numba.
"""

from __future__ import annotations

import math

import numpy as np

from audit.physics.kernel_cache import kernel
from audit.physics.spectrum_kernel import fill_displacement


@kernel()
def may_repeat(window: np.ndarray, cycle_tolerance: float, max_length: int) -> bool:
    """Whether the iterates ``window`` (newest last) may hold a settled cycle (see
    :func:`procedures.iteration_cycles.cycle_length`).

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


@kernel(inline="always")
def _push(window: np.ndarray, new: float, tolerance: float):
    """Push the iterate ``new`` into one block's ``window`` (newest last; 1 for an overturning
    one). Returns (over, done): it overturns (θ/α ≥ 1), or has converged (|Δθ|/α ≤
    ``tolerance``)."""
    width = window.size
    over = new >= 1.0
    done = not over and abs(new - window[width - 1]) <= tolerance
    window[:width - 1] = window[1:].copy()
    window[width - 1] = 1.0 if over else new
    return over, done


@kernel()
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
    rows = recent.shape[0]
    over = np.zeros(rows, dtype=np.bool_)
    done = np.zeros(rows, dtype=np.bool_)
    maybe = np.zeros(rows, dtype=np.bool_)
    for row in range(rows):
        over[row], done[row] = _push(recent[row], new[row], tolerance)
        maybe[row] = (not (over[row] or done[row])
                      and may_repeat(recent[row], cycle_tolerance, max_length))
    return over, done, maybe


@kernel()
def nodes_read(x: float, xp: np.ndarray):
    """The nodes (low, high) ``numpy.interp`` reads for x (not NaN): xp[low] ≤ x < xp[high]
    inside the table, the end node twice beyond either end."""
    n = xp.size
    if x < xp[0]:
        return 0, 0
    if x >= xp[n - 1]:
        return n - 1, n - 1
    low, high = 0, n - 1
    while high - low > 1:
        middle = (low + high) // 2
        if xp[middle] <= x:
            low = middle
        else:
            high = middle
    return low, high


@kernel()
def interp_between(x: float, xp: np.ndarray, fp: np.ndarray, low: int, high: int) -> float:
    """``numpy.interp``'s value at x (not NaN) from the nodes it reads (:func:`nodes_read`), with
    its arithmetic: slope·(x − xpⱼ) + fpⱼ between nodes (retried from the right node where that
    is NaN), the node's value at a node, the end values held beyond both ends."""
    if low == high or xp[low] == x:
        return fp[low]
    slope = (fp[low + 1] - fp[low]) / (xp[low + 1] - xp[low])
    value = slope * (x - xp[low]) + fp[low]
    if value != value:
        value = slope * (x - xp[low + 1]) + fp[low + 1]
        if value != value and fp[low] == fp[low + 1]:
            value = fp[low]
    return value


@kernel()
def interp(x: float, xp: np.ndarray, fp: np.ndarray) -> float:
    """``numpy.interp(x, xp, fp)`` for one x (:func:`interp_between`)."""
    if x != x:
        return x
    low, high = nodes_read(x, xp)
    return interp_between(x, xp, fp, low, high)


@kernel()
def cycle_length(window: np.ndarray, cycle_tolerance: float, subcycle_tolerance: float,
                 max_length: int) -> int:
    """:func:`procedures.iteration_cycles.cycle_length` of one window of iterates (newest
    last)."""
    width = window.size
    length = 0
    for size in range(2, max_length + 1):
        high, low, finite = -np.inf, np.inf, True
        for k in range(size):
            value = window[width - 1 - k]
            if value != value:
                finite = False
                break
            high, low = max(high, value), min(low, value)
        spread = high - low
        if not finite or not spread > 0.0:
            continue
        bound = cycle_tolerance * spread
        repeats = True
        for k in range(size):
            if not abs(window[width - 1 - k] - window[width - 1 - k - size]) <= bound:
                repeats = False
                break
        if repeats:
            length = size
            break
    if length == 0:
        return 0
    high, low = -np.inf, np.inf
    for k in range(width - length, width):
        high, low = max(high, window[k]), min(low, window[k])
    bound = subcycle_tolerance * (high - low)
    start = width - length
    for size in range(2, length + 1):
        if length % size:
            continue
        repeats = True
        for k in range(length - size):
            if not abs(window[start + size + k] - window[start + k]) <= bound:
                repeats = False
                break
        if repeats:
            return size
    return length


#: Outcome codes of :func:`iterate_tabulated`.
NOT_SETTLED, CONVERGED, OVERTURNED, CYCLING = 0, 1, 2, 3


@kernel(inline="always")
def rocking_period(ratio, p):
    """T = (4/p) acosh(1/(1 − θ/α)) of Eq. 8.1 at one θ/α [s], in the operations of
    :func:`audit.physics.damping.housner_period`."""
    return 4.0 / p * math.acosh(1.0 / (1.0 - ratio))


@kernel()
def push_iterate(recent, new, tolerance, cycle_tolerance, subcycle_tolerance, max_length):
    """One block's step of :func:`advance` and :func:`cycle_length`: push the iterate ``new``
    into its window ``recent`` (newest last; 1 for an overturning one) and say how the
    iteration stands.

    Returns
    -------
    outcome, cycle : int
        Outcome code (:data:`NOT_SETTLED` while it goes on) and the cycle's length (0 unless
        cycling).
    """
    over, done = _push(recent, new, tolerance)
    if over or done:
        return (OVERTURNED if over else CONVERGED), 0
    if may_repeat(recent, cycle_tolerance, max_length):
        length = cycle_length(recent, cycle_tolerance, subcycle_tolerance, max_length)
        if length:
            return CYCLING, length
    return NOT_SETTLED, 0


@kernel()
def _read_on_demand(period, period_s, table, source):
    """Make ``table`` known at the nodes :func:`interp` reads for ``period``: each computed by
    :func:`~audit.physics.spectrum_kernel.fill_displacement` where unknown, × the factor
    (``source`` as :meth:`procedures.tabulated.TabulatedOnDemand.kernel_arguments`)."""
    known, factor, acc, dt, coeffs, omega, damping, raw, raw_known = source
    if period != period:
        return
    for j in nodes_read(period, period_s):
        if not known[j]:
            fill_displacement(acc, dt, coeffs, omega, damping, raw, raw_known, j)
            table[j] = raw[j] * factor
            known[j] = True


@kernel()
def _iterate_block(period_s, table, p, scale, initial_ratio, tolerance, cycle_tolerance,
                   subcycle_tolerance, max_length, max_iterations, recent, source):
    """One block of :func:`iterate_tabulated`, its window of iterates in ``recent``; ``source``
    None, or how to compute the table where it is read (:func:`_read_on_demand`).

    Returns
    -------
    outcome, iterations, cycle : int
    """
    width = recent.size
    recent[:] = np.nan
    recent[width - 1] = initial_ratio
    for i in range(1, max_iterations + 1):
        period = rocking_period(recent[width - 1], p)
        if source is not None:
            _read_on_demand(period, period_s, table, source)
        code, length = push_iterate(recent, interp(period, period_s, table) * scale, tolerance,
                                    cycle_tolerance, subcycle_tolerance, max_length)
        if code != NOT_SETTLED:
            return code, i, length
    return NOT_SETTLED, max_iterations, 0


@kernel()
def _iterate_blocks(period_s, sd_m, rows, p, scale, initial_ratio, tolerance, cycle_tolerance,
                    subcycle_tolerance, max_length, max_iterations, source):
    """:func:`iterate_tabulated`, the tables computed where read when ``source`` is not None."""
    n = p.size
    outcome = np.zeros(n, dtype=np.int8)
    iterations = np.zeros(n, dtype=np.int64)
    cycle = np.zeros(n, dtype=np.int64)
    windows = np.empty((n, 2 * max_length))
    for b in range(n):
        outcome[b], iterations[b], cycle[b] = _iterate_block(
            period_s, sd_m[rows[b]], p[b], scale[b], initial_ratio, tolerance, cycle_tolerance,
            subcycle_tolerance, max_length, max_iterations, windows[b], source)
    return outcome, iterations, cycle, windows


@kernel()
def iterate_tabulated(period_s, sd_m, rows, p, scale, initial_ratio, tolerance,
                      cycle_tolerance, subcycle_tolerance, max_length, max_iterations):
    """The iteration of :func:`procedures.iteration.iterate_rotation`, compiled, each block
    reading its own row ``rows[b]`` of tabulated spectra ``sd_m`` on ``period_s``: the same
    steps, in the same floating-point operations (Eq. 8.1 as
    :func:`audit.physics.damping.housner_period` writes it, :func:`interp`, the bookkeeping of
    :func:`advance` and :func:`cycle_length`), block after block.

    Returns
    -------
    outcome, iterations, cycle, recent : numpy.ndarray
        Outcome code (:data:`CONVERGED`, :data:`OVERTURNED`, :data:`CYCLING` or
        :data:`NOT_SETTLED`), iterations used, the cycle's length (0 unless cycling), and the
        last 2·``max_length`` iterates θ/α of each block, newest last.
    """
    return _iterate_blocks(period_s, sd_m, rows, p, scale, initial_ratio, tolerance,
                           cycle_tolerance, subcycle_tolerance, max_length, max_iterations, None)


@kernel()
def iterate_on_demand(period_s, table, source, p, scale, initial_ratio, tolerance,
                      cycle_tolerance, subcycle_tolerance, max_length, max_iterations):
    """:func:`iterate_tabulated` of blocks that all read one table computed where it is read
    (``table`` and ``source`` of a :class:`procedures.tabulated.TabulatedOnDemand`, filled in
    place): the same iterates, the values read being those the whole table holds."""
    return _iterate_blocks(period_s, table.reshape((1, table.size)),
                           np.zeros(p.size, dtype=np.int64), p, scale, initial_ratio, tolerance,
                           cycle_tolerance, subcycle_tolerance, max_length, max_iterations,
                           source)


__all__ = ["advance", "cycle_length", "interp", "interp_between", "iterate_on_demand",
           "iterate_tabulated", "may_repeat", "nodes_read", "push_iterate", "rocking_period"]
