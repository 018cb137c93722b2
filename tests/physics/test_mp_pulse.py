"""Mavroeidis & Papageorgiou (2003) pulse: closed forms against numerical derivative and
integrals, the least-squares fit, and a synthetic round trip through the identification."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from audit import G
from audit.errors import InputError
from audit.physics.pulses.mp_fit import fit_mp_pulse
from audit.physics.pulses.shahi_baker_2014 import shahi_baker_2014, velocity_cm_s
from records import mp_pulse
from records.mavroeidis_papageorgiou_2003 import (mp_acceleration, mp_displacement,
                                                  mp_residual_displacement, mp_velocity)

CASES = [(0.8, 0.5, 2.0, 0.0), (0.5, 1.25, 1.6, 1.1), (1.2, 0.3, 2.7, -2.0), (0.3, 2.0, 3.0, 0.5)]


@pytest.mark.parametrize("amplitude,frequency,gamma,nu", CASES)
def test_acceleration_is_the_derivative_of_the_velocity(amplitude, frequency, gamma, nu):
    half = gamma / (2 * frequency)
    tau, h = np.linspace(-0.99 * half, 0.99 * half, 301), 1e-6 / frequency
    numerical = (mp_velocity(tau + h, amplitude, frequency, gamma, nu)
                 - mp_velocity(tau - h, amplitude, frequency, gamma, nu)) / (2 * h)
    closed = mp_acceleration(tau, amplitude, frequency, gamma, nu)
    assert np.max(np.abs(closed - numerical)) < 1e-6 * amplitude * frequency


@pytest.mark.parametrize("amplitude,frequency,gamma,nu", CASES)
def test_displacement_and_its_residual_are_the_integrals_of_the_velocity(amplitude, frequency,
                                                                          gamma, nu):
    half = gamma / (2 * frequency)
    args = (amplitude, frequency, gamma, nu)
    for tau in (-half, -0.3 * half, 0.0, 0.71 * half, half, 3 * half):
        integral = quad(lambda s: float(mp_velocity(s, *args)), -half, min(tau, half),
                        limit=200, epsabs=1e-13)[0]
        assert float(mp_displacement(tau, *args)) == pytest.approx(integral, abs=1e-10)
    assert float(mp_displacement(-2 * half, *args)) == 0.0
    residual = quad(lambda s: float(mp_velocity(s, *args)), -half, half, limit=200,
                    epsabs=1e-13)[0]
    assert mp_residual_displacement(*args) == pytest.approx(residual, abs=1e-10)


def test_residual_displacement_vanishes_for_nu_90_and_integer_gamma():
    assert mp_residual_displacement(1.0, 1.0, 2.3, math.pi / 2) == pytest.approx(0.0, abs=1e-15)
    assert mp_residual_displacement(1.0, 1.0, 2.0, 0.3) == pytest.approx(0.0, abs=1e-15)
    assert mp_residual_displacement(1.0, 1.0, 2.5, 0.0) == pytest.approx(
        math.sin(2.5 * math.pi) / (2 * math.pi * (1 - 6.25)))


def test_zero_outside_the_support_whatever_t0():
    """On relative time the pulse is not shifted or cut: zero just outside ±γ/(2f_p)."""
    half = 2.0 / (2 * 0.5)
    tau = np.array([-half - 1e-9, half + 1e-9])
    assert np.all(mp_velocity(tau, 1.0, 0.5, 2.0, 0.4) == 0.0)
    assert np.all(mp_acceleration(tau, 1.0, 0.5, 2.0, 0.4) == 0.0)


def test_built_in_motion_has_the_peak_acceleration_asked():
    motion = mp_pulse(0.4, 1.5, 2.0, 30.0)
    assert np.max(np.abs(motion.acceleration)) == pytest.approx(0.4 * G, rel=1e-4)
    assert motion.duration == pytest.approx(2.0 * 1.5)
    # the ground's velocity starts and ends at rest (the pulse's velocity is zero at its ends)
    assert np.trapezoid(motion.acceleration, dx=motion.dt) == pytest.approx(0.0, abs=1e-6)
    with pytest.raises(InputError, match="gamma"):
        mp_pulse(0.4, 1.5, 1.0, 30.0)


def test_fit_recovers_a_clean_pulse():
    dt, truth = 0.01, (0.55, 0.6, 2.2, 1.3, 7.0)
    t = np.arange(2000) * dt
    velocity = mp_velocity(t - truth[4], *truth[:4])
    fit = fit_mp_pulse(velocity, dt, period_s=1.0 / 0.6 * 1.1)  # a start 10 % off
    assert (fit.amplitude_m_s, fit.frequency_hz, fit.gamma, fit.nu_rad, fit.t0_s) == \
        pytest.approx(truth, rel=1e-5)
    assert fit.rms_m_s < 1e-6


# (T_p [s], γ, ν [deg], direction [rad]) of the pulse added to two components of noise
ROUND_TRIPS = [(1.0, 2.0, 90.0, 0.3), (2.0, 2.0, 90.0, 0.5), (3.0, 1.8, 0.0, 1.2),
               (1.5, 3.0, 180.0, 0.0)]


@pytest.mark.parametrize("period_s,gamma,nu_deg,direction", ROUND_TRIPS)
def test_a_pulse_added_to_noise_is_found(period_s, gamma, nu_deg, direction):
    dt = 0.01
    t = np.arange(3000) * dt
    noise = (np.random.default_rng(7).normal(scale=0.05 * G, size=(2, t.size))
             * np.sin(np.pi * t / t[-1]) ** 2)
    pulse = mp_acceleration(t - 10.0, 0.6, 1.0 / period_s, gamma, math.radians(nu_deg))
    found = shahi_baker_2014(
        velocity_cm_s(noise[0] + pulse * math.cos(direction), dt),
        velocity_cm_s(noise[1] + pulse * math.sin(direction), dt), dt).pulse
    assert found is not None
    assert found.tp_s == pytest.approx(period_s, rel=0.15)
    assert found.direction_rad == pytest.approx(direction, abs=0.1)
    fit = fit_mp_pulse(found.pulse_cm_s / 100.0, dt, found.tp_s)
    assert fit.period_s == pytest.approx(period_s, rel=0.10)
    assert fit.t0_s == pytest.approx(10.0, abs=0.2 * period_s)


def test_rock_takes_an_mp_pulse_and_refuses_gamma_without_it(capsys):
    from audit.cli import main
    assert main(["rock", "--block", "0.6x1.8", "--pulse", "mp", "--amplitude", "0.4",
                 "--pulse-period", "1", "--gamma", "2", "--nu", "90", "--json"]) == 0
    assert main(["rock", "--block", "0.6x1.8", "--pulse", "cosine", "--amplitude", "0.4",
                 "--pulse-period", "1", "--gamma", "2"]) == 2
    assert "--gamma and --nu: only for --pulse mp" in capsys.readouterr().err


@pytest.mark.parametrize("t0_s,late", [(8.0, False), (30.0, True)])
def test_a_pulse_after_the_strong_shaking_is_late(t0_s, late):
    """The late-pulse test: a pulse arriving after 15 s of strong shaking (well over 17 % of
    the record's Σv² before the pulse's first 5 %) is late; one inside the shaking is not."""
    dt = 0.01
    t = np.arange(4000) * dt
    shaking = (np.random.default_rng(3).normal(scale=0.15 * G, size=t.size) * (t < 15)
               * np.sin(np.pi * t / 15) ** 2)
    record = shaking + mp_acceleration(t - t0_s, 0.5, 0.5, 2.0, math.pi / 2)
    first = shahi_baker_2014(velocity_cm_s(record, dt), np.zeros(t.size), dt).candidates[0]
    assert first.sample * dt == pytest.approx(t0_s, abs=1.0)  # the pulse is the candidate
    assert first.late == late
    if late:
        assert not first.is_pulse  # whatever its PI
