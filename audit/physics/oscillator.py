"""Response spectra of the viscously damped linear oscillator (Eq. 3.2 of Makris & Konstantinidis 2001).

u'' + 2ξω u' + ω² u = −üg, ω = 2π/T, 0 ≤ ξ < 1, solved exactly for ground acceleration that is
linear between samples (Nigam & Jennings 1969): each step is x_{k+1} = Φ x_k + Γ₀ üg_k + Γ₁ üg_{k+1}
with x = (u, u'). The coefficients are the Nigam–Jennings closed forms, written through the
functions φ₁(z) = (eᶻ − 1)/z and φ₂(z) = (eᶻ − 1 − z)/z² of the complex eigenvalue
z = (−ξω + iω_d)·dt, ω_d = ω√(1 − ξ²), so they are evaluated without the cancellation the textbook
form suffers at long periods (ω·dt → 0), vectorised over all oscillators at once; the recurrence
runs for every (period, damping) pair in one compiled loop. Overdamped oscillators (ξ ≥ 1) are
refused: no spectrum of this tool needs them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.tiers import tiered

#: Time of one step of the recurrence run interpreted (see audit.physics.tiers) [s].
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


@numba.njit(cache=True, nogil=True)
def _step(c, u, v, acc_k, acc_next):
    """One exact step of the recurrence: (u, u') at the next sample."""
    return (c[0, 0] * u + c[0, 1] * v + c[0, 2] * acc_k + c[0, 3] * acc_next,
            c[1, 0] * u + c[1, 1] * v + c[1, 2] * acc_k + c[1, 3] * acc_next)


@numba.njit(cache=True, nogil=True)
def _history(acc, coeffs, u_out):
    """u_out[k] = u at sample k for one oscillator, from rest."""
    u = 0.0
    v = 0.0
    u_out[0] = 0.0
    for k in range(acc.size - 1):
        u, v = _step(coeffs, u, v, acc[k], acc[k + 1])
        u_out[k + 1] = u


@numba.njit(cache=True, nogil=True)
def _derivatives(u, v, acc, slope, two_xi_omega, omega2):
    """u, u', …, u⁽⁵⁾ at one instant from Eq. 3.2 (üg = acc with slope ``slope``, üg'' = 0)."""
    d2 = -two_xi_omega * v - omega2 * u - acc
    d3 = -two_xi_omega * d2 - omega2 * v - slope
    d4 = -two_xi_omega * d3 - omega2 * d2
    return u, v, d2, d3, d4, -two_xi_omega * d4 - omega2 * d3


@numba.njit(cache=True, nogil=True)
def _closed_form(f0, g0, f2, f3, xi_omega, omega_d, omega2):
    """f(τ) = p + q·τ + e^{−ξωτ}(P cos ω_dτ + Q sin ω_dτ) from f, f', f'', f''' at τ = 0.

    Between samples f'' solves the free equation of Eq. 3.2 (the forcing is linear), so f is a
    line plus a free damped oscillation H; H(0) and H'(0) follow from H'' = f'' and H''' = f'''.
    """
    two_xi_omega = 2.0 * xi_omega
    h1 = -(f3 + two_xi_omega * f2) / omega2
    h0 = -(f2 + two_xi_omega * h1) / omega2
    return f0 - h0, g0 - h1, h0, (h1 + xi_omega * h0) / omega_d


@numba.njit(cache=True, nogil=True)
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


@numba.njit(cache=True, nogil=True)
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


@numba.njit(cache=True, nogil=True)
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
    amplitude = abs(f2) + abs((f3 + xi_omega * f2) * inv_omega_d)
    if max(abs(f0), abs(f1)) + amplitude * reach <= peak:
        return False
    return g0 * g1 < 0.0 or (g0 * f2 < 0.0 and f2 * f2_end < 0.0)


@numba.njit(cache=True, nogil=True)
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


@numba.njit(cache=True, nogil=True)
def _step_peaks(u, v, u_next, v_next, acc_k, slope, n_segments, xi_omega, omega_d, omega2,
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


@numba.njit(cache=True, nogil=True)
def _peaks(acc, dt, coeffs, omega, damping, between_samples, displacement_only, out):
    """out[i] = (max|u|, max|u'|, max|u'' + üg|) of oscillator i (see :func:`response_spectra`);
    with ``displacement_only`` the last two are NaN and only max|u| is searched between samples.

    Two passes per oscillator. The first runs the recurrence, keeps the states at the samples
    and their peaks. The second looks inside a step only where an extremum there could beat
    those peaks. Inside a step each f of u, u', ü + üg has f'' = e^{−ξωτ}(P cos ω_dτ + Q sin ω_dτ)
    (:func:`_closed_form`), so |f''| ≤ |P| + |Q| over the whole step, and an interior extremum
    exceeds max(|f|) at the step's ends by at most (|P| + |Q|)·dt²/8 (:func:`_may_peak_inside`).
    By Eq. 3.2, |P| and |Q| at every sample are bounded by the sampled peaks, max|üg| and
    max|üg'|: almost every step fails the test at the cost of two loads, and the few that pass
    get the exact search of :func:`_step_peaks`.
    """
    n = acc.size
    u_at = np.empty(n)
    v_at = np.empty(n)
    acc_max = 0.0
    slope_max = 0.0
    for k in range(n):
        acc_max = max(acc_max, abs(acc[k]))
        if k:
            slope_max = max(slope_max, abs(acc[k] - acc[k - 1]) / dt)
    for i in range(coeffs.shape[0]):
        c = coeffs[i]
        xi_omega = damping[i] * omega[i]
        two_xi_omega = 2.0 * xi_omega
        omega2 = omega[i] * omega[i]
        omega_d = omega[i] * math.sqrt(1.0 - damping[i] * damping[i])
        u = 0.0
        v = 0.0
        u_at[0] = 0.0
        v_at[0] = 0.0
        sd = 0.0
        sv = 0.0
        sa = 0.0
        for k in range(n - 1):
            u, v = _step(c, u, v, acc[k], acc[k + 1])
            u_at[k + 1] = u
            v_at[k + 1] = v
            sd = max(sd, abs(u))
            sv = max(sv, abs(v))
            sa = max(sa, abs(two_xi_omega * v + omega2 * u))
        if between_samples:
            # bounds on |u''|, …, |u⁽⁵⁾| at every sample by Eq. 3.2 (see _derivatives)
            d2 = two_xi_omega * sv + omega2 * sd + acc_max
            d3 = two_xi_omega * d2 + omega2 * sv + slope_max
            d4 = two_xi_omega * d3 + omega2 * d2
            d5 = two_xi_omega * d4 + omega2 * d3
            reach = dt * dt / 8.0
            margin_d = (d2 + (d3 + xi_omega * d2) / omega_d) * reach
            margin_v = (d3 + (d4 + xi_omega * d3) / omega_d) * reach
            margin_a = (d4 + (d5 + xi_omega * d4) / omega_d) * reach
            n_segments = int(omega_d * dt / 3.0) + 1
            sa_k = 0.0
            for k in range(n - 1):
                sa_next = abs(two_xi_omega * v_at[k + 1] + omega2 * u_at[k + 1])
                if (max(abs(u_at[k]), abs(u_at[k + 1])) + margin_d > sd
                        or not displacement_only
                        and (max(abs(v_at[k]), abs(v_at[k + 1])) + margin_v > sv
                             or max(sa_k, sa_next) + margin_a > sa)):
                    sd, sv, sa = _step_peaks(u_at[k], v_at[k], u_at[k + 1], v_at[k + 1], acc[k],
                                             (acc[k + 1] - acc[k]) / dt, n_segments, xi_omega,
                                             omega_d, omega2, dt, sd, sv, sa, displacement_only)
                sa_k = sa_next
        out[i, 0] = sd
        out[i, 1] = math.nan if displacement_only else sv
        out[i, 2] = math.nan if displacement_only else sa


@dataclass(frozen=True)
class ResponseSpectra:
    """True response spectra of one record, arrays shaped (len(damping), len(period_s)).

    Attributes
    ----------
    period_s : numpy.ndarray
        Periods T [s].
    damping : numpy.ndarray
        Damping ratios ξ [-].
    sd : numpy.ndarray
        max|u|, relative displacement [m].
    sv : numpy.ndarray
        max|u'|, relative velocity [m/s] (not the pseudo-velocity).
    sa : numpy.ndarray
        max|u'' + üg|, absolute acceleration [m/s²] (not the pseudo-acceleration).
    """

    period_s: np.ndarray
    damping: np.ndarray
    sd: np.ndarray
    sv: np.ndarray
    sa: np.ndarray

    def scaled(self, factor: float) -> ResponseSpectra:
        """The spectra of the record scaled by ``factor``: a linear oscillator's response is
        linear in the ground motion, so every spectrum is ``factor`` times this one."""
        return ResponseSpectra(self.period_s, self.damping, self.sd * factor, self.sv * factor,
                               self.sa * factor)

    @property
    def pseudo_velocity(self) -> np.ndarray:
        """PSv = ω·Sd [m/s], a pseudo spectrum (not max|u'|); 0 at T = 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.period_s > 0, 2.0 * np.pi / self.period_s * self.sd, 0.0)

    @property
    def pseudo_acceleration(self) -> np.ndarray:
        """PSa = ω²·Sd [m/s²], a pseudo spectrum (not max|u'' + üg|); PGA at T = 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.period_s > 0, (2.0 * np.pi / self.period_s) ** 2 * self.sd,
                            self.sa)

    def to_frame(self):
        """One row per (damping, period): ``period_s, damping_pct, sd_m, sv_m_s, sa_g, psv_m_s,
        psa_g`` (accelerations in g and damping in %, the units of every CSV and figure)."""
        import pandas as pd  # only tables need pandas: keeps the solver's import light
        return pd.concat([pd.DataFrame({
            "period_s": self.period_s, "damping_pct": 100.0 * damping, "sd_m": self.sd[i],
            "sv_m_s": self.sv[i], "sa_g": self.sa[i] / G, "psv_m_s": self.pseudo_velocity[i],
            "psa_g": self.pseudo_acceleration[i] / G})
            for i, damping in enumerate(self.damping)], ignore_index=True)

    def displacement_at(self, period_s, damping_index: int) -> np.ndarray:
        """Sd [m] at arbitrary periods [s] by linear interpolation in T.

        Beyond the longest computed period the last value is held (the displacement spectrum
        of a record tends to the peak ground displacement there).
        """
        return np.interp(period_s, self.period_s, self.sd[damping_index])


def response_spectra(motion, period_s, damping, free_motion_s: float = 0.0,
                     between_samples: bool = True, jobs: int = 1,
                     displacement_only: bool = False) -> ResponseSpectra:
    """True displacement, velocity and acceleration spectra of a record (Eq. 3.2).

    The peaks are those of the exact response to the piecewise-linear record, also between
    samples: for periods up to ~20·dt a peak read at the samples only is several per cent low.
    Inside a step the forcing is linear, so each of f = u, u', ü + üg is a line plus a free damped
    oscillation, known in closed form from the state at the step's start; an interior extremum is
    a root of f', which is looked for only where the sampled f', f'' say one can lie inside and a
    bound on |f| there says it could beat the running peak (see :func:`_segment_peak`), and is
    then located by safeguarded Newton iteration to ~1e-13 of the step (|f| to rounding).

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²], linear between samples.
    period_s : array
        Periods T ≥ 0 [s]; T = 0 gives Sd = Sv = 0 and Sa = PGA.
    damping : array
        Damping ratios 0 ≤ ξ < 1 [-] (0.05 for 5 %).
    free_motion_s : float
        Free vibration included after the record ends [s] (the record is followed by zeros).
    between_samples : bool
        Locate the peaks between samples (default); False reads them at the samples only, as
        most software does.
    jobs : int
        Threads sharing the oscillators (the kernel releases the GIL); every oscillator is
        computed alone, so the values do not depend on it.
    displacement_only : bool
        Sd alone (Sv and Sa are NaN, except Sa = PGA at T = 0): what the procedures read,
        at about half the cost of the search between samples.

    Returns
    -------
    ResponseSpectra
    """
    period_s = np.atleast_1d(np.asarray(period_s, dtype=float))
    damping = np.atleast_1d(np.asarray(damping, dtype=float))
    if not np.all(np.isfinite(period_s) & (period_s >= 0)):
        raise InputError("periods: every T must be a number of seconds ≥ 0")
    if not (np.isfinite(free_motion_s) and free_motion_s >= 0):
        raise InputError(f"free motion: must be ≥ 0 s, got {free_motion_s}")
    acc = motion.acceleration
    n_tail = int(np.ceil(free_motion_s / motion.dt - 1e-9))
    if n_tail:
        acc = np.concatenate((acc, np.zeros(n_tail)))
    grid_xi, grid_t = np.meshgrid(damping, period_s, indexing="ij")
    positive = grid_t > 0
    peaks = np.zeros(grid_t.shape + (3,))
    peaks[~positive, 2] = np.max(np.abs(motion.acceleration))
    periods, dampings = grid_t[positive], grid_xi[positive]
    out = np.empty((periods.size, 3))
    coeffs = recurrence_coefficients(periods, dampings, motion.dt)
    omega = 2.0 * np.pi / periods
    # interleaved chunks: short periods (costly peaks between samples) spread over the threads
    chunks = [np.arange(i, periods.size, max(1, jobs)) for i in range(max(1, min(jobs, periods.size)))]

    def run(chunk):
        part = np.empty((chunk.size, 3))
        _peaks(acc, motion.dt, coeffs[chunk], omega[chunk], dampings[chunk], between_samples,
               displacement_only, part)
        out[chunk] = part

    if len(chunks) == 1:
        run(chunks[0])
    else:
        from concurrent.futures import ThreadPoolExecutor
        with ThreadPoolExecutor(len(chunks)) as pool:
            list(pool.map(run, chunks))
    peaks[positive] = out
    return ResponseSpectra(period_s, damping, peaks[..., 0], peaks[..., 1], peaks[..., 2])


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
