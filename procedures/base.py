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
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, ClassVar

import numpy as np

from audit import G
from audit.physics.block import radius_from_p
from audit.physics.damping import housner_period

#: Initial guess θ₀/α of the iteration: a small rotation, so the iteration climbs to the
#: smallest non-trivial fixed point (θ = 0 is always one, and unstable when the block uplifts).
INITIAL_ROTATION_RATIO = 0.1
#: Convergence when successive iterates differ by at most this much in θ/α.
TOLERANCE_RATIO = 1e-6
#: A settled 2-cycle re-reads the same two periods, so its iterates repeat to round-off; a
#: slowly contracting alternation differs by far more than this between every other iterate.
CYCLE_TOLERANCE_RATIO = 1e-12
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
        For non-converged iterations, the range the iterates kept oscillating in.
    damping : float
        β used [-].
    """

    theta: np.ndarray
    period_s: np.ndarray
    iterations: np.ndarray
    outcome: np.ndarray
    detail: np.ndarray
    damping: float


def iterate_rotation(displacement: Callable[[np.ndarray], np.ndarray], p, alpha_rad: float,
                     g: float = G, initial_ratio: float = INITIAL_ROTATION_RATIO,
                     tolerance: float = TOLERANCE_RATIO, max_iterations: int = MAX_ITERATIONS):
    """Fixed-point iteration θ ← Sd(T(θ)) / (R cos α) of Eqs. 8.1–8.2, for many blocks at once.

    Parameters
    ----------
    displacement : callable
        Sd [m] as a function of the period T [s] (array in, array out).
    p : array
        Frequency parameters of the blocks [rad/s].
    alpha_rad : float
        Slenderness α [rad].
    g : float
        Acceleration of gravity [m/s²] (R = 3g/(4p²)).
    initial_ratio, tolerance, max_iterations :
        Initial guess θ₀/α, tolerance on |Δθ|/α, iteration cap.

    Returns
    -------
    ratio, outcome, iterations, detail : numpy.ndarray
        Final θ/α, outcome (``converged``, ``overturn``, ``not-converged``), iterations used,
        and for non-converged blocks what the iterates did: an exact 2-cycle (detected as soon
        as it settles) or no settled value within the cap.
    """
    p = np.asarray(p, dtype=float)
    scale = 1.0 / (radius_from_p(p, g) * np.cos(alpha_rad) * alpha_rad)
    ratio = np.full(p.shape, initial_ratio)
    previous = np.full(p.shape, np.nan)  # the iterate before ``ratio``
    outcome = np.full(p.shape, NOT_CONVERGED, dtype=object)
    iterations = np.full(p.shape, max_iterations)
    detail = np.full(p.shape, "", dtype=object)
    active = np.ones(p.shape, dtype=bool)
    for i in range(1, max_iterations + 1):
        idx = np.flatnonzero(active)
        new = displacement(housner_period(ratio[idx], p[idx])) * scale[idx]
        over = new >= 1.0
        done = ~over & (np.abs(new - ratio[idx]) <= tolerance)
        # a settled 2-cycle: back where it was two steps ago, yet still jumping
        cycle = ~over & ~done & (np.abs(new - previous[idx]) <= CYCLE_TOLERANCE_RATIO)
        outcome[idx[over]] = OVERTURN
        outcome[idx[done]] = CONVERGED
        iterations[idx[over | done | cycle]] = i
        for j, low, high in zip(idx[cycle], np.minimum(new, ratio[idx])[cycle],
                                np.maximum(new, ratio[idx])[cycle]):
            detail[j] = (f"iterates alternate between θ/α = {low:.4f} and {high:.4f} "
                         f"(a 2-cycle: no attracting fixed point)")
        previous[idx] = ratio[idx]
        ratio[idx] = np.where(over, 1.0, new)
        active[idx[over | done | cycle]] = False
        if not active.any():
            break
    for j in np.flatnonzero(active):
        detail[j] = (f"no convergence after {max_iterations} iterations "
                     f"(last iterates θ/α = {previous[j]:.4f}, {ratio[j]:.4f})")
    return ratio, outcome, iterations, detail


class Procedure:
    """Base class of the guideline procedures: the contract the audit relies on.

    Subclasses declare the class attributes and implement :meth:`damping` and
    :meth:`displacement_spectrum`; :meth:`estimate` runs the shared iteration.
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

    def unmet_requirements(self, entry) -> str | None:
        """Why this procedure cannot estimate for the record ``entry``, or None."""
        if self.requires_motion and entry.motion is None:
            return f"no record file ({entry.missing_reason})"
        missing = [key for key in self.requires_site if entry.site.get(key) is None]
        if missing:
            return f"no {self.title} site parameters ({', '.join(missing)})"
        return None

    def checks(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> list[Check]:
        """Limit-state checks of blocks (p [rad/s], α [rad], r) under the record ``entry``.

        Same arguments as :meth:`estimate`. A procedure that verifies limit states returns one
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

    def estimate(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> Estimate:
        """Peak rotation of blocks (p [rad/s], α [rad], r) under the record (SPEC §5–6).

        Parameters
        ----------
        entry : records.RecordEntry
        p : array
            Frequency parameters [rad/s].
        alpha_rad : float
            Slenderness α [rad].
        r : float
            Coefficient of restitution [-].
        context : audit.engine.runner.RecordContext
            Cache of the record's spectra.
        """
        p = np.asarray(p, dtype=float)
        beta = float(self.damping(r))
        theta = np.zeros(p.shape)
        period = np.zeros(p.shape)
        iterations = np.zeros(p.shape, dtype=int)
        outcome = np.full(p.shape, NO_UPLIFT, dtype=object)
        detail = np.full(p.shape, "", dtype=object)
        if self.peak_ground_acceleration(entry, context) > g * np.tan(alpha_rad):
            spectrum = self.displacement_spectrum(entry, beta, context)
            ratio, outcome, iterations, detail = iterate_rotation(spectrum, p, alpha_rad, g)
            # no single rotation to report when overturning is predicted or nothing converged
            undefined = outcome != CONVERGED
            theta = np.where(undefined, np.nan, ratio * alpha_rad)
            period = np.where(undefined, np.nan, housner_period(ratio, p))
        return Estimate(theta, period, iterations, outcome, detail, beta)


# ---------------------------------------------------------------------------------------------
# Limit-state checks: procedures that verify a block rather than (or besides) estimating θ.
#
# A check names its limit state, the event of the exact response it is audited against, and the
# procedure's pass/fail per block; the audit needs nothing else to build a confusion matrix.
# ---------------------------------------------------------------------------------------------

#: Exact events a check is audited against.
EXACT_UPLIFT = "uplift"  # the exact block uplifts
EXACT_ROTATION = "rotation"  # exact max θ ≥ the check's ``theta_limit_rad``, or overturning

# Verdicts of a check against the exact response.
AGREES_SAFE = "agrees-safe"
AGREES_UNSAFE = "agrees-unsafe"
MISSED = "missed"  # the procedure passes the block, the exact response exceeds: unsafe
FALSE_ALARM = "false-alarm"  # the procedure fails the block, the exact response does not exceed
CHECK_VERDICTS = (AGREES_SAFE, AGREES_UNSAFE, MISSED, FALSE_ALARM)


@dataclass(frozen=True)
class Check:
    """One limit-state check of a procedure, arrays over the block sizes of one slenderness.

    A check is either in accelerations (``demand_m_s2`` ≤ ``capacity_m_s2``) or in
    displacements (``demand_m`` ≤ ``capacity_m``); the other pair is NaN.

    Attributes
    ----------
    limit_state : str
        Name of the limit state, e.g. ``SLD``, ``SLV-linear``, ``SLV``, ``SLC``.
    exact_event : str
        :data:`EXACT_UPLIFT` or :data:`EXACT_ROTATION`: the exact response's "exceeded".
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


def centroid_displacement(theta_rad, alpha_rad, radius_m):
    """Horizontal displacement of the centroid d = R [sin α − sin(α − θ)] [m] (§1).

    Parameters
    ----------
    theta_rad : float or array
        Rotation about the pivot corner θ [rad].
    alpha_rad : float or array
        Slenderness α [rad].
    radius_m : float or array
        R, centroid to corner [m].
    """
    return radius_m * (np.sin(alpha_rad) - np.sin(alpha_rad - np.asarray(theta_rad, dtype=float)))


def rotation_at_displacement(displacement_m, alpha_rad, radius_m):
    """θ(d) = α − asin(sin α − d/R) [rad], the inverse of :func:`centroid_displacement` (§1).

    NaN for d outside [0, R(1 + sin α)]; d ≥ R sin α = b is at or beyond instability (θ ≥ α).
    """
    with np.errstate(invalid="ignore"):
        return alpha_rad - np.arcsin(np.sin(alpha_rad)
                                     - np.asarray(displacement_m, dtype=float) / radius_m)


def exact_exceeded(check: Check, theta_peak, overturned, uplifted) -> np.ndarray:
    """Whether the exact response exceeds the check's limit state, per block (§2.5).

    Parameters
    ----------
    check : Check
    theta_peak : array
        Exact max |θ| [rad] of the same blocks.
    overturned, uplifted : array of bool
        Exact overturning and uplift of the same blocks.

    Returns
    -------
    numpy.ndarray of bool
        ``uplifted`` for :data:`EXACT_UPLIFT`; θ_peak ≥ θ_limit or overturned for
        :data:`EXACT_ROTATION`. Blocks with no exact response (NaN) are the caller's to mask.
    """
    if check.exact_event == EXACT_UPLIFT:
        return np.asarray(uplifted, dtype=bool)
    if check.exact_event == EXACT_ROTATION:
        with np.errstate(invalid="ignore"):
            return (np.asarray(theta_peak) >= check.theta_limit_rad) | np.asarray(overturned,
                                                                                   dtype=bool)
    raise ValueError(f"check {check.limit_state}: unknown exact event {check.exact_event!r}")


def check_verdicts(passes, exceeded) -> np.ndarray:
    """Verdict of each block on one check: procedure's pass/fail against the exact event.

    Parameters
    ----------
    passes : array of bool
        The procedure passes the block.
    exceeded : array of bool
        The exact response exceeds the limit state (:func:`exact_exceeded`).

    Returns
    -------
    numpy.ndarray of str
        ``agrees-safe`` (passes, not exceeded), ``agrees-unsafe`` (fails, exceeded), ``missed``
        (passes, exceeded: unconservative) or ``false-alarm`` (fails, not exceeded).
    """
    passes = np.asarray(passes, dtype=bool)
    exceeded = np.asarray(exceeded, dtype=bool)
    return np.where(passes, np.where(exceeded, MISSED, AGREES_SAFE),
                    np.where(exceeded, AGREES_UNSAFE, FALSE_ALARM)).astype(object)

