"""The rest rule: when a chatter (the Zeno sequence of ever smaller rebounds after an impact)
ends in rest, summed in closed form by :func:`chatter_time_bound`."""

from __future__ import annotations

import math

from audit.physics.kernel_cache import kernel
from audit.physics.rocking.motion_equation import _COSINE, _SAMPLED, _ground

#: Smallest rest tolerance: smaller rebounds fly for less than the 1e-15 s to which impacts
#: are located, so their velocities would be noise and a chatter might never end.
MIN_REST_TOLERANCE = 1e-20


@kernel()
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


@kernel()
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



@kernel()
def _restoring(t_a, t_b, kind, a0, slope, t0, amp, omega_p, v0, vslope, p2, alpha, g):
    """Smallest restoring deceleration on either corner at small θ over [t_a, t_b] inside one
    smooth interval [rad/s²] (negative where the ground can lift the block there)."""
    largest = _largest_ground(t_a, t_b, kind, a0, slope, t0, amp, omega_p)
    weight = g + min(v0 + vslope * (t_a - t0), v0 + vslope * (t_b - t0))
    return p2 * math.cos(alpha) * (weight * math.tan(alpha) - largest) / g


@kernel()
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


