"""A slow, independent reference solver of the rocking block, built on ``scipy.integrate``.

It solves the same physics as :mod:`audit.physics.rocking` (Eq. 4.3, uplift, impacts with √r,
rest, overturning) by a different route: ``solve_ivp`` with DOP853 and its event location,
the record interpolated by ``numpy.interp``. It exists to check the fast solver (tests, golden
values, ``benchmarks/rocking_spectrum.py``), not for production runs: it is ~1000× slower.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from audit.physics.rocking import DEFAULT_FREE_MOTION_S

#: The reference rests only after rebounds far smaller than the solver's rest rule allows (and
#: with the ground unable to lift the block at the impact): it follows a chatter almost to its
#: end instead of summing it (:func:`audit.physics.rocking.chatter_time_bound`), another route.
REFERENCE_REST_TOLERANCE = 1e-12


def simulate_reference(block, motion, free_motion_s: float = DEFAULT_FREE_MOTION_S,
                       rtol: float = 1e-10, atol: float = 1e-13,
                       rest_tolerance: float = REFERENCE_REST_TOLERANCE) -> dict:
    """Peak rotation and overturning of ``block`` under ``motion`` with ``solve_ivp``.

    Parameters
    ----------
    block : audit.physics.block.RigidBlock
    motion : records.GroundMotion
        Ground acceleration [m/s²], linear between samples.
    free_motion_s : float
        Free motion after the record [s].
    rtol, atol : float
        DOP853 tolerances; the step is capped at the record's dt.

    Returns
    -------
    dict
        ``peak_rotation`` [rad], ``overturned`` (bool), ``n_impacts`` and their times
        ``impact_times`` [s], and the time [s] and
        θ [rad] of every turning point θ' = 0 (``turning_times``, ``turning_rotations``).
    """
    time = motion.time
    acc = motion.acceleration
    t_end = time[-1] + free_motion_s
    p2, alpha, g = block.p ** 2, block.alpha, block.g
    threshold = g * math.tan(alpha)
    velocity_ratio = math.sqrt(block.r)
    rest_omega2 = 2.0 * rest_tolerance * p2 * alpha ** 2

    def ground(t):
        return float(np.interp(t, time, acc, right=0.0))

    def next_uplift(t_from):
        """First time ≥ t_from at which |üg| exceeds g tan α, or None."""
        k = int(np.searchsorted(time, t_from, side="right"))
        if abs(ground(t_from)) > threshold:
            return t_from
        above = np.flatnonzero(np.abs(acc[k:]) > threshold)
        if above.size == 0:
            return None
        j = k + above[0]
        a0, a1 = acc[j - 1], acc[j]
        level = math.copysign(threshold, a1)
        return max(t_from, time[j - 1] + (level - a0) / (a1 - a0) * (time[j] - time[j - 1]))

    peak, impacts = 0.0, []
    turns = []  # (t, θ) of every turning point

    def result(peak_rotation, overturned):
        times, rotations = np.array(turns).reshape(-1, 2).T
        return {"peak_rotation": peak_rotation, "overturned": overturned,
                "n_impacts": len(impacts), "impact_times": np.array(impacts),
                "turning_times": times, "turning_rotations": rotations}
    t = next_uplift(0.0)
    theta, omega = 0.0, 0.0
    side = -math.copysign(1.0, ground(t)) if t is not None else 1.0
    while t is not None and t < t_end:
        def rhs(tt, y, side=side):
            phi = side * alpha - y[0]
            return [y[1], -p2 * (math.sin(phi) + ground(tt) / g * math.cos(phi))]

        def impact(tt, y, side=side):
            return side * y[0]
        impact.terminal, impact.direction = True, -1

        def overturn(tt, y, side=side):
            return side * y[0] - alpha
        overturn.terminal, overturn.direction = True, 1

        def turning(tt, y):
            return y[1]

        sol = solve_ivp(rhs, (t, t_end), [theta, omega], method="DOP853", rtol=rtol, atol=atol,
                        max_step=motion.dt, events=(impact, overturn, turning))
        peak = max(peak, float(np.max(np.abs(sol.y[0]))),
                   *(abs(y[0]) for y in sol.y_events[2]))
        turns.extend(zip(sol.t_events[2], (y[0] for y in sol.y_events[2])))
        if sol.t_events[1].size:
            return result(alpha, True)
        if not sol.t_events[0].size:
            break
        t = float(sol.t_events[0][0])
        impacts.append(t)
        omega = velocity_ratio * float(sol.y_events[0][0][1])
        theta = 0.0
        side = math.copysign(1.0, omega)
        if omega ** 2 < rest_omega2 and abs(ground(t)) <= threshold:
            t = next_uplift(t)
            if t is not None:
                omega = 0.0
                side = -math.copysign(1.0, ground(t))
    return result(peak, False)
