"""Analytic acceleration pulses: the cycloidal pulses of Makris & Konstantinidis (Section 4 and
Figure 4.1) and the Mavroeidis & Papageorgiou (2003) pulse."""

from __future__ import annotations

import numpy as np

from audit import G
from audit.errors import InputError
from records.mavroeidis_papageorgiou_2003 import (check_parameters, mp_acceleration,
                                                 mp_peak_acceleration)
from records.motion import GroundMotion, Pulse, pulse_acceleration

PULSE_SHAPES = ("cosine", "sine")
#: The Mavroeidis & Papageorgiou pulse, next to the cycloidal shapes at the command line.
MP = "mp"

#: Samples per pulse period used for the tabulated copy of a pulse (plots, oscillator spectra);
#: the rocking solver evaluates the closed form instead.
SAMPLES_PER_PERIOD = 2000


def one_pulse(shape: str, amplitude_g: float, period_s: float, record_id: str | None = None,
              component: str = "") -> GroundMotion:
    """A one-cycle analytic pulse as a :class:`GroundMotion`.

    Parameters
    ----------
    shape : {"cosine", "sine"}
        Pulse shape, see :func:`records.motion.pulse_acceleration`.
    amplitude_g : float
        a_p [g].
    period_s : float
        T_p [s].
    record_id : str, optional
        Id of the motion; default names the pulse.

    Returns
    -------
    GroundMotion
        Sampled at T_p/2000 over one period, with :attr:`GroundMotion.pulse` set.
    """
    if shape not in PULSE_SHAPES:
        raise InputError(f"pulse shape: unknown '{shape}', expected one of {', '.join(PULSE_SHAPES)}")
    if not (np.isfinite(amplitude_g) and amplitude_g > 0):
        raise InputError(f"pulse amplitude: must be a positive number of g, got {amplitude_g}")
    if not (np.isfinite(period_s) and period_s > 0):
        raise InputError(f"pulse period: must be a positive number of seconds, got {period_s}")
    dt = period_s / SAMPLES_PER_PERIOD
    t = np.arange(SAMPLES_PER_PERIOD + 1) * dt
    amplitude = amplitude_g * G
    return GroundMotion(
        id=record_id or f"{shape}-pulse-{amplitude_g:g}g-{period_s:g}s",
        acceleration=pulse_acceleration(shape, amplitude, period_s, t),
        dt=dt,
        component=component or f"one-{shape} pulse, a_p = {amplitude_g:g} g, T_p = {period_s:g} s",
        source="analytic pulse",
        pulse=Pulse(shape, amplitude, period_s),
    )


def mp_pulse(amplitude_g: float, period_s: float, gamma: float, nu_deg: float,
             record_id: str | None = None) -> GroundMotion:
    """A Mavroeidis & Papageorgiou (2003) pulse as a :class:`GroundMotion`.

    Parameters
    ----------
    amplitude_g : float
        Peak |acceleration| of the pulse [g] (a_p, as for the cycloidal pulses); the velocity
        amplitude A follows from it.
    period_s : float
        T_p = 1/f_p [s].
    gamma : float
        γ > 1 [-].
    nu_deg : float
        Phase ν [degrees].

    Returns
    -------
    GroundMotion
        The closed-form acceleration sampled at about T_p/2000 from the pulse's start (t = 0)
        to its end γ·T_p, linear between samples for the solver; the parameters (A [m/s] too)
        in :attr:`GroundMotion.metadata` under ``"mavroeidis_papageorgiou"``.
    """
    if not (np.isfinite(amplitude_g) and amplitude_g > 0):
        raise InputError(f"pulse amplitude: must be a positive number of g, got {amplitude_g}")
    if not (np.isfinite(period_s) and period_s > 0):
        raise InputError(f"pulse period: must be a positive number of seconds, got {period_s}")
    nu_rad = np.radians(nu_deg)
    check_parameters(1.0, 1.0 / period_s, gamma, nu_rad)
    frequency_hz = 1.0 / period_s
    velocity_amplitude = amplitude_g * G / mp_peak_acceleration(1.0, frequency_hz, gamma, nu_rad)
    samples = int(np.ceil(gamma * SAMPLES_PER_PERIOD))
    duration = gamma * period_s
    tau = np.linspace(0.0, duration, samples + 1) - duration / 2.0
    name = f"mp-pulse-{amplitude_g:g}g-{period_s:g}s-gamma{gamma:g}-nu{nu_deg:g}"
    return GroundMotion(
        id=record_id or name,
        acceleration=mp_acceleration(tau, velocity_amplitude, frequency_hz, gamma, nu_rad),
        dt=duration / samples,
        component=(f"Mavroeidis-Papageorgiou pulse, peak {amplitude_g:g} g, T_p = {period_s:g} s, "
                   f"gamma = {gamma:g}, nu = {nu_deg:g} deg (A = {velocity_amplitude:.4g} m/s)"),
        source="analytic pulse",
        metadata={"mavroeidis_papageorgiou": {
            "amplitude_m_s": velocity_amplitude, "frequency_hz": frequency_hz, "gamma": gamma,
            "nu_rad": float(nu_rad), "t0_s": duration / 2.0}},
    )
