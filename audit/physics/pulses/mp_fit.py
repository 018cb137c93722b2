"""A Mavroeidis & Papageorgiou (2003) pulse fitted by least squares to an extracted pulse.

The five parameters (A, f_p, γ, ν, t₀) minimise Σ (v_MP(t_k − t₀) − v_k)² over the samples of
the extracted pulse, with :func:`scipy.optimize.least_squares` started from several (γ, ν) and
the best of the local optima kept (the cost is not convex in ν and γ).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from records.mavroeidis_papageorgiou_2003 import mp_peak_acceleration, mp_velocity

#: Starting values of γ [-] and ν [rad]; A, f_p and t₀ start from the extracted pulse.
GAMMA_STARTS = (1.5, 2.5, 4.0)
NU_STARTS = (0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi)
#: γ range of the fit (the paper's pulses have 1 < γ ≲ 3; wider so the bound rarely binds).
GAMMA_BOUNDS = (1.01, 8.0)
#: Samples per T_p the misfit is summed over, at most.
FIT_SAMPLES_PER_PERIOD = 200


@dataclass(frozen=True)
class MPFit:
    """The fitted pulse, v(t) = v_MP(t − t₀; A, f_p, γ, ν).

    Attributes
    ----------
    amplitude_m_s : float
        A [m/s].
    frequency_hz : float
        f_p [Hz].
    gamma : float
        γ [-].
    nu_rad : float
        ν [rad], wrapped to [0, 2π).
    t0_s : float
        t₀ [s] from the record's first sample.
    rms_m_s : float
        Root-mean-square misfit over the fitted samples [m/s].
    """

    amplitude_m_s: float
    frequency_hz: float
    gamma: float
    nu_rad: float
    t0_s: float
    rms_m_s: float

    @property
    def period_s(self) -> float:
        """T_p = 1/f_p [s]."""
        return 1.0 / self.frequency_hz

    @property
    def peak_acceleration_m_s2(self) -> float:
        """max |a| of the fitted pulse [m/s²]."""
        return mp_peak_acceleration(self.amplitude_m_s, self.frequency_hz, self.gamma,
                                    self.nu_rad)

    def velocity(self, time_s) -> np.ndarray:
        """v at times t [s] of the record [m/s]."""
        return mp_velocity(np.asarray(time_s) - self.t0_s, self.amplitude_m_s,
                           self.frequency_hz, self.gamma, self.nu_rad)


def fit_mp_pulse(velocity_m_s, dt: float, period_s: float) -> MPFit:
    """Fit a Mavroeidis & Papageorgiou pulse to an extracted pulse.

    Parameters
    ----------
    velocity_m_s : array_like
        The extracted pulse's velocity at t = k·dt [m/s].
    dt : float
        Sampling step [s].
    period_s : float
        The identification's T_p [s]: f_p starts at 1/T_p and stays within a factor 3 of it.

    Returns
    -------
    MPFit
        The best of the starts.
    """
    v = np.asarray(velocity_m_s, dtype=float)
    nonzero = np.flatnonzero(v)
    margin = int(period_s / dt)
    # the pulse and a period either side, at no finer than T_p/200 (a smooth pulse: the long
    # ones would otherwise cost ~10 s for no change)
    stride = max(1, int(period_s / FIT_SAMPLES_PER_PERIOD / dt))
    window = slice(max(0, nonzero[0] - margin), min(v.size, nonzero[-1] + margin + 1), stride)
    t, target = np.arange(v.size)[window] * dt, v[window]
    peak = float(np.max(np.abs(target)))
    t_peak = float(t[np.argmax(np.abs(target))])
    f0 = 1.0 / period_s

    def misfit(x):
        return mp_velocity(t - x[4], x[0], x[1], x[2], x[3]) - target

    lower = [1e-3 * peak, f0 / 3.0, GAMMA_BOUNDS[0], -math.pi, t[0]]
    upper = [5.0 * peak, 3.0 * f0, GAMMA_BOUNDS[1], 3.0 * math.pi, t[-1]]
    best = None
    for gamma, nu in itertools.product(GAMMA_STARTS, NU_STARTS):
        start = [peak, f0, gamma, nu, t_peak]
        result = least_squares(misfit, start, bounds=(lower, upper), x_scale=[peak, f0, 1.0,
                                                                              1.0, period_s])
        if best is None or result.cost < best.cost:
            best = result
    amplitude, frequency, gamma, nu, t0 = best.x
    return MPFit(float(amplitude), float(frequency), float(gamma), float(nu % (2.0 * math.pi)),
                 float(t0), float(np.sqrt(2.0 * best.cost / target.size)))
