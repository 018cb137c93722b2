"""Floor motions of linear buildings (audit.physics.building) against independent facts: a
state-space solution of the whole MDOF shear building, closed forms, and the beam limits."""

import math

import numpy as np
import pytest
from scipy import signal
from scipy.linalg import eigh

from audit.physics.building.continuum import (ContinuumBuilding, eigenvalues, mode_shape,
                                              participation_factor)
from audit.physics.building.floor import Building, Floor
from audit.physics.building.floor_motion import floor_acceleration, floor_modes
from audit.physics.building.shear import ShearBuilding
from audit.physics.oscillator import oscillator_history
from records import GroundMotion


def _state_space_floor(acc, dt, storeys, period_s, damping, z_over_h):
    """Absolute acceleration of floor z/H of the uniform shear building, by scipy.signal.lsim
    on the full system M ü + C u̇ + K u = −M 1 üg (u relative to the ground), with C the
    classical damping Φ⁻ᵀ diag(2ζω_n) Φ⁻¹ built from eigh's modes, and the input linear between
    samples (lsim's first-order hold) — nothing shared with the code under test."""
    n = storeys
    k_matrix = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    k_matrix[-1, -1] = 1.0
    omega2, shapes = eigh(k_matrix)  # m = 1, k = 1: scale K so that ω_1 = 2π/T1
    k_matrix *= (2.0 * np.pi / period_s) ** 2 / omega2[0]
    omega2, shapes = eigh(k_matrix)
    shapes = shapes / np.sqrt(np.sum(shapes ** 2, axis=0))  # mass-orthonormal (M = I)
    c_matrix = shapes @ np.diag(2.0 * damping * np.sqrt(omega2)) @ shapes.T
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-k_matrix, -c_matrix]])
    b = np.concatenate((np.zeros(n), -np.ones(n)))[:, None]
    # absolute acceleration = ü + üg = −K u − C u̇
    c_out = np.hstack((-k_matrix, -c_matrix))
    t = np.arange(acc.size) * dt
    _, y, _ = signal.lsim((a, b, c_out, np.zeros((n, 1))), acc, t, interp=True)
    j = z_over_h * n
    below = int(math.floor(j))
    if below == j:
        return y[:, below - 1]
    return (below + 1 - j) * (y[:, below - 1] if below else 0.0) + (j - below) * y[:, below]


@pytest.fixture(scope="module")
def nis000():
    from records import p695_suite
    return p695_suite("p695-far-field").get("rsn1111_nis000").motion


@pytest.mark.parametrize("z_over_h", [1.0, 0.5])
def test_shear_building_floor_equals_state_space(nis000, z_over_h):
    floor = Floor.parse(Floor(z_over_h, Building(1.0, "shear:10", 0.05)))
    mine = floor_acceleration(nis000.acceleration, nis000.dt, floor)[:nis000.acceleration.size]
    reference = _state_space_floor(nis000.acceleration, nis000.dt, 10, 1.0, 0.05, z_over_h)
    assert np.max(np.abs(mine - reference)) <= 1e-3 * np.max(np.abs(reference))


def test_shear_building_between_floors_equals_state_space():
    rng = np.random.default_rng(3)
    acc, dt = rng.normal(size=1500), 0.01
    floor = Floor.parse(Floor(0.43, Building(0.7, "shear:5")))
    mine = floor_acceleration(acc, dt, floor)[:acc.size]
    reference = _state_space_floor(acc, dt, 5, 0.7, 0.05, 0.43)
    assert np.max(np.abs(mine - reference)) <= 1e-3 * np.max(np.abs(reference))


def test_one_storey_is_one_oscillator():
    # N = 1: the roof is an oscillator of period T1; its absolute acceleration is
    # −2ζωu̇ − ω²u, and u comes from the spectra's own history routine
    rng = np.random.default_rng(1)
    acc, dt = rng.normal(size=800), 0.02
    floor = Floor.parse(Floor(1.0, Building(0.6, "shear:1", 0.03)))
    mine = floor_acceleration(acc, dt, floor)[:acc.size]
    _, u = oscillator_history(GroundMotion("x", acc, dt), 0.6, 0.03)
    omega = 2 * np.pi / 0.6
    v = np.gradient(u, dt, edge_order=2)  # a second, coarser route to u̇: compare loosely
    absolute = -2 * 0.03 * omega * v - omega ** 2 * u
    assert np.max(np.abs(mine - absolute)) <= 2e-2 * np.max(np.abs(absolute))
    # the displacement route alone, exactly: ü_abs + 2ζωu̇ = −ω²u is what the ζ = 0 limit gives
    undamped = Floor.parse(Floor(1.0, Building(0.6, "shear:1", 1e-9)))
    _, u0 = oscillator_history(GroundMotion("x", acc, dt), 0.6, 1e-9)
    np.testing.assert_allclose(floor_acceleration(acc, dt, undamped)[:acc.size],
                               -omega ** 2 * u0, atol=1e-6 * np.max(np.abs(omega ** 2 * u0)))


@pytest.mark.parametrize("model", ["shear:10", "continuum:10", "continuum:0"])
def test_very_stiff_building_returns_the_ground_motion(model):
    rng = np.random.default_rng(2)
    acc, dt = rng.normal(size=500), 0.01
    floor = Floor.parse(Floor(1.0, Building(1e-4, model)))
    out = floor_acceleration(acc, dt, floor)
    # from the first step on: at t = 0 a building at rest has no acceleration whatever üg(0) is
    np.testing.assert_allclose(out[1:acc.size], acc[1:], atol=1e-6)


@pytest.mark.parametrize("storeys", [1, 3, 10])
def test_shear_modes_sum_to_one_and_match_eigh(storeys):
    building = ShearBuilding(storeys)
    k_matrix = 2.0 * np.eye(storeys) - np.eye(storeys, k=1) - np.eye(storeys, k=-1)
    k_matrix[-1, -1] = 1.0
    omega2, _ = eigh(k_matrix)
    np.testing.assert_allclose(building.period_ratios(), np.sqrt(omega2[0] / omega2), rtol=1e-12)
    at_floors = [np.sum(building.participation() * building.shapes_at(j / storeys))
                 for j in range(1, storeys + 1)]
    np.testing.assert_allclose(at_floors, 1.0, rtol=1e-12)


def test_shear_modes_between_floors_sum_to_the_interpolated_one():
    building = ShearBuilding(4)
    # between the ground (φ = 0) and floor 1, the straight line: Σ Γφ = 4·z/H
    assert np.sum(building.participation() * building.shapes_at(0.1)) == pytest.approx(0.4)
    assert np.sum(building.participation() * building.shapes_at(0.6)) == pytest.approx(1.0)


def test_continuum_limits_are_the_textbook_beams():
    # α0 → 0: flexural cantilever, 1 + cos γ cosh γ = 0: γ = 1.8751, 4.6941, 7.8548
    np.testing.assert_allclose(eigenvalues(0.0, 3), [1.875104, 4.694091, 7.854757], atol=1e-6)
    flexural = ContinuumBuilding(0.0)
    np.testing.assert_allclose(flexural.period_ratios(eigenvalues(0.0, 3)),
                               [1, (1.875104 / 4.694091) ** 2, (1.875104 / 7.854757) ** 2],
                               rtol=1e-5)
    # the cantilever's first mode normalised to 1 at the tip has Γ = 1.566 (roof Γφ)
    g1 = eigenvalues(0.0, 1)[0]
    assert participation_factor(g1, 0.0) * mode_shape(g1, 0.0, 1.0) == pytest.approx(1.566, abs=1e-3)
    # α0 → ∞: shear cantilever, T_i/T1 = 1/(2i − 1), Γ_i φ_i(1) = 4(−1)^{i+1}/((2i − 1)π)
    alpha0 = 1000.0
    gammas = eigenvalues(alpha0, 3)
    np.testing.assert_allclose(ContinuumBuilding(alpha0).period_ratios(gammas), [1, 1 / 3, 1 / 5],
                               rtol=2e-4)
    roof = [participation_factor(g, alpha0) * mode_shape(g, alpha0, 1.0) for g in gammas]
    np.testing.assert_allclose(roof, [4 / np.pi, -4 / (3 * np.pi), 4 / (5 * np.pi)], rtol=2e-3)


def _finite_difference_modes(alpha0, points=400):
    """Periods ratios and roof Γφ of the beam φ'''' − α0² φ'' = λ φ by a Rayleigh–Ritz
    solution on a polynomial-free basis: clamped-free finite elements (Hermite beams with a
    geometric shear stiffness), independent of the characteristic equation."""
    n = points
    h = 1.0 / n
    dof = 2 * (n + 1)
    k_global = np.zeros((dof, dof))
    m_global = np.zeros((dof, dof))
    kb = np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                   [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]]) / h ** 3
    ks = np.array([[36, 3 * h, -36, 3 * h], [3 * h, 4 * h * h, -3 * h, -h * h],
                   [-36, -3 * h, 36, -3 * h], [3 * h, -h * h, -3 * h, 4 * h * h]]) / (30 * h)
    me = h / 420 * np.array([[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                             [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    for e in range(n):
        idx = slice(2 * e, 2 * e + 4)
        k_global[idx, idx] += kb + alpha0 ** 2 * ks
        m_global[idx, idx] += me
    free = slice(2, dof)
    lam, vec = eigh(k_global[free, free], m_global[free, free])
    influence = np.zeros(dof - 2)
    influence[0::2] = 1.0  # rigid translation: displacements 1, rotations 0
    gammas = (vec.T @ m_global[free, free] @ influence) / np.einsum(
        "ij,ij->j", vec, m_global[free, free] @ vec)
    roof = gammas * vec[-2]
    return np.sqrt(lam[0] / lam), roof


@pytest.mark.parametrize("alpha0", [0.5, 5.0, 10.0, 20.0])
def test_continuum_modes_against_finite_elements(alpha0):
    ratios, roof = _finite_difference_modes(alpha0)
    gammas = eigenvalues(alpha0, 4)
    mine = ContinuumBuilding(alpha0).period_ratios(gammas)
    np.testing.assert_allclose(mine, ratios[:4], rtol=1e-4)
    mine_roof = [participation_factor(g, alpha0) * mode_shape(g, alpha0, 1.0) for g in gammas]
    np.testing.assert_allclose(mine_roof, roof[:4], rtol=1e-4)


@pytest.mark.parametrize("alpha0", [0.0, 10.0, 1000.0])
def test_continuum_modes_sum_towards_one(alpha0):
    floor = Floor.parse(Floor(1.0, Building(1.0, f"continuum:{alpha0}")))
    periods, weights = floor_modes(floor, 0.0005)
    coarse_periods, coarse = floor_modes(floor, 0.005)
    # every mode down to the Nyquist period 2·dt, and no other
    assert periods[-1] >= 0.001 and coarse_periods[-1] >= 0.01
    assert periods.size > coarse_periods.size >= 6
    # the left-out modes, carried rigidly, shrink as the sampling resolves more of them
    assert abs(1.0 - weights.sum()) < min(0.04, abs(1.0 - coarse.sum()))
