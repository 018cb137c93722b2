"""The equation of motion of a rocking block (Eq. 4.3 of Makris & Konstantinidis 2001), its
Runge–Kutta step, the location of events inside a step, and the pivot reactions."""

from __future__ import annotations

import math

from audit.physics.kernel_cache import kernel

# Ground-motion kinds understood by the kernel.
_SAMPLED, _COSINE, _SINE = 0, 1, 2


@kernel(inline="always")
def _ground(t, kind, a0, slope, t0, amp, omega_p):
    """üg at time t on the current smooth interval."""
    if kind == _SAMPLED:
        return a0 + slope * (t - t0)
    if kind == _COSINE:
        return amp * math.cos(omega_p * t)
    return amp * math.sin(omega_p * t)


@kernel(inline="always")
def _moment(sin_phi, cos_phi, ug, g_uv):
    """M(φ) = (g + üv) sin φ + üg cos φ: the moment of the weight and the ground's inertia force
    about the pivot per m·R, with φ = sα − θ (s the side of the current pivot) and ``g_uv`` the
    gravity g + üv under a vertical ground acceleration üv. Eq. 4.3 is θ'' = −(p²/g) M(φ)
    (g → g + üv in its moment of the weight; p² = 3g/(4R) keeps the nominal g); without
    vertical motion g + 0 is g exactly, so the horizontal-only response is the same as without
    the term to the last bit. dM/dφ is (g + üv) cos φ − üg sin φ."""
    return g_uv * sin_phi + ug * cos_phi


@kernel(inline="always")
def _theta_acc(theta, ug, uv, side, p2, alpha, g):
    """Eq. 4.3 with sgn(θ) replaced by the side of the current pivot (:func:`_moment`)."""
    phi = side * alpha - theta
    return -p2 / g * _moment(math.sin(phi), math.cos(phi), ug, g + uv)


#: Largest |δ| for which :func:`_turned_moment` uses its polynomials: their first omitted
#: terms, δ⁹/9! and δ¹⁰/10!, are below 1e-19 there, far under the rounding of φ itself
#: (~1e-17). A step of h ≤ 1/(40 p) turns φ by |h θ'| < 0.02 on the seed records, scaled × 3
#: too; beyond the bound libm takes over.
_SHORT_TURN = 1.0 / 32.0
# Taylor coefficients of sin δ (δ³ … δ⁷) and cos δ − 1 (δ² … δ⁸).
_S3, _S5, _S7 = -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0
_C2, _C4, _C6, _C8 = -0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0


@kernel(inline="always")
def _turned_moment(moment, moment_slope, phi, delta, ug, g_uv):
    """M(φ + δ) = M(φ) cos δ + M'(φ) sin δ (angle addition) from M = :func:`_moment` and
    M' = dM/dφ at φ, with sin δ and cos δ − 1 as short polynomials in δ (Estrin's scheme, for a
    short chain of dependent operations: a solve is one such chain). Exact to rounding for
    |δ| ≤ :data:`_SHORT_TURN`; libm beyond."""
    if abs(delta) > _SHORT_TURN:
        return _moment(math.sin(phi + delta), math.cos(phi + delta), ug, g_uv)
    d2 = delta * delta
    d4 = d2 * d2
    sin_d = delta + delta * d2 * ((_S3 + _S5 * d2) + _S7 * d4)
    cos_d1 = d2 * ((_C2 + _C4 * d2) + d4 * (_C6 + _C8 * d2))
    return moment + (moment * cos_d1 + moment_slope * sin_d)


@kernel(inline="always")
def _lifts(ug, uv, g, tan_alpha):
    """Whether the ground lifts a block at rest: |üg| > (g + üv) tan α."""
    return abs(ug) > (g + uv) * tan_alpha



@kernel()
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


@kernel(inline="always")
def _friction_ratio(horizontal, vertical):
    """|H| / V, infinite where V ≤ 0 (no friction keeps a jumping block in place)."""
    return abs(horizontal) / vertical if vertical > 0.0 else math.inf


@kernel()
def _rk4(theta, omega, t, h, side, p2, alpha, g, kind, a0, slope, t0, amp, omega_p, v0, vslope):
    """One classical Runge–Kutta step of length h from (θ, θ') at t; the vertical ground
    acceleration is v0 + vslope·(t − t0) on the interval (zero without vertical motion).

    One libm sin and cos per step: the later stages' angles φ − δ differ from the step's
    φ = sα − θ by θ's stage increments δ = h/2·k1, h/2·k2, h·k3, and their moments are turned
    from φ's (:func:`_turned_moment`)."""
    u1 = _ground(t, kind, a0, slope, t0, amp, omega_p)
    u2 = _ground(t + 0.5 * h, kind, a0, slope, t0, amp, omega_p)
    u3 = _ground(t + h, kind, a0, slope, t0, amp, omega_p)
    w1 = g + (v0 + vslope * (t - t0))
    w2 = g + (v0 + vslope * (t + 0.5 * h - t0))
    w3 = g + (v0 + vslope * (t + h - t0))
    to_acc = -p2 / g
    phi = side * alpha - theta
    sin_phi = math.sin(phi)
    cos_phi = math.cos(phi)
    # M and dM/dφ at φ under the ground of each time the stages read
    m1 = _moment(sin_phi, cos_phi, u1, w1)
    m2 = _moment(sin_phi, cos_phi, u2, w2)
    m2_slope = _moment(cos_phi, -sin_phi, u2, w2)
    m3 = _moment(sin_phi, cos_phi, u3, w3)
    m3_slope = _moment(cos_phi, -sin_phi, u3, w3)
    k1t = omega
    k1w = to_acc * m1
    k2t = omega + 0.5 * h * k1w
    k2w = to_acc * _turned_moment(m2, m2_slope, phi, -0.5 * h * k1t, u2, w2)
    k3t = omega + 0.5 * h * k2w
    k3w = to_acc * _turned_moment(m2, m2_slope, phi, -0.5 * h * k2t, u2, w2)
    k4t = omega + h * k3w
    k4w = to_acc * _turned_moment(m3, m3_slope, phi, -h * k3t, u3, w3)
    return (theta + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t),
            omega + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w))


@kernel()
def _locate(which, target, lo, hi, hi_value, theta, omega, t, side, p2, alpha, g,
            kind, a0, slope, t0, amp, omega_p, v0, vslope):
    """Step length τ in [lo, hi] at which θ (which=0) or θ' (which=1) equals ``target``;
    ``hi_value`` is that θ or θ' at the end of the step of length ``hi``, which the caller has
    taken already.

    The bracket must hold a sign change of (value − target). Newton steps use the exact
    derivative of the continuous Runge–Kutta trajectory (θ' or Eq. 4.3), with bisection
    whenever Newton leaves the bracket. Returns (τ, θ(τ), θ'(τ)).
    """
    hi_positive = (hi_value - target) > 0.0
    th, om = theta, omega
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

