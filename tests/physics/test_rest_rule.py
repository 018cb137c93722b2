"""When a rocking block comes back to rest: the chatter's Zeno sequence against its closed form,
and the two far-field cases an independent solver (scipy, no rest shortcut) decided otherwise."""

import math

import numpy as np
import pytest

from audit import G
from audit.errors import InputError
from audit.physics.block import RigidBlock
from audit.physics.rocking import MIN_REST_TOLERANCE, chatter_time_bound, simulate
from records import GroundMotion


@pytest.mark.parametrize("push", [0.0, 0.5, -0.7])
def test_chatter_lasts_the_summed_zeno_series(push):
    """A block kicked at θ' = ω0 on ground pushing at a constant üg = push·g tan α chatters
    to rest. Small flights are parabolas of deceleration D± = p² cos α (tan α ± üg/g), so by
    hand the impacts end after 2ω0/(1 − r) (1/D+ + √r/D−). With the smallest rest tolerance (1e-20 α)
    the integrator must chatter almost that long, impact after impact."""
    block = RigidBlock.from_size(2.0 * math.pi / 2.0, math.radians(15.0))
    ug = push * G * math.tan(block.alpha)
    omega0 = 1e-4
    motion = GroundMotion("constant", np.full(101, ug), 0.01)
    response = simulate(block, motion, free_motion_s=0.0, rest_tolerance=MIN_REST_TOLERANCE,
                        initial_velocity=omega0)
    p2, cos_a, tan_a, r = block.p ** 2, math.cos(block.alpha), math.tan(block.alpha), block.r
    d_plus = p2 * cos_a * (tan_a + ug / G)
    d_minus = p2 * cos_a * (tan_a - ug / G)
    by_hand = 2.0 * omega0 / (1.0 - r) * (1.0 / d_plus + math.sqrt(r) / d_minus)
    assert response.n_impacts > 100  # the sequence was followed, not cut short
    assert response.impact_times[-1] == pytest.approx(by_hand, rel=1e-6)
    assert not response.overturned
    # the bound the rest rule uses holds the series for the smaller deceleration
    bound = chatter_time_bound(omega0, min(d_plus, d_minus), math.sqrt(r))
    assert by_hand <= bound <= 2.0 * by_hand


def test_a_rest_tolerance_below_the_impact_resolution_is_refused():
    block = RigidBlock.from_size(2.0, math.radians(15.0))
    with pytest.raises(InputError, match="rest tolerance"):
        simulate(block, GroundMotion("still", np.zeros(3), 0.01), rest_tolerance=1e-30)


def test_chatter_bound_is_infinite_without_restoring_or_dissipation():
    assert chatter_time_bound(1e-3, 0.0, 0.8) == math.inf
    assert chatter_time_bound(1e-3, -1.0, 0.8) == math.inf
    assert chatter_time_bound(1e-3, 1.0, 1.0) == math.inf


def test_a_small_rebound_on_quiet_ground_ends_in_rest_at_once():
    """With the ground still, a tiny rebound converges long before anything changes: one impact
    is recorded and the block rests (the shortcut keeps long chatters cheap)."""
    block = RigidBlock.from_size(2.0, math.radians(15.0))
    motion = GroundMotion("still", np.zeros(101), 0.01)
    response = simulate(block, motion, free_motion_s=0.0, initial_velocity=1e-6)
    assert response.n_impacts == 1


@pytest.fixture(scope="module")
def far_field():
    import records
    return records.load("p695-far-field")


@pytest.mark.parametrize("record_id, factor, overturned, peak_rad", [
    # numbers of the independent re-computation (scipy solver without a rest shortcut)
    ("rsn953_mul279", 1.3516312909972128, False, 0.2736),
    ("rsn848_clw_tr", 3.4817677576834485, True, None),
])
def test_rest_is_physical_on_the_cases_an_independent_solver_decided(far_field, record_id,
                                                                     factor, overturned, peak_rad):
    """The 0.8 m × 2.0 m block rested at θ' ≈ 1e-3 α while the ground stayed near g tan α, then
    missed the rocking that followed; the rest rule now lets it rock on."""
    block = RigidBlock.from_dimensions(0.4, 1.0)
    response = simulate(block, far_field.get(record_id).motion.scaled(factor))
    assert response.overturned == overturned
    if peak_rad is not None:
        assert response.peak_rotation == pytest.approx(peak_rad, rel=0.01)
