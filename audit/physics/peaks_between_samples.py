"""The exact peaks of a damped linear oscillator's response between the samples of a record
(Eq. 3.2, ground acceleration linear between samples): within a step each of u, u', ü + üg is a
line plus a free damped oscillation, known in closed form, so an interior extremum is a root of
its derivative, looked for only where a bound says it could beat the running peak.
"""

from __future__ import annotations

import math

from audit.physics.kernel_cache import kernel


@kernel()
def _derivatives(u, v, acc, slope, two_xi_omega, omega2):
    """u, u', …, u⁽⁵⁾ at one instant from Eq. 3.2 (üg = acc with slope ``slope``, üg'' = 0)."""
    d2 = -two_xi_omega * v - omega2 * u - acc
    d3 = -two_xi_omega * d2 - omega2 * v - slope
    d4 = -two_xi_omega * d3 - omega2 * d2
    return u, v, d2, d3, d4, -two_xi_omega * d4 - omega2 * d3


@kernel()
def _closed_form(f0, g0, f2, f3, xi_omega, omega_d, omega2):
    """f(τ) = p + q·τ + e^{−ξωτ}(P cos ω_dτ + Q sin ω_dτ) from f, f', f'', f''' at τ = 0.

    Between samples f'' solves the free equation of Eq. 3.2 (the forcing is linear), so f is a
    line plus a free damped oscillation H; H(0) and H'(0) follow from H'' = f'' and H''' = f'''.
    """
    two_xi_omega = 2.0 * xi_omega
    h1 = -(f3 + two_xi_omega * f2) / omega2
    h0 = -(f2 + two_xi_omega * h1) / omega2
    return f0 - h0, g0 - h1, h0, (h1 + xi_omega * h0) / omega_d


@kernel()
def _evaluate(tau, form, xi_omega, omega_d):
    """f(τ), f'(τ), f''(τ) of a closed form from :func:`_closed_form`."""
    p, q, big_p, big_q = form
    decay = math.exp(-xi_omega * tau)
    cos = math.cos(omega_d * tau) * decay
    sin = math.sin(omega_d * tau) * decay
    p1 = -xi_omega * big_p + omega_d * big_q
    q1 = -xi_omega * big_q - omega_d * big_p
    p2 = -xi_omega * p1 + omega_d * q1
    q2 = -xi_omega * q1 - omega_d * p1
    return (p + q * tau + big_p * cos + big_q * sin, q + p1 * cos + q1 * sin,
            p2 * cos + q2 * sin)


@kernel()
def _extremum(form, low, g_low, high, xi_omega, omega_d):
    """|f| at the root of f' in [low, high], where f' changes sign and is monotone."""
    tau = low + (high - low) * 0.5
    for _ in range(60):
        _, g, g_prime = _evaluate(tau, form, xi_omega, omega_d)
        if (g > 0.0) == (g_low > 0.0):
            low = tau
        else:
            high = tau
        step = g / g_prime if g_prime != 0.0 else 0.0
        new = tau - step
        if not low < new < high:  # Newton left the bracket: bisect
            new = 0.5 * (low + high)
        if abs(new - tau) <= 1e-13 * (high - low + tau):
            tau = new
            break
        tau = new
    return abs(_evaluate(tau, form, xi_omega, omega_d)[0])


@kernel()
def _may_peak_inside(f0, g0, f2, f3, f1, g1, f2_end, reach, xi_omega, inv_omega_d, peak):
    """Whether f may have an extremum strictly inside a segment with |f| above ``peak``.

    f0, g0, f2, f3 are f, f', f'', f''' at the segment's start and f1, g1, f2_end f, f', f'' at
    its end (f is u, u' or ü + üg; all follow from the state by Eq. 3.2). Between samples the
    forcing is linear, so f'' is a free damped oscillation e^{−ξωτ}(P cos ω_dτ + Q sin ω_dτ); with
    ω_d·length < π it has at most one zero inside, hence f' at most two: one if f' changes sign
    between the ends; two only if it does not but heads for zero first (f'·f'' < 0 at the start)
    and f'' changes sign. An extremum at τ* has f'(τ*) = 0, so |f'| ≤ max|f''|·|τ − τ*| and
    |f(τ*)| ≤ max(|f(0)|, |f(L)|) + max|f''|·L²/8, with max|f''| ≤ √(P² + Q²) ≤ |P| + |Q|
    (``reach`` = L²/8, ``inv_omega_d`` = 1/ω_d: no division in this hot test).
    """
    # the bound first: once the peak is established it almost always rules the step out
    if not _may_exceed(f0, f1, f2, f3, reach, xi_omega, inv_omega_d, peak):
        return False
    return g0 * g1 < 0.0 or (g0 * f2 < 0.0 and f2 * f2_end < 0.0)


@kernel()
def _may_exceed(f0, f1, f2, f3, reach, xi_omega, inv_omega_d, peak):
    """Whether the bound of :func:`_may_peak_inside` on |f| at an extremum inside a stretch of
    length L (``reach`` = L²/8) exceeds ``peak``; it holds over a whole step, since |f''| ≤
    |P| + |Q| wherever the free oscillation of f'' runs from its start."""
    amplitude = abs(f2) + abs((f3 + xi_omega * f2) * inv_omega_d)
    return not max(abs(f0), abs(f1)) + amplitude * reach <= peak


@kernel()
def step_may_peak(u, v, u_next, v_next, acc_k, slope, n_segments, xi_omega, omega2, dt,
                  inv_omega_d, sd, sv, sa, displacement_only):
    """Whether :func:`step_peaks` may raise (sd, sv, sa) inside this step: the tests of
    :func:`_may_peak_inside` on the step's own derivatives at both ends (not the record's
    bounds of the first test), in the same operations. With one segment the step is then
    examined exactly where one of the tests inside it passes; with several, where the bound
    over the whole step does (f' may change sign more than once in it)."""
    two_xi_omega = 2.0 * xi_omega
    reach = dt * dt / 8.0
    acc_end = acc_k + slope * dt
    start = _derivatives(u, v, acc_k, slope, two_xi_omega, omega2)
    end = _derivatives(u_next, v_next, acc_end, slope, two_xi_omega, omega2)
    one = n_segments == 1
    if one:
        if _may_peak_inside(start[0], start[1], start[2], start[3], end[0], end[1], end[2],
                            reach, xi_omega, inv_omega_d, sd):
            return True
    elif _may_exceed(start[0], end[0], start[2], start[3], reach, xi_omega, inv_omega_d, sd):
        return True
    if displacement_only:
        return False
    if one:
        return (_may_peak_inside(start[1], start[2], start[3], start[4], end[1], end[2], end[3],
                                 reach, xi_omega, inv_omega_d, sv)
                or _may_peak_inside(start[2] + acc_k, start[3] + slope, start[4], start[5],
                                    end[2] + acc_end, end[3] + slope, end[4], reach, xi_omega,
                                    inv_omega_d, sa))
    return (_may_exceed(start[1], end[1], start[3], start[4], reach, xi_omega, inv_omega_d, sv)
            or _may_exceed(start[2] + acc_k, end[2] + acc_end, start[4], start[5], reach,
                           xi_omega, inv_omega_d, sa))


@kernel()
def _segment_peak(f0, g0, f2, f3, g1, length, xi_omega, omega_d, omega2):
    """Largest |f| at the roots of f' strictly inside a segment (0 if none); arguments as in
    :func:`_may_peak_inside`. Each root is bracketed where f' is monotone and located by
    :func:`_extremum`; the zero of f'' that separates two roots has a closed form."""
    form = _closed_form(f0, g0, f2, f3, xi_omega, omega_d, omega2)
    if g0 * g1 < 0.0:
        return _extremum(form, 0.0, g0, length, xi_omega, omega_d)
    # the zero of f'' = e^{−ξωτ}(P₂ cos ω_dτ + Q₂ sin ω_dτ), (P₂, Q₂) = (f''(0), (f''' + ξωf'')/ω_d)
    phase = (math.atan2((f3 + xi_omega * f2) / omega_d, f2) + 0.5 * math.pi) % math.pi
    middle = phase / omega_d
    if not 0.0 < middle < length:
        return 0.0
    g_middle = _evaluate(middle, form, xi_omega, omega_d)[1]
    if (g_middle > 0.0) == (g0 > 0.0):
        return 0.0
    return max(_extremum(form, 0.0, g0, middle, xi_omega, omega_d),
               _extremum(form, middle, g_middle, length, xi_omega, omega_d))


@kernel()
def step_peaks(u, v, u_next, v_next, acc_k, slope, n_segments, xi_omega, omega_d, omega2,
               dt, sd, sv, sa, displacement_only):
    """(sd, sv, sa) raised to the extrema of u, u', ü + üg strictly inside one step from
    (u, u') to (u_next, v_next) under üg = acc_k + slope·τ (sd alone if ``displacement_only``).

    The step is cut into ``n_segments`` sub-segments short enough that f'' has at most one zero
    in each (ω_d·length < 3 < π); each is examined where :func:`_may_peak_inside` allows.
    """
    two_xi_omega = 2.0 * xi_omega
    length = dt / n_segments
    reach = length * length / 8.0
    inv_omega_d = 1.0 / omega_d
    d_start = _derivatives(u, v, acc_k, slope, two_xi_omega, omega2)
    acc_start = acc_k
    if n_segments > 1:  # the closed form of u over the whole step
        displacement = _closed_form(u, v, d_start[2], d_start[3], xi_omega, omega_d, omega2)
    for j in range(n_segments):
        acc_end = acc_k + slope * (j + 1) * length
        if j == n_segments - 1:
            u_j, v_j = u_next, v_next
        else:
            u_j, v_j, _ = _evaluate((j + 1) * length, displacement, xi_omega, omega_d)
        d_end = _derivatives(u_j, v_j, acc_end, slope, two_xi_omega, omega2)
        if _may_peak_inside(d_start[0], d_start[1], d_start[2], d_start[3], d_end[0],
                            d_end[1], d_end[2], reach, xi_omega, inv_omega_d, sd):
            sd = max(sd, _segment_peak(d_start[0], d_start[1], d_start[2], d_start[3],
                                       d_end[1], length, xi_omega, omega_d, omega2))
        if not displacement_only:
            if _may_peak_inside(d_start[1], d_start[2], d_start[3], d_start[4], d_end[1],
                                d_end[2], d_end[3], reach, xi_omega, inv_omega_d, sv):
                sv = max(sv, _segment_peak(d_start[1], d_start[2], d_start[3], d_start[4],
                                           d_end[2], length, xi_omega, omega_d, omega2))
            sa_start = d_start[2] + acc_start
            if _may_peak_inside(sa_start, d_start[3] + slope, d_start[4], d_start[5],
                                d_end[2] + acc_end, d_end[3] + slope, d_end[4], reach,
                                xi_omega, inv_omega_d, sa):
                sa = max(sa, _segment_peak(sa_start, d_start[3] + slope, d_start[4],
                                           d_start[5], d_end[3] + slope, length, xi_omega,
                                           omega_d, omega2))
        d_start = d_end
        acc_start = acc_end
    return sd, sv, sa


__all__ = ["step_may_peak", "step_peaks"]
