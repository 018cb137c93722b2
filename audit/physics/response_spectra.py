"""True response spectra of a record (Eq. 3.2): the peaks of every oscillator of a set of periods
and dampings, exact between samples (:mod:`audit.physics.peaks_between_samples`), on the
recurrence of :mod:`audit.physics.oscillator`, computed by :mod:`audit.physics.spectrum_kernel`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.kernel_threads import run_chunks
from audit.physics.oscillator import recurrence_coefficients
from audit.physics.spectrum_kernel import spectrum_peaks

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


def _with_free_motion(motion, free_motion_s: float) -> np.ndarray:
    """The record's acceleration [m/s²] followed by ``free_motion_s`` of zeros."""
    n_tail = int(np.ceil(free_motion_s / motion.dt - 1e-9))
    if n_tail:
        return np.concatenate((motion.acceleration, np.zeros(n_tail)))
    return motion.acceleration


def _oscillators(period_s, damping, dt):
    """Recurrence coefficients and ω [rad/s] of the oscillators (T > 0, ξ) [s, -], 1-D."""
    return recurrence_coefficients(period_s, damping, dt), 2.0 * np.pi / period_s


#: Oscillator tables kept (~64 kB each for the 801 periods): a check asks for one per damping
#: (Priestley's β(r(α)): one per object and width tried) and record step, record by record,
#: so fewer than the objects in flight make every record compute them all again.
TABLES_KEPT = 1024


@lru_cache(maxsize=TABLES_KEPT)
def _table_oscillators(period_bytes: bytes, damping: float, dt: float) -> tuple:
    """(coeffs, omega, damping) of every period of a table (its bytes) at one damping and
    step; rows at T = 0 are placeholders, never computed (known), so indices stay the
    table's. Callers only read them."""
    period_s = np.frombuffer(period_bytes)
    positive = period_s > 0
    damping = np.full(period_s.size, damping)
    coeffs = np.zeros((period_s.size, 2, 4))
    omega = np.ones(period_s.size)
    coeffs[positive], omega[positive] = _oscillators(period_s[positive], damping[positive], dt)
    return coeffs, omega, damping


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
    acc = _with_free_motion(motion, free_motion_s)
    grid_xi, grid_t = np.meshgrid(damping, period_s, indexing="ij")
    positive = grid_t > 0
    peaks = np.zeros(grid_t.shape + (3,))
    peaks[~positive, 2] = np.max(np.abs(motion.acceleration))
    periods, dampings = grid_t[positive], grid_xi[positive]
    out = np.empty((periods.size, 3))
    coeffs, omega = _oscillators(periods, dampings, motion.dt)
    # interleaved chunks: short periods (costly peaks between samples) spread over the threads
    chunks = [np.arange(i, periods.size, max(1, jobs)) for i in range(max(1, min(jobs, periods.size)))]

    def run(chunk):
        part = np.empty((chunk.size, 3))
        spectrum_peaks(acc, motion.dt, coeffs[chunk], omega[chunk], dampings[chunk], between_samples,
               displacement_only, part)
        out[chunk] = part

    if len(chunks) == 1:
        run(chunks[0])
    else:
        run_chunks(run, chunks)
    peaks[positive] = out
    return ResponseSpectra(period_s, damping, peaks[..., 0], peaks[..., 1], peaks[..., 2])


class DisplacementOnDemand:
    """The displacement spectrum of a record at one damping on a table of periods, each value
    computed when first asked for and kept: for a reader of a few periods of a long table (the
    iteration behind a guideline's verdict reads a few dozen of 801). The values are those of
    :func:`response_spectra` with ``displacement_only``, bit for bit: the same coefficients,
    every oscillator computed alone by the same kernel.

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²], linear between samples.
    period_s : array
        Periods T ≥ 0 [s] (Sd = 0 at T = 0).
    damping : float
        Damping ratio 0 ≤ ξ < 1 [-].
    free_motion_s : float
        Free vibration included after the record ends [s].

    Attributes
    ----------
    period_s : numpy.ndarray
    sd_m : numpy.ndarray
        Sd [m] where ``known``, NaN elsewhere.
    known : numpy.ndarray of bool
    """

    def __init__(self, motion, period_s, damping: float, free_motion_s: float = 0.0):
        self.motion, self.free_motion_s = motion, free_motion_s
        self.period_s = np.asarray(period_s, dtype=float)
        self.damping = float(damping)
        positive = self.period_s > 0
        self.sd_m = np.where(positive, np.nan, 0.0)
        self.known = ~positive
        self._arguments = None  # the kernel's arguments, built when first read

    def fill(self, index) -> None:
        """Compute Sd at the table's indices ``index`` where not known yet."""
        index = np.asarray(index, dtype=np.intp)
        missing = np.unique(index[~self.known[index]])
        if missing.size:
            acc, dt, coeffs, omega, damping, _, _ = self.kernel_arguments()
            out = np.empty((missing.size, 3))
            spectrum_peaks(acc, dt, coeffs[missing], omega[missing], damping[missing], True,
                           True, out)
            self.sd_m[missing] = out[:, 0]
            self.known[missing] = True

    def kernel_arguments(self) -> tuple:
        """What :func:`~audit.physics.spectrum_kernel.fill_displacement` needs, for a
        compiled reader: (acc, dt, coeffs, omega, damping, sd_m, known), the oscillators of
        every period of the table. The oscillators are kept by (table, damping, step), not
        here: a check holds one of these per record and damping tried, and its records share
        a step and the dampings its widths try. Built once: a verdict reads them at every
        iteration it runs on this table."""
        if self._arguments is None:
            coeffs, omega, damping = _table_oscillators(self.period_s.tobytes(), self.damping,
                                                        self.motion.dt)
            self._arguments = (_with_free_motion(self.motion, self.free_motion_s),
                               self.motion.dt, coeffs, omega, damping, self.sd_m, self.known)
        return self._arguments


__all__ = ["DisplacementOnDemand", "ResponseSpectra", "response_spectra"]
