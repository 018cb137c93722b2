"""The map θ ← Sd(T(θ)) / (R cos α) of Priestley, Evison & Carr (1978), Eqs. 8.1–8.2, and
every fixed point of it on (0, α) with its stability.

The iteration (:mod:`procedures.iteration`) decides a procedure's estimate; :func:`fixed_points`
lists every fixed point of the same map, so a report can say which branch the iteration took
and why it did not settle (a cycle around a repelling fixed point).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from audit import G
from audit.physics.block import radius_from_p
from audit.physics.damping import housner_period

#: Fixed points are scanned on a grid uniform in ln v, v = pT/4 = acosh(1/(1 − θ/α)) (Eq. 8.1),
#: with this step: successive periods 0.25 % apart. The record spectra are linear in T between
#: tabulated periods 1.16 % apart (:data:`procedures.base.SPECTRUM_PERIODS_S`), so every linear
#: piece holds ≥ 4 grid points and, on it, F(θ) − θ is linear in T minus the smooth inverse of
#: Eq. 8.1: each simple root changes sign between two grid points; only two roots less than a
#: grid step apart (a near tangency) can be missed. A grid in θ/α would not do: T ∝ sqrt(θ/α)
#: near 0 and T → ∞ as θ → α, so its steps in T would be coarse at both ends.
SCAN_STEP_LOG_PERIOD = 0.0025
#: Range of v scanned: θ/α from 5e-9 to 1 − 3e-11.
SCAN_V_RANGE = (1e-4, 25.0)
#: Fixed points are polished to this absolute tolerance in θ/α.
ROOT_TOLERANCE_RATIO = 1e-10
#: Step of the central difference for F'(θ*) in θ/α, well inside one linear piece of a spectrum.
SLOPE_STEP_RATIO = 1e-6


def rotation_map(displacement, ratio, p, scale):
    """F(θ)/α = Sd(T(θ)) / (R cos α α) of Eqs. 8.1–8.2 at θ/α = ``ratio`` [-]."""
    return displacement(housner_period(ratio, p)) * scale


def map_scale(p, alpha_rad: float, g: float):
    """1 / (R cos α α) [1/m]: turns Sd [m] into θ/α by Eq. 8.2."""
    return 1.0 / (radius_from_p(p, g) * np.cos(alpha_rad) * alpha_rad)


def ratios_text(values, suffixes=None) -> str:
    """θ/α values as ``0.2397s;0.2551u`` (4 decimals, ``;``-separated, optional suffixes)."""
    suffixes = [""] * len(values) if suffixes is None else suffixes
    return ";".join(f"{value:.4f}{suffix}" for value, suffix in zip(values, suffixes))


@dataclass(frozen=True)
class FixedPoints:
    """Fixed points of the map of Eqs. 8.1–8.2, flat over the blocks (see :func:`fixed_points`).

    Attributes
    ----------
    block : numpy.ndarray of int
        Index of the block each fixed point belongs to (ascending).
    ratio : numpy.ndarray
        θ*/α [-], ascending within a block.
    slope : numpy.ndarray
        F'(θ*) [-] by a central difference.
    """

    block: np.ndarray
    ratio: np.ndarray
    slope: np.ndarray

    @property
    def stable(self) -> np.ndarray:
        """True where the fixed point attracts the iteration, |F'(θ*)| < 1."""
        return np.abs(self.slope) < 1.0

    def text(self, n_blocks: int) -> np.ndarray:
        """Per block, the fixed points as ``0.2397s;0.2551u;0.4821s`` (empty where none)."""
        out = np.full(n_blocks, "", dtype=object)
        suffix = np.where(self.stable, "s", "u")
        for i in np.unique(self.block):
            mine = self.block == i
            out[i] = ratios_text(self.ratio[mine], suffix[mine])
        return out


def fixed_points(displacement: Callable[[np.ndarray], np.ndarray], p, alpha_rad: float,
                 g: float = G) -> FixedPoints:
    """Every fixed point θ* = F(θ*) on (0, α) of the map of Eqs. 8.1–8.2, with its stability.

    F(θ) = Sd(T(θ)) / (R cos α), T(θ) = (4/p) acosh(1/(1 − θ/α)). F(θ) − θ is evaluated for
    all blocks at once on a grid uniform in ln(pT/4) (:data:`SCAN_STEP_LOG_PERIOD` explains the
    step), every sign change is polished to :data:`ROOT_TOLERANCE_RATIO` in θ/α by Chandrupatla's
    bracketing method, all roots at once (``scipy.optimize.elementwise.find_root``), and F'(θ*)
    is taken by a central difference. The trivial fixed point θ = 0 is left out.

    Parameters
    ----------
    displacement : callable
        Sd [m] as a function of the period T [s] (array in, array out, elementwise).
    p : array
        Frequency parameters of the blocks [rad/s], 1-D.
    alpha_rad : float
        Slenderness α [rad].
    g : float
        Acceleration of gravity [m/s²] (R = 3g/(4p²)).

    Returns
    -------
    FixedPoints
    """
    from scipy.optimize.elementwise import find_root

    p = np.atleast_1d(np.asarray(p, dtype=float))
    scale = map_scale(p, alpha_rad, g)
    low, high = SCAN_V_RANGE
    v = np.exp(np.arange(np.log(low), np.log(high), SCAN_STEP_LOG_PERIOD))
    grid = 1.0 - 1.0 / np.cosh(v)  # θ/α at v (inverse of Eq. 8.1)
    excess = (displacement(4.0 * v / p[:, None]) * scale[:, None] - grid) > 0.0
    blocks, left = np.nonzero(excess[:, :-1] != excess[:, 1:])

    def excess_of(ratio, p_block, scale_block):
        return rotation_map(displacement, ratio, p_block, scale_block) - ratio

    ratios = find_root(excess_of, (grid[left], grid[left + 1]), args=(p[blocks], scale[blocks]),
                       tolerances={"xatol": ROOT_TOLERANCE_RATIO, "xrtol": 0.0}).x
    step = np.minimum(SLOPE_STEP_RATIO, 0.5 * np.minimum(ratios, 1.0 - ratios))
    slopes = (excess_of(ratios + step, p[blocks], scale[blocks])
              - excess_of(ratios - step, p[blocks], scale[blocks])) / (2.0 * step) + 1.0
    return FixedPoints(blocks, ratios, slopes)



__all__ = ["FixedPoints", "fixed_points", "map_scale", "ratios_text", "rotation_map"]
