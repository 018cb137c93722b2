"""The contract of a guideline procedure, and the fixed-point iteration they share (Eqs. 8.1–8.2).

In the manner of OpenQuake hazardlib's GSIMs, a procedure is a small class that *declares*
what it needs from a record (:attr:`Procedure.requires_motion`, :attr:`Procedure.requires_site`)
so the audit can say which records it cannot audit before running, and implements only its own
physics: a damping law β(r) and a displacement spectrum Sd(T, β). The iteration of
Priestley, Evison & Carr (1978) is common to all of them:

1. no rocking when PGA ≤ g tan α;
2. guess θ, T(θ) = (4/p) acosh(1/(1 − θ/α)) (Eq. 8.1);
3. δ = Sd(T(θ), β);
4. θ ← δ / (R cos α) (Eq. 8.2); repeat until |Δθ|/α ≤ tolerance.

The literal iteration decides the estimate; :func:`fixed_points` lists every fixed point of the
same map on (0, α) with its stability, so a report can say which branch the iteration took and
why it did not settle (a cycle around a repelling fixed point).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, ClassVar

import numpy as np

from audit import G
from audit.physics.block import radius_from_p
from audit.physics.damping import housner_period

#: Periods on which procedures read record spectra, linear in T in between [s]: 0, then 800
#: periods 1.16 % apart from 0.01 s to 100 s (:class:`procedures.context.RecordContext`).
SPECTRUM_PERIODS_S = np.concatenate(([0.0], np.geomspace(0.01, 100.0, 800)))
#: Periods at which the spectrum a procedure read is stored with the audit (Figures 8.x, 9.x) [s].
STORED_SPECTRUM_PERIODS_S = SPECTRUM_PERIODS_S[SPECTRUM_PERIODS_S <= 20.0]
#: Initial guess θ₀/α of the iteration: a small rotation, so the iteration climbs to the
#: smallest non-trivial fixed point (θ = 0 is always one, and unstable when the block uplifts).
INITIAL_ROTATION_RATIO = 0.1
#: Convergence when successive iterates differ by at most this much in θ/α.
TOLERANCE_RATIO = 1e-6
#: Longest cycle of the iteration that is recognised as such.
MAX_CYCLE_LENGTH = 8
#: A cycle of length L has settled when the last L iterates repeat the L before them to this
#: fraction of the cycle's spread (max − min). Relative, because cycles settle geometrically at
#: their own rate and amplitude; a contracting alternation towards a fixed point (slope −0.99)
#: differs by ~1 % of its spread between every other iterate, far above this.
CYCLE_TOLERANCE_RATIO = 1e-6
#: A settled cycle of length L is read as one of length d | L when its iterates repeat after d
#: steps to this fraction of its spread (see :func:`_cycle_length`).
SUBCYCLE_TOLERANCE_RATIO = 1e-3
#: Fixed points are scanned on a grid uniform in ln v, v = pT/4 = acosh(1/(1 − θ/α)) (Eq. 8.1),
#: with this step: successive periods 0.25 % apart. The record spectra are linear in T between
#: tabulated periods 1.16 % apart (:data:`SPECTRUM_PERIODS_S`), so every linear
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


def _rotation_map(displacement, ratio, p, scale):
    """F(θ)/α = Sd(T(θ)) / (R cos α α) of Eqs. 8.1–8.2 at θ/α = ``ratio`` [-]."""
    return displacement(housner_period(ratio, p)) * scale


def _map_scale(p, alpha_rad: float, g: float):
    """1 / (R cos α α) [1/m]: turns Sd [m] into θ/α by Eq. 8.2."""
    return 1.0 / (radius_from_p(p, g) * np.cos(alpha_rad) * alpha_rad)


def _ratios_text(values, suffixes=None) -> str:
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
            out[i] = _ratios_text(self.ratio[mine], suffix[mine])
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
    scale = _map_scale(p, alpha_rad, g)
    low, high = SCAN_V_RANGE
    v = np.exp(np.arange(np.log(low), np.log(high), SCAN_STEP_LOG_PERIOD))
    grid = 1.0 - 1.0 / np.cosh(v)  # θ/α at v (inverse of Eq. 8.1)
    excess = (displacement(4.0 * v / p[:, None]) * scale[:, None] - grid) > 0.0
    blocks, left = np.nonzero(excess[:, :-1] != excess[:, 1:])

    def excess_of(ratio, p_block, scale_block):
        return _rotation_map(displacement, ratio, p_block, scale_block) - ratio

    ratios = find_root(excess_of, (grid[left], grid[left + 1]), args=(p[blocks], scale[blocks]),
                       tolerances={"xatol": ROOT_TOLERANCE_RATIO, "xrtol": 0.0}).x
    step = np.minimum(SLOPE_STEP_RATIO, 0.5 * np.minimum(ratios, 1.0 - ratios))
    slopes = (excess_of(ratios + step, p[blocks], scale[blocks])
              - excess_of(ratios - step, p[blocks], scale[blocks])) / (2.0 * step) + 1.0
    return FixedPoints(blocks, ratios, slopes)


# All cycle lengths L are tested at once: row L − 2 of _PERIOD_INDEX picks the last L iterates
# of ``recent`` (its oldest repeated up to MAX_CYCLE_LENGTH columns, harmless for max, min and
# the comparison), and _PERIOD_INDEX − L the L iterates before them.
_CYCLE_SIZES = np.arange(2, MAX_CYCLE_LENGTH + 1)[:, None]
_PERIOD_INDEX = -1 - np.minimum(np.arange(MAX_CYCLE_LENGTH), _CYCLE_SIZES - 1)


def _cycle_length(recent: np.ndarray) -> np.ndarray:
    """Length L ≤ :data:`MAX_CYCLE_LENGTH` of the cycle the rows of ``recent`` settled in, or 0.

    ``recent`` holds the last 2·MAX_CYCLE_LENGTH iterates θ/α of each block, newest last (NaN
    before the first). A cycle of length L has settled when a whole period, the last L iterates,
    repeats the L before it to :data:`CYCLE_TOLERANCE_RATIO` of its spread; the shortest such L
    counts. A cycle that settles from alternate sides (multiplier of F∘F near −1) repeats at 2L
    before it does at L, so the period found is reduced to its shortest divisor whose iterates
    already repeat to :data:`SUBCYCLE_TOLERANCE_RATIO` of the spread.
    """
    period, before = recent[:, _PERIOD_INDEX], recent[:, _PERIOD_INDEX - _CYCLE_SIZES]
    spread = period.max(axis=2) - period.min(axis=2)
    repeats = (np.all(np.abs(period - before) <= CYCLE_TOLERANCE_RATIO * spread[..., None], axis=2)
               & (spread > 0.0))
    length = np.where(repeats.any(axis=1), _CYCLE_SIZES[np.argmax(repeats, axis=1), 0], 0)
    for row in np.flatnonzero(length):
        window = recent[row, -length[row]:]
        bound = SUBCYCLE_TOLERANCE_RATIO * np.ptp(window)
        length[row] = next(size for size in range(2, length[row] + 1)
                           if length[row] % size == 0
                           and np.all(np.abs(window[size:] - window[:-size]) <= bound))
    return length


def iterate_rotation(displacement: Callable[[np.ndarray], np.ndarray], p, alpha_rad: float,
                     g: float = G, initial_ratio: float = INITIAL_ROTATION_RATIO,
                     tolerance: float = TOLERANCE_RATIO, max_iterations: int = MAX_ITERATIONS):
    """Fixed-point iteration θ ← Sd(T(θ)) / (R cos α) of Eqs. 8.1–8.2, for many blocks at once.

    Parameters
    ----------
    displacement : callable
        Sd [m] as a function of the period T [s] (array in, array out).
    p : array
        Frequency parameters of the blocks [rad/s], 1-D.
    alpha_rad : float
        Slenderness α [rad].
    g : float
        Acceleration of gravity [m/s²] (R = 3g/(4p²)).
    initial_ratio, tolerance, max_iterations :
        Initial guess θ₀/α, tolerance on |Δθ|/α, iteration cap.

    Returns
    -------
    ratio, outcome, iterations, detail, cycle : numpy.ndarray
        Final θ/α, outcome (``converged``, ``overturn``, ``not-converged``), iterations used,
        what a non-converged iteration did (settled in a cycle of length ≤
        :data:`MAX_CYCLE_LENGTH`, detected as soon as one whole period repeats, or no settled
        value or cycle within the cap), and the settled cycle's θ/α ascending
        (``0.5753;0.8854``, empty when there is none).
    """
    from procedures.iteration_kernels import advance  # compiled: numba loads only here
    p = np.asarray(p, dtype=float)
    outcome = np.full(p.shape, NOT_CONVERGED, dtype=object)
    iterations = np.full(p.shape, max_iterations)
    detail = np.full(p.shape, "", dtype=object)
    cycle = np.full(p.shape, "", dtype=object)
    final = np.empty(p.shape)
    # the blocks still iterating, compacted whenever some settle: each iteration is a handful
    # of array operations on them alone
    live = np.arange(p.size)
    live_p, live_scale = p, _map_scale(p, alpha_rad, g)
    recent = np.full((p.size, 2 * MAX_CYCLE_LENGTH), np.nan)  # last iterates, newest last
    recent[:, -1] = initial_ratio
    for i in range(1, max_iterations + 1):
        if not live.size:
            break
        new = _rotation_map(displacement, recent[:, -1], live_p, live_scale)
        over, done, maybe = advance(recent, np.ascontiguousarray(new, dtype=float), tolerance,
                                    CYCLE_TOLERANCE_RATIO, MAX_CYCLE_LENGTH)
        settled = over | done
        if maybe.any():
            length = np.zeros(live.size, dtype=int)
            length[maybe] = _cycle_length(recent[maybe])
            for k in np.flatnonzero(length):
                values = np.sort(recent[k, -length[k]:])
                cycle[live[k]] = _ratios_text(values)
                detail[live[k]] = (
                    f"iterates settle in a {length[k]}-cycle between θ/α = {values[0]:.4f} and "
                    f"{values[-1]:.4f} (no fixed point reached from θ₀/α = {initial_ratio:g})")
            settled |= length > 0
        if settled.any():
            outcome[live[over]] = OVERTURN
            outcome[live[done]] = CONVERGED
            iterations[live[settled]] = i
            final[live[settled]] = recent[settled, -1]
            keep = ~settled
            live, live_p, live_scale, recent = live[keep], live_p[keep], live_scale[keep], recent[keep]
    final[live] = recent[:, -1]
    for k, j in enumerate(live):
        detail[j] = (f"no settled value or cycle after {max_iterations} iterations "
                     f"(last iterates θ/α = {recent[k, -2]:.4f}, {recent[k, -1]:.4f})")
    return final, outcome, iterations, detail, cycle


def estimate_rotation(displacement: Callable[[np.ndarray], np.ndarray], pga_m_s2: float, p,
                      alpha_rad: float, damping: float, g: float = G) -> Estimate:
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
    """
    p = np.asarray(p, dtype=float)
    theta = np.zeros(p.shape)
    period = np.zeros(p.shape)
    iterations = np.zeros(p.shape, dtype=int)
    outcome = np.full(p.shape, NO_UPLIFT, dtype=object)
    detail = np.full(p.shape, "", dtype=object)
    cycle = np.full(p.shape, "", dtype=object)
    roots = np.full(p.shape, "", dtype=object)
    if pga_m_s2 > g * np.tan(alpha_rad):
        ratio, outcome, iterations, detail, cycle = iterate_rotation(displacement, p, alpha_rad, g)
        roots = fixed_points(displacement, p, alpha_rad, g).text(p.size)
        # no single rotation to report when overturning is predicted or nothing converged
        undefined = outcome != CONVERGED
        theta = np.where(undefined, np.nan, ratio * alpha_rad)
        period = np.where(undefined, np.nan, housner_period(ratio, p))
    return Estimate(theta, period, iterations, outcome, detail, float(damping),
                    fixed_points=roots, cycle=cycle)


@dataclass(frozen=True)
class Evaluation:
    """Everything a procedure says about blocks of one slenderness under one record.

    Attributes
    ----------
    estimate : Estimate or None
        The peak rotation it estimates; None for a procedure that only checks limit states.
    spectrum_sd_m : numpy.ndarray or None
        The displacement spectrum it read, at its damping, on
        :data:`STORED_SPECTRUM_PERIODS_S` [m]; None when it reads none.
    checks : list of Check
        Its limit-state checks (none for a procedure that only estimates a rotation).
    """

    estimate: Estimate | None
    spectrum_sd_m: np.ndarray | None
    checks: list


class Procedure:
    """Base class of the guideline procedures: the contract the audit relies on.

    Subclasses declare the class attributes and implement :meth:`damping`,
    :meth:`peak_ground_acceleration` and :meth:`displacement_spectrum` (a rotation estimate by
    the shared iteration), and/or :meth:`checks` (limit states). The audit makes one call per
    record and slenderness, :meth:`evaluate`, and decides every verdict itself.
    """

    #: Registry key, as typed on the command line (e.g. ``"priestley1978"``).
    name: ClassVar[str] = ""
    #: Display title.
    title: ClassVar[str] = ""
    #: Bibliographic reference.
    reference: ClassVar[str] = ""
    #: Damping law and spectrum source, in words with equation numbers (for the report).
    damping_law: ClassVar[str] = ""
    spectrum_source: ClassVar[str] = ""
    #: Figure series of the reference report that this procedure's audit reproduces.
    figure_series: ClassVar[str] = ""
    #: True when the recorded acceleration itself is needed (its spectrum, its PGA).
    requires_motion: ClassVar[bool] = False
    #: Site parameters the record must carry, keys of ``RecordEntry.site``.
    requires_site: ClassVar[tuple[str, ...]] = ()
    #: False for a procedure that only checks limit states and estimates no rotation.
    estimates_rotation: ClassVar[bool] = True

    def unmet_requirements(self, entry) -> str | None:
        """Why this procedure cannot evaluate the record ``entry``, or None."""
        if self.requires_motion and entry.motion is None:
            return f"no record file ({entry.missing_reason})"
        missing = [key for key in self.requires_site if entry.site.get(key) is None]
        if missing:
            return f"no {self.title} site parameters ({', '.join(missing)})"
        return None

    def reads_record(self, entry) -> bool:
        """Whether the procedure reads the record itself for ``entry`` (its spectrum, its PGA),
        not only the site's design spectrum: a record scaled to a level then gives each record
        its own answer, a design spectrum scaled to the level one answer for all."""
        return self.requires_motion

    def evaluate(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> Evaluation:
        """The procedure's estimate, the spectrum it read and its checks for blocks
        (p [rad/s], α [rad], r [-]) under the record ``entry``.

        Parameters
        ----------
        entry : records.RecordEntry
        p : array
            Frequency parameters [rad/s].
        alpha_rad : float
            Slenderness α [rad].
        r : float
            Coefficient of restitution [-].
        context : procedures.context.RecordContext
            Cache of the record's spectra.
        g : float
            Acceleration of gravity [m/s²].
        """
        checks = self.checks(entry, p, alpha_rad, r, context, g)
        if not self.estimates_rotation:
            return Evaluation(None, None, checks)
        beta = float(self.damping(r))
        spectrum = self.displacement_spectrum(entry, beta, context)
        estimate = estimate_rotation(spectrum, self.peak_ground_acceleration(entry, context), p,
                                     alpha_rad, beta, g)
        return Evaluation(estimate, spectrum(STORED_SPECTRUM_PERIODS_S), checks)

    def checks(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> list[Check]:
        """Limit-state checks of blocks (p [rad/s], α [rad], r) under the record ``entry``.

        Same arguments as :meth:`evaluate`. A procedure that verifies limit states returns one
        :class:`Check` per limit state (see the end of this module); the default, for
        procedures that only estimate a rotation, is none.
        """
        return []

    def damping(self, r):
        """Equivalent damping β [-] for a coefficient of restitution r [-]."""
        raise NotImplementedError

    def peak_ground_acceleration(self, entry, context) -> float:
        """PGA [m/s²] for the uplift check of step 1."""
        raise NotImplementedError

    def displacement_spectrum(self, entry, damping: float, context) -> Callable[[np.ndarray], np.ndarray]:
        """Sd(T) [m] at damping β for the record ``entry``; ``context`` caches record spectra."""
        raise NotImplementedError


# ---------------------------------------------------------------------------------------------
# Limit-state checks: procedures that verify a block rather than (or besides) estimating θ.
#
# A check names its limit state, the event of the exact response it is audited against, and the
# procedure's pass/fail per block; the audit needs nothing else to build a confusion matrix.
# ---------------------------------------------------------------------------------------------

#: Exact events a check is audited against.
EXACT_UPLIFT = "uplift"  # the exact block uplifts
EXACT_ROTATION = "rotation"  # exact max θ ≥ the check's ``theta_limit_rad``, or overturning
EXACT_OVERTURNING = "overturning"  # the exact block overturns

@dataclass(frozen=True)
class Check:
    """One limit-state check of a procedure, arrays over the block sizes of one slenderness.

    A check is in displacements (``demand_m`` ≤ ``capacity_m``), accelerations
    (``demand_m_s2`` ≤ ``capacity_m_s2``) or velocities (``demand_m_s`` ≤ ``capacity_m_s``);
    the other pairs are NaN.

    Attributes
    ----------
    limit_state : str
        Name of the limit state, e.g. ``SLD``, ``SLV-linear``, ``SLV``, ``SLC``.
    exact_event : str
        :data:`EXACT_UPLIFT`, :data:`EXACT_ROTATION` or :data:`EXACT_OVERTURNING`: the exact
        response's "exceeded".
    passes : numpy.ndarray of bool
        The procedure's verdict per block.
    demand_m, capacity_m : numpy.ndarray
        Displacement demand and capacity [m] (NaN for an acceleration check).
    demand_m_s2, capacity_m_s2 : numpy.ndarray
        Acceleration demand and capacity [m/s²] (NaN for a displacement check).
    demand_theta_rad : numpy.ndarray
        Rotation θ(demand_m) of the demand displacement [rad]; NaN where undefined (an
        acceleration check, or a demand at or beyond instability).
    theta_limit_rad : numpy.ndarray
        Exact max θ at and above which the exact response exceeds [rad] (NaN for uplift).
    period_s : numpy.ndarray
        Period the demand was read at [s] (NaN for an acceleration check).
    detail : str
        The check in words, with the equations implemented (for the report).
    demand_m_s, capacity_m_s : numpy.ndarray
        Velocity demand and capacity [m/s] (NaN unless a velocity check).
    """

    limit_state: str
    exact_event: str
    passes: np.ndarray
    demand_m: np.ndarray
    capacity_m: np.ndarray
    demand_m_s2: np.ndarray
    capacity_m_s2: np.ndarray
    demand_theta_rad: np.ndarray
    theta_limit_rad: np.ndarray
    period_s: np.ndarray
    detail: str
    demand_m_s: np.ndarray | float = np.nan
    capacity_m_s: np.ndarray | float = np.nan


def rotation_at_displacement(displacement_m, alpha_rad, radius_m):
    """θ(d) = α − asin(sin α − d/R) [rad]: the rotation at which the centroid has moved
    d = R [sin α − sin(α − θ)] (rotation about the base corner).

    NaN for d outside [0, R(1 + sin α)]; d ≥ R sin α = b is at or beyond instability (θ ≥ α).
    """
    with np.errstate(invalid="ignore"):
        return alpha_rad - np.arcsin(np.sin(alpha_rad)
                                     - np.asarray(displacement_m, dtype=float) / radius_m)


# The contract of a probabilistic procedure: P(event | IM) for a block, not a rotation or a check.
#: Intensity measures a probabilistic procedure may declare: peak ground velocity [m/s] and peak
#: ground acceleration [m/s²] (a procedure written for floor motion is read at the ground floor).
INTENSITY_MEASURES = ("PGV", "PGA")


@dataclass(frozen=True)
class LognormalFragility:
    """P(event | IM) = Φ(ln(IM/θ)/β), the lognormal fragility.

    Attributes
    ----------
    median : float
        θ, the intensity at which the event has probability 1/2 [m/s for PGV, m/s² for PGA].
    beta : float
        β, the logarithmic standard deviation [-].
    """

    median: float
    beta: float

    def probability(self, intensity):
        """P(event | IM = ``intensity``) [-]; 0 at zero intensity."""
        from scipy.special import ndtr  # kept local: only probabilistic audits need scipy here
        intensity = np.asarray(intensity, dtype=float)
        with np.errstate(divide="ignore"):
            return ndtr(np.log(intensity / self.median) / self.beta)


@dataclass(frozen=True)
class FragilityComponent:
    """One component of a probabilistic procedure and the rocking block it stands for.

    Attributes
    ----------
    id : str
        The procedure's component id (e.g. ``E.20.22.104a``).
    description : str
        The procedure's description of the component.
    intensity_measure : str
        One of :data:`INTENSITY_MEASURES`.
    fragility : LognormalFragility
        The procedure's fragility for the event, in SI.
    depth_m, height_m : float
        Full depth (the dimension it rocks across) and full height of the block [m]; NaN where
        the procedure gives no geometry, and the component then has no block to audit.
    """

    id: str
    description: str
    intensity_measure: str
    fragility: LognormalFragility
    depth_m: float = float("nan")
    height_m: float = float("nan")

    @property
    def has_block(self) -> bool:
        """Whether the component has dimensions, hence a rocking block to audit."""
        return bool(np.isfinite(self.depth_m) and np.isfinite(self.height_m))


class ProbabilisticProcedure:
    """Base class of a procedure that gives P(event | IM) for listed components.

    A subclass declares its ``name``, the ``event`` its fragilities are for and its
    ``components``; the engine audits each component with a block against the frequency of the
    event in exact solves (calibration, Brier score, log-likelihood, exact fragility).
    """

    name: ClassVar[str] = ""
    title: ClassVar[str] = ""
    #: The event the fragilities give the probability of.
    event: ClassVar[str] = OVERTURN
    components: ClassVar[tuple[FragilityComponent, ...]] = ()

    def component(self, component_id: str) -> FragilityComponent:
        """The component ``component_id``."""
        for component in self.components:
            if component.id == component_id:
                return component
        raise KeyError(component_id)

    def probability(self, component_id: str, intensity):
        """P(event | IM = ``intensity``) of the component ``component_id`` [-] (SI intensity)."""
        return self.component(component_id).fragility.probability(intensity)
