"""Every fixed point of Priestley's map and the cycles of its iteration (issue 9, item 1).

Synthetic maps with known roots and cycles check the scan, the stability and the cycle test;
on the real Pacoima Dam record the tool's fixed points and cycle are checked against an
independent path: Sd(T) computed at exactly the periods asked for with scipy's exact
first-order-hold discretisation and ``lfilter`` (not the tool's recurrence nor its period
table), Eq. 8.1 written out again, roots bracketed on a grid and polished by ``brentq``.
"""

import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import signal
from scipy.optimize import brentq

from procedures.context import RecordContext
from audit.physics.block import coefficient_of_restitution, radius_from_p
from audit.physics.damping import housner_rotation_ratio
from procedures import iterate_rotation
from procedures.rotation_map import ROOT_TOLERANCE_RATIO, fixed_points
from procedures.priestley_1978 import PriestleyEvisonCarr1978

ALPHA = math.radians(10)


def spectrum_for_map(rotation_map, p, alpha=ALPHA):
    """Sd(T) [m] that makes F(θ)/α = ``rotation_map``(θ/α) for one block of p [rad/s]."""
    scale = float(radius_from_p(p)) * math.cos(alpha) * alpha
    return lambda period: rotation_map(housner_rotation_ratio(period, p)) * scale


def test_roots_and_stability_of_a_cubic_map():
    """F(x) = x + 5(x − 0.2)(x − 0.3)(x − 0.6): roots 0.2, 0.3, 0.6 with F' = 1.2, 0.85, 1.6."""
    found = fixed_points(spectrum_for_map(lambda x: x + 5 * (x - 0.2) * (x - 0.3) * (x - 0.6), 2.0),
                         np.array([2.0]), ALPHA)
    # bisected to the stated tolerance (the roots are exact in the map's arithmetic)
    np.testing.assert_allclose(found.ratio, [0.2, 0.3, 0.6], rtol=0, atol=ROOT_TOLERANCE_RATIO)
    np.testing.assert_allclose(found.slope, [1.2, 0.85, 1.6], atol=1e-5)
    assert list(found.text(1)) == ["0.2000u;0.3000s;0.6000u"]


def test_constant_spectrum_has_one_attracting_fixed_point_per_block():
    """Sd = D: F = D/(R cos α) everywhere, so θ*/α = D/(R cos α α), F' = 0 (Eq. 8.2)."""
    p = np.array([0.5, 1.0, 2.0, 6.0])
    depth = 0.05
    found = fixed_points(lambda period: np.full(np.shape(period), depth), p, ALPHA)
    expected = depth / (radius_from_p(p) * math.cos(ALPHA) * ALPHA)
    assert expected[-1] > 1  # the smallest block's only root would lie beyond α: none
    assert list(found.block) == [0, 1, 2]
    np.testing.assert_allclose(found.ratio, expected[:3], rtol=0, atol=ROOT_TOLERANCE_RATIO)
    assert list(found.text(4)) == [f"{x:.4f}s" for x in expected[:3]] + [""]


def test_a_three_cycle_is_named():
    # 0.1 → 0.7 → 0.3 → 0.5 → 0.7 → …
    def steps(x):
        return np.select([x < 0.2, x < 0.4, x < 0.6], [0.7, 0.5, 0.7], 0.3)

    _, outcome, iterations, detail, cycle = iterate_rotation(spectrum_for_map(steps, 2.0),
                                                              np.array([2.0]), ALPHA)
    assert outcome[0] == "not-converged" and cycle[0] == "0.3000;0.5000;0.7000"
    assert iterations[0] == 6 and "3-cycle between θ/α = 0.3000 and 0.7000" in detail[0]


def test_a_slowly_settling_two_cycle_is_found():
    """Slope 0.99 on both branches: the 2-cycle (0.3, 0.8) attracts with F∘F' = 0.98.

    Every other iterate then differs by 0.02·e, e the distance to the cycle, so an absolute
    test |Δ| ≤ 1e-12 needs ~2200 iterations (beyond the cap); one relative to the spread
    (0.5) settles after ~900."""
    def two_branches(x):
        return np.where(x < 0.5, 0.8 + 0.99 * (x - 0.3), 0.3 + 0.99 * (x - 0.8))

    _, outcome, iterations, detail, cycle = iterate_rotation(spectrum_for_map(two_branches, 2.0),
                                                              np.array([2.0]), ALPHA)
    assert outcome[0] == "not-converged" and cycle[0] == "0.3000;0.8000"
    assert 500 < iterations[0] < 2000 and "2-cycle" in detail[0]


def test_chaos_is_reported_as_neither_settled_nor_cycling():
    """The logistic map 3.9 x (1 − x) is chaotic: no fixed point or cycle ever settles."""
    _, outcome, iterations, detail, cycle = iterate_rotation(
        spectrum_for_map(lambda x: 3.9 * x * (1 - x), 2.0), np.array([2.0]), ALPHA,
        max_iterations=400)
    assert outcome[0] == "not-converged" and cycle[0] == "" and iterations[0] == 400
    assert detail[0].startswith("no settled value or cycle after 400 iterations")


# --- the real record: Pacoima Dam, α = 10°, Priestley et al. (1978) --------------------------

def independent_map(motion, size_s, alpha=ALPHA, g=9.81, free_motion_s=10.0):
    """θ/α ↦ F(θ)/α of Eqs. 8.1–8.2 with Sd from scipy at exactly T(θ).

    lfilter starts the record's linear interpolation from rest one sample before t = 0 (the
    tool starts at rest at t = 0); the difference in Sd is below 1e-4 relative here."""
    beta = -0.34 * math.log((1 - 1.5 * math.sin(alpha) ** 2) ** 2)  # Eqs. 4.8, 7.10
    p = 2 * math.pi / size_s
    radius = 3 * g / (4 * p ** 2)
    ground = np.concatenate((motion.acceleration,
                             np.zeros(int(round(free_motion_s / motion.dt)))))

    @functools.cache
    def sd(period):
        w = 2 * math.pi / period
        system = signal.cont2discrete(
            (np.array([[0.0, 1.0], [-w * w, -2 * beta * w]]), np.array([[0.0], [-1.0]]),
             np.array([[1.0, 0.0]]), np.zeros((1, 1))), motion.dt, method="foh")
        b, a = signal.ss2tf(*system[:4])
        return float(np.max(np.abs(signal.lfilter(b[0], a, ground))))

    return lambda x: sd(4 / p * math.acosh(1 / (1 - x))) / (radius * math.cos(alpha) * alpha)


def independent_fixed_points(rotation_map, step=0.005):
    """Roots of F(x) − x on [0.01, 0.99] with their slopes F'(x*) (central difference)."""
    grid = np.arange(0.01, 0.99, step)
    excess = np.array([rotation_map(x) - x for x in grid])
    roots = []
    for k in np.flatnonzero(np.sign(excess[:-1]) != np.sign(excess[1:])):
        root = brentq(lambda x: rotation_map(x) - x, grid[k], grid[k + 1], xtol=1e-9)
        slope = (rotation_map(root + 1e-4) - rotation_map(root - 1e-4)) / 2e-4
        roots.append((root, abs(slope) < 1))
    return roots


def parse(text):
    """``0.2397s;0.2551u`` → [(0.2397, True), (0.2551, False)]."""
    return [(float(item[:-1]), item[-1] == "s") for item in text.split(";")] if text else []


@pytest.fixture(scope="module")
def pacoima(seed_suite):
    entry = seed_suite.get("pacoima_dam_1971")
    context = RecordContext(entry, 10.0)
    sizes = np.array([6.0, 8.0])
    estimate = PriestleyEvisonCarr1978().evaluate(
        entry, 2 * np.pi / sizes, ALPHA, float(coefficient_of_restitution(ALPHA)), context).estimate
    return entry.motion, estimate


def test_pacoima_8s_has_three_fixed_points(pacoima):
    """Issue 9: 2π/p = 8 s, α = 10°: θ/α ≈ 0.240 (s), 0.255 (u), 0.482 (s)."""
    motion, estimate = pacoima
    expected = independent_fixed_points(independent_map(motion, 8.0))
    assert [stable for _, stable in expected] == [True, False, True]
    np.testing.assert_allclose([x for x, _ in expected], [0.240, 0.255, 0.482], atol=0.005)
    tool = parse(estimate.fixed_points[1])
    assert [stable for _, stable in tool] == [True, False, True]
    np.testing.assert_allclose([x for x, _ in tool], [x for x, _ in expected], atol=0.005)
    # the literal iteration from θ₀/α = 0.1 stops at the lowest attracting one
    assert estimate.outcome[1] == "converged" and estimate.cycle[1] == ""
    assert estimate.theta[1] / ALPHA == pytest.approx(expected[0][0], abs=0.005)


def test_pacoima_6s_settles_in_a_two_cycle_around_a_repelling_fixed_point(pacoima):
    """Issue 9: 2π/p = 6 s, α = 10°: θ/α alternates 0.5753 ↔ 0.8854; θ*/α ≈ 0.737 repels."""
    motion, estimate = pacoima
    rotation_map = independent_map(motion, 6.0)
    expected = independent_fixed_points(rotation_map)
    assert len(expected) == 1 and not expected[0][1]
    assert expected[0][0] == pytest.approx(0.737, abs=0.005)
    x = 0.1
    for _ in range(300):
        x = rotation_map(x)
    cycle = sorted([x, rotation_map(x)])
    assert rotation_map(rotation_map(cycle[0])) == pytest.approx(cycle[0], abs=1e-6)
    np.testing.assert_allclose(cycle, [0.5753, 0.8854], atol=0.005)
    tool_points = parse(estimate.fixed_points[0])
    assert len(tool_points) == 1 and not tool_points[0][1]
    assert tool_points[0][0] == pytest.approx(expected[0][0], abs=0.005)
    assert estimate.outcome[0] == "not-converged" and np.isnan(estimate.theta[0])
    np.testing.assert_allclose([float(v) for v in estimate.cycle[0].split(";")], cycle, atol=0.005)
    assert "2-cycle" in estimate.detail[0]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.lists(st.one_of(st.floats(0, 1), st.just(float("nan"))), min_size=16,
                         max_size=16), min_size=1, max_size=6),
       st.integers(2, 8))
def test_cycle_precheck_against_array_operations(rows, length):
    """The compiled pre-check of settled cycles against the same test written with array
    operations: newest iterate within CYCLE_TOLERANCE_RATIO × window spread of the one L
    before, NaN left out of the spread."""
    from procedures.iteration import CYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH
    from procedures.iteration_kernels import may_repeat
    recent = np.array(rows, dtype=float)
    recent[0, -1] = recent[0, -1 - length]  # one row that repeats exactly (if not NaN)
    sizes = np.arange(2, MAX_CYCLE_LENGTH + 1)
    gaps = np.abs(recent[:, -1:] - recent[:, -1 - sizes])
    spread = np.fmax.reduce(recent, axis=1) - np.fmin.reduce(recent, axis=1)
    with np.errstate(invalid="ignore"):
        expected = np.any(gaps <= CYCLE_TOLERANCE_RATIO * spread[:, None], axis=1)
    assert [may_repeat(row, CYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH)
            for row in recent] == expected.tolist()
