"""Oscillator response spectra, design spectra and damping laws against closed forms."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import signal

from audit.errors import InputError
from audit.physics.block import coefficient_of_restitution
from audit.physics.damping import (damping_fema356, damping_free_rocking, damping_priestley,
                           housner_period, housner_rotation_ratio)
from audit.physics.design_spectra import FEMA356_TABLE_1_6, FEMA356Spectrum, UBC97Spectrum, \
    fema356_damping_coefficients
from audit.physics.oscillator import (oscillator_history, oscillator_step, recurrence_coefficients,
                                      step_coefficients)
from audit.physics.peaks_between_samples import step_peaks
from audit.physics.spectrum_kernel import spectrum_peaks
from audit.physics.response_spectra import response_spectra
from records import GroundMotion

DT = 0.001


def motion_from(function, duration):
    t = np.arange(0.0, duration + DT / 2, DT)
    return GroundMotion("analytic", function(t), DT), t


@pytest.mark.parametrize("damping", [0.0, 0.05, 0.2])
def test_step_response(damping):
    """üg = −a0 from t = 0: u = (a0/ω²)[1 − e^{−ξωt}(cos ωd t + ξ/√(1−ξ²) sin ωd t)]."""
    a0, period = 2.0, 0.8
    omega = 2 * math.pi / period
    omega_d = omega * math.sqrt(1 - damping ** 2)
    motion, t = motion_from(lambda t: np.full(t.shape, -a0), 4.0)
    _, u = oscillator_history(motion, period, damping)
    # the record starts with the step already on: the discrete input jumps at t = 0 exactly
    exact = a0 / omega ** 2 * (1 - np.exp(-damping * omega * t) * (
        np.cos(omega_d * t) + damping / math.sqrt(1 - damping ** 2) * np.sin(omega_d * t)))
    np.testing.assert_allclose(u, exact, atol=1e-10 * a0 / omega ** 2)
    spectra = response_spectra(motion, [period], [damping])
    overshoot = 1 + math.exp(-damping * math.pi / math.sqrt(1 - damping ** 2))
    assert spectra.sd[0, 0] == pytest.approx(a0 / omega ** 2 * overshoot, rel=1e-10)


def test_ramp_response_undamped():
    """üg = −c t: u = (c/ω²)(t − sin(ωt)/ω)."""
    c, period = 1.5, 0.5
    omega = 2 * math.pi / period
    motion, t = motion_from(lambda t: -c * t, 3.0)
    _, u = oscillator_history(motion, period, 0.0)
    np.testing.assert_allclose(u, c / omega ** 2 * (t - np.sin(omega * t) / omega), atol=1e-12)


@pytest.mark.parametrize("frequency_ratio", [0.5, 1.0, 1.7])
def test_steady_state_harmonic_amplitude(frequency_ratio):
    amplitude, period, damping = 1.0, 0.4, 0.05
    omega = 2 * math.pi / period
    forcing = frequency_ratio * omega
    motion, t = motion_from(lambda t: amplitude * np.sin(forcing * t), 60.0)
    _, u = oscillator_history(motion, period, damping)
    expected = amplitude / omega ** 2 / math.hypot(1 - frequency_ratio ** 2,
                                                   2 * damping * frequency_ratio)
    assert np.max(np.abs(u[t > 50.0])) == pytest.approx(expected, rel=2e-3)


def lsim_peaks(acceleration, time, period, damping):
    """(max|u|, max|u'|, max|ü + üg|) at the given samples by scipy.signal.lsim (first-order hold)."""
    w = 2 * math.pi / period
    system = signal.lti([[0, 1], [-w * w, -2 * damping * w]], [[0], [1]], np.eye(2), [[0], [0]])
    _, y, _ = signal.lsim(system, -acceleration, time, interp=True)
    u, v = y[:, 0], y[:, 1]
    return np.array([np.max(np.abs(u)), np.max(np.abs(v)),
                     np.max(np.abs(2 * damping * w * v + w * w * u))]), u


def test_sampled_peaks_and_histories_match_lsim_on_the_seed_records(seed_suite):
    """The closed-form recurrence is exact: same samples as lsim to 1e-10 (Sd, Sv, Sa, u(t))."""
    periods = np.array([0.05, 0.2, 1.0, 4.0, 20.0])
    dampings = [0.0, 0.05, 0.3]
    for entry in seed_suite:
        if entry.motion is None:
            continue
        motion = entry.motion
        spectra = response_spectra(motion, periods, dampings, between_samples=False)
        for j, xi in enumerate(dampings):
            for i, period in enumerate(periods):
                expected, u_lsim = lsim_peaks(motion.acceleration, motion.time, period, xi)
                ours = [spectra.sd[j, i], spectra.sv[j, i], spectra.sa[j, i]]
                np.testing.assert_allclose(ours, expected, rtol=1e-10, err_msg=entry.id)
        _, u = oscillator_history(motion, 0.3, 0.05)
        np.testing.assert_allclose(u, lsim_peaks(motion.acceleration, motion.time, 0.3, 0.05)[1],
                                   rtol=0, atol=1e-10 * np.max(np.abs(u)))


@pytest.mark.slow  # ~25 s: scipy's lsim on a 200x finer record
def test_peaks_between_samples_match_lsim_on_a_200x_finer_record(seed_suite):
    """Pacoima (dt = 0.01 s), T = 0.05–0.2 s: sampled peaks are percents low, located ones exact.

    Linear interpolation 200× finer is the same piecewise-linear input; lsim read on it misses
    a peak by at most ~(π·dt/200/T)²/2 < 1e-5 relative.
    """
    motion = seed_suite.get("pacoima_dam_1971").motion
    count = 1500  # the first 15 s hold the strong motion and every peak
    acceleration, time = motion.acceleration[:count], motion.time[:count]
    fine_time = np.linspace(0.0, time[-1], 200 * (count - 1) + 1)
    fine_acceleration = np.interp(fine_time, time, acceleration)
    clipped = GroundMotion("pacoima-15s", acceleration, motion.dt)
    periods, dampings = [0.05, 0.1, 0.2], [0.0, 0.05, 0.2]
    located = response_spectra(clipped, periods, dampings)
    sampled = response_spectra(clipped, periods, dampings, between_samples=False)
    displacement = response_spectra(clipped, periods, dampings, displacement_only=True)
    assert np.isnan(displacement.sv).all() and np.isnan(displacement.sa).all()
    worst_sampled = 0.0
    for j, xi in enumerate(dampings):
        for i, period in enumerate(periods):
            truth, _ = lsim_peaks(fine_acceleration, fine_time, period, xi)
            ours = [located.sd[j, i], located.sv[j, i], located.sa[j, i]]
            np.testing.assert_allclose(ours, truth, rtol=1e-4)
            assert displacement.sd[j, i] == pytest.approx(truth[0], rel=1e-4)
            at_samples = np.array([sampled.sd[j, i], sampled.sv[j, i], sampled.sa[j, i]])
            worst_sampled = max(worst_sampled, np.max(1 - at_samples / truth))
    assert worst_sampled > 0.02  # the located peaks fix an error the sampled ones do have


@pytest.mark.parametrize("damping", [0.0, 0.2])
@pytest.mark.parametrize("period, dt", [(1.0, 0.03), (0.05, 0.04), (0.01, 0.04)])
def test_step_peaks_between_samples(period, dt, damping):
    """üg = −a0: u = (a0/ω²)[1 − e^{−ξωt}(cos ω_dt + ξω/ω_d sin ω_dt)], u' = (a0/ω_d) e^{−ξωt} sin ω_dt.

    Sd = (a0/ω²)(1 + e^{−ξπ/√(1−ξ²)}) at t = π/ω_d; Sv at tan ω_dt = ω_d/(ξω); for ξ = 0,
    Sa = max|ω²u| = 2a0. The samples miss these instants; with dt > T several extrema lie in
    one step.
    """
    a0 = 3.0
    omega = 2 * math.pi / period
    omega_d = omega * math.sqrt(1 - damping ** 2)
    motion = GroundMotion("step", np.full(int(3 * period / dt) + 3, -a0), dt)
    spectra = response_spectra(motion, [period], [damping])
    sd = a0 / omega ** 2 * (1 + math.exp(-damping * math.pi / math.sqrt(1 - damping ** 2)))
    t_sv = math.atan2(omega_d, damping * omega) / omega_d
    sv = a0 / omega_d * math.exp(-damping * omega * t_sv) * math.sin(omega_d * t_sv)
    np.testing.assert_allclose([spectra.sd[0, 0], spectra.sv[0, 0]], [sd, sv], rtol=1e-10)
    if damping == 0.0:
        assert spectra.sa[0, 0] == pytest.approx(2 * a0, rel=1e-10)


@pytest.mark.parametrize("displacement_only", [True, False])
def test_steps_left_unexamined_change_no_peak(seed_suite, displacement_only):
    """The steps the search between samples passes over (the record's bounds, then each step's
    own) hold no extremum above the running peaks: examining every step gives the same spectra,
    bit for bit. Pacoima (dt = 0.01 s) at short periods, one to three segments a step, where
    nearly every step holds an extremum of u, u' or ü + üg."""
    motion = seed_suite.get("pacoima_dam_1971").motion
    acc, dt = motion.acceleration[:1500], motion.dt
    periods = np.array([0.008, 0.012, 0.02, 0.035, 0.06, 0.1])
    for damping in (0.0, 0.05, 0.2):
        dampings = np.full(periods.size, damping)
        coeffs = recurrence_coefficients(periods, dampings, dt)
        omega = 2.0 * np.pi / periods
        searched = np.empty((periods.size, 3))
        spectrum_peaks(acc, dt, coeffs, omega, dampings, True, displacement_only, searched)
        at_samples = np.empty((periods.size, 3))
        spectrum_peaks(acc, dt, coeffs, omega, dampings, False, displacement_only, at_samples)
        for i, period in enumerate(periods):
            xi_omega = damping * omega[i]
            omega_d = omega[i] * math.sqrt(1.0 - damping * damping)
            u, v = np.zeros(acc.size), np.zeros(acc.size)
            step = step_coefficients(coeffs[i])
            for k in range(acc.size - 1):
                u[k + 1], v[k + 1] = oscillator_step(step, u[k], v[k], acc[k], acc[k + 1])
            peaks = tuple(np.nan_to_num(at_samples[i]))
            for k in range(acc.size - 1):
                peaks = step_peaks(u[k], v[k], u[k + 1], v[k + 1], acc[k],
                                   (acc[k + 1] - acc[k]) / dt, int(omega_d * dt / 3.0) + 1,
                                   xi_omega, omega_d, omega[i] * omega[i], dt, *peaks,
                                   displacement_only)
            expected = peaks[:1] + (np.nan, np.nan) if displacement_only else peaks
            np.testing.assert_array_equal(searched[i], expected, err_msg=f"T = {period} s")
        assert np.all(searched[:, 0] > at_samples[:, 0])  # peaks between samples were found


@settings(max_examples=25, deadline=None)
@given(periods=st.lists(st.floats(0.02, 6.0), min_size=1, max_size=11),
       damping=st.sampled_from([0.0, 0.05, 0.3]), start=st.integers(0, 2500),
       between_samples=st.booleans(), displacement_only=st.booleans())
def test_a_table_computes_each_oscillator_as_alone(seed_suite, periods, damping, start,
                                                   between_samples, displacement_only):
    """spectrum_peaks runs the recurrences of four oscillators side by side (the last lanes of a
    table not a multiple of four repeat its last one; a table of one runs one lane): each
    oscillator's peaks are those of a table of it alone, bit for bit, at every position of any
    table."""
    motion = seed_suite.get("rinaldi_1994").motion
    acc, dt = motion.acceleration[start:start + 1500], motion.dt
    periods = np.array(periods)
    dampings = np.full(periods.size, damping)
    coeffs, omega = recurrence_coefficients(periods, dampings, dt), 2.0 * np.pi / periods
    table = np.empty((periods.size, 3))
    spectrum_peaks(acc, dt, coeffs, omega, dampings, between_samples, displacement_only, table)
    for i in range(periods.size):
        alone = np.empty((1, 3))
        spectrum_peaks(acc, dt, coeffs[i:i + 1], omega[i:i + 1], dampings[i:i + 1],
                       between_samples, displacement_only, alone)
        np.testing.assert_array_equal(table[i].view(np.int64), alone[0].view(np.int64))


def test_overdamped_oscillators_are_refused():
    motion = GroundMotion("step", np.ones(10), 0.01)
    with pytest.raises(InputError, match="damping"):
        response_spectra(motion, [1.0], [1.0])


def test_zero_period_and_pseudo_spectra(seed_suite):
    motion = seed_suite.get("sylmar_1994").motion
    spectra = response_spectra(motion, [0.0, 1.0], [0.05])
    assert spectra.sd[0, 0] == 0.0 and spectra.sv[0, 0] == 0.0
    assert spectra.sa[0, 0] == pytest.approx(motion.pga)
    assert spectra.pseudo_acceleration[0, 1] == pytest.approx((2 * math.pi) ** 2 * spectra.sd[0, 1])
    assert spectra.pseudo_acceleration[0, 0] == pytest.approx(motion.pga)
    assert spectra.pseudo_velocity[0, 0] == 0.0
    # a stiff oscillator follows the ground: Sa → PGA (T = 0.1·dt: the ringing after each kink
    # of the piecewise-linear input, ~Δüg'/ω, is small)
    stiff = response_spectra(motion, [0.002], [0.05])
    assert stiff.sa[0, 0] == pytest.approx(motion.pga, rel=0.02)


def test_free_motion_tail_only_adds_response(seed_suite):
    motion = seed_suite.get("erzincan_1992").motion
    periods = [1.0, 5.0, 20.0]
    short = response_spectra(motion, periods, [0.05])
    long = response_spectra(motion, periods, [0.05], free_motion_s=30.0)
    assert np.all(long.sd >= short.sd)


def test_priestley_and_fema_damping_values():
    r = coefficient_of_restitution(np.radians([10, 15, 20]))
    np.testing.assert_allclose(100 * damping_priestley(r), [3.15, 7.20, 13.12], atol=0.005)
    np.testing.assert_allclose(100 * damping_fema356(r), [1.8, 4.0, 7.0], atol=0.05)
    # "the FEMA damping of Eq. 9.1 is about half of Eq. 7.10"
    ratio = damping_fema356(r) / damping_priestley(r)
    assert np.all((ratio > 0.45) & (ratio < 0.6))


def test_free_rocking_damping_eq_7_9():
    r = coefficient_of_restitution(np.radians([10, 15, 20]))
    # small-amplitude limit of Eq. 7.9: θn/α → rⁿ θ₀/α, so β → −ln(r)/π
    np.testing.assert_allclose(damping_free_rocking(1e-7, 4, r), -np.log(r) / np.pi, rtol=1e-5)
    # over 16 impacts it approaches Eq. 7.10 within 10 % for θ₀/α ≤ 0.5 …
    for x in (0.1, 0.2, 0.3, 0.4, 0.5):
        np.testing.assert_allclose(damping_free_rocking(x, 16, r), damping_priestley(r), rtol=0.1)
    # … and the deviation shrinks as the count of impacts grows, for the larger amplitudes
    deviation = [np.abs(damping_free_rocking(0.5, n, r) / damping_priestley(r) - 1)
                 for n in (2, 4, 8, 16)]
    assert np.all(np.diff(deviation, axis=0) < 0)


def test_housner_period_and_inverse():
    p = 2.0
    assert housner_period(0.0, p) == 0.0
    assert housner_period(0.5, p) == pytest.approx(2.0 * math.acosh(2.0))
    ratios = np.array([0.01, 0.3, 0.9, 0.999])
    np.testing.assert_allclose(housner_rotation_ratio(housner_period(ratios, p), p), ratios)


def test_fema_table_rows_and_continuity():
    for beta, b_s, b_1 in FEMA356_TABLE_1_6:
        assert fema356_damping_coefficients(beta) == (pytest.approx(b_s), pytest.approx(b_1))
    assert fema356_damping_coefficients(0.01) == (0.8, 0.8)
    assert fema356_damping_coefficients(0.7) == (3.0, 2.0)
    assert fema356_damping_coefficients(0.075) == (pytest.approx(1.15), pytest.approx(1.1))
    spectrum = FEMA356Spectrum(1.59, 0.50)
    for beta in (0.018, 0.05, 0.1, 0.35):
        t_0, t_s = spectrum.corner_periods(beta)
        b_s, b_1 = fema356_damping_coefficients(beta)
        assert t_s == pytest.approx(0.50 * b_s / (1.59 * b_1))
        for corner in (t_0, t_s):
            below, above = spectrum.acceleration([corner * (1 - 1e-9), corner * (1 + 1e-9)], beta)
            assert below == pytest.approx(above, rel=1e-6)
        assert spectrum.acceleration(0.0, beta) == pytest.approx(0.4 * 1.59)
        assert spectrum.acceleration(t_s, beta) == pytest.approx(1.59 / b_s)
        assert spectrum.acceleration(2.0, beta) == pytest.approx(0.50 / (b_1 * 2.0))
    # Eq. 3.5: Sa = 1 g at T = 2π s is a displacement of g metres
    assert float(spectrum.displacement(2 * math.pi, 0.05)) == pytest.approx(
        0.5 / (2 * math.pi) * 9.81)


def test_ubc97_zone_4_soil_sd():
    spectrum = UBC97Spectrum()
    assert spectrum.ca == pytest.approx(0.44) and spectrum.cv == pytest.approx(0.64)
    t_s = 0.64 / (2.5 * 0.44)
    assert spectrum.acceleration(0.0) == pytest.approx(0.44)
    assert spectrum.acceleration(t_s) == pytest.approx(1.1)
    assert spectrum.acceleration(1.0) == pytest.approx(0.64)
    assert spectrum.acceleration(1.0, 0.10) == pytest.approx(0.64 / 1.2)
    near = UBC97Spectrum(1.5, 2.0)
    assert near.acceleration(2.0) == pytest.approx(0.64 * 2.0 / 2.0)
