"""Shahi & Baker (2014): velocity pulses in two orthogonal ground-motion components.

Shahi, S. K. and Baker, J. W. (2014). An efficient algorithm to identify strong-velocity pulses in
multicomponent ground motions. BSSA 104(5), 2456–2466. Written in Python by the project from the
authors' MATLAB (github.com/shreyshahi/PulseClassification, MIT: ``classification_algo.m``,
``analyze_record.m``), step by step, and tested against that MATLAB's own result for its El
Centro Array #4 example (tests/physics/test_pulse_identification.py):

1. velocities v = Σ a[g]·dt·981 [cm/s] (rectangle rule, no baseline correction);
2. the legacy db4 continuous transform of both components at 51 scales (T_p 0.25–15 s at
   T_p = 1.4·a·dt), energy map E = C₁² + C₂²;
3. five candidates: the largest E at (scale, sample), direction θ = atan(C₂/C₁) (atan, not
   atan2), the record rotated to v₁cos θ + v₂sin θ and classified, then E zeroed within
   ±0.4·scale samples of the candidate at every scale;
4. a candidate: its scale refined over the integers between the neighbouring scales, ten db4
   wavelets at that scale summed into the pulse (each at the largest |C| of what is left within
   ±⌈0.4·scale⌉ samples of the first), T_p = scale·dt / f_c (f_c the db4 centre frequency,
   5/7); late when, where the pulse has reached 5 % of its Σv², the record has reached 17 %;
   PGV ratio and energy ratio (Σ of the squared approximation coefficients of a one-level db4
   DWT, half-point symmetric) of the residual to the record, and the pulse indicator
   PI = −7.817 − 0.5679P² − 0.1516V² − 3.0253P − 1.7396V − 2.7156PV of the centred principal
   component P = (0.63·PGV ratio + 0.777·energy ratio − 1.208421)/0.2462717 and
   V = (PGV[cm/s] − 11.58861)/18.88015; pulse-like when PI > 0 and not late;
5. the record is pulse-like when a candidate is; its T_p is the *first* pulse-like candidate's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pywt

from audit import G
from audit.physics.pulses.legacy_cwt import legacy_cwt

WAVELET = "db4"
#: Pulse periods searched [s] and the number of scale steps between them.
TP_MIN_S, TP_MAX_S, SCALE_STEPS = 0.25, 15.0, 50
#: Candidates per record, wavelets per pulse, and the half-width of the search window [scales].
CANDIDATES, WAVELETS_PER_PULSE, WINDOW = 5, 10, 0.4
#: Cascade iterations of the db4 wavelet the pulse is drawn from (the MATLAB's ``iter``).
PULSE_WAVELET_LEVEL = 4
#: The MATLAB's velocity from acceleration in g: cm/s² per g (981, not g = 980.665).
CM_S2_PER_G = 981.0


def centre_frequency() -> float:
    """Centre frequency of db4 [cycles per sample at scale 1] (MATLAB's centfrq: 0.7143)."""
    return pywt.central_frequency(WAVELET)


def velocity_cm_s(acceleration_m_s2, dt: float) -> np.ndarray:
    """Velocity as the MATLAB integrates it, Σ a[g]·dt·981 [cm/s]."""
    return np.cumsum(np.asarray(acceleration_m_s2, dtype=float) / G) * dt * CM_S2_PER_G


def scales(dt: float) -> np.ndarray:
    """The 51 scales [samples] of the energy map, T_p = 1.4·a·dt from 0.25 s up to 15 s."""
    first = math.floor(TP_MIN_S / 1.4 / dt)
    step = math.ceil((TP_MAX_S / 1.4 / dt - first) / SCALE_STEPS)
    return first + step * np.arange(SCALE_STEPS + 1)


@dataclass(frozen=True)
class PulseCandidate:
    """One candidate pulse and its classification.

    Attributes
    ----------
    direction_rad : float
        θ: the rotated record is v₁cos θ + v₂sin θ [rad], in (−π/2, π/2].
    sample : int
        Sample of the energy map's maximum (0-based).
    scale : int
        Refined scale of the pulse [samples].
    tp_s : float
        Pulse period T_p = scale·dt/f_c [s].
    pulse_indicator : float
        PI [-] (pulse-like above 0).
    pgv_cm_s, pgv_ratio, energy_ratio : float
        PGV of the rotated record [cm/s]; residual-to-record PGV and energy ratios [-].
    late : bool
        The late-pulse test.
    velocity_cm_s, pulse_cm_s : numpy.ndarray
        The rotated record's velocity and the extracted pulse [cm/s], at the record's samples.
    dt : float
        Sampling step [s].
    """

    direction_rad: float
    sample: int
    scale: int
    tp_s: float
    pulse_indicator: float
    pgv_cm_s: float
    pgv_ratio: float
    energy_ratio: float
    late: bool
    velocity_cm_s: np.ndarray
    pulse_cm_s: np.ndarray
    dt: float

    @property
    def is_pulse(self) -> bool:
        return bool(self.pulse_indicator > 0.0 and not self.late)

    @property
    def pulse_pgv_cm_s(self) -> float:
        """Peak |velocity| of the extracted pulse [cm/s]."""
        return float(np.max(np.abs(self.pulse_cm_s)))


@dataclass(frozen=True)
class PulseClassification:
    """The candidates of one record, in the order found (largest wavelet energy first)."""

    candidates: tuple[PulseCandidate, ...]

    @property
    def pulse(self) -> PulseCandidate | None:
        """The first pulse-like candidate (whose T_p is the record's), or None."""
        return next((c for c in self.candidates if c.is_pulse), None)

    @property
    def pulse_like(self) -> bool:
        return self.pulse is not None

    @property
    def pulse_indicator(self) -> float:
        """PI of the record's pulse, else the largest PI of its candidates."""
        pulse = self.pulse
        return (pulse.pulse_indicator if pulse is not None
                else max(c.pulse_indicator for c in self.candidates))


def pulse_indicator(pgv_cm_s: float, pgv_ratio: float, energy_ratio: float) -> float:
    """PI [-] of Shahi & Baker (2014) in the MATLAB's centred form (see the module docstring)."""
    p = (0.63 * pgv_ratio + 0.777 * energy_ratio - 1.208421) / 0.2462717
    v = (pgv_cm_s - 11.58861) / 18.88015
    return (-7.817 - 0.5679 * p * p - 0.1516 * v * v - 3.0253 * p - 1.7396 * v
            - 2.7156 * p * v)


def _approximation_energy(signal: np.ndarray) -> float:
    return float(np.sum(pywt.dwt(signal, WAVELET, mode="symmetric")[0] ** 2))


def _wavelet(scale: int, centre: int, coefficient: float, n: int) -> np.ndarray:
    """A db4 wavelet of ``scale`` centred on sample ``centre``, × coefficient/√scale, on the
    record's samples (linear between the cascade points, zero outside)."""
    _, psi, x = pywt.Wavelet(WAVELET).wavefun(level=PULSE_WAVELET_LEVEL)
    position = x * scale
    position += centre - np.median(position)
    return np.interp(np.arange(n), position, psi * coefficient / math.sqrt(scale),
                     left=0.0, right=0.0)


def _late(signal: np.ndarray, pulse: np.ndarray) -> bool:
    if not (np.any(signal) and np.any(pulse)):
        return False
    signal_energy = np.cumsum(signal ** 2) / np.sum(signal ** 2) * 100.0
    pulse_energy = np.cumsum(pulse ** 2) / np.sum(pulse ** 2) * 100.0
    early = np.flatnonzero(pulse_energy <= 5.0)
    return bool(early.size and signal_energy[early[-1]] >= 17.0)


def classify_candidate(signal: np.ndarray, dt: float, sample: int, row: int,
                       grid: np.ndarray, direction_rad: float) -> PulseCandidate:
    """Extract and classify the pulse at (``grid[row]``, ``sample``) of a rotated velocity."""
    n = signal.size
    fine = np.arange(grid[max(0, row - 1)], grid[min(grid.size - 1, row + 1)] + 1)
    scale = int(fine[np.argmax(np.abs(legacy_cwt(signal, fine)[:, sample]))])
    half_width = math.ceil(scale * WINDOW)
    pulse, residual, centre = np.zeros(n), signal.copy(), sample
    for i in range(WAVELETS_PER_PULSE):
        window = slice(max(0, centre - half_width), min(n, centre + half_width + 1))
        coefficients = legacy_cwt(residual, [scale])[0]
        found = window.start + int(np.argmax(np.abs(coefficients[window])))
        if i == 0:
            centre = found  # the later wavelets are looked for around the first
        pulse += _wavelet(scale, found, coefficients[found], n)
        residual = signal - pulse
    pgv = float(np.max(np.abs(signal)))
    # a record at rest has nothing to extract: both ratios 1 (and PI < 0)
    pgv_ratio = float(np.max(np.abs(residual))) / pgv if pgv else 1.0
    energy = _approximation_energy(signal)
    energy_ratio = _approximation_energy(residual) / energy if energy else 1.0
    return PulseCandidate(direction_rad, sample, scale, scale * dt / centre_frequency(),
                          pulse_indicator(pgv, pgv_ratio, energy_ratio), pgv, pgv_ratio,
                          energy_ratio, _late(signal, pulse), signal, pulse, dt)


def shahi_baker_2014(velocity_1_cm_s, velocity_2_cm_s, dt: float) -> PulseClassification:
    """Classify a record by its two orthogonal velocity components.

    Parameters
    ----------
    velocity_1_cm_s, velocity_2_cm_s : array_like
        The components' velocities [cm/s] (:func:`velocity_cm_s`), one length; a record of
        one component passes zeros as the second (every direction is then 0).
    dt : float
        Sampling step [s].

    Returns
    -------
    PulseClassification
        Five candidates.
    """
    v1 = np.asarray(velocity_1_cm_s, dtype=float)
    v2 = np.asarray(velocity_2_cm_s, dtype=float)
    grid = scales(dt)
    c1, c2 = legacy_cwt(v1, grid), legacy_cwt(v2, grid)
    energy = c1 ** 2 + c2 ** 2
    samples = np.arange(v1.size)
    candidates = []
    for _ in range(CANDIDATES):
        row, sample = np.unravel_index(np.argmax(energy), energy.shape)
        # atan, as published: θ in (−π/2, π/2]; C₁ = 0 is the direction π/2
        direction = math.atan(c2[row, sample] / c1[row, sample]) if c1[row, sample] else math.pi / 2
        rotated = v1 * math.cos(direction) + v2 * math.sin(direction)
        candidates.append(classify_candidate(rotated, dt, int(sample), int(row), grid, direction))
        half_width = WINDOW * grid[row]
        energy[:, np.abs(samples - sample) < half_width] = 0.0
    return PulseClassification(tuple(candidates))
