"""Response spectra of the viscously damped linear oscillator (Eq. 3.2 of Makris & Konstantinidis 2001).

u'' + 2ξω u' + ω² u = −üg, ω = 2π/T, 0 ≤ ξ < 1, solved exactly for ground acceleration that is
linear between samples (Nigam & Jennings 1969): each step is x_{k+1} = Φ x_k + Γ₀ üg_k + Γ₁ üg_{k+1}
with x = (u, u'). The coefficients are the Nigam–Jennings closed forms, written through the
functions φ₁(z) = (eᶻ − 1)/z and φ₂(z) = (eᶻ − 1 − z)/z² of the complex eigenvalue
z = (−ξω + iω_d)·dt, ω_d = ω√(1 − ξ²), so they are evaluated without the cancellation the textbook
form suffers at long periods (ω·dt → 0), vectorised over all oscillators at once; the recurrence
runs for four (period, damping) pairs at a time in one compiled loop. Overdamped oscillators
(ξ ≥ 1) are refused: no spectrum of this tool needs them. The peaks between samples are found in
:mod:`audit.physics.peaks_between_samples`, a table's spectra computed in
:mod:`audit.physics.spectrum_kernel` and assembled in :mod:`audit.physics.response_spectra`.
"""

from __future__ import annotations

import math

import numpy as np

from audit.errors import InputError
from audit.physics.kernel_cache import kernel
from audit.physics.tiers import tiered

INTERPRETED_STEP_S = 1e-6
#: Terms of the Taylor series of φ₂ used for |z| < 1 (the next term is below 1e-19).
_PHI2_TERMS = 18


def _phi2(z):
    """φ₂(z) = (eᶻ − 1 − z)/z² of complex z, to rounding: series for |z| < 1, closed form else."""
    small = np.abs(z) < 1.0
    series = np.zeros_like(z)
    for k in range(_PHI2_TERMS - 1, -1, -1):
        series = series * z + 1.0 / math.factorial(k + 2)
    # eᶻ − 1 = expm1(x) cos y − 2 sin²(y/2) + i eˣ sin y: no cancellation for any x ≤ 0
    x, y = z.real, z.imag
    expm1 = np.expm1(x) * np.cos(y) - 2.0 * np.sin(0.5 * y) ** 2 + 1j * np.exp(x) * np.sin(y)
    with np.errstate(divide="ignore", invalid="ignore"):
        closed = (expm1 - z) / (z * z)
    return np.where(small, series, closed)


def recurrence_coefficients(period_s, damping, dt):
    """Exact one-step coefficients of Eq. 3.2 for üg linear between samples (Nigam & Jennings).

    With A = [[0, 1], [−ω², −2ξω]] and b = (0, −1), the step is
    x(dt) = e^{A·dt} x₀ + dt [φ₁ − φ₂](A·dt) b üg_k + dt φ₂(A·dt) b üg_{k+1}.
    Any function f of the 2×2 matrix A·dt, whose eigenvalues are z and z̄, is f(A·dt) =
    α₀ I + α₁ A·dt with α₁ = Im f(z)/Im z and α₀ = Re f(z) − α₁ Re z; f = exp, φ₁ − φ₂ and φ₂
    give Φ, Γ₀ and Γ₁ in closed form (the Nigam–Jennings coefficients, term for term).

    Parameters
    ----------
    period_s : array
        Natural periods T > 0 [s].
    damping : array
        Damping ratios 0 ≤ ξ < 1 [-], broadcast against ``period_s``.
    dt : float
        Sampling step [s].

    Returns
    -------
    numpy.ndarray
        Shape (n, 2, 4): rows u and u'; columns Φ (2), Γ₀, Γ₁ multiplying üg_k, üg_{k+1}.
    """
    period_s, damping = np.broadcast_arrays(np.asarray(period_s, dtype=float),
                                            np.asarray(damping, dtype=float))
    period_s, damping = period_s.ravel(), damping.ravel()
    if not np.all(np.isfinite(period_s) & (period_s > 0)):
        raise InputError("periods: every T must be a positive number of seconds")
    if not np.all((damping >= 0) & (damping < 1)):
        raise InputError("damping: every ratio must lie in [0, 100) % (overdamped oscillators "
                         "are not supported)")
    omega = 2.0 * np.pi / period_s
    z = dt * omega * (-damping + 1j * np.sqrt(1.0 - damping ** 2))
    phi2 = _phi2(z)
    phi1 = 1.0 + z * phi2

    def matrix_terms(f):
        """(α₀, α₁·dt) of f(A·dt) = α₀ I + α₁ A·dt."""
        alpha1 = f.imag / z.imag
        return f.real - alpha1 * z.real, alpha1 * dt

    coeffs = np.empty((period_s.size, 2, 4))
    a0, a1 = matrix_terms(np.exp(z))
    coeffs[:, 0, 0], coeffs[:, 0, 1] = a0, a1
    coeffs[:, 1, 0], coeffs[:, 1, 1] = -omega ** 2 * a1, a0 - 2.0 * damping * omega * a1
    for column, f in ((2, phi1 - phi2), (3, phi2)):
        # f(A·dt)·b·dt, b = (0, −1): A·b = (−1, 2ξω)
        a0, a1 = matrix_terms(f)
        coeffs[:, 0, column] = -dt * a1
        coeffs[:, 1, column] = -dt * (a0 - 2.0 * damping * omega * a1)
    return coeffs


#: Oscillators whose recurrences :func:`sampled_responses` runs side by side: one step waits on
#: the last (a multiply and three adds in a chain), so four independent chains keep the core
#: busy where one leaves it waiting; each runs the same operations as alone, so bit for bit.
LANES = 4


@kernel(inline="always")
def step_coefficients(c):
    """The eight numbers :func:`oscillator_step` reads, from an oscillator's (2, 4) row of
    :func:`recurrence_coefficients`; held as values, a loop keeps them in registers instead of
    loading them at every step."""
    return (c[0, 0], c[0, 1], c[0, 2], c[0, 3], c[1, 0], c[1, 1], c[1, 2], c[1, 3])


@kernel(inline="always")
def oscillator_step(c, u, v, acc_k, acc_next):
    """One exact step of the recurrence: (u, u') at the next sample (``c`` from
    :func:`step_coefficients`)."""
    return (c[0] * u + c[1] * v + c[2] * acc_k + c[3] * acc_next,
            c[4] * u + c[5] * v + c[6] * acc_k + c[7] * acc_next)


@kernel(inline="always")
def _raised(peaks, u, v, two_xi_omega, omega2):
    """(max|u|, max|u'|, max|ü + üg|) raised to one sample's state (ü + üg = −2ξωu' − ω²u)."""
    return (max(peaks[0], abs(u)), max(peaks[1], abs(v)),
            max(peaks[2], abs(two_xi_omega * v + omega2 * u)))


@kernel()
def sampled_responses(acc, coeffs, two_xi_omega, omega2, lanes, u_at, v_at, peaks):
    """The states of :data:`LANES` oscillators at every sample, from rest, and their peaks there.

    ``lanes`` holds four indices into ``coeffs`` (its rows from :func:`recurrence_coefficients`),
    ``two_xi_omega`` and ``omega2`` (2ξω [1/s] and ω² [1/s²]); an index may repeat (the last
    oscillators of a table). Fills ``u_at[lane]``, ``v_at[lane]`` with u [m] and u' [m/s] at the
    samples of ``acc`` and ``peaks[lane]`` with (max|u|, max|u'|, max|ü + üg|) over them.
    """
    a, b, c, d = lanes
    ca, cb = step_coefficients(coeffs[a]), step_coefficients(coeffs[b])
    cc, cd = step_coefficients(coeffs[c]), step_coefficients(coeffs[d])
    ta, tb, tc, td = two_xi_omega[a], two_xi_omega[b], two_xi_omega[c], two_xi_omega[d]
    oa, ob, oc, od = omega2[a], omega2[b], omega2[c], omega2[d]
    ua = va = ub = vb = uc = vc = ud = vd = 0.0
    pa = pb = pc = pd = (0.0, 0.0, 0.0)
    u_at[:, 0] = 0.0
    v_at[:, 0] = 0.0
    for k in range(acc.size - 1):
        ua, va = oscillator_step(ca, ua, va, acc[k], acc[k + 1])
        ub, vb = oscillator_step(cb, ub, vb, acc[k], acc[k + 1])
        uc, vc = oscillator_step(cc, uc, vc, acc[k], acc[k + 1])
        ud, vd = oscillator_step(cd, ud, vd, acc[k], acc[k + 1])
        u_at[0, k + 1], u_at[1, k + 1], u_at[2, k + 1], u_at[3, k + 1] = ua, ub, uc, ud
        v_at[0, k + 1], v_at[1, k + 1], v_at[2, k + 1], v_at[3, k + 1] = va, vb, vc, vd
        pa = _raised(pa, ua, va, ta, oa)
        pb = _raised(pb, ub, vb, tb, ob)
        pc = _raised(pc, uc, vc, tc, oc)
        pd = _raised(pd, ud, vd, td, od)
    for lane, lane_peaks in enumerate((pa, pb, pc, pd)):
        peaks[lane, 0], peaks[lane, 1], peaks[lane, 2] = lane_peaks


@kernel()
def sampled_response(acc, c, two_xi_omega, omega2, u_at, v_at):
    """:func:`sampled_responses` of one oscillator (``c`` from :func:`step_coefficients`), for a
    table of one, where four lanes would do the work four times: fills ``u_at``, ``v_at`` and
    returns the peaks."""
    u = v = 0.0
    peaks = (0.0, 0.0, 0.0)
    u_at[0] = v_at[0] = 0.0
    for k in range(acc.size - 1):
        u, v = oscillator_step(c, u, v, acc[k], acc[k + 1])
        u_at[k + 1], v_at[k + 1] = u, v
        peaks = _raised(peaks, u, v, two_xi_omega, omega2)
    return peaks


@kernel()
def _history(acc, coeffs, u_out):
    """u_out[k] = u at sample k for one oscillator, from rest."""
    c = step_coefficients(coeffs)
    u = 0.0
    v = 0.0
    u_out[0] = 0.0
    for k in range(acc.size - 1):
        u, v = oscillator_step(c, u, v, acc[k], acc[k + 1])
        u_out[k + 1] = u


def oscillator_history(motion, period_s: float, damping: float, free_motion_s: float = 0.0):
    """Relative displacement history u(t) of one oscillator (Eq. 3.2), same recurrence.

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²].
    period_s : float
        Natural period T > 0 [s].
    damping : float
        Damping ratio 0 ≤ ξ < 1 [-].
    free_motion_s : float
        Free vibration after the record [s].

    Returns
    -------
    time, u : numpy.ndarray
        Times [s] and relative displacement [m].
    """
    if not (np.isfinite(period_s) and period_s > 0):
        raise InputError(f"period: must be a positive number of seconds, got {period_s}")
    n_tail = int(np.ceil(free_motion_s / motion.dt - 1e-9))
    acc = np.concatenate((motion.acceleration, np.zeros(n_tail)))
    u = np.empty(acc.size)
    coeffs = recurrence_coefficients(period_s, damping, motion.dt)[0]
    tiered(_history, acc.size * INTERPRETED_STEP_S)(acc, coeffs, u)
    return np.arange(acc.size) * motion.dt, u


__all__ = ["recurrence_coefficients", "step_coefficients", "oscillator_step",
           "sampled_responses", "sampled_response", "oscillator_history", "LANES",
           "INTERPRETED_STEP_S"]
