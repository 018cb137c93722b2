"""The fixed-point iteration on FEMA 356's design spectrum, compiled (see
:func:`procedures.iteration.iterate_rotation`).

The design-level audit locates the intensity at which FEMA 356 turns to predicting overturning
by bisection, each halving a whole iteration of every open block on its own scaled site: tens
of thousands of iterations, each a dozen small numpy operations in Python. Here each block is
iterated on its own, Sd read in the floating-point operations of
:meth:`audit.physics.design_spectra.FEMA356Spectrum.acceleration` and Eq. 3.5.

Apart from :mod:`procedures.fema_356` so that reading a run back never loads numba.
"""

from __future__ import annotations

import math

import numpy as np

from audit.physics.kernel_cache import kernel
from procedures.iteration_kernels import NOT_SETTLED, push_iterate, rocking_period

#: 4π² of Eq. 3.5, computed as :func:`audit.physics.design_spectra.displacement_from_acceleration`
#: computes it.
_FOUR_PI_SQUARED = 4.0 * math.pi ** 2


@kernel()
def fema356_displacement(period, sxs, sx1, b_s, b_1, t_0, t_s, g):
    """Sd [m] at one period T [s] of a FEMA 356 spectrum (S_XS, S_X1 [g]; B_S, B_1 of Table
    1-6; corner periods T_0, T_S [s]): Sa in its branch, then Sa·g·T²/(4π²)."""
    if period < t_0:
        sa = sxs * ((5.0 / b_s - 2.0) * period / t_s + 0.4)
    elif period <= t_s:
        sa = sxs / b_s
    else:  # beyond T_S, and a NaN period (whose Sa is NaN)
        sa = sx1 / (b_1 * period)
    return sa * g * (period * period) / _FOUR_PI_SQUARED


@kernel()
def iterate_fema356(p, scale, site, g, initial_ratio, tolerance, cycle_tolerance,
                    subcycle_tolerance, max_length, max_iterations):
    """:func:`procedures.iteration_kernels.iterate_tabulated`'s iteration with Sd read from
    block b's FEMA 356 spectrum, ``site[b]`` = (S_XS, S_X1, B_S, B_1, T_0, T_S), g the
    spectrum's [m/s²].

    Returns
    -------
    outcome, iterations, cycle, recent : numpy.ndarray
        As :func:`~procedures.iteration_kernels.iterate_tabulated`.
    """
    n = p.size
    outcome = np.zeros(n, dtype=np.int8)
    iterations = np.full(n, max_iterations, dtype=np.int64)
    cycle = np.zeros(n, dtype=np.int64)
    windows = np.full((n, 2 * max_length), np.nan)
    for b in range(n):
        recent = windows[b]
        recent[-1] = initial_ratio
        for i in range(1, max_iterations + 1):
            sd = fema356_displacement(rocking_period(recent[-1], p[b]), site[b, 0], site[b, 1],
                                      site[b, 2], site[b, 3], site[b, 4], site[b, 5], g)
            code, length = push_iterate(recent, sd * scale[b], tolerance, cycle_tolerance,
                                        subcycle_tolerance, max_length)
            if code != NOT_SETTLED:
                outcome[b], iterations[b], cycle[b] = code, i, length
                break
    return outcome, iterations, cycle, windows


__all__ = ["fema356_displacement", "iterate_fema356"]
