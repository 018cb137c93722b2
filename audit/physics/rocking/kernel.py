"""The compiled solver: one block's response to one motion (:func:`_simulate`), summarised by
:class:`ResponseSummary`, and many blocks under one motion (:func:`_spectrum`)."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from audit.errors import InputError
from audit.physics.kernel_cache import kernel
from audit.physics.rocking.motion_equation import (_COSINE, _SAMPLED, _SINE, _friction_ratio,
                                                   _ground, _lifts, _locate, _rk4,
                                                   pivot_reactions)
from audit.physics.rocking.rest import _chatter_ends

# The kernel's vertical ground acceleration when there is none (horizontal motion only).
_NO_VERTICAL = np.empty(0)
# Columns of the event buffers the kernel fills: each impact's time, rocking episode and θ' just
# before and just after it; each turning point's time and θ.
_IMPACT_TIME, _IMPACT_EPISODE, _OMEGA_BEFORE_IMPACT, _OMEGA_AFTER_IMPACT = range(4)
_TURN_TIME, _TURN_THETA = range(2)


class ResponseSummary(NamedTuple):
    """What :func:`_simulate` returns besides the histories it fills (a NamedTuple: numba
    compiles it to the same struct as a plain tuple)."""

    peak_rotation: float  # max |θ| [rad] (α when overturned)
    peak_angular_velocity: float  # max |θ'| [rad/s]
    peak_rotation_after_excitation: float  # max |θ| after the excitation ends [rad]
    overturned: bool
    overturn_time: float  # [s], NaN when the block survives
    n_impacts: int
    uplifted: bool
    peak_rotation_signed: float  # θ at the peak [rad]
    n_turns: int  # turning points θ' = 0
    required_friction: float  # max |H|/V [-], inf where the block would jump
    min_vertical_reaction: float  # min V/(mg) [-]


@kernel()
def _simulate(acc, vertical, dt, n_tail, kind, amp, omega_p, p, alpha, velocity_ratio, g,
              steps_per_radian, rest_tolerance, theta0, omega0, theta_out, omega_out, impacts_out,
              turns_out, stride=1, reactions=False, peaks_only=False, scale=1.0):
    """Simulate one block; see :func:`simulate`. History arrays of length 0 store nothing;
    otherwise every ``stride``-th sample is stored. ``vertical`` holds the vertical ground
    acceleration at the samples of ``acc`` [m/s²], or nothing (horizontal motion only).

    ``impacts_out`` holds a row per impact, ``turns_out`` a row per turning point (θ' = 0),
    in the columns named above (``_IMPACT_TIME`` …, ``_TURN_TIME`` …).

    With ``reactions``, the pivot reactions (:func:`pivot_reactions`) are evaluated at the end
    of every Runge–Kutta step of the rocking motion and on both sides of every impact; at rest
    on the base H = m üg and V = m (g + üv), whose largest ratio over the samples is capped at
    tan α (beyond it the block uplifts, at exactly tan α).

    ``scale`` multiplies every ground acceleration as it is read (the record's, the vertical
    one's, a pulse's amplitude): the response to ``motion.scaled(scale)``, bit for bit (each
    sample is the same product), without a scaled copy of the record.

    With ``peaks_only`` (no histories, no reactions) the free motion after the excitation stops
    once it has had a turning point and an impact: with the ground at rest the energy only falls
    from there, so no later |θ| or |θ'| can exceed those already seen, and the peaks are those
    of the whole free motion, bit for bit; the counts of impacts and turning points stop there.

    Returns a :class:`ResponseSummary`; its reactions are NaN without ``reactions``.
    """
    n_rec = acc.size
    n_seg = n_rec - 1 + n_tail
    t_exc_end = (n_rec - 1) * dt
    store = theta_out.size > 0
    has_vertical = vertical.size > 0
    amp = amp * scale
    p2 = p * p
    tan_alpha = math.tan(alpha)
    n_sub = max(1, int(math.ceil(dt * p * steps_per_radian)))
    h_sub = dt / n_sub
    last_exceed = -1
    max_ratio = 0.0
    min_vertical = math.inf
    for i in range(n_rec):
        uv = vertical[i] * scale if has_vertical else 0.0
        ui = acc[i] * scale
        if _lifts(ui, uv, g, tan_alpha):
            last_exceed = i
        if reactions:
            max_ratio = max(max_ratio, min(_friction_ratio(ui, g + uv), tan_alpha))
            min_vertical = min(min_vertical, (g + uv) / g)

    theta = theta0
    omega = omega0
    resting = theta0 == 0.0 and omega0 == 0.0
    side = 1.0 if theta0 > 0.0 or (theta0 == 0.0 and omega0 > 0.0) else -1.0
    overturned = False
    uplifted = not resting
    t_over = math.nan
    peak = 0.0
    peak_signed = 0.0
    peak_omega = 0.0
    peak_after = 0.0
    n_impacts = 0
    n_turns = 0
    episode = 0
    turned_after = False  # a turning point and an impact in the free motion (``peaks_only``)
    impact_after = False
    filled = 0  # history samples written so far
    if store:
        theta_out[0] = theta0
        omega_out[0] = omega0
        filled = 1

    for k in range(n_seg):
        if resting and k > last_exceed:
            break  # at rest and the ground can no longer lift it: nothing more happens
        t0 = k * dt
        t1 = (k + 1) * dt
        v0 = 0.0
        vslope = 0.0
        if k < n_rec - 1:
            seg_kind = kind
            a0 = acc[k] * scale
            slope = (acc[k + 1] * scale - a0) / dt
            if has_vertical:
                v0 = vertical[k] * scale
                vslope = (vertical[k + 1] * scale - v0) / dt
        else:
            seg_kind = _SAMPLED
            a0 = 0.0
            slope = 0.0
        after = t0 >= t_exc_end - 1e-12 * dt
        t = t0
        while t < t1 - 1e-12 * dt:
            if turned_after and impact_after:
                break
            if resting:
                ua = _ground(t, seg_kind, a0, slope, t0, amp, omega_p)
                ub = _ground(t1, seg_kind, a0, slope, t0, amp, omega_p)
                if _lifts(ua, v0 + vslope * (t - t0), g, tan_alpha):
                    t_up, u_up = t, ua
                elif _lifts(ub, v0 + vslope * dt, g, tan_alpha):
                    # first time |üg| reaches (g + üv) tan α: bisection is exact enough and only
                    # runs at uplifts
                    lo, hi = t, t1
                    for _ in range(60):
                        mid = 0.5 * (lo + hi)
                        if _lifts(_ground(mid, seg_kind, a0, slope, t0, amp, omega_p),
                                  v0 + vslope * (mid - t0), g, tan_alpha):
                            hi = mid
                        else:
                            lo = mid
                    t_up = hi
                    u_up = _ground(hi, seg_kind, a0, slope, t0, amp, omega_p)
                else:
                    break
                resting = False
                uplifted = True
                episode += 1
                theta = 0.0
                omega = 0.0
                side = -1.0 if u_up > 0.0 else 1.0
                t = t_up
                continue

            h = min(h_sub, t1 - t)
            th_n, om_n = _rk4(theta, omega, t, h, side, p2, alpha, g,
                              seg_kind, a0, slope, t0, amp, omega_p, v0, vslope)
            lo = 0.0
            if omega * om_n < 0.0:
                # a peak of |θ| inside the step
                tau, th_e, om_e = _locate(1, 0.0, 0.0, h, om_n, theta, omega, t, side, p2,
                                          alpha, g, seg_kind, a0, slope, t0, amp, omega_p, v0,
                                          vslope)
                lo = tau
                if abs(th_e) >= alpha:
                    th_n = th_e  # overturned before the turning point: handled below
                    h = tau
                else:
                    if n_turns < turns_out.shape[0]:
                        turns_out[n_turns, _TURN_TIME] = t + tau
                        turns_out[n_turns, _TURN_THETA] = th_e
                    n_turns += 1
                    turned_after = after and peaks_only
                    if abs(th_e) > peak:
                        peak = abs(th_e)
                        peak_signed = th_e
                    if after and abs(th_e) > peak_after:
                        peak_after = abs(th_e)
            if side * th_n >= alpha:
                tau, th_o, om_o = _locate(0, side * alpha, 0.0, h, th_n, theta, omega, t, side,
                                          p2, alpha, g, seg_kind, a0, slope, t0, amp, omega_p,
                                          v0, vslope)
                overturned = True
                t_over = t + tau
                peak = alpha
                peak_signed = side * alpha
                if abs(om_o) > peak_omega:
                    peak_omega = abs(om_o)
                if after:
                    peak_after = alpha
                break
            if side * th_n < 0.0:
                # impact: θ returns to zero inside the step (after the turning point, if any)
                tau, th_i, om_i = _locate(0, 0.0, lo, h, th_n, theta, omega, t, side, p2,
                                          alpha, g, seg_kind, a0, slope, t0, amp, omega_p, v0,
                                          vslope)
                if abs(om_i) > peak_omega:
                    peak_omega = abs(om_i)
                t_imp = t + tau
                if n_impacts < impacts_out.shape[0]:
                    impacts_out[n_impacts, _IMPACT_TIME] = t_imp
                    impacts_out[n_impacts, _IMPACT_EPISODE] = episode
                u_imp = _ground(t_imp, seg_kind, a0, slope, t0, amp, omega_p)
                w_imp = v0 + vslope * (t_imp - t0)
                if reactions:  # on the old pivot just before, on the new one just after
                    hr, vr = pivot_reactions(0.0, om_i, u_imp, w_imp, side, p2, alpha, g)
                    max_ratio = max(max_ratio, _friction_ratio(hr, vr))
                    min_vertical = min(min_vertical, vr)
                omega = velocity_ratio * om_i
                theta = 0.0
                side = 1.0 if omega > 0.0 else -1.0
                t = t_imp
                if omega == 0.0 or _chatter_ends(omega, t_imp, t1, seg_kind, a0, slope, t0, amp,
                                                 omega_p, v0, vslope, p2, alpha, g,
                                                 velocity_ratio, rest_tolerance):
                    resting = True
                    omega = 0.0
                elif reactions:
                    hr, vr = pivot_reactions(0.0, omega, u_imp, w_imp, side, p2, alpha, g)
                    max_ratio = max(max_ratio, _friction_ratio(hr, vr))
                    min_vertical = min(min_vertical, vr)
                if n_impacts < impacts_out.shape[0]:
                    impacts_out[n_impacts, _OMEGA_BEFORE_IMPACT] = om_i
                    impacts_out[n_impacts, _OMEGA_AFTER_IMPACT] = omega
                n_impacts += 1
                impact_after = after and peaks_only
                continue
            theta = th_n
            omega = om_n
            t += h
            if reactions:
                hr, vr = pivot_reactions(theta, omega,
                                         _ground(t, seg_kind, a0, slope, t0, amp, omega_p),
                                         v0 + vslope * (t - t0), side, p2, alpha, g)
                max_ratio = max(max_ratio, _friction_ratio(hr, vr))
                min_vertical = min(min_vertical, vr)
            if abs(omega) > peak_omega:
                peak_omega = abs(omega)
            if abs(theta) > peak:
                peak = abs(theta)
                peak_signed = theta
            if after and abs(theta) > peak_after:
                peak_after = abs(theta)
        if overturned or (turned_after and impact_after):
            break
        if store and (k + 1) % stride == 0:
            theta_out[(k + 1) // stride] = theta
            omega_out[(k + 1) // stride] = omega
            filled = (k + 1) // stride + 1

    if store:
        # after overturning nothing is defined; after a final rest the block stays at rest
        fill = math.nan if overturned else 0.0
        theta_out[filled:] = fill
        omega_out[filled:] = fill
    if not reactions:
        max_ratio = math.nan
        min_vertical = math.nan
    return ResponseSummary(peak, peak_omega, peak_after, overturned, t_over, n_impacts, uplifted,
                           peak_signed, n_turns, max_ratio, min_vertical)


@kernel()
def _spectrum(acc, vertical, dt, n_tail, kind, amp, omega_p, p, alpha, velocity_ratio, scale,
              g, steps_per_radian, rest_tolerance, reactions, out):
    """Peaks of many blocks under one motion, block i's × ``scale[i]``; fills ``out``, a
    :class:`audit.physics.rocking.spectrum.BlockPeaks`."""
    empty = np.empty(0)
    no_events = np.empty((0, 4))
    for i in range(p.size):
        res = _simulate(acc, vertical, dt, n_tail, kind, amp, omega_p, p[i], alpha[i],
                        velocity_ratio[i], g, steps_per_radian, rest_tolerance, 0.0, 0.0, empty,
                        empty, no_events, no_events, 1, reactions, not reactions, scale[i])
        out.theta_peak[i] = res.peak_rotation
        out.omega_peak[i] = res.peak_angular_velocity
        out.theta_after[i] = res.peak_rotation_after_excitation
        out.overturned[i] = res.overturned
        out.uplifted[i] = res.uplifted
        out.required_friction[i] = res.required_friction
        out.min_vertical_reaction[i] = res.min_vertical_reaction


def _free_samples(motion, free_motion_s) -> int:
    """Samples of free motion simulated after the excitation ends."""
    if free_motion_s < 0 or not math.isfinite(free_motion_s):
        raise InputError(f"duration of free motion: must be ≥ 0 s, got {free_motion_s}")
    return int(math.ceil(free_motion_s / motion.dt - 1e-9))


def _motion_arguments(motion, free_motion_s, vertical: bool = False):
    """Kernel arguments describing the excitation of a GroundMotion (its vertical component
    too with ``vertical``, where it has one)."""
    n_tail = _free_samples(motion, free_motion_s)
    up = motion.vertical if vertical and motion.vertical is not None else _NO_VERTICAL
    if motion.pulse is None:
        return motion.acceleration, up, motion.dt, n_tail, _SAMPLED, 0.0, 0.0
    kind = _COSINE if motion.pulse.shape == "cosine" else _SINE
    return (motion.acceleration, up, motion.dt, n_tail, kind, motion.pulse.amplitude,
            2.0 * math.pi / motion.pulse.period_s)


