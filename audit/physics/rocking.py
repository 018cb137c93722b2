"""Exact rocking response of a rigid block (Eqs. 4.3–4.8 of Makris & Konstantinidis 2001) and rocking spectra (Section 5).

The equation of motion (Eq. 4.3)

    θ'' = −p² { sin[α sgn(θ) − θ] + (üg/g) cos[α sgn(θ) − θ] }

is integrated with a classical fixed-step Runge–Kutta scheme inside each interval on which the
ground acceleration is smooth (between two samples of a record, where it is linear, or inside an
analytic pulse, evaluated in closed form). Every event is located inside its step rather than
stepped across:

- uplift, when |üg| first exceeds g·tan α (a positive üg starts a negative rotation);
- impact, when θ returns to zero: the crossing time is found by safeguarded Newton iteration on
  the Runge–Kutta step length, then θ' is multiplied by sqrt(r) (Eq. 4.6–4.8) and the pivot
  switches;
- peaks of |θ|, where θ' vanishes, located the same way;
- overturning, when |θ| reaches α;
- return to rest, after an impact whose chatter (the Zeno sequence of ever smaller rebounds,
  summed in closed form by :func:`chatter_time_bound`) converges, with rebounds below
  ``rest_tolerance``·α, before the ground could lift the block on either corner.

The step is h ≤ 1/(``steps_per_radian``·p) and no longer than the record's sampling step, so a
run is accurate to ~1e-7 relative away from the overturning boundary (see the convergence test).
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numba
import numpy as np

from audit.physics.block import RigidBlock, coefficient_of_restitution
from audit.physics.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_REST_TOLERANCE,
                                    DEFAULT_STEPS_PER_RADIAN)
from audit.physics.tiers import tiered
from audit.errors import InputError

#: Impacts whose times are kept by :func:`simulate`.
IMPACT_CAPACITY = 100_000
#: Most samples of θ(t) and θ'(t) kept by :func:`simulate` (longer histories are decimated, so
#: one block's history stays within ~10 MB; peaks and impacts are located exactly regardless).
HISTORY_CAPACITY = 400_000
#: Smallest rest tolerance: smaller rebounds fly for less than the 1e-15 s to which impacts
#: are located, so their velocities would be noise and a chatter might never end.
MIN_REST_TOLERANCE = 1e-20
#: Time of one Runge–Kutta step of the kernel run interpreted (see audit.physics.tiers) [s].
INTERPRETED_STEP_S = 5e-6

# Ground-motion kinds understood by the kernel.
_SAMPLED, _COSINE, _SINE = 0, 1, 2
# The kernel's vertical ground acceleration when there is none (horizontal motion only).
_NO_VERTICAL = np.empty(0)


@numba.njit(cache=True, nogil=True, inline="always")
def _ground(t, kind, a0, slope, t0, amp, omega_p):
    """üg at time t on the current smooth interval."""
    if kind == _SAMPLED:
        return a0 + slope * (t - t0)
    if kind == _COSINE:
        return amp * math.cos(omega_p * t)
    return amp * math.sin(omega_p * t)


@numba.njit(cache=True, nogil=True, inline="always")
def _theta_acc(theta, ug, uv, side, p2, alpha, g):
    """Eq. 4.3 with sgn(θ) replaced by the side of the current pivot, and gravity g + üv under
    a vertical ground acceleration üv (Eq. 4.3 with g → g + üv in its moment of the weight;
    p² = 3g/(4R) keeps the nominal g). Without vertical motion üv = 0 and (1 + 0/g)·sin φ is
    sin φ exactly, so the horizontal-only response is unchanged to the last bit."""
    phi = side * alpha - theta
    return -p2 * ((1.0 + uv / g) * math.sin(phi) + ug / g * math.cos(phi))


@numba.njit(cache=True, nogil=True, inline="always")
def _lifts(ug, uv, g, tan_alpha):
    """Whether the ground lifts a block at rest: |üg| > (g + üv) tan α."""
    return abs(ug) > (g + uv) * tan_alpha


@numba.njit(cache=True, nogil=True)
def _largest_ground(t_a, t_b, kind, a0, slope, t0, amp, omega_p):
    """max |üg| over [t_a, t_b] inside one smooth interval: the ends where üg is linear (a
    record), |amp| too where a crest of the pulse's cosine or sine lies between them."""
    largest = max(abs(_ground(t_a, kind, a0, slope, t0, amp, omega_p)),
                  abs(_ground(t_b, kind, a0, slope, t0, amp, omega_p)))
    if kind != _SAMPLED:
        shift = 0.0 if kind == _COSINE else 0.5 * math.pi  # crests at ω_p t = shift + kπ
        crests_a = math.floor((omega_p * t_a - shift) / math.pi)
        if crests_a != math.floor((omega_p * t_b - shift) / math.pi):
            largest = abs(amp)
    return largest


@numba.njit(cache=True, nogil=True)
def chatter_time_bound(omega, restoring, velocity_ratio):
    """Upper bound of the time a block rebounding at θ' = ``omega`` chatters until it is at rest
    (a Zeno sequence of impacts, summed in closed form) [s].

    For small θ the flight on either corner is one of constant deceleration d ≥ ``restoring``
    (θ'' = −p²[(1 + üv/g) sin α ± (üg/g) cos α] at θ = 0), so it lasts 2|θ'|/d and comes back at
    |θ'|, which the impact multiplies by √r. The flights form a geometric series:

        Σ 2|θ'| (√r)ⁿ / d  =  2|θ'| / ((1 − √r) d)

    infinitely many impacts in finite time. Infinite where the series does not converge
    (r ≥ 1, or no restoring deceleration: the ground can lift the block).

    Parameters
    ----------
    omega : float
        Rebound angular velocity after an impact [rad/s].
    restoring : float
        Lower bound of the restoring deceleration on both corners [rad/s²].
    velocity_ratio : float
        √r [-].
    """
    if restoring <= 0.0 or velocity_ratio >= 1.0:
        return math.inf
    return 2.0 * abs(omega) / ((1.0 - velocity_ratio) * restoring)


@numba.njit(cache=True, nogil=True)
def pivot_reactions(theta, omega, ug, uv, side, p2, alpha, g):
    """Horizontal and vertical reactions H/(mg), V/(mg) [-] at the pivot of a rocking block.

    Newton's law for the centroid of the block (mass m, R = 3g/(4p²), α) rocking about a
    corner, with s = ±1 the side of the pivot and φ = sα − θ; the centroid sits at
    (−R sin φ, R cos φ) from the pivot, so

        H / m = üg      + R (θ'' cos φ + θ'² sin φ)
        V / m = g + üv  + R (θ'' sin φ − θ'² cos φ)

    with θ'' from Eq. 4.3. Pure rocking needs V ≥ 0 (else the block jumps) and a friction
    coefficient μ ≥ |H| / V; at uplift (θ = θ' = 0, |üg| = g tan α, θ'' = 0) that is the
    classic μ ≥ tan α (derivation in docs/ground-truth-assumptions.md).

    Parameters
    ----------
    theta, omega : float
        θ [rad] and θ' [rad/s].
    ug, uv : float
        Horizontal and vertical ground accelerations [m/s²].
    side : float
        +1 rocking on the corner of θ > 0, −1 on the other.
    p2 : float
        p² [rad²/s²].
    alpha, g : float
        α [rad]; acceleration of gravity [m/s²].
    """
    phi = side * alpha - theta
    theta_acc = _theta_acc(theta, ug, uv, side, p2, alpha, g)
    radius = 0.75 * g / p2
    horizontal = ug + radius * (theta_acc * math.cos(phi) + omega * omega * math.sin(phi))
    vertical = g + uv + radius * (theta_acc * math.sin(phi) - omega * omega * math.cos(phi))
    return horizontal / g, vertical / g


@numba.njit(cache=True, nogil=True, inline="always")
def _friction_ratio(horizontal, vertical):
    """|H| / V, infinite where V ≤ 0 (no friction keeps a jumping block in place)."""
    return abs(horizontal) / vertical if vertical > 0.0 else math.inf


@numba.njit(cache=True, nogil=True)
def _rk4(theta, omega, t, h, side, p2, alpha, g, kind, a0, slope, t0, amp, omega_p, v0, vslope):
    """One classical Runge–Kutta step of length h from (θ, θ') at t; the vertical ground
    acceleration is v0 + vslope·(t − t0) on the interval (zero without vertical motion)."""
    u1 = _ground(t, kind, a0, slope, t0, amp, omega_p)
    u2 = _ground(t + 0.5 * h, kind, a0, slope, t0, amp, omega_p)
    u3 = _ground(t + h, kind, a0, slope, t0, amp, omega_p)
    w1 = v0 + vslope * (t - t0)
    w2 = v0 + vslope * (t + 0.5 * h - t0)
    w3 = v0 + vslope * (t + h - t0)
    k1t = omega
    k1w = _theta_acc(theta, u1, w1, side, p2, alpha, g)
    k2t = omega + 0.5 * h * k1w
    k2w = _theta_acc(theta + 0.5 * h * k1t, u2, w2, side, p2, alpha, g)
    k3t = omega + 0.5 * h * k2w
    k3w = _theta_acc(theta + 0.5 * h * k2t, u2, w2, side, p2, alpha, g)
    k4t = omega + h * k3w
    k4w = _theta_acc(theta + h * k3t, u3, w3, side, p2, alpha, g)
    return (theta + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t),
            omega + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w))


@numba.njit(cache=True, nogil=True)
def _locate(which, target, lo, hi, theta, omega, t, side, p2, alpha, g,
            kind, a0, slope, t0, amp, omega_p, v0, vslope):
    """Step length τ in [lo, hi] at which θ (which=0) or θ' (which=1) equals ``target``.

    The bracket must hold a sign change of (value − target). Newton steps use the exact
    derivative of the continuous Runge–Kutta trajectory (θ' or Eq. 4.3), with bisection
    whenever Newton leaves the bracket. Returns (τ, θ(τ), θ'(τ)).
    """
    th, om = _rk4(theta, omega, t, hi, side, p2, alpha, g, kind, a0, slope, t0, amp, omega_p,
                  v0, vslope)
    hi_positive = ((th if which == 0 else om) - target) > 0.0
    tau = 0.5 * (lo + hi)
    for _ in range(100):
        th, om = _rk4(theta, omega, t, tau, side, p2, alpha, g, kind, a0, slope, t0, amp,
                      omega_p, v0, vslope)
        f = (th if which == 0 else om) - target
        if f == 0.0 or hi - lo < 1e-15 * (1.0 + t):
            break
        # orient on the end whose sign is known strictly, so a root at lo itself is never taken
        if (f > 0.0) == hi_positive:
            hi = tau
        else:
            lo = tau
        if which == 0:
            slope_f = om
        else:
            slope_f = _theta_acc(th, _ground(t + tau, kind, a0, slope, t0, amp, omega_p),
                                 v0 + vslope * (t + tau - t0), side, p2, alpha, g)
        step = tau - f / slope_f if slope_f != 0.0 else 0.5 * (lo + hi)
        tau = step if lo < step < hi else 0.5 * (lo + hi)
    return tau, th, om


@numba.njit(cache=True, nogil=True)
def _restoring(t_a, t_b, kind, a0, slope, t0, amp, omega_p, v0, vslope, p2, alpha, g):
    """Smallest restoring deceleration on either corner at small θ over [t_a, t_b] inside one
    smooth interval [rad/s²] (negative where the ground can lift the block there)."""
    largest = _largest_ground(t_a, t_b, kind, a0, slope, t0, amp, omega_p)
    weight = g + min(v0 + vslope * (t_a - t0), v0 + vslope * (t_b - t0))
    return p2 * math.cos(alpha) * (weight * math.tan(alpha) - largest) / g


@numba.njit(cache=True, nogil=True)
def _chatter_ends(omega, t_imp, t1, kind, a0, slope, t0, amp, omega_p, v0, vslope, p2, alpha, g,
                  velocity_ratio, rest_tolerance):
    """Whether a rebound at θ' = ``omega`` at ``t_imp`` ends in rest: its chatter converges
    (:func:`chatter_time_bound`) inside the smooth interval that ends at ``t1``, before the
    ground could lift the block on either corner, with rebounds below ``rest_tolerance``·α so
    the linearised flights hold. The bound is taken over a window twice the chatter's time at
    the impact's deceleration and must fit in it. Otherwise the block rocks on: a small
    rebound while the ground is near g tan α is not rest (it can grow into real rocking)."""
    if abs(omega) < 1e-150:
        return True  # no motion left to follow (and √r·ω would stall among denormals)
    at_impact = _restoring(t_imp, t_imp, kind, a0, slope, t0, amp, omega_p, v0, vslope, p2,
                           alpha, g)
    if at_impact <= 0.0:
        return False
    window = min(2.0 * chatter_time_bound(omega, at_impact, velocity_ratio), t1 - t_imp)
    restoring = _restoring(t_imp, t_imp + window, kind, a0, slope, t0, amp, omega_p, v0, vslope,
                           p2, alpha, g)
    if restoring <= 0.0 or omega * omega >= 2.0 * restoring * rest_tolerance * alpha:
        return False
    return chatter_time_bound(omega, restoring, velocity_ratio) <= window


@numba.njit(cache=True, nogil=True)
def _simulate(acc, vertical, dt, n_tail, kind, amp, omega_p, p, alpha, velocity_ratio, g,
              steps_per_radian, rest_tolerance, theta0, omega0, theta_out, omega_out, impacts_out,
              turns_out, stride=1, reactions=False):
    """Simulate one block; see :func:`simulate`. History arrays of length 0 store nothing;
    otherwise every ``stride``-th sample is stored. ``vertical`` holds the vertical ground
    acceleration at the samples of ``acc`` [m/s²], or nothing (horizontal motion only).

    ``impacts_out`` rows: time, episode, θ' just before and just after the impact;
    ``turns_out`` rows: time and θ of each turning point (θ' = 0).

    With ``reactions``, the pivot reactions (:func:`pivot_reactions`) are evaluated at the end
    of every Runge–Kutta step of the rocking motion and on both sides of every impact; at rest
    on the base H = m üg and V = m (g + üv), whose largest ratio over the samples is capped at
    tan α (beyond it the block uplifts, at exactly tan α).

    Returns (peak |θ|, peak |θ'|, peak |θ| after the excitation, overturned, overturn time,
    number of impacts, uplifted, peak θ signed, number of turning points, max |H|/V (the
    friction pure rocking requires, inf where the block would jump), min V/(mg)); the last two
    are NaN without ``reactions``.
    """
    n_rec = acc.size
    n_seg = n_rec - 1 + n_tail
    t_exc_end = (n_rec - 1) * dt
    store = theta_out.size > 0
    has_vertical = vertical.size > 0
    p2 = p * p
    tan_alpha = math.tan(alpha)
    n_sub = max(1, int(math.ceil(dt * p * steps_per_radian)))
    h_sub = dt / n_sub
    last_exceed = -1
    max_ratio = 0.0
    min_vertical = math.inf
    for i in range(n_rec):
        uv = vertical[i] if has_vertical else 0.0
        if _lifts(acc[i], uv, g, tan_alpha):
            last_exceed = i
        if reactions:
            max_ratio = max(max_ratio, min(_friction_ratio(acc[i], g + uv), tan_alpha))
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
            a0 = acc[k]
            slope = (acc[k + 1] - acc[k]) / dt
            if has_vertical:
                v0 = vertical[k]
                vslope = (vertical[k + 1] - vertical[k]) / dt
        else:
            seg_kind = _SAMPLED
            a0 = 0.0
            slope = 0.0
        after = t0 >= t_exc_end - 1e-12 * dt
        t = t0
        while t < t1 - 1e-12 * dt:
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
                tau, th_e, om_e = _locate(1, 0.0, 0.0, h, theta, omega, t, side, p2, alpha, g,
                                          seg_kind, a0, slope, t0, amp, omega_p, v0, vslope)
                lo = tau
                if abs(th_e) >= alpha:
                    th_n = th_e  # overturned before the turning point: handled below
                    h = tau
                else:
                    if n_turns < turns_out.shape[0]:
                        turns_out[n_turns, 0] = t + tau
                        turns_out[n_turns, 1] = th_e
                    n_turns += 1
                    if abs(th_e) > peak:
                        peak = abs(th_e)
                        peak_signed = th_e
                    if after and abs(th_e) > peak_after:
                        peak_after = abs(th_e)
            if side * th_n >= alpha:
                tau, th_o, om_o = _locate(0, side * alpha, 0.0, h, theta, omega, t, side, p2, alpha,
                                          g, seg_kind, a0, slope, t0, amp, omega_p, v0, vslope)
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
                tau, th_i, om_i = _locate(0, 0.0, lo, h, theta, omega, t, side, p2, alpha, g,
                                          seg_kind, a0, slope, t0, amp, omega_p, v0, vslope)
                if abs(om_i) > peak_omega:
                    peak_omega = abs(om_i)
                t_imp = t + tau
                if n_impacts < impacts_out.shape[0]:
                    impacts_out[n_impacts, 0] = t_imp
                    impacts_out[n_impacts, 1] = episode
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
                    impacts_out[n_impacts, 2] = om_i
                    impacts_out[n_impacts, 3] = omega
                n_impacts += 1
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
        if overturned:
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
    return (peak, peak_omega, peak_after, overturned, t_over, n_impacts, uplifted, peak_signed,
            n_turns, max_ratio, min_vertical)


@numba.njit(cache=True, nogil=True)
def _spectrum(acc, vertical, dt, n_tail, kind, amp, omega_p, p, alpha, velocity_ratio, g,
              steps_per_radian, rest_tolerance, reactions, out):
    """Peaks of many blocks under one motion; fills ``out`` (n_blocks × 7)."""
    empty = np.empty(0)
    no_events = np.empty((0, 4))
    for i in range(p.size):
        res = _simulate(acc, vertical, dt, n_tail, kind, amp, omega_p, p[i], alpha[i],
                        velocity_ratio[i], g, steps_per_radian, rest_tolerance, 0.0, 0.0, empty,
                        empty, no_events, no_events, 1, reactions)
        out[i, 0] = res[0]
        out[i, 1] = res[1]
        out[i, 2] = res[2]
        out[i, 3] = 1.0 if res[3] else 0.0
        out[i, 4] = 1.0 if res[6] else 0.0
        out[i, 5] = res[9]
        out[i, 6] = res[10]


def _motion_arguments(motion, free_motion_s, vertical: bool = False):
    """Kernel arguments describing the excitation of a GroundMotion (its vertical component
    too with ``vertical``, where it has one)."""
    if free_motion_s < 0 or not math.isfinite(free_motion_s):
        raise InputError(f"duration of free motion: must be ≥ 0 s, got {free_motion_s}")
    n_tail = int(math.ceil(free_motion_s / motion.dt - 1e-9))
    up = motion.vertical if vertical and motion.vertical is not None else _NO_VERTICAL
    if motion.pulse is None:
        return motion.acceleration, up, motion.dt, n_tail, _SAMPLED, 0.0, 0.0
    kind = _COSINE if motion.pulse.shape == "cosine" else _SINE
    return (motion.acceleration, up, motion.dt, n_tail, kind, motion.pulse.amplitude,
            2.0 * math.pi / motion.pulse.period_s)


@dataclass(frozen=True)
class RockingResponse:
    """Result of one simulation (all angles in rad, times in s).

    Attributes
    ----------
    time, theta, omega : numpy.ndarray
        θ(t) [rad] and θ'(t) [rad/s] on the motion's sampling grid, extended over the free
        motion (every k-th sample where that would exceed :data:`HISTORY_CAPACITY`); NaN
        after overturning.
    impact_times : numpy.ndarray
        Times of the impacts [s] (the first :data:`IMPACT_CAPACITY`).
    impact_episode : numpy.ndarray
        Rocking episode (1, 2, …; a return to rest ends one) of each impact.
    impact_velocities : numpy.ndarray
        θ' just before and just after each impact [rad/s], shape (n, 2) (Eq. 4.6–4.8; 0 after
        an impact that ends in rest).
    turning_times, turning_rotations : numpy.ndarray
        Time [s] and θ [rad] of every turning point θ' = 0 (the first
        :data:`IMPACT_CAPACITY`), located inside the solver's steps.
    overturned : bool
    overturn_time : float
        NaN when the block survives.
    peak_rotation : float
        max |θ| [rad] (α when overturned).
    peak_rotation_signed : float
        θ at the peak [rad].
    peak_angular_velocity : float
        max |θ'| [rad/s].
    peak_rotation_after_excitation : float
        max |θ| after the excitation ends [rad].
    n_impacts : int
    uplifted : bool
    block : RigidBlock
    excitation_end : float
        End of the excitation [s].
    required_friction : float
        Friction coefficient max |H|/V [-] the pure-rocking response needs at its pivot
        (:func:`pivot_reactions`; inf where it would jump).
    min_vertical_reaction : float
        Smallest vertical reaction V/(mg) [-]; below zero the block would jump.
    """

    time: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    impact_times: np.ndarray
    impact_episode: np.ndarray
    impact_velocities: np.ndarray
    turning_times: np.ndarray
    turning_rotations: np.ndarray
    overturned: bool
    overturn_time: float
    peak_rotation: float
    peak_rotation_signed: float
    peak_angular_velocity: float
    peak_rotation_after_excitation: float
    n_impacts: int
    uplifted: bool
    block: RigidBlock
    excitation_end: float
    required_friction: float = math.nan
    min_vertical_reaction: float = math.nan

    @property
    def jumps(self) -> bool:
        """Whether the vertical pivot reaction becomes negative: the block would leave the
        ground, which pure rocking does not model."""
        return bool(self.min_vertical_reaction < 0)

    @property
    def peak_rotation_ratio(self) -> float:
        """max |θ| / α [-]."""
        return self.peak_rotation / self.block.alpha

    @property
    def peak_rotation_free_vibration(self) -> float:
        """Largest |θ| at a turning point (θ' = 0) strictly after the excitation ends [rad].

        The peak of the free vibration of Figures 4.1–4.2 (0.38α in Figure 4.2); NaN when the
        block overturns or has no turning point after the excitation.
        """
        after = self.turning_times > self.excitation_end
        if self.overturned or not after.any():
            return math.nan
        return float(np.max(np.abs(self.turning_rotations[after])))

    def history(self):
        """The response at every solver output point, in time order.

        The motion's sampling grid (up to overturning) merged with every turning point
        (θ' = 0) and every impact, which appears twice at its time: θ' just before, then just
        after.

        Returns
        -------
        time, theta, omega : numpy.ndarray
            t [s], θ [rad], θ' [rad/s].
        """
        defined = np.isfinite(self.theta)
        n_impacts, n_turns = self.impact_times.size, self.turning_times.size
        time = np.concatenate((self.time[defined], self.turning_times, self.impact_times,
                               self.impact_times))
        theta = np.concatenate((self.theta[defined], self.turning_rotations,
                                np.zeros(2 * n_impacts)))
        omega = np.concatenate((self.omega[defined], np.zeros(n_turns),
                                self.impact_velocities[:, 0], self.impact_velocities[:, 1]))
        # ties at one time: grid point and turning point, then before, then after an impact
        rank = np.repeat([0, 0, 1, 2], [int(defined.sum()), n_turns, n_impacts, n_impacts])
        order = np.lexsort((rank, time))
        return time[order], theta[order], omega[order]

    @property
    def cycle_starts(self) -> np.ndarray:
        """Start times of the full rocking cycles of :attr:`cycle_durations` [s]."""
        return self._cycles()[0]

    @property
    def cycle_durations(self) -> np.ndarray:
        """Durations of full rocking cycles [s]: time between every second impact.

        Cycles are counted from the first impact of each rocking episode; a return to rest
        ends the episode, so no cycle spans a rest.
        """
        return self._cycles()[1]

    def _cycles(self):
        starts, durations = [], []
        for episode in np.unique(self.impact_episode):
            times = self.impact_times[self.impact_episode == episode]
            starts.extend(times[:-2:2])
            durations.extend(times[2::2] - times[:-2:2])
        return np.asarray(starts), np.asarray(durations)


def simulate(block: RigidBlock, motion, free_motion_s: float = DEFAULT_FREE_MOTION_S,
             steps_per_radian: float = DEFAULT_STEPS_PER_RADIAN,
             rest_tolerance: float = DEFAULT_REST_TOLERANCE, initial_rotation: float = 0.0,
             initial_velocity: float = 0.0, vertical: bool = False) -> RockingResponse:
    """Exact rocking response of one block to one ground motion (Eq. 4.3).

    Parameters
    ----------
    block : RigidBlock
        The block (p [rad/s], α [rad], r [-], g [m/s²]).
    motion : records.GroundMotion
        Ground acceleration [m/s²], linear between samples or an analytic pulse.
    free_motion_s : float
        Free motion simulated after the excitation ends [s].
    steps_per_radian : float
        Accuracy setting: Runge–Kutta step h ≤ 1/(steps_per_radian·p) [-].
    rest_tolerance : float
        Largest rebound, as a fraction of α, of a chatter that may end in rest [-].
    initial_rotation, initial_velocity : float
        θ(0) [rad] and θ'(0) [rad/s]; the block starts at rest when both are zero.
    vertical : bool
        Include the motion's vertical component (gravity g + üv), where it has one.

    Returns
    -------
    RockingResponse
    """
    if not MIN_REST_TOLERANCE <= rest_tolerance < 1.0:
        raise InputError(f"rest tolerance: must be at least {MIN_REST_TOLERANCE:g} and below 1, "
                         f"got {rest_tolerance:g}")
    if abs(initial_rotation) >= block.alpha:
        raise InputError(f"initial rotation: |θ0| must be below α = {block.alpha:g} rad, "
                         f"got {initial_rotation:g}")
    args = _motion_arguments(motion, free_motion_s, vertical)
    n_samples = motion.acceleration.size + args[3]
    stride = -(-n_samples // HISTORY_CAPACITY)
    n_out = (n_samples - 1) // stride + 1
    theta = np.empty(n_out)
    omega = np.empty(n_out)
    impacts = np.empty((IMPACT_CAPACITY, 4))
    turns = np.empty((IMPACT_CAPACITY, 2))
    n_steps = (n_samples - 1) * math.ceil(motion.dt * block.p * steps_per_radian)
    kernel = tiered(_simulate, n_steps * INTERPRETED_STEP_S)
    res = kernel(*args, block.p, block.alpha, math.sqrt(block.r), block.g, steps_per_radian,
                 rest_tolerance, initial_rotation, initial_velocity, theta, omega, impacts, turns,
                 stride, True)
    n_kept = min(int(res[5]), IMPACT_CAPACITY)
    n_turns = min(int(res[8]), IMPACT_CAPACITY)
    return RockingResponse(
        time=np.arange(n_out) * (stride * motion.dt), theta=theta, omega=omega,
        impact_times=impacts[:n_kept, 0].copy(), impact_episode=impacts[:n_kept, 1].astype(int),
        impact_velocities=impacts[:n_kept, 2:].copy(), turning_times=turns[:n_turns, 0].copy(),
        turning_rotations=turns[:n_turns, 1].copy(),
        overturned=bool(res[3]), overturn_time=float(res[4]), peak_rotation=float(res[0]),
        peak_rotation_signed=float(res[7]), peak_angular_velocity=float(res[1]),
        peak_rotation_after_excitation=float(res[2]), n_impacts=int(res[5]),
        uplifted=bool(res[6]), block=block, excitation_end=motion.duration,
        required_friction=float(res[9]), min_vertical_reaction=float(res[10]),
    )


@dataclass(frozen=True)
class RockingSpectrum:
    """Rocking spectra of one record over a grid of blocks (Section 5).

    Arrays are shaped (len(alpha_rad), len(size_s)).

    Attributes
    ----------
    size_s : numpy.ndarray
        Block "sizes" 2π/p [s].
    alpha_rad : numpy.ndarray
        Slendernesses α [rad].
    theta_peak : numpy.ndarray
        max |θ| [rad] (α where the block overturns).
    omega_peak : numpy.ndarray
        max |θ'| [rad/s].
    theta_after : numpy.ndarray
        max |θ| after the excitation [rad].
    overturned, uplifted : numpy.ndarray of bool
    required_friction : numpy.ndarray
        Friction coefficient max |H|/V [-] pure rocking needs (inf where the block would jump).
    min_vertical_reaction : numpy.ndarray
        Smallest vertical pivot reaction V/(mg) [-]; below zero the block would jump.
    """

    size_s: np.ndarray
    alpha_rad: np.ndarray
    theta_peak: np.ndarray
    omega_peak: np.ndarray
    theta_after: np.ndarray
    overturned: np.ndarray
    uplifted: np.ndarray
    required_friction: np.ndarray
    min_vertical_reaction: np.ndarray

    @property
    def jumps(self) -> np.ndarray:
        """Blocks whose vertical pivot reaction becomes negative (they would leave the ground)."""
        return self.min_vertical_reaction < 0

    @property
    def p(self) -> np.ndarray:
        """Frequency parameters 2π/size [rad/s]."""
        return 2.0 * np.pi / self.size_s

    @property
    def theta_ratio(self) -> np.ndarray:
        """max |θ| / α [-]."""
        return self.theta_peak / self.alpha_rad[:, None]

    def to_frame(self):
        """One row per block: ``alpha_deg, size_s, p_rad_s, theta_peak_rad, theta_ratio,
        overturned, omega_peak_rad_s, theta_after_rad, uplifted, required_friction, jumps`` (the
        CSV of ``spectrum`` and ``rocking.csv``)."""
        import pandas as pd  # here, so that one simulation (``rock``) does not load pandas
        alpha_deg = np.round(np.degrees(self.alpha_rad), 10)  # 15, not 14.999999999999998
        return pd.concat([pd.DataFrame({
            "alpha_deg": alpha_deg[i], "size_s": self.size_s, "p_rad_s": self.p,
            "theta_peak_rad": self.theta_peak[i], "theta_ratio": self.theta_ratio[i],
            "overturned": self.overturned[i], "omega_peak_rad_s": self.omega_peak[i],
            "theta_after_rad": self.theta_after[i], "uplifted": self.uplifted[i],
            "required_friction": self.required_friction[i], "jumps": self.jumps[i]})
            for i in range(self.alpha_rad.size)], ignore_index=True)


def rocking_blocks(motion, size_s, alpha_rad, r=None, g: float | None = None,
                   free_motion_s: float = DEFAULT_FREE_MOTION_S,
                   steps_per_radian: float = DEFAULT_STEPS_PER_RADIAN,
                   rest_tolerance: float = DEFAULT_REST_TOLERANCE, jobs: int = 1,
                   reactions: bool = False, vertical: bool = False) -> np.ndarray:
    """Peaks of blocks given one by one, ``size_s[i]`` with ``alpha_rad[i]``, under one motion.

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²].
    size_s, alpha_rad : array
        Size 2π/p [s] and slenderness α [rad] of each block (same length).
    r : float or Restitution, optional
        Coefficient of restitution for every block, or the impact model giving each α its r;
        Eq. 4.8 of each α when not given.
    g : float, optional
        Acceleration of gravity [m/s²].
    jobs : int
        Threads sharing the blocks (the kernel releases the GIL).
    reactions : bool
        Also evaluate the pivot reactions over the response (about 25 % more work).
    vertical : bool
        Include the motion's vertical component (gravity g + üv), where it has one.

    Returns
    -------
    numpy.ndarray
        Shaped (block, 7): max |θ| [rad], max |θ'| [rad/s], max |θ| after the excitation
        [rad], overturned, uplifted (0 or 1), the friction coefficient pure rocking requires
        [-] and the smallest vertical reaction V/(mg) [-] (both NaN without ``reactions``).
    """
    size_s = np.atleast_1d(np.asarray(size_s, dtype=float))
    alpha = np.atleast_1d(np.asarray(alpha_rad, dtype=float))
    if not (size_s.size and np.all(np.isfinite(size_s) & (size_s > 0))):
        raise InputError("sizes: every 2π/p must be a positive number of seconds")
    # RigidBlock validates α, r and g once per slenderness, with the same messages as elsewhere
    unique, inverse = np.unique(alpha, return_inverse=True)
    blocks = [RigidBlock(2 * np.pi / size_s.max(), a, r, **({} if g is None else {"g": g}))
              for a in unique]
    p = 2.0 * np.pi / size_s
    ratio = np.sqrt(np.array([b.r for b in blocks]))[inverse.ravel()]
    args = _motion_arguments(motion, free_motion_s, vertical)
    out = np.empty((p.size, 7))
    # longest runs (small blocks: many steps) first, spread round-robin over the threads
    order = np.argsort(p, kind="stable")[::-1]
    chunks = [order[i::max(1, jobs)] for i in range(max(1, jobs))]

    def run(chunk):
        part = np.empty((chunk.size, 7))
        _spectrum(*args, p[chunk], alpha[chunk], ratio[chunk], blocks[0].g,
                  steps_per_radian, rest_tolerance, reactions, part)
        out[chunk] = part

    # even one chunk runs in a worker thread, so that Ctrl-C reaches the main thread at once
    # instead of after the compiled kernel returns; on an interrupt nothing waits for the rest
    pool = ThreadPoolExecutor(len(chunks))
    try:
        list(pool.map(run, chunks))
    finally:
        pool.shutdown(wait=False, cancel_futures=True)
    return out


def rocking_spectrum(motion, size_s, alpha_rad, r=None, g: float | None = None,
                     free_motion_s: float = DEFAULT_FREE_MOTION_S,
                     steps_per_radian: float = DEFAULT_STEPS_PER_RADIAN,
                     rest_tolerance: float = DEFAULT_REST_TOLERANCE, jobs: int = 1,
                     reactions: bool = True, vertical: bool = False) -> RockingSpectrum:
    """Peak rotation and angular velocity of every block of a (α, 2π/p) grid under one motion
    (:func:`rocking_blocks` over the grid).

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²].
    size_s : array
        Block sizes 2π/p [s].
    alpha_rad : array
        Slendernesses α [rad].
    r : float or Restitution, optional
        Coefficient of restitution for every block, or the impact model giving each α its r;
        Eq. 4.8 of each α when not given.
    g : float, optional
        Acceleration of gravity [m/s²].
    jobs : int
        Threads sharing the blocks (the kernel releases the GIL).
    reactions, vertical : bool
        As for :func:`rocking_blocks`.

    Returns
    -------
    RockingSpectrum
    """
    size_s = np.atleast_1d(np.asarray(size_s, dtype=float))
    alpha_rad = np.atleast_1d(np.asarray(alpha_rad, dtype=float))
    grid_alpha, grid_size = np.meshgrid(alpha_rad, size_s, indexing="ij")
    out = rocking_blocks(motion, grid_size.ravel(), grid_alpha.ravel(), r, g, free_motion_s,
                         steps_per_radian, rest_tolerance, jobs, reactions, vertical)
    shape = grid_size.shape
    return RockingSpectrum(size_s, alpha_rad, out[:, 0].reshape(shape), out[:, 1].reshape(shape),
                           out[:, 2].reshape(shape), out[:, 3].reshape(shape).astype(bool),
                           out[:, 4].reshape(shape).astype(bool), out[:, 5].reshape(shape),
                           out[:, 6].reshape(shape))


__all__ = ["simulate", "rocking_spectrum", "rocking_blocks", "pivot_reactions", "RockingResponse",
           "RockingSpectrum",
           "coefficient_of_restitution", "DEFAULT_FREE_MOTION_S"]
