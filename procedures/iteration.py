"""The fixed-point iteration of Priestley, Evison & Carr (1978), Eqs. 8.1–8.2, common to the
procedures that estimate a rotation (the cycles it may settle in:
:mod:`procedures.iteration_cycles`):

1. no rocking when PGA ≤ g tan α;
2. guess θ, T(θ) = (4/p) acosh(1/(1 − θ/α)) (Eq. 8.1);
3. δ = Sd(T(θ), β);
4. θ ← δ / (R cos α) (Eq. 8.2); repeat until |Δθ|/α ≤ tolerance.

The literal iteration decides the estimate; :func:`procedures.rotation_map.fixed_points` lists
every fixed point of the same map on (0, α) with its stability.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from audit import G
from audit.physics.damping import housner_period
from audit.physics.design_spectra import DesignDisplacement, FEMA356Spectrum
from procedures.iteration_cycles import (CYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH,
                                         SUBCYCLE_TOLERANCE_RATIO, cycle_length, cycle_text,
                                         unsettled_text)
from procedures.rotation_map import fixed_points, map_scale, rotation_map
from procedures.tabulated import TabulatedDisplacement, TabulatedOnDemand

#: Initial guess θ₀/α of the iteration: a small rotation, so the iteration climbs to the
#: smallest non-trivial fixed point (θ = 0 is always one, and unstable when the block uplifts).
INITIAL_ROTATION_RATIO = 0.1
#: Convergence when successive iterates differ by at most this much in θ/α.
TOLERANCE_RATIO = 1e-6
#: Iterations allowed: enough for slowly alternating iterations (slope near −1 at the fixed
#: point) to converge, which on the seed records take up to ~300.
MAX_ITERATIONS = 2000

# Outcomes of an estimate.
CONVERGED = "converged"
OVERTURN = "overturn"
NO_UPLIFT = "no-uplift"
NOT_CONVERGED = "not-converged"


@dataclass(frozen=True)
class Estimate:
    """A procedure's estimates for blocks of one slenderness, arrays over the block sizes.

    Attributes
    ----------
    theta : numpy.ndarray
        Converged peak rotation [rad]; 0 for no uplift; NaN where overturning is predicted
        or the iteration did not converge (see ``detail``).
    period_s : numpy.ndarray
        T(θ) of Eq. 8.1 at the converged θ [s]; NaN where θ is.
    iterations : numpy.ndarray
        Iterations used (0 for no uplift).
    outcome : numpy.ndarray of str
        ``converged``, ``overturn``, ``no-uplift`` or ``not-converged``.
    detail : numpy.ndarray of str
        For non-converged iterations, the cycle the iterates settled in, or that they settled
        in none.
    damping : float
        β used [-].
    fixed_points : numpy.ndarray of str
        Every fixed point of the map on (0, α) as θ/α, ascending, ``;``-separated, 4 decimals,
        each suffixed ``s`` (attracting, |F'| < 1) or ``u`` (repelling), e.g.
        ``0.2397s;0.2551u;0.4821s``; empty where there is none or the block does not uplift.
    cycle : numpy.ndarray of str
        The values θ/α of the cycle the iteration settled in, ascending, ``;``-separated,
        4 decimals (e.g. ``0.5753;0.8854``); empty otherwise.
    """

    theta: np.ndarray
    period_s: np.ndarray
    iterations: np.ndarray
    outcome: np.ndarray
    detail: np.ndarray
    damping: float
    fixed_points: np.ndarray
    cycle: np.ndarray



def iterate_rotation(displacement: Callable[[np.ndarray], np.ndarray], p, alpha_rad: float,
                     g: float = G, initial_ratio: float = INITIAL_ROTATION_RATIO,
                     tolerance: float = TOLERANCE_RATIO, max_iterations: int = MAX_ITERATIONS,
                     blockwise: bool = False):
    """Fixed-point iteration θ ← Sd(T(θ)) / (R cos α) of Eqs. 8.1–8.2, for many blocks at once.

    Parameters
    ----------
    displacement : callable
        Sd [m] as a function of the period T [s] (array in, array out); with ``blockwise``,
        ``displacement(blocks)`` gives that function for the blocks ``blocks`` (indices into
        ``p``), each period it is given read on the spectrum of its own block.
    p : array
        Frequency parameters of the blocks [rad/s], 1-D.
    alpha_rad : float
        Slenderness α [rad].
    g : float
        Acceleration of gravity [m/s²] (R = 3g/(4p²)).
    initial_ratio, tolerance, max_iterations :
        Initial guess θ₀/α, tolerance on |Δθ|/α, iteration cap.
    blockwise : bool
        Whether each block has a spectrum of its own. A block's iterates depend on its own
        spectrum alone, so they are those of an iteration of that block by itself.

    Returns
    -------
    ratio, outcome, iterations, detail, cycle : numpy.ndarray
        Final θ/α, outcome (``converged``, ``overturn``, ``not-converged``), iterations used,
        what a non-converged iteration did (settled in a cycle of length ≤
        :data:`MAX_CYCLE_LENGTH`, detected as soon as one whole period repeats, or no settled
        value or cycle within the cap), and the settled cycle's θ/α ascending
        (``0.5753;0.8854``, empty when there is none).
    """
    p = np.asarray(p, dtype=float)
    if isinstance(displacement, TabulatedDisplacement):
        return iterate_tabulated(displacement.period_s, displacement.sd_m[None, :],
                                 np.zeros(p.size, dtype=np.int64), p,
                                 map_scale(p, alpha_rad, g), initial_ratio, tolerance,
                                 max_iterations)
    if isinstance(displacement, TabulatedOnDemand):
        from procedures import iteration_kernels as kernels  # compiled: numba loads only here
        return _outcomes(*kernels.iterate_on_demand(
            displacement.period_s, displacement.sd_m, displacement.kernel_arguments(),
            np.ascontiguousarray(p),
            np.ascontiguousarray(map_scale(p, alpha_rad, g), dtype=float), float(initial_ratio),
            float(tolerance), CYCLE_TOLERANCE_RATIO, SUBCYCLE_TOLERANCE_RATIO,
            MAX_CYCLE_LENGTH, int(max_iterations)), initial_ratio, max_iterations)
    spectrum = displacement(np.arange(p.size)) if blockwise else displacement
    # exactly these types: a subclass may read Sd otherwise than the compiled formula
    if type(spectrum) is DesignDisplacement and type(spectrum.spectrum) is FEMA356Spectrum:
        return _iterate_fema356(spectrum, p, alpha_rad, g, initial_ratio, tolerance,
                                max_iterations)
    from procedures.iteration_kernels import advance  # compiled: numba loads only here
    outcome = np.full(p.shape, NOT_CONVERGED, dtype=object)
    iterations = np.full(p.shape, max_iterations)
    detail = np.full(p.shape, "", dtype=object)
    cycle = np.full(p.shape, "", dtype=object)
    final = np.empty(p.shape)
    # the blocks still iterating, compacted whenever some settle: each iteration is a handful
    # of array operations on them alone
    live = np.arange(p.size)
    live_p, live_scale = p, map_scale(p, alpha_rad, g)
    recent = np.full((p.size, 2 * MAX_CYCLE_LENGTH), np.nan)  # last iterates, newest last
    recent[:, -1] = initial_ratio
    for i in range(1, max_iterations + 1):
        if not live.size:
            break
        new = rotation_map(spectrum, recent[:, -1], live_p, live_scale)
        over, done, maybe = advance(recent, np.ascontiguousarray(new, dtype=float), tolerance,
                                    CYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH)
        settled = over | done
        if maybe.any():
            length = np.zeros(live.size, dtype=int)
            length[maybe] = cycle_length(recent[maybe])
            for k in np.flatnonzero(length):
                cycle[live[k]], detail[live[k]] = cycle_text(recent[k], length[k],
                                                              initial_ratio)
            settled |= length > 0
        if settled.any():
            outcome[live[over]] = OVERTURN
            outcome[live[done]] = CONVERGED
            iterations[live[settled]] = i
            final[live[settled]] = recent[settled, -1]
            keep = ~settled
            live, live_p, live_scale, recent = live[keep], live_p[keep], live_scale[keep], recent[keep]
            spectrum = displacement(live) if blockwise and live.size else spectrum
    final[live] = recent[:, -1]
    for k, j in enumerate(live):
        detail[j] = unsettled_text(recent[k], max_iterations)
    return final, outcome, iterations, detail, cycle



def iterate_tabulated(period_s, sd_m, rows, p, scale,
                      initial_ratio: float = INITIAL_ROTATION_RATIO,
                      tolerance: float = TOLERANCE_RATIO, max_iterations: int = MAX_ITERATIONS):
    """:func:`iterate_rotation` of blocks that each read their own tabulated spectrum (linear in
    T between ``period_s``), compiled (:func:`procedures.iteration_kernels.iterate_tabulated`):
    a record's stripes and slendernesses in one call, each block with the iterates, bit for
    bit, of :func:`iterate_rotation` on its own spectrum.

    Parameters
    ----------
    period_s : numpy.ndarray
        Periods of the tables [s], ascending.
    sd_m : numpy.ndarray
        Sd [m], shaped (table, len(period_s)).
    rows : numpy.ndarray of int
        The table each block reads.
    p, scale : numpy.ndarray
        Frequency parameter [rad/s] and 1/(R cos α α) [1/m] of each block
        (:func:`procedures.rotation_map.map_scale` at the block's α).
    initial_ratio, tolerance, max_iterations :
        As for :func:`iterate_rotation`.

    Returns
    -------
    As :func:`iterate_rotation`.
    """
    from procedures import iteration_kernels as kernels  # compiled: numba loads only here
    code, iterations, length, recent = kernels.iterate_tabulated(
        np.ascontiguousarray(period_s, dtype=float), np.ascontiguousarray(sd_m, dtype=float),
        np.ascontiguousarray(rows, dtype=np.int64), np.ascontiguousarray(p, dtype=float),
        np.ascontiguousarray(scale, dtype=float), float(initial_ratio), float(tolerance),
        CYCLE_TOLERANCE_RATIO, SUBCYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH, int(max_iterations))
    return _outcomes(code, iterations, length, recent, initial_ratio, max_iterations)


def _iterate_fema356(displacement: DesignDisplacement, p, alpha_rad: float, g: float,
                     initial_ratio: float, tolerance: float, max_iterations: int):
    """:func:`iterate_rotation` on FEMA 356 spectra (a site, or a site per block), compiled
    (:func:`procedures.design_spectrum_kernels.iterate_fema356`): each block's iterates those
    of the array loop, bit for bit."""
    from procedures.design_spectrum_kernels import iterate_fema356  # numba loads only here
    site = displacement.spectrum.branch_constants(displacement.damping, p.size)
    # G: a DesignDisplacement reads Sd at the default gravity (DesignSpectrum.displacement's);
    # the caller's g sizes the blocks (map_scale) only
    return _outcomes(*iterate_fema356(
        np.ascontiguousarray(p), np.ascontiguousarray(map_scale(p, alpha_rad, g), dtype=float),
        site, G, float(initial_ratio), float(tolerance), CYCLE_TOLERANCE_RATIO,
        SUBCYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH, int(max_iterations)),
        initial_ratio, max_iterations)


def _outcomes(code, iterations, length, recent, initial_ratio: float, max_iterations: int):
    """What :func:`iterate_rotation` returns, from the compiled iteration's codes."""
    from procedures import iteration_kernels as kernels
    outcome = np.full(code.shape, NOT_CONVERGED, dtype=object)
    outcome[code == kernels.CONVERGED] = CONVERGED
    outcome[code == kernels.OVERTURNED] = OVERTURN
    detail = np.full(code.shape, "", dtype=object)
    cycle = np.full(code.shape, "", dtype=object)
    for k in np.flatnonzero(code == kernels.CYCLING):
        cycle[k], detail[k] = cycle_text(recent[k], int(length[k]), initial_ratio)
    for k in np.flatnonzero(code == kernels.NOT_SETTLED):
        detail[k] = unsettled_text(recent[k], max_iterations)
    return recent[:, -1].copy(), outcome, iterations, detail, cycle


def uplifts(pga_m_s2, alpha_rad: float, g: float = G):
    """Step 1 of the iteration: whether the block uplifts, PGA > g tan α (array in, array out
    for the PGAs)."""
    return pga_m_s2 > g * np.tan(alpha_rad)


def estimate_rotation(displacement: Callable[[np.ndarray], np.ndarray], pga_m_s2: float, p,
                      alpha_rad: float, damping: float, g: float = G,
                      with_fixed_points: bool = True) -> Estimate:
    """Peak rotation of blocks by the iteration of Priestley et al. (1978), Eqs. 8.1–8.2.

    Step 1 (no uplift when PGA ≤ g tan α), then :func:`iterate_rotation` from
    θ₀/α = :data:`INITIAL_ROTATION_RATIO`, and :func:`fixed_points` of the same map.

    Parameters
    ----------
    displacement : callable
        Sd [m] as a function of the period T [s] at damping ``damping``.
    pga_m_s2 : float
        Peak ground acceleration of the uplift check [m/s²].
    p : array
        Frequency parameters [rad/s].
    alpha_rad : float
        Slenderness α [rad].
    damping : float
        β the spectrum is at [-] (recorded on the estimate).
    g : float
        Acceleration of gravity [m/s²].
    with_fixed_points : bool
        False leaves ``fixed_points`` empty: their scan reads Sd at every period.
    """
    p = np.asarray(p, dtype=float)
    theta = np.zeros(p.shape)
    period = np.zeros(p.shape)
    iterations = np.zeros(p.shape, dtype=int)
    outcome = np.full(p.shape, NO_UPLIFT, dtype=object)
    detail = np.full(p.shape, "", dtype=object)
    cycle = np.full(p.shape, "", dtype=object)
    roots = np.full(p.shape, "", dtype=object)
    if uplifts(pga_m_s2, alpha_rad, g):
        ratio, outcome, iterations, detail, cycle = iterate_rotation(displacement, p, alpha_rad, g)
        if with_fixed_points:
            roots = fixed_points(displacement, p, alpha_rad, g).text(p.size)
        # no single rotation to report when overturning is predicted or nothing converged
        undefined = outcome != CONVERGED
        theta = np.where(undefined, np.nan, ratio * alpha_rad)
        period = np.where(undefined, np.nan, housner_period(ratio, p))
    return Estimate(theta, period, iterations, outcome, detail, float(damping),
                    fixed_points=roots, cycle=cycle)


__all__ = ["CONVERGED", "NOT_CONVERGED", "NO_UPLIFT", "OVERTURN", "Estimate", "estimate_rotation",
           "iterate_rotation", "iterate_tabulated", "uplifts"]
