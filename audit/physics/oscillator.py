"""Response spectra of the viscously damped linear oscillator (SPEC §3, Eq. 3.2).

u'' + 2ξω u' + ω² u = −üg, ω = 2π/T, solved exactly for ground acceleration that is linear
between samples (Nigam & Jennings 1969): each step is x_{k+1} = Φ x_k + Γ₀ üg_k + Γ₁ üg_{k+1},
with Φ, Γ₀, Γ₁ taken from the matrix exponential of the first-order-hold augmented system, so
they are exact for any damping (also ξ ≥ 1), and the recurrence is run for every
(period, damping) pair in one compiled loop.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
import pandas as pd
from scipy.linalg import expm

from audit import G
from audit.errors import InputError


def recurrence_coefficients(period_s, damping, dt):
    """Exact one-step coefficients of Eq. 3.2 for piecewise-linear üg.

    Parameters
    ----------
    period_s : array
        Natural periods T > 0 [s].
    damping : array
        Damping ratios ξ ≥ 0 [-], same shape as ``period_s``.
    dt : float
        Sampling step [s].

    Returns
    -------
    numpy.ndarray
        Shape (n, 2, 4): rows u and u'; columns Φ (2), Γ₀, Γ₁ multiplying üg_k, üg_{k+1}.
    """
    coeffs = np.empty((np.size(period_s), 2, 4))
    for i, (period, xi) in enumerate(zip(np.ravel(period_s), np.ravel(damping))):
        omega = 2.0 * np.pi / period
        # state (u, u', f, f') with f = −üg linear in the step: f' constant
        system = np.zeros((4, 4))
        system[0, 1] = 1.0
        system[1, 0] = -omega ** 2
        system[1, 1] = -2.0 * xi * omega
        system[1, 2] = 1.0
        system[2, 3] = 1.0
        step = expm(system * dt)
        coeffs[i, :, :2] = step[:2, :2]
        # f_k and (f_{k+1} − f_k)/dt enter through columns 2 and 3; f = −üg
        coeffs[i, :, 2] = -(step[:2, 2] - step[:2, 3] / dt)
        coeffs[i, :, 3] = -step[:2, 3] / dt
    return coeffs


@numba.njit(cache=True, nogil=True)
def _peaks(acc, coeffs, omega, damping, out):
    """Run the recurrence for each oscillator; out[i] = (max|u|, max|u'|, max|u'' + üg|)."""
    for i in range(coeffs.shape[0]):
        c = coeffs[i]
        two_xi_omega = 2.0 * damping[i] * omega[i]
        omega2 = omega[i] * omega[i]
        u = 0.0
        v = 0.0
        sd = 0.0
        sv = 0.0
        sa = 0.0
        for k in range(acc.size - 1):
            u, v = (c[0, 0] * u + c[0, 1] * v + c[0, 2] * acc[k] + c[0, 3] * acc[k + 1],
                    c[1, 0] * u + c[1, 1] * v + c[1, 2] * acc[k] + c[1, 3] * acc[k + 1])
            sd = max(sd, abs(u))
            sv = max(sv, abs(v))
            sa = max(sa, abs(two_xi_omega * v + omega2 * u))
        out[i, 0] = sd
        out[i, 1] = sv
        out[i, 2] = sa


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

    def to_frame(self) -> pd.DataFrame:
        """One row per (damping, period): ``period_s, damping_pct, sd_m, sv_m_s, sa_g, psv_m_s,
        psa_g`` (accelerations in g and damping in %, the units of every CSV and figure)."""
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


def response_spectra(motion, period_s, damping, free_motion_s: float = 0.0) -> ResponseSpectra:
    """True displacement, velocity and acceleration spectra of a record (Eq. 3.2).

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²], linear between samples.
    period_s : array
        Periods T ≥ 0 [s]; T = 0 gives Sd = Sv = 0 and Sa = PGA.
    damping : array
        Damping ratios ξ ≥ 0 [-] (0.05 for 5 %).
    free_motion_s : float
        Free vibration included after the record ends [s] (the record is followed by zeros).

    Returns
    -------
    ResponseSpectra
    """
    period_s = np.atleast_1d(np.asarray(period_s, dtype=float))
    damping = np.atleast_1d(np.asarray(damping, dtype=float))
    if not np.all(np.isfinite(period_s) & (period_s >= 0)):
        raise InputError("periods: every T must be a number of seconds ≥ 0")
    if not np.all(np.isfinite(damping) & (damping >= 0)):
        raise InputError("damping: every ratio must be a number ≥ 0")
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
    _peaks(acc, recurrence_coefficients(periods, dampings, motion.dt),
           2.0 * np.pi / periods, dampings, out)
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
        Damping ratio ξ [-].
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
    c = recurrence_coefficients([period_s], [damping], motion.dt)[0]
    state = np.zeros(2)
    u = np.zeros(acc.size)
    for k in range(acc.size - 1):
        state = c[:, :2] @ state + c[:, 2] * acc[k] + c[:, 3] * acc[k + 1]
        u[k + 1] = state[0]
    return np.arange(acc.size) * motion.dt, u
