"""Pivot reactions, required friction, jumping and vertical motion against independent facts:
hand calculations (uplift, free rocking by energy and moments), Newton's law on the centroid's
path differentiated numerically, and a constant vertical acceleration run as a changed g."""

import math

import numpy as np
import pytest

from audit.physics.block import RigidBlock
from audit.physics.rocking import RockingOptions, pivot_reactions, rocking_spectrum, simulate
from records.motion import GroundMotion

G = 9.81


def reactions(theta, omega, ug, side, p, alpha, uv=0.0):
    return pivot_reactions(theta, omega, ug, uv, side, p * p, alpha, G)


@pytest.mark.parametrize("alpha_deg", [10, 15, 20])
def test_uplift_needs_tan_alpha(alpha_deg):
    # at uplift about the corner of θ > 0: θ = θ' = 0 and ü_g = −g tan α, so θ'' = 0 and the
    # block is in equilibrium: H = m ü_g, V = m g, |H| / V = tan α
    alpha = math.radians(alpha_deg)
    h, v = reactions(0.0, 0.0, -G * math.tan(alpha), 1, 2.0, alpha)
    assert h == pytest.approx(-math.tan(alpha), rel=1e-12)
    assert v == pytest.approx(1.0, rel=1e-12)


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
    h, v = reactions(theta, omega, 0.0, side, p, alpha)
    assert h == pytest.approx(acc[0] / G, rel=1e-12)
    assert v == pytest.approx(1 + acc[1] / G, rel=1e-12)
    # the friction force points under the block (towards the centroid, away from the side of
    # the pivot) and the pivot carries less than the weight
    assert side * h < 0 and 0 < v < 1


def test_fast_rotation_makes_the_block_jump():
    # at θ = 0, no ground motion: θ'' = −p² sin α, R p² = 3g/4, so
    # V/m = g − (3g/4) sin²α − R ω² cos α, negative from ω² = g (1 − 0.75 sin²α) / (R cos α)
    p, alpha = 2.0, math.radians(10)
    radius = 3 * G / (4 * p ** 2)
    critical = math.sqrt(G * (1 - 0.75 * math.sin(alpha) ** 2) / (radius * math.cos(alpha)))
    assert reactions(0.0, 0.99 * critical, 0.0, 1, p, alpha)[1] > 0
    assert reactions(0.0, 1.01 * critical, 0.0, 1, p, alpha)[1] < 0


def _rocking_record(amplitude_g=0.45, period_s=0.8, dt=0.002, seconds=3.0):
    t = np.arange(0, seconds, dt)
    acc = amplitude_g * G * np.sin(2 * np.pi * t / period_s) * np.exp(-0.5 * t)
    return GroundMotion(id="decaying sine", acceleration=acc, dt=dt)


def test_reactions_are_newtons_law_on_the_centroid_path():
    # independent path: the centroid's position from θ(t) on the solver's grid, differentiated
    # twice by central differences, plus the ground's acceleration, is the force per unit mass
    alpha = math.radians(15)
    block = RigidBlock.from_size(2.0, alpha)
    motion = _rocking_record()
    response = simulate(block, motion, free_motion_s=0.0)
    theta, omega = response.theta, response.omega
    radius, dt = block.radius, motion.dt
    side = np.sign(theta)
    x = -side * radius * np.sin(alpha - np.abs(theta))
    y = radius * np.cos(alpha - np.abs(theta))
    # interior points away from impacts and rest: the same pivot over the whole stencil
    same = (side[:-2] == side[1:-1]) & (side[1:-1] == side[2:]) & (side[1:-1] != 0)
    k = np.flatnonzero(same) + 1
    assert k.size > 200
    ax = (x[k + 1] - 2 * x[k] + x[k - 1]) / dt ** 2
    ay = (y[k + 1] - 2 * y[k] + y[k - 1]) / dt ** 2
    h_newton = (motion.acceleration[k] + ax) / G
    v_newton = 1 + ay / G
    h, v = np.array([reactions(theta[i], omega[i], motion.acceleration[i], side[i], block.p,
                               alpha) for i in k]).T
    # central differences are second order: error ~ dt² θ'''' R / g, well below 1e-3 here
    assert np.max(np.abs(h - h_newton)) < 2e-3
    assert np.max(np.abs(v - v_newton)) < 2e-3


def test_required_friction_of_a_whole_response():
    t = np.arange(0, 2, 0.01)
    alpha = math.radians(15)
    block = RigidBlock.from_size(4.0, alpha)
    # below uplift the block rests on its base: H = m ü_g, V = m g, so μ_req = PGA / g
    still = GroundMotion(id="still", acceleration=0.2 * G * np.sin(2 * np.pi * t), dt=0.01)
    response = simulate(block, still, free_motion_s=1.0)
    assert not response.uplifted
    assert response.required_friction == pytest.approx(0.2, rel=1e-9)
    assert response.min_vertical_reaction == 1.0 and not response.jumps
    # a rocking block needs at least tan α (at uplift), and the kernel's tracking over every
    # step is at least the largest |H|/V at the output points (turning points, both sides of
    # each impact), and not much more
    motion = _rocking_record()
    response = simulate(RigidBlock.from_size(2.0, alpha), motion, free_motion_s=1.0)
    assert response.uplifted and not response.overturned
    time, theta, omega = response.history()
    ug = motion.acceleration_at(time)
    rocking = theta != 0
    ratios = [abs(h) / v for h, v in (reactions(th, om, u, np.sign(th), response.block.p, alpha)
                                      for th, om, u in zip(theta[rocking], omega[rocking],
                                                           ug[rocking]))]
    at_points = max(max(ratios), math.tan(alpha))
    assert at_points <= response.required_friction * (1 + 1e-9)
    assert response.required_friction <= at_points * 1.05
    assert response.required_friction >= math.tan(alpha) * (1 - 1e-12)


def test_spectrum_reports_the_same_reactions_as_one_simulation():
    motion = _rocking_record()
    sizes, alphas = [1.0, 2.0, 3.0], np.radians([10, 20])
    spectrum = rocking_spectrum(motion, sizes, alphas, options=RockingOptions(free_motion_s=1.0))
    for i, alpha in enumerate(alphas):
        for j, size in enumerate(sizes):
            one = simulate(RigidBlock.from_size(size, alpha), motion, free_motion_s=1.0)
            assert spectrum.required_friction[i, j] == one.required_friction
            assert spectrum.jumps[i, j] == one.jumps
    off = rocking_spectrum(motion, sizes, alphas, options=RockingOptions(free_motion_s=1.0),
                           reactions=False)
    assert np.all(np.isnan(off.required_friction))
    assert np.array_equal(off.theta_peak, spectrum.theta_peak)  # tracking changes nothing


@pytest.mark.parametrize("vertical_g", [0.3, -0.25])
def test_constant_vertical_acceleration_is_a_changed_gravity(vertical_g):
    # θ'' = −p²[(1 + a_v/g) sin φ + (ü_g/g) cos φ]; a block of the same R under gravity
    # g' = g + a_v has p'² = p² g'/g and θ'' = −p'²[sin φ + (ü_g/g') cos φ], the same equation;
    # uplift at |ü_g| = g' tan α in both
    alpha, size = math.radians(12), 2.0
    base = _rocking_record(amplitude_g=0.5)
    a_v = vertical_g * G
    motion = GroundMotion(id="with vertical", acceleration=base.acceleration, dt=base.dt,
                          vertical=np.full(base.acceleration.size, a_v))
    block = RigidBlock.from_size(size, alpha)
    with_vertical = simulate(block, motion, free_motion_s=2.0, vertical=True)
    g_changed = G + a_v
    changed = RigidBlock(block.p * math.sqrt(g_changed / G), alpha, block.r, g=g_changed)
    assert changed.radius == pytest.approx(block.radius, rel=1e-12)
    reference = simulate(changed, base, free_motion_s=2.0)
    assert with_vertical.uplifted and reference.uplifted
    assert with_vertical.overturned == reference.overturned
    assert with_vertical.peak_rotation == pytest.approx(reference.peak_rotation, rel=1e-5)
    assert with_vertical.peak_angular_velocity == pytest.approx(
        reference.peak_angular_velocity, rel=1e-5)
    assert with_vertical.required_friction == pytest.approx(reference.required_friction,
                                                            rel=1e-5)
    # without --vertical the component is ignored: bit for bit the horizontal-only response
    ignored = simulate(block, motion, free_motion_s=2.0)
    horizontal = simulate(block, base, free_motion_s=2.0)
    assert ignored.peak_rotation == horizontal.peak_rotation
    assert ignored.required_friction == horizontal.required_friction
    assert with_vertical.peak_rotation != horizontal.peak_rotation


def test_vertical_component_scales_with_the_record_and_flips_for_down():
    base = _rocking_record()
    up = GroundMotion(id="up", acceleration=0.1 * base.acceleration, dt=base.dt)
    motion = base.with_vertical(up)
    assert np.array_equal(motion.vertical, up.acceleration)
    assert np.array_equal(base.with_vertical(up, down=True).vertical, -up.acceleration)
    assert np.array_equal(motion.scaled(2.0).vertical, 2.0 * up.acceleration)
    # another sampling: read linearly on the record's own samples, zero past its end
    coarse = GroundMotion(id="up", acceleration=np.array([0.0, 1.0]), dt=0.004)
    resampled = base.with_vertical(coarse).vertical
    assert resampled[1] == pytest.approx(0.5) and resampled[2] == pytest.approx(1.0)
    assert np.all(resampled[3:] == 0.0)
