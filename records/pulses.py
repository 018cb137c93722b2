"""Analytic acceleration pulses (Makris & Konstantinidis, Section 4 and Figure 4.1)."""

from __future__ import annotations

import numpy as np

from audit import G
from audit.errors import InputError
from records.motion import GroundMotion, Pulse, pulse_acceleration

PULSE_SHAPES = ("cosine", "sine")

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
