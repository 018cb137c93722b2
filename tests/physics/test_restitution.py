"""The impact model: housner | VALUE | xFACTOR, parsed once and applied per slenderness."""

import math

import numpy as np
import pytest

from audit.errors import InputError
from audit.physics.block import Restitution, RigidBlock


def test_housner_is_eq_4_8():
    alpha = math.radians(15)
    # Eq. 4.8 by hand: (1 - 1.5 sin²15°)² = (1 - 1.5 · 0.0669873)² = 0.80665...
    expected = (1 - 1.5 * 0.25881904510252074 ** 2) ** 2
    assert Restitution.parse("housner").r(alpha) == pytest.approx(expected, rel=1e-12)
    assert RigidBlock(2.0, alpha, Restitution.parse("HOUSNER")).r == pytest.approx(expected)


def test_factor_and_value():
    alpha = math.radians(20)
    housner = (1 - 1.5 * math.sin(alpha) ** 2) ** 2
    assert Restitution.parse("x0.9").r(alpha) == pytest.approx(0.9 * housner, rel=1e-12)
    assert Restitution.parse("0.8x").r(alpha) == pytest.approx(0.8 * housner, rel=1e-12)
    assert RigidBlock(2.0, alpha, Restitution.parse("0.7")).r == 0.7
    assert np.allclose(Restitution.parse("0.7").r(np.radians([10, 20])), [0.7, 0.7])


@pytest.mark.parametrize("text", ["", "x", "abc", "0", "-0.5", "1.2", "x1.5", "nan", "inf", "x0"])
def test_bad_values_name_the_field(text):
    with pytest.raises(InputError, match="^restitution: "):  # the command line: --restitution
        Restitution.parse(text)


def test_spectrum_uses_the_model():
    from records.motion import GroundMotion
    from audit.physics.rocking import rocking_spectrum
    t = np.arange(0, 2, 0.01)
    motion = GroundMotion(id="pulse", acceleration=0.25 * 9.81 * np.sin(2 * np.pi * t), dt=0.01)
    sizes, alphas = [4.0, 6.0], np.radians([10, 12])
    fixed = [RigidBlock.from_size(4.0, a, float(Restitution.parse("x0.8").r(a))) for a in alphas]
    by_model = rocking_spectrum(motion, sizes, alphas, Restitution.parse("x0.8"))
    by_value = [rocking_spectrum(motion, sizes, [a], b.r) for a, b in zip(alphas, fixed)]
    housner = rocking_spectrum(motion, sizes, alphas)
    # each α gets 0.8 × its own Eq. 4.8, and the model reaches the kernel (impacts lose more: smaller peaks)
    for i in range(2):
        assert np.array_equal(by_model.theta_peak[i], by_value[i].theta_peak[0])
    assert np.all(by_model.theta_peak < housner.theta_peak)


def test_r_one_conserves_energy_between_and_at_impacts():
    # after the excitation, E / (m g R) = cos(α − |θ|) + θ'² / (2 p²) (I_O = 4/3 m R², p² = 3g/4R)
    # is constant along the free rocking, and r = 1 keeps it through each impact
    from records.motion import GroundMotion
    from audit.physics.rocking import simulate
    t = np.arange(0, 1, 0.01)
    motion = GroundMotion(id="pulse", acceleration=0.22 * 9.81 * np.sin(2 * np.pi * t), dt=0.01)
    block = RigidBlock.from_size(4.0, math.radians(10), Restitution.parse("1.0"))
    response = simulate(block, motion, free_motion_s=6.0)
    assert not response.overturned
    time, theta, omega = response.history()
    free = time > response.excitation_end
    energy = np.cos(block.alpha - np.abs(theta[free])) + omega[free] ** 2 / (2 * block.p ** 2)
    assert response.impact_times[response.impact_times > response.excitation_end].size >= 2
    assert np.ptp(energy) < 1e-7 * (1 - math.cos(block.alpha))
    before, after = response.omega_before_impact, response.omega_after_impact
    assert np.allclose(np.abs(after), np.abs(before), rtol=1e-12)
