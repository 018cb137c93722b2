"""The Miranda & Taghavi (2005) continuum building: a flexural cantilever and a shear cantilever
of uniform stiffness joined by axially rigid links (Miranda & Taghavi, *Approximate floor
acceleration demands in multistory buildings. I: Formulation*, J. Struct. Eng. 131(2); the model
of Miranda 1999 and Miranda & Reyes 2002).

With x = z/H and the lateral stiffness ratio α0 = H·√(GA/EI) (0: a pure flexural beam, wall
buildings ≈ 0–2; ∞: a pure shear beam, moment frames ≈ 5–20), the mode shapes solve
φ'''' − α0² φ'' = (ρH⁴ω²/EI) φ with φ(0) = φ'(0) = 0 (fixed base), φ''(1) = 0 (no moment) and
φ'''(1) − α0² φ'(1) = 0 (no shear) at the roof:

    φ_i(x) = sin γ_i x − (γ_i/β_i) sinh β_i x + η_i (cosh β_i x − cos γ_i x),
    β_i² = α0² + γ_i²,  η_i = (γ_i² sin γ_i + γ_i β_i sinh β_i)/(γ_i² cos γ_i + β_i² cosh β_i),

γ_i the i-th positive root of the characteristic equation

    2 + [2 + α0⁴/(γ² β²)] cos γ cosh β + [α0²/(γ β)] sin γ sinh β = 0,

and ω_i ∝ γ_i β_i, so T_i/T_1 = γ_1 β_1/(γ_i β_i). Γ_i = ∫φ_i dx / ∫φ_i² dx (uniform mass).
These equations were not read from the paper (no copy was at hand): they were derived here from
the beam equation and its four boundary conditions, and checked against the two limits whose
modes are textbook closed forms (α0 → 0: the flexural cantilever, 1 + cos γ cosh γ = 0;
α0 → ∞: the shear cantilever, T_i/T_1 = 1/(2i − 1), Γ_i = 4(−1)^{i+1}/((2i − 1)π)) and against a
finite-difference solution of the beam equation (tests/physics/test_floors.py).

Everything is evaluated divided by cosh β (and with e^{β(x−1)} for the growing exponential), so
that α0 up to 1000 neither overflows nor cancels.

How many modes: every mode whose period is at least the record's shortest period that sampling
resolves (2·dt, the Nyquist period); the faster modes are rigid at the record's frequencies and
move with the ground, so they add (1 − Σ_kept Γ_i φ_i(z))·üg to the floor (the missing-mass
correction). The floor motion is then converged to what the record's samples hold, and
Σ Γ_i φ_i(z) over all modes is 1 by construction.
"""

from __future__ import annotations

import math

import numpy as np

#: Most modes kept (a stiff limit for flexible buildings sampled finely) [-].
MAX_MODES = 400
#: Gauss–Legendre points per panel of the participation integrals.
_GAUSS_POINTS = 48


def _characteristic(gamma: float, alpha0: float) -> float:
    """The characteristic equation divided by cosh β (zero at the modes' γ)."""
    beta = math.hypot(alpha0, gamma)
    ratio = alpha0 ** 2 / (gamma * beta)
    return (2.0 / math.cosh(beta) if beta < 700.0 else 0.0) \
        + (2.0 + ratio ** 2) * math.cos(gamma) + ratio * math.sin(gamma) * math.tanh(beta)


def eigenvalues(alpha0: float, count: int) -> np.ndarray:
    """The first ``count`` roots γ_i of the characteristic equation [-].

    Between the pure-flexure root (≈ (i − ½)π) and the pure-shear one ((i − ½)π), every root
    lies in ((i − 1)π, iπ]; each is bracketed on a grid of that interval and found by Brent's
    method."""
    from scipy.optimize import brentq  # only here: commands on the ground start without it
    roots = []
    step = math.pi / 64.0
    gamma = 1e-9
    value = _characteristic(gamma, alpha0)
    while len(roots) < count:
        nxt = gamma + step
        nxt_value = _characteristic(nxt, alpha0)
        if value == 0.0 or value * nxt_value < 0.0:
            roots.append(brentq(_characteristic, gamma, nxt, args=(alpha0,), xtol=1e-14,
                                rtol=1e-14, maxiter=200))
        gamma, value = nxt, nxt_value
    return np.array(roots)


def mode_shape(gamma: float, alpha0: float, x) -> np.ndarray:
    """φ(x) of the mode of root γ (the equation of the module), evaluated without overflow."""
    x = np.asarray(x, dtype=float)
    beta = math.hypot(alpha0, gamma)
    e = math.exp(-beta)
    # η, numerator and denominator divided by cosh β
    cosh_b = 0.5 * (1.0 + e * e)  # cosh β · e^{−β}
    eta = ((gamma ** 2 * math.sin(gamma) * e + gamma * beta * 0.5 * (1.0 - e * e))
           / (gamma ** 2 * math.cos(gamma) * e + beta ** 2 * cosh_b))
    # η cosh βx − (γ/β) sinh βx = ½e^{βx}(η − γ/β) + ½e^{−βx}(η + γ/β), with
    # ½e^{βx}(η − γ/β) = e^{β(x−1)}·(βγ² sin γ − γ³ cos γ − γβ² e^{−β})/(β(2γ² cos γ e^{−β} +
    # β²(1 + e^{−2β}))) (η − γ/β written over one denominator, so nothing cancels)
    growing = ((beta * gamma ** 2 * math.sin(gamma) - gamma ** 3 * math.cos(gamma)
                - gamma * beta ** 2 * e)
               / (beta * (2.0 * gamma ** 2 * math.cos(gamma) * e + beta ** 2 * (1.0 + e * e))))
    hyperbolic = growing * np.exp(beta * (x - 1.0)) + 0.5 * np.exp(-beta * x) * (eta + gamma / beta)
    return np.sin(gamma * x) - eta * np.cos(gamma * x) + hyperbolic


def _panels(beta: float) -> np.ndarray:
    """Panel edges on [0, 1]: fine within the boundary layers of width 1/β at either end."""
    layer = min(0.25, 8.0 / beta) if beta > 0 else 0.25
    inner = np.linspace(layer, 1.0 - layer, 33)
    ends = layer * np.array([0.0, 0.02, 0.1, 0.3, 0.6])
    return np.unique(np.concatenate((ends, inner, 1.0 - ends)))


def participation_factor(gamma: float, alpha0: float) -> float:
    """Γ = ∫₀¹ φ dx / ∫₀¹ φ² dx (uniform mass), by Gauss–Legendre quadrature on panels [-]."""
    nodes, weights = np.polynomial.legendre.leggauss(_GAUSS_POINTS)
    edges = _panels(math.hypot(alpha0, gamma))
    half = 0.5 * np.diff(edges)[:, None]
    x = (0.5 * (edges[1:] + edges[:-1]))[:, None] + half * nodes
    phi = mode_shape(gamma, alpha0, x.ravel()).reshape(x.shape)
    w = half * weights
    return float((w * phi).sum() / (w * phi * phi).sum())


class ContinuumBuilding:
    """``continuum:α0``: Miranda & Taghavi's shear–flexure continuum beam (see the module).

    Parameters
    ----------
    alpha0 : float
        Lateral stiffness ratio α0 ≥ 0 [-].
    """

    def __init__(self, alpha0: float):
        self.alpha0 = float(alpha0)

    def period_ratios(self, gammas: np.ndarray) -> np.ndarray:
        """T_i/T_1 = γ_1β_1/(γ_iβ_i) [-]."""
        omega = gammas * np.hypot(self.alpha0, gammas)
        return omega[0] / omega

    def modes(self, period_s: float, z_over_h: float, shortest_period_s: float):
        """(T_i [s], Γ_i φ_i(z) [-]) of the modes with T_i ≥ ``shortest_period_s`` (see the
        module's rule; none when T1 itself is shorter)."""
        count = 8
        while True:
            gammas = eigenvalues(self.alpha0, count)
            periods = period_s * self.period_ratios(gammas)
            if periods[-1] < shortest_period_s or count >= MAX_MODES:
                break
            count = min(2 * count, MAX_MODES)
        gammas = gammas[periods >= shortest_period_s]
        periods = periods[periods >= shortest_period_s]
        factors = np.array([participation_factor(g, self.alpha0) * float(
            mode_shape(g, self.alpha0, z_over_h)) for g in gammas])
        return periods, factors.reshape(periods.shape)


__all__ = ["ContinuumBuilding", "eigenvalues", "mode_shape", "participation_factor",
           "MAX_MODES"]
