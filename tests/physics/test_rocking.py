"""The exact rocking solver against closed forms, the SPEC anchors, invariants and a reference."""

import math

import numpy as np
import pytest

from audit import G
from audit.physics.block import RigidBlock, coefficient_of_restitution, frequency_parameter
from audit.physics.damping import housner_peak_ratio, housner_period
from audit.errors import InputError
from audit.physics.reference import simulate_reference
from audit.physics.rocking import RockingOptions, rocking_blocks, rocking_spectrum, simulate
from records import GroundMotion, one_pulse


def still(dt=0.0005):
    return GroundMotion("still", np.zeros(2), dt)


def peaks_between_impacts(response, count):
    """max |θ| between the first ``count`` + 1 impacts (the peaks θ1, θ2, … of free rocking;
    the chatter's last flights before rest are shorter than a sample)."""
    out = []
    times = response.impact_times[:count + 1]
    for before, after in zip(times[:-1], times[1:]):
        inside = (response.time > before) & (response.time < after)
        out.append(np.max(np.abs(response.theta[inside])))
    return np.array(out)


def test_block_geometry():
    block = RigidBlock.from_dimensions(b=0.5, h=2.0)
    assert block.alpha == pytest.approx(math.atan(0.25))
    assert block.radius == pytest.approx(math.hypot(0.5, 2.0))
    assert block.p == pytest.approx(math.sqrt(3 * G / (4 * math.hypot(0.5, 2.0))))
    assert block.half_width == pytest.approx(0.5) and block.half_height == pytest.approx(2.0)
    assert float(frequency_parameter(block.radius)) == pytest.approx(block.p)
    assert coefficient_of_restitution(math.radians(15)) == pytest.approx(0.809, abs=5e-4)
    assert RigidBlock.from_size(2 * math.pi, 0.2).p == pytest.approx(1.0)


@pytest.mark.parametrize("kwargs,message", [
    ({"p": 0.0, "alpha": 0.2}, "p: must be a positive"),
    ({"p": 2.0, "alpha": math.radians(50)}, "alpha: must lie between 0 and 45"),
    ({"p": 2.0, "alpha": 0.0}, "alpha"),
    ({"p": 2.0, "alpha": 0.2, "r": 1.5}, "r: coefficient of restitution"),
    ({"p": float("nan"), "alpha": 0.2}, "p: must be a positive"),
])
def test_impossible_blocks(kwargs, message):
    with pytest.raises(InputError, match=message):
        RigidBlock(**kwargs)


@pytest.mark.parametrize("theta0_ratio", [0.1, 0.3, 0.5])
def test_housner_free_rocking_decay(theta0_ratio):
    """Eq. 7.5 for a slender block (α = 5°): within 1 % for n ≤ 8."""
    block = RigidBlock(2.0, math.radians(5))
    response = simulate(block, still(), free_motion_s=40.0,
                        initial_rotation=theta0_ratio * block.alpha)
    measured = peaks_between_impacts(response, 8) / block.alpha
    expected = housner_peak_ratio(theta0_ratio, np.arange(1, 9), block.r)
    np.testing.assert_allclose(measured, expected, rtol=0.01)


def test_energy_ratio_per_impact_is_r():
    """Each impact multiplies the kinetic energy by r: for the nonlinear free block, the peak
    potential p²[cos(α − θk) − cos α] of successive peaks falls by exactly r."""
    block = RigidBlock(3.0, math.radians(20))
    response = simulate(block, still(0.0002), free_motion_s=20.0,
                        initial_rotation=0.8 * block.alpha)
    peaks = np.concatenate(([0.8 * block.alpha], peaks_between_impacts(response, 6)))
    energy = np.cos(block.alpha - peaks) - np.cos(block.alpha)
    np.testing.assert_allclose(energy[1:] / energy[:-1], block.r, rtol=1e-4)


def test_cycle_durations_match_housner_period_without_damping():
    """With r = 1 free rocking is periodic; for a slender block its full cycle is Eq. 8.1."""
    block = RigidBlock(2.0, math.radians(3), r=1.0)
    response = simulate(block, still(0.001), free_motion_s=30.0,
                        initial_rotation=0.4 * block.alpha)
    durations = response.cycle_durations
    assert durations.size >= 5
    np.testing.assert_allclose(durations, housner_period(0.4, block.p), rtol=0.005)


@pytest.fixture(scope="module")
def pulse_anchor():
    """SPEC §2: p = 2 rad/s, α = 15°, one-cosine T_p = 2 s, 8 s of free motion after it."""
    block = RigidBlock(2.0, math.radians(15))
    return {a: simulate(block, one_pulse("cosine", a, 2.0), free_motion_s=8.0)
            for a in (0.310, 0.315, 0.316)}


def test_pulse_anchor_sensitivity(pulse_anchor):
    survives, near, falls = pulse_anchor[0.310], pulse_anchor[0.315], pulse_anchor[0.316]
    assert not survives.overturned
    assert 0.3 <= survives.peak_rotation_after_excitation / survives.block.alpha <= 0.4
    assert not near.overturned
    assert near.peak_rotation_after_excitation / near.block.alpha > 0.75
    assert falls.overturned and 2.0 < falls.overturn_time < 10.0


def test_pulse_anchor_against_reference(pulse_anchor):
    for amplitude, response in pulse_anchor.items():
        ref = simulate_reference(response.block, one_pulse("cosine", amplitude, 2.0), 8.0)
        assert ref["overturned"] == response.overturned
        assert ref["peak_rotation"] == pytest.approx(response.peak_rotation, rel=2e-3)


def test_history_is_complete_and_bounded(seed_suite):
    motion = seed_suite.get("pacoima_dam_1971").motion
    for size, alpha in ((5.65, 15), (7.3, 15), (3.95, 15), (2.0, 20)):
        response = simulate(RigidBlock.from_size(size, math.radians(alpha)), motion)
        assert response.time.size == motion.acceleration.size + 1000
        valid = np.isfinite(response.theta)
        if response.overturned:
            assert not valid[-1] and valid[0]
        else:
            assert valid.all() and np.isfinite(response.omega).all()
            assert np.abs(response.theta).max() <= response.peak_rotation * (1 + 1e-12)
            assert np.abs(response.omega).max() <= response.peak_angular_velocity * (1 + 1e-12)


def test_sign_of_ground_motion_flips_rotation():
    block = RigidBlock(2.5, math.radians(12))
    pulse = one_pulse("sine", 0.4, 1.5)
    flipped = GroundMotion("neg", -pulse.acceleration, pulse.dt)
    a = simulate(block, GroundMotion("pos", pulse.acceleration, pulse.dt))
    b = simulate(block, flipped)
    np.testing.assert_allclose(a.theta, -b.theta, atol=1e-12)
    # a positive ground acceleration starts a negative rotation
    first = np.flatnonzero(a.theta != 0)[0]
    assert a.theta[first] < 0


def test_dimensionless_similarity_of_pulse_response():
    """Same α, a_p/(g tan α) and ω_p/p ⇒ same θ as a function of p·t."""
    alpha = math.radians(14)
    small = simulate(RigidBlock(4.0, alpha), one_pulse("cosine", 0.35, 1.0), free_motion_s=5.0)
    large = simulate(RigidBlock(2.0, alpha), one_pulse("cosine", 0.35, 2.0), free_motion_s=10.0)
    tau = np.linspace(0.0, 30.0, 400)
    np.testing.assert_allclose(np.interp(tau, small.time * 4.0, small.theta),
                               np.interp(tau, large.time * 2.0, large.theta), atol=2e-6)
    assert small.peak_rotation == pytest.approx(large.peak_rotation, rel=1e-6)


def test_no_uplift_below_g_tan_alpha():
    pulse = one_pulse("cosine", 0.3, 1.0)  # atan(0.3) = 16.70°
    calm = simulate(RigidBlock(2.0, math.radians(16.8)), pulse)
    assert not calm.uplifted and calm.peak_rotation == 0.0 and calm.n_impacts == 0
    assert simulate(RigidBlock(2.0, math.radians(16.6)), pulse).uplifted


def test_real_record_against_reference(seed_suite):
    motion = seed_suite.get("pacoima_dam_1971").motion
    for size, alpha in ((3.5, 20), (2.5, 20), (5.65, 15)):
        block = RigidBlock.from_size(size, math.radians(alpha))
        ours, ref = simulate(block, motion), simulate_reference(block, motion)
        assert ours.overturned == ref["overturned"]
        # impacts agree one to one until the response decays into a chatter of small rocks, where
        # differences of 1e-8 s grow by impact (55 against 57 impacts for the 3.5 s block with
        # scipy 1.17, 55 each with earlier releases): the count there is not a fact to test
        np.testing.assert_allclose(ours.impact_times[:15], ref["impact_times"][:15], atol=1e-4)
        assert ours.peak_rotation == pytest.approx(ref["peak_rotation"], rel=1e-4)


def test_halving_the_step_changes_surviving_peaks_by_less_than_0_1_percent(seed_suite):
    sizes = np.arange(0.5, 8.01, 0.25)
    alphas = np.radians([10, 15, 20])
    for record in ("rinaldi_1994", "sylmar_1994"):
        motion = seed_suite.get(record).motion
        base = rocking_spectrum(motion, sizes, alphas)
        fine = rocking_spectrum(motion, sizes, alphas, options=RockingOptions(steps_per_radian=80.0))
        survive = ~base.overturned & ~fine.overturned & base.uplifted
        assert survive.sum() > 20
        np.testing.assert_allclose(base.theta_peak[survive], fine.theta_peak[survive], rtol=1e-3)


def test_spectrum_threads_agree_and_grid_shape():
    pulse = one_pulse("cosine", 0.5, 1.0)
    one = rocking_spectrum(pulse, [0.5, 1.0, 2.0, 4.0], np.radians([10, 20]), jobs=1)
    two = rocking_spectrum(pulse, [0.5, 1.0, 2.0, 4.0], np.radians([10, 20]), jobs=2)
    assert one.theta_peak.shape == (2, 4)
    np.testing.assert_array_equal(one.theta_peak, two.theta_peak)
    single = simulate(RigidBlock.from_size(2.0, math.radians(20)), pulse)
    assert one.theta_peak[1, 2] == single.peak_rotation


def test_block_peaks_are_the_single_simulations_field_by_field():
    """Each field of ``rocking_blocks`` is the same-named number of ``simulate`` for that block
    (a block that overturns, one that rocks and rests, one that never uplifts)."""
    pulse = one_pulse("cosine", 0.3, 2.0)
    sizes, alphas = [2.0, math.pi, 3.0], np.radians([10, 15, 30])
    peaks = rocking_blocks(pulse, sizes, alphas, reactions=True, jobs=2)
    singles = [simulate(RigidBlock.from_size(size, alpha), pulse)
               for size, alpha in zip(sizes, alphas)]
    assert [s.overturned for s in singles] == [True, False, False]
    assert [s.uplifted for s in singles] == [True, True, False]
    for name, single_name in [("theta_peak", "peak_rotation"),
                              ("omega_peak", "peak_angular_velocity"),
                              ("theta_after", "peak_rotation_after_excitation"),
                              ("overturned", "overturned"), ("uplifted", "uplifted"),
                              ("required_friction", "required_friction"),
                              ("min_vertical_reaction", "min_vertical_reaction")]:
        np.testing.assert_array_equal(getattr(peaks, name),
                                      [getattr(s, single_name) for s in singles], err_msg=name)


@pytest.mark.parametrize("reactions", [False, True])
def test_a_scale_per_block_is_the_scaled_motion_bit_for_bit(seed_suite, reactions):
    """Blocks solved at many levels in one call (``scale``) have every peak of the same
    blocks under ``motion.scaled(level)``, one call per level: a record and an analytic pulse
    (its amplitude scaled), levels where the blocks rest, rock and overturn."""
    sizes, alphas = np.array([0.6, 1.5, 3.0, 6.0]), np.radians([8, 12, 16, 25])
    levels = np.geomspace(0.2, 5.0, 7)
    for motion in (seed_suite.get("pacoima_dam_1971").motion, one_pulse("cosine", 0.25, 1.5)):
        one_call = rocking_blocks(motion, np.tile(sizes, levels.size),
                                  np.tile(alphas, levels.size), jobs=2, reactions=reactions,
                                  scale=np.repeat(levels, sizes.size))
        by_level = [rocking_blocks(motion.scaled(float(level)), sizes, alphas, jobs=2,
                                   reactions=reactions) for level in levels]
        for name in one_call._fields:
            np.testing.assert_array_equal(
                getattr(one_call, name), np.concatenate([getattr(p, name) for p in by_level]),
                err_msg=name)
        assert 0 < one_call.overturned.sum() < one_call.uplifted.sum() < levels.size * sizes.size


def test_peaks_stop_early_in_the_free_motion_with_the_whole_free_motions_peaks():
    """Without reactions the peaks stop in the free motion after its first turning point and
    impact (the energy only falls after them); every peak is still bit for bit the one of
    ``simulate``, which runs the whole free motion, for blocks still rocking when a sine of
    0.3 g stops mid-cycle (and one that overturns)."""
    time_s = np.arange(0.0, 3.0, 0.005)
    motion = GroundMotion("sine", 0.3 * G * np.sin(2 * np.pi * time_s / 0.8), 0.005)
    sizes, alphas = np.array([2.5, 3.0, 2.0, 4.0, 3.0, 0.8]), np.radians([12, 12, 14, 15, 10, 8])
    peaks = rocking_blocks(motion, sizes, alphas, jobs=2)
    singles = [simulate(RigidBlock.from_size(size, alpha), motion)
               for size, alpha in zip(sizes, alphas)]
    end_s = (motion.acceleration.size - 1) * motion.dt
    assert [s.overturned for s in singles] == [False] * 5 + [True]
    assert all(np.sum(s.impact_times > end_s) > 30 for s in singles[:5])
    for name, single_name in [("theta_peak", "peak_rotation"),
                              ("omega_peak", "peak_angular_velocity"),
                              ("theta_after", "peak_rotation_after_excitation"),
                              ("overturned", "overturned"), ("uplifted", "uplifted")]:
        np.testing.assert_array_equal(getattr(peaks, name),
                                      [getattr(s, single_name) for s in singles], err_msg=name)


@pytest.mark.parametrize("case", ["pulse-rocks", "pulse-overturns", "record"])
def test_interpreted_and_compiled_kernels_agree(case, seed_suite, monkeypatch):
    """A short ``simulate`` runs the kernel in the interpreter; the compiled code must give the
    same response to rounding, including impacts, turning points and overturning."""
    from audit.physics.rocking import history, kernel
    from audit.physics.tiers import interpreted
    motion, size_s, alpha_deg = {
        "pulse-rocks": (one_pulse("cosine", 0.3, 2.0), math.pi, 15),
        "pulse-overturns": (one_pulse("cosine", 0.2, 2.0), 2.0, 10),
        "record": (seed_suite.get("pacoima_dam_1971").motion, 3.5, 20)}[case]
    block = RigidBlock.from_size(size_s, math.radians(alpha_deg))
    monkeypatch.setattr(history, "tiered", lambda run, n: interpreted(run))
    slow = simulate(block, motion)
    monkeypatch.setattr(history, "tiered", lambda run, n: run)
    compiled = simulate(block, motion)
    assert interpreted(kernel._simulate) is not kernel._simulate
    assert slow.overturned == compiled.overturned == (case == "pulse-overturns")
    assert slow.n_impacts == compiled.n_impacts
    assert slow.turning_times.size == compiled.turning_times.size > 0
    for name in ("theta", "omega", "impact_times", "omega_before_impact", "omega_after_impact",
                 "turning_times", "turning_rotations"):
        np.testing.assert_allclose(getattr(slow, name), getattr(compiled, name),
                                   rtol=1e-12, atol=1e-15, err_msg=name)
    assert slow.peak_rotation == pytest.approx(compiled.peak_rotation, rel=1e-12)
    assert slow.overturn_time == pytest.approx(compiled.overturn_time, rel=1e-12, nan_ok=True)


def test_tiered_kernels_turn_compiled_past_the_budget(monkeypatch):
    """Interpreted while the process's interpreted runs fit the budget and nothing is compiled;
    compiled after that."""
    from audit.physics import oscillator, tiers
    monkeypatch.setattr(tiers, "_interpreted_s", 0.0)
    monkeypatch.setattr(tiers, "_any_compiled", lambda: False)
    budget = tiers.INTERPRETED_BUDGET_S
    slow = tiers.interpreted(oscillator._history)
    assert tiers.tiered(oscillator._history, 0.75 * budget) is slow
    assert tiers.tiered(oscillator._history, 0.5 * budget) is oscillator._history
    assert tiers.tiered(oscillator._history, 0.25 * budget) is slow
    monkeypatch.setattr(tiers, "_any_compiled", lambda: True)
    monkeypatch.setattr(tiers, "_interpreted_s", 0.0)
    assert tiers.tiered(oscillator._history, 0.0) is oscillator._history


def test_a_batch_beyond_the_budget_runs_compiled_from_its_first_run(monkeypatch):
    """``expect`` judges a batch as a whole: one within the budget leaves each run counted as
    it comes; one beyond it sends every later run, however short, to the compiled kernel."""
    from audit.physics import oscillator, tiers
    monkeypatch.setattr(tiers, "_interpreted_s", 0.0)
    monkeypatch.setattr(tiers, "_any_compiled", lambda: False)
    budget = tiers.INTERPRETED_BUDGET_S
    slow = tiers.interpreted(oscillator._history)
    tiers.expect(0.5 * budget)
    assert tiers.tiered(oscillator._history, 0.5 * budget) is slow
    tiers.expect(0.6 * budget)
    assert tiers.tiered(oscillator._history, 1e-9) is oscillator._history


def test_blocks_the_record_cannot_lift_are_at_rest_as_simulate_has_them(seed_suite):
    """A block whose g tan α is at or above the scaled record's peak |üg| is answered without
    the kernel (θ = 0, at rest): every field is ``simulate``'s for it, bit for bit, on both
    sides of the threshold (just below it the block uplifts and is solved)."""
    motion = seed_suite.get("pacoima_dam_1971").motion
    alpha = math.radians(15.0)
    # the record scaled so its peak is 2, 1.001, 1, 0.999 and 0.5 × g tan α
    scales = (G * math.tan(alpha) / float(np.max(np.abs(motion.acceleration)))
              * np.array([2.0, 1.001, 1.0, 0.999, 0.5]))
    sizes, alphas = np.full(scales.size, 2.0), np.full(scales.size, alpha)
    peaks = rocking_blocks(motion, sizes, alphas, jobs=2, scale=scales)
    singles = [simulate(RigidBlock.from_size(2.0, alpha), motion.scaled(float(scale)))
               for scale in scales]
    assert [s.uplifted for s in singles] == [True, True, False, False, False]
    for name, single_name in [("theta_peak", "peak_rotation"),
                              ("omega_peak", "peak_angular_velocity"),
                              ("theta_after", "peak_rotation_after_excitation"),
                              ("overturned", "overturned"), ("uplifted", "uplifted")]:
        np.testing.assert_array_equal(getattr(peaks, name),
                                      [getattr(s, single_name) for s in singles], err_msg=name)
    assert np.all(np.isnan(peaks.required_friction[2:]))  # no reactions asked for


@pytest.mark.parametrize("function", [rocking_blocks, rocking_spectrum])
def test_the_many_block_solvers_take_at_most_eight_parameters(function):
    """Gravity, free motion, the step, the rest rule and the vertical component travel
    together as :class:`RockingOptions`."""
    import inspect
    assert len(inspect.signature(function).parameters) <= 8
