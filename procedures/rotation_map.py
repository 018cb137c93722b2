"""The map θ ← Sd(T(θ)) / (R cos α) of Priestley, Evison & Carr (1978), Eqs. 8.1–8.2, and
every fixed point of it on (0, α) with its stability.

The iteration (:mod:`procedures.iteration`) decides a procedure's estimate; :func:`fixed_points`
lists every fixed point of the same map, so a report can say which branch the iteration took
and why it did not settle (a cycle around a repelling fixed point).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from audit import G
from audit.physics.block import radius_from_p
from audit.physics.damping import housner_period
from procedures.tabulated import TabulatedDisplacement

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
#: Grid points whose signs are settled together where Sd's range over them decides them all.
SCAN_CHUNK = 32
#: Room a chunk's bounds leave for the rounding of the values inside it, relative to the
#: bounds' largest magnitude: ~4.5·10⁶ ulps, where a value is rounded to a few.
ROUNDING_ROOM = 1e-9
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


def _excess_positive(displacement, v, grid, p, scale) -> np.ndarray:
    """F(θ) > θ at every grid point (v, θ/α = ``grid``) of every block: Sd(4v/p)·scale > θ/α.

    Each value is that of the array expression ``displacement(4v/p)·scale − grid > 0``; a
    tabulated spectrum's are found compiled (:mod:`procedures.fixed_point_scan`), and a
    nondecreasing Sd's (``displacement.nondecreasing``) only in the chunks of
    :data:`SCAN_CHUNK` grid points where Sd at the chunk's ends leaves a sign open: the others
    lie wholly above or below the chunk's θ/α. The array expression read ~10⁶ periods a call.
    """
    if isinstance(displacement, TabulatedDisplacement):
        from procedures.fixed_point_scan import tabulated_excess  # numba loads only here
        return tabulated_excess(v, grid, p, scale, displacement.period_s, displacement.sd_m,
                                SCAN_CHUNK, ROUNDING_ROOM)
    if not getattr(displacement, "nondecreasing", False):
        return (displacement(4.0 * v / p[:, None]) * scale[:, None] - grid) > 0.0
    period = 4.0 * v
    first = np.arange(0, v.size, SCAN_CHUNK)
    last = np.minimum(first + SCAN_CHUNK, v.size) - 1
    lowest, highest = np.minimum.reduceat(grid, first), np.maximum.reduceat(grid, first)
    bottom = displacement(period[first] / p[:, None]) * scale[:, None]
    top = displacement(period[last] / p[:, None]) * scale[:, None]
    margin = ROUNDING_ROOM * np.maximum(np.abs(top), np.abs(bottom))
    above = bottom - margin > highest
    below = top + margin < lowest
    out = np.repeat(above, SCAN_CHUNK, axis=1)[:, :v.size]
    blocks, chunks = np.nonzero(~(above | below))
    points = (first[chunks][:, None] + np.arange(SCAN_CHUNK)).ravel()
    blocks = np.repeat(blocks, SCAN_CHUNK)
    inside = points < v.size
    points, blocks = points[inside], blocks[inside]
    out[blocks, points] = (displacement(period[points] / p[blocks]) * scale[blocks]
                           - grid[points]) > 0.0
    return out


def _bisected(excess_of, low, high, positive_low, args) -> np.ndarray:
    """The root of ``excess_of(ratio, *args)`` in each bracket [``low``, ``high``] (whose sign
    at ``low`` is ``positive_low``), all brackets halved together until narrower than
    :data:`ROOT_TOLERANCE_RATIO`: the midpoint is then within half of it of the root.

    Bisection, not scipy's bracketing solvers: importing ``scipy.optimize`` took 0.5 s of every
    audit's start, and a bracket a scan step wide needs about 28 halvings, each one array
    expression over every root."""
    width = float(np.max(high - low, initial=0.0))
    halvings = (math.ceil(math.log2(width / ROOT_TOLERANCE_RATIO))
                if width > ROOT_TOLERANCE_RATIO else 0)
    for _ in range(halvings):
        middle = 0.5 * (low + high)
        same = (excess_of(middle, *args) > 0.0) == positive_low
        low, high = np.where(same, middle, low), np.where(same, high, middle)
    return 0.5 * (low + high)


def fixed_points(displacement: Callable[[np.ndarray], np.ndarray], p, alpha_rad: float,
                 g: float = G) -> FixedPoints:
    """Every fixed point θ* = F(θ*) on (0, α) of the map of Eqs. 8.1–8.2, with its stability.

    F(θ) = Sd(T(θ)) / (R cos α), T(θ) = (4/p) acosh(1/(1 − θ/α)). The sign of F(θ) − θ is
    found for all blocks on a grid uniform in ln(pT/4) (:data:`SCAN_STEP_LOG_PERIOD` explains
    the step; :func:`_excess_positive` reads Sd only where a sign can change), every sign
    change is bisected to :data:`ROOT_TOLERANCE_RATIO` in θ/α, all roots at once, and F'(θ*)
    is taken by a central difference. The trivial fixed point θ = 0 is left out.

    Parameters
    ----------
    displacement : callable
        Sd [m] as a function of the period T [s] (array in, array out, elementwise): a
        :class:`~procedures.tabulated.TabulatedDisplacement`, or a callable whose true
        ``nondecreasing`` attribute promises that Sd never falls as T grows, which the scan
        then trusts (:class:`~audit.physics.design_spectra.DesignDisplacement`), or any other.
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
    p = np.atleast_1d(np.asarray(p, dtype=float))
    scale = map_scale(p, alpha_rad, g)
    low, high = SCAN_V_RANGE
    v = np.exp(np.arange(np.log(low), np.log(high), SCAN_STEP_LOG_PERIOD))
    grid = 1.0 - 1.0 / np.cosh(v)  # θ/α at v (inverse of Eq. 8.1)
    excess = _excess_positive(displacement, v, grid, p, scale)
    changes = excess[:, :-1] != excess[:, 1:]
    # numpy's 1-D search of a boolean array is ~10x faster than its 2-D one; same indices
    blocks, left = np.divmod(np.flatnonzero(changes), changes.shape[1])

    def excess_of(ratio, p_block, scale_block):
        return rotation_map(displacement, ratio, p_block, scale_block) - ratio

    ratios = _bisected(excess_of, grid[left], grid[left + 1], excess[blocks, left],
                       (p[blocks], scale[blocks]))
    step = np.minimum(SLOPE_STEP_RATIO, 0.5 * np.minimum(ratios, 1.0 - ratios))
    slopes = (excess_of(ratios + step, p[blocks], scale[blocks])
              - excess_of(ratios - step, p[blocks], scale[blocks])) / (2.0 * step) + 1.0
    return FixedPoints(blocks, ratios, slopes)



__all__ = ["FixedPoints", "fixed_points", "map_scale", "ratios_text", "rotation_map"]
