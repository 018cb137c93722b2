"""Mavroeidis & Papageorgiou (2003): the analytic near-fault velocity pulse.

Mavroeidis, G. P. and Papageorgiou, A. S. (2003). A mathematical representation of near-fault
ground motions. BSSA 93(3), 1099–1131, eqs 2–4. On the pulse's own time τ = t − t₀ (so no
phase shift or truncation, whatever t₀), for |τ| ≤ γ/(2f_p) and zero outside:

    v(τ) = (A/2) [1 + cos(2πf_p τ/γ)] cos(2πf_p τ + ν)

with A the velocity amplitude [m/s], f_p the prevailing frequency [Hz] (T_p = 1/f_p), γ > 1 the
oscillatory character (zero-crossings) and ν the phase [rad]. The acceleration is dv/dτ and the
displacement the integral from the pulse's start (zero before it), in closed form; its residual
after the pulse is A cos ν sin(πγ) / (2πf_p (1 − γ²)). Written by the project from the paper's
velocity; the derivative and integral are tested numerically.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from audit.errors import InputError


def check_parameters(amplitude: float, frequency_hz: float, gamma: float, nu_rad: float) -> None:
    """InputError naming the first parameter outside the model's range."""
    if not (math.isfinite(amplitude) and amplitude > 0):
        raise InputError(f"Mavroeidis-Papageorgiou pulse amplitude: must be positive, got {amplitude}")
    if not (math.isfinite(frequency_hz) and frequency_hz > 0):
        raise InputError(f"Mavroeidis-Papageorgiou pulse period: must be positive, got "
                         f"{1 / frequency_hz if frequency_hz else frequency_hz}")
    if not (math.isfinite(gamma) and gamma > 1):
        raise InputError(f"Mavroeidis-Papageorgiou gamma: must exceed 1, got {gamma}")
    if not math.isfinite(nu_rad):
        raise InputError(f"Mavroeidis-Papageorgiou nu: must be a finite angle, got {nu_rad}")


def _inside(tau, frequency_hz, gamma):
    tau = np.asarray(tau, dtype=float)
    return tau, np.abs(tau) <= gamma / (2.0 * frequency_hz)


def mp_velocity(tau, amplitude, frequency_hz, gamma, nu_rad):
    """v(τ) [m/s], eq. 2; τ = t − t₀ [s], A [m/s], f_p [Hz], γ [-], ν [rad]."""
    tau, inside = _inside(tau, frequency_hz, gamma)
    w = 2.0 * np.pi * frequency_hz
    v = 0.5 * amplitude * (1.0 + np.cos(w * tau / gamma)) * np.cos(w * tau + nu_rad)
    return np.where(inside, v, 0.0)


def mp_acceleration(tau, amplitude, frequency_hz, gamma, nu_rad):
    """a(τ) = dv/dτ [m/s²], eq. 3:
    −(Aπf_p/γ)[sin(2πf_pτ/γ) cos(2πf_pτ + ν) + γ sin(2πf_pτ + ν)(1 + cos(2πf_pτ/γ))]."""
    tau, inside = _inside(tau, frequency_hz, gamma)
    w = 2.0 * np.pi * frequency_hz
    a = -(amplitude * np.pi * frequency_hz / gamma) * (
        np.sin(w * tau / gamma) * np.cos(w * tau + nu_rad)
        + gamma * np.sin(w * tau + nu_rad) * (1.0 + np.cos(w * tau / gamma)))
    return np.where(inside, a, 0.0)


def _velocity_integral(tau, amplitude, frequency_hz, gamma, nu_rad):
    """An antiderivative of v: v = (A/2)[cos(ωτ+ν) + ½cos((ω+ω/γ)τ+ν) + ½cos((ω−ω/γ)τ+ν)]."""
    w = 2.0 * np.pi * frequency_hz
    plus, minus = w * (1.0 + 1.0 / gamma), w * (1.0 - 1.0 / gamma)  # minus > 0 as γ > 1
    return 0.5 * amplitude * (np.sin(w * tau + nu_rad) / w
                              + np.sin(plus * tau + nu_rad) / (2.0 * plus)
                              + np.sin(minus * tau + nu_rad) / (2.0 * minus))


def mp_displacement(tau, amplitude, frequency_hz, gamma, nu_rad):
    """d(τ) [m]: ∫v from the pulse's start, zero before it, its residual after (eq. 4 with the
    constant that makes it start at rest)."""
    tau = np.asarray(tau, dtype=float)
    half = gamma / (2.0 * frequency_hz)
    clipped = np.clip(tau, -half, half)
    args = (amplitude, frequency_hz, gamma, nu_rad)
    d = _velocity_integral(clipped, *args) - _velocity_integral(-half, *args)
    return np.where(tau < -half, 0.0, d)


def mp_residual_displacement(amplitude, frequency_hz, gamma, nu_rad) -> float:
    """d after the pulse [m]: A cos ν sin(πγ) / (2πf_p (1 − γ²))."""
    return (amplitude * math.cos(nu_rad) * math.sin(math.pi * gamma)
            / (2.0 * math.pi * frequency_hz * (1.0 - gamma * gamma)))


@functools.lru_cache(maxsize=1024)  # a check asks for each record's pulse at every stripe
def mp_peak_acceleration(amplitude, frequency_hz, gamma, nu_rad, samples: int = 20001) -> float:
    """max |a(τ)| [m/s²] over the pulse (on a grid of ``samples`` points of its support)."""
    half = gamma / (2.0 * frequency_hz)
    tau = np.linspace(-half, half, samples)
    return float(np.max(np.abs(mp_acceleration(tau, amplitude, frequency_hz, gamma, nu_rad))))
