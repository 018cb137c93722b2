"""Housner (1963) and Makris & Roussos (2000) / Zhang & Makris (2001) overturning criteria,
against numbers worked independently of this code (the project's research note, §11 T2–T10),
and the two procedures built on them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from audit.physics.block import RigidBlock
from audit.physics.damping import housner_period
from audit.physics.overturning_criteria import (HALF_SINE, ONE_COSINE, ONE_SINE,
                                                exact_minimum_amplitude,
                                                half_sine_minimum_amplitude,
                                                housner_critical_velocity,
                                                housner_critical_velocity_slender,
                                                housner_half_sine_amplitude,
                                                impulse_minimum_amplitude,
                                                linear_minimum_amplitude,
                                                one_sine_no_impact_amplitude,
                                                required_alpha_housner, required_alpha_pulse)
from audit.engine.shared.verdicts import check_verdicts, exact_exceeded
from procedures import get_procedures
from procedures.context import RecordContext
from procedures.housner_1963 import Housner1963
from procedures.makris_roussos_2000 import MakrisRoussos2000
from records import RecordEntry, one_pulse, pulse_suite

G = 9.81
# the block b = 0.2 m, h = 1.0 m of the note's §2.6
BLOCK = RigidBlock.from_dimensions(0.2, 1.0, g=G)
ALPHA, RADIUS = math.atan(0.2), math.hypot(0.2, 1.0)


def test_block_of_the_anchors():
    assert BLOCK.alpha == pytest.approx(0.197396, abs=1e-6)
    assert BLOCK.radius == pytest.approx(1.019804, abs=1e-6)
    assert BLOCK.p == pytest.approx(2.68600, abs=1e-5)


def test_t2_half_sine_eq_27():
    got = half_sine_minimum_amplitude([0.5, 1.0, 2.0, 3.0, 5.0])
    np.testing.assert_allclose(got, [1.1094, 1.3224, 1.8007, 2.2939, 3.2891], atol=6e-5)


def test_t3_one_sine_no_impact_eq_47():
    got = one_sine_no_impact_amplitude([0.5, 1.0, 2.0, 3.0, 5.0])
    np.testing.assert_allclose(got, [1.1180, 1.4183, 2.3499, 3.6311, 7.1681], atol=6e-5)


def test_impulse_criterion_reproduces_eqs_27_and_47():
    # §2.5: the weighted-impulse condition is the general form of both closed forms
    for ratio in (0.5, 1.0, 2.0, 3.0):
        assert impulse_minimum_amplitude(ratio, HALF_SINE) == pytest.approx(
            float(half_sine_minimum_amplitude(ratio)), abs=1e-6)
    for ratio in (1.0, 2.0, 5.0):
        assert impulse_minimum_amplitude(ratio, ONE_SINE) == pytest.approx(
            float(one_sine_no_impact_amplitude(ratio)), abs=1e-6)


def test_impulse_criterion_of_the_one_cosine_pulse_in_closed_form():
    # the block uplifts at t = 0 under a_p cos(ω_p t): p∫₀^T (a/g) cos(ω_p s) e^{−ps} ds = α with
    # T = 2π/ω_p gives a/(αg) = (1 + (ω_p/p)²) / (1 − e^{−2π p/ω_p}), worked by hand
    for ratio in (0.5, 1.0, 2.0, 3.0):
        closed = (1 + ratio ** 2) / (1 - math.exp(-2 * math.pi / ratio))
        assert impulse_minimum_amplitude(ratio, ONE_COSINE) == pytest.approx(closed, rel=1e-7)


def test_published_lines_and_housner_eq_12():
    ratios = np.array([0.5, 1.0, 2.0, 3.0])
    np.testing.assert_allclose(linear_minimum_amplitude(ratios, ONE_SINE),
                               [1.0833, 1.1667, 1.3333, 1.5000], atol=5e-5)
    np.testing.assert_allclose(linear_minimum_amplitude(ratios, ONE_COSINE),
                               [1.125, 1.25, 1.5, 1.75])
    np.testing.assert_allclose(linear_minimum_amplitude(ratios, HALF_SINE), [1.25, 1.5, 2.0, 2.5])
    np.testing.assert_allclose(housner_half_sine_amplitude(ratios),
                               [1.1180, 1.4142, 2.2361, 3.1623], atol=5e-5)


@pytest.mark.parametrize("shape, ratio, expected", [(ONE_SINE, 2.0, 1.2199),
                                                    (ONE_COSINE, 3.0, 1.8145),
                                                    (ONE_SINE, 0.5, 1.0453)])
def test_t5_exact_minimum_overturning(shape, ratio, expected):
    period = 2 * math.pi / (ratio * BLOCK.p)
    minimum, safe = exact_minimum_amplitude(BLOCK, shape, period, beyond=1.02)
    assert minimum == pytest.approx(expected, abs=0.005)
    assert all(minimum < low <= high for low, high in safe)


def test_t6_velocity_form_and_t10_design_inversion():
    # one-sine, T_p = 1 s: a_p0 = αg(1 + ω_p/6p) = 2.6914 m/s², v_p0 = 2 a_p0/ω_p = 0.8567 m/s
    omega = 2 * math.pi
    a_p0 = ALPHA * G * float(linear_minimum_amplitude(omega / BLOCK.p, ONE_SINE))
    assert a_p0 == pytest.approx(2.6914, abs=1e-4)
    assert 2 * a_p0 / omega == pytest.approx(0.8567, abs=1e-4)
    # a_p = 0.5 g, T_p = 1 s, R = 1.0198 m: α_req = 0.3597 rad
    assert float(required_alpha_pulse(0.5 * G, 1.0, 1.0198, ONE_SINE, G)) == pytest.approx(
        0.3597, abs=1e-4)
    # Housner inverted: the S_v of the block's own criterion gives back its α
    assert float(required_alpha_housner(housner_critical_velocity(ALPHA, BLOCK.p, G), BLOCK.p,
                                        G)) == pytest.approx(ALPHA, rel=1e-12)


def test_t7_housner_critical_velocity_and_t8_period():
    assert float(housner_critical_velocity(ALPHA, BLOCK.p, G)) == pytest.approx(0.7209, abs=1e-4)
    assert float(housner_critical_velocity_slender(ALPHA, RADIUS, G)) == pytest.approx(
        0.6244, abs=1e-4)
    assert float(housner_period(0.5, 2.686)) == pytest.approx(1.9612, abs=1e-4)


def test_makris_roussos_check_on_a_one_cosine_pulse():
    # a one-cosine pulse of 0.3 g, T_p = 2 s; blocks α = 10°, sizes 1–4 s; small-angle αg
    entry = RecordEntry("pulse", one_pulse("cosine", 0.3, 2.0))
    p = 2 * np.pi / np.array([1.0, 2.0, 4.0])
    alpha = math.radians(10)
    check, = MakrisRoussos2000().checks(entry, p, alpha, 0.9, None, G)
    capacity = alpha * G * (1 + 0.25 * (math.pi / p))  # ω_p = π rad/s
    np.testing.assert_allclose(check.capacity_m_s2, capacity, rtol=1e-12)
    np.testing.assert_array_equal(check.passes, 0.3 * G < capacity)
    housner = MakrisRoussos2000(variant="housner").checks(entry, p, alpha, 0.9, None, G)[0]
    np.testing.assert_allclose(housner.capacity_m_s2,
                               alpha * G * np.sqrt(1 + (math.pi / p) ** 2), rtol=1e-12)
    # a record without a pulse is classified, found not pulse-like, and not audited
    from records import GroundMotion
    plain = RecordEntry("plain", GroundMotion("plain", np.zeros(10), 0.01))
    assert "not pulse-like (PI -" in MakrisRoussos2000().unmet_requirements(plain)


def test_housner_check_reads_the_peak_velocity_spectrum():
    entry = pulse_suite().get("rinaldi_1994")
    context = RecordContext(entry, 10.0)
    p = 2 * np.pi / np.array([1.0, 3.0])
    alpha = math.radians(15)
    check, = Housner1963().checks(entry, p, alpha, 0.9, context, G)
    spectra = context.true_spectra(0.02)
    peak = spectra.sv[0][spectra.period_s <= 10.0].max()
    np.testing.assert_allclose(check.demand_m_s, peak)
    np.testing.assert_allclose(check.capacity_m_s, G * alpha / p)
    # overturning checks are audited against exact overturning
    exceeded = exact_exceeded(check, np.array([0.1, 0.2]), np.array([True, False]),
                              np.array([True, True]))
    np.testing.assert_array_equal(exceeded, [True, False])
    assert list(check_verdicts([True, False], exceeded)) == ["missed", "false-alarm"]


def test_run_all_audits_five_procedures():
    names = [procedure.name for procedure in get_procedures("all")]
    assert names[:5] == ["priestley1978", "fema356", "ntc2018", "housner1963",
                         "makrisroussos2000"]
