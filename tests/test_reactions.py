"""Pivot reactions against hand calculations: uplift, and free rocking by energy and moments."""

import math

import numpy as np
import pytest

from audit.physics.reactions import pivot_reactions, required_friction

G = 9.81


@pytest.mark.parametrize("alpha_deg", [10, 15, 20])
def test_uplift_needs_tan_alpha(alpha_deg):
    # at uplift about the corner of θ > 0: θ = θ' = 0 and ü_g = −g tan α, so θ'' = 0 and the
    # block is in equilibrium: H = m ü_g, V = m g, |H| / V = tan α
    alpha = math.radians(alpha_deg)
    h, v = pivot_reactions(0.0, 0.0, -G * math.tan(alpha), 1, 2.0, alpha, G)
    assert h == pytest.approx(-math.tan(alpha), rel=1e-12)
    assert v == pytest.approx(1.0, rel=1e-12)
    assert required_friction([h], [v]) == pytest.approx(math.tan(alpha), rel=1e-12)


@pytest.mark.parametrize("side", [1, -1])
def test_free_rocking_by_energy_and_moments(side):
    # block released at rest from θ0 on one corner, no ground motion; at θ:
    # energy  ½ I_O θ'² = m g R (cos(α − |θ0|) − cos(α − |θ|)), I_O = 4/3 m R²
    # moments I_O θ'' = −s m g R sin(α − |θ|)
    # centroid r = (−s R sin(α − |θ|), R cos(α − |θ|)) from the pivot, turning at ω_z = −θ'
    p, alpha, theta0, theta = 2.5, math.radians(14), side * 0.15, side * 0.04
    radius = 3 * G / (4 * p ** 2)
    omega = -side * math.sqrt(1.5 * G / radius * (math.cos(alpha - abs(theta0))
                                                  - math.cos(alpha - abs(theta))))
    theta_acc = -side * 0.75 * G / radius * math.sin(alpha - abs(theta))
    r = np.array([-side * radius * math.sin(alpha - abs(theta)),
                  radius * math.cos(alpha - abs(theta))])
    acc = -theta_acc * np.array([-r[1], r[0]]) - omega ** 2 * r
    h, v = pivot_reactions(theta, omega, 0.0, side, p, alpha, G)
    assert h == pytest.approx(acc[0] / G, rel=1e-12)
    assert v == pytest.approx(1 + acc[1] / G, rel=1e-12)
    # the friction force points under the block (towards the centroid, away from the side of
    # the pivot) and the pivot carries less than the weight
    assert side * h < 0 and 0 < v < 1


def test_jumping_has_no_friction_bound():
    # fast enough rotation lifts the centroid's need for V below zero: V < 0 means jumping
    h, v = pivot_reactions(0.0, 10.0, 0.0, 1, 2.0, math.radians(10), G)
    assert v < 0
    assert required_friction([h], [v]) == math.inf


def test_validity_of_a_whole_response():
    from audit.physics.block import RigidBlock
    from audit.physics.reactions import rocking_validity
    from audit.physics.rocking import simulate
    from records.motion import GroundMotion
    t = np.arange(0, 2, 0.01)
    alpha = math.radians(15)
    block = RigidBlock.from_size(4.0, alpha)
    # below uplift the block rests on its base: H = m ü_g, V = m g, so μ_req = PGA / g
    still = GroundMotion(id="still", acceleration=0.2 * G * np.sin(2 * np.pi * t), dt=0.01)
    friction, jumps = rocking_validity(simulate(block, still, free_motion_s=1.0), still)
    assert friction == pytest.approx(0.2, rel=1e-6) and not jumps
    # a rocking block needs at least tan α (at uplift)
    rocking = GroundMotion(id="rock", acceleration=0.4 * G * np.sin(2 * np.pi * t), dt=0.01)
    friction, jumps = rocking_validity(simulate(block, rocking, free_motion_s=1.0), rocking)
    assert friction >= math.tan(alpha) * (1 - 1e-9) and not jumps
