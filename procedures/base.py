"""The contract of a guideline procedure: what it declares, what it is asked, what it answers.

In the manner of OpenQuake hazardlib's GSIMs, a procedure is a small class that *declares*
what it needs from a record (:attr:`Procedure.requires_motion`, :attr:`Procedure.requires_site`)
so the audit can say which records it cannot audit before running, and implements only its own
physics: a damping law β(r) and a displacement spectrum Sd(T, β), from which the shared
iteration of Priestley, Evison & Carr (1978) (:mod:`procedures.iteration`) estimates a peak
rotation, and/or limit-state :class:`Check` s.

The types a procedure answers with are part of the contract and importable from here:
:class:`Evaluation`, :class:`Check` and the exact events, :class:`~procedures.iteration.Estimate`
and its outcomes (a procedure that overrides :meth:`Procedure.evaluate` builds its own).
Probabilistic procedures have a contract of their own, :mod:`procedures.probabilistic`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, ClassVar

import numpy as np

from audit import G
from procedures.parameters import check_parameters
from procedures.iteration import (CONVERGED, NO_UPLIFT, NOT_CONVERGED, OVERTURN, Estimate,
                                  estimate_rotation)

#: Periods on which procedures read record spectra, linear in T in between [s]: 0, then 800
#: periods 1.16 % apart from 0.01 s to 100 s (:class:`procedures.context.RecordContext`).
SPECTRUM_PERIODS_S = np.concatenate(([0.0], np.geomspace(0.01, 100.0, 800)))
#: Periods at which the spectrum a procedure read is stored with the audit (Figures 8.x, 9.x) [s].
STORED_SPECTRUM_PERIODS_S = SPECTRUM_PERIODS_S[SPECTRUM_PERIODS_S <= 20.0]


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
    #: Settable parameters (:class:`~procedures.parameters.Parameter`), checked when an
    #: instance is constructed (:func:`~procedures.parameters.check_parameters`).
    parameters: ClassVar[tuple] = ()
    #: A sentence ``check`` adds to the basis of the procedure's verdicts: where an input the
    #: guideline leaves to the user comes from (e.g. a pulse's period).
    basis_note: ClassVar[str] = ""
    #: Figure series of the reference report that this procedure's audit reproduces.
    figure_series: ClassVar[str] = ""
    #: True when the recorded acceleration itself is needed (its spectrum, its PGA).
    requires_motion: ClassVar[bool] = False
    #: Site parameters the record must carry, keys of ``RecordEntry.site``.
    requires_site: ClassVar[tuple[str, ...]] = ()
    #: False for a procedure that only checks limit states and estimates no rotation.
    estimates_rotation: ClassVar[bool] = True
    #: True for a procedure whose :meth:`evaluate_for_verdict` takes α and r as arrays of p's
    #: shape, one per block, element by element (closed forms in numpy, no iteration): blocks
    #: of many slendernesses are then judged in one call, with the numbers of one call each.
    alpha_per_block: ClassVar[bool] = False
    #: True for a procedure with a limit state whose exact event is the peak rotation reaching
    #: a limit short of α (:data:`EXACT_ROTATION`): judging it needs each record's exact peak θ,
    #: which a check reading the atlas otherwise does not solve.
    rotation_limits: ClassVar[bool] = False

    def unmet_requirements(self, entry) -> str | None:
        """Why this procedure cannot evaluate the record ``entry``, or None."""
        if self.requires_motion and entry.motion is None:
            return f"no record file ({entry.missing_reason})"
        missing = [key for key in self.requires_site if entry.site.get(key) is None]
        if missing:
            return f"no {self.title} site parameters ({', '.join(missing)})"
        return None

    def __post_init__(self):  # a dataclass subclass's declared parameters, checked once
        check_parameters(self)

    def spectrum_read(self, entry) -> str:
        """Which spectrum the procedure reads for ``entry``, in words (check.json's
        ``spectrum_read``): its :attr:`spectrum_source` unless it chooses per record."""
        return self.spectrum_source

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
        return self._evaluation(entry, p, alpha_rad, r, context, g, for_report=True)

    def evaluate_for_verdict(self, entry, p, alpha_rad: float, r: float, context,
                             g: float = G) -> Evaluation:
        """:meth:`evaluate` without what only a report shows: the same checks and estimate
        (θ, outcome, iterations, cycle), with no fixed points (empty) and no stored spectrum
        (None), so the iteration reads the spectrum only where it goes (a context's
        :meth:`~procedures.context.RecordContext.on_demand` spectra then compute a few dozen
        periods, not all). A procedure that overrides :meth:`evaluate` is evaluated.

        Same arguments as :meth:`evaluate`.
        """
        if type(self).evaluate is not Procedure.evaluate:
            return self.evaluate(entry, p, alpha_rad, r, context, g)
        return self._evaluation(entry, p, alpha_rad, r, context, g, for_report=False)

    def _evaluation(self, entry, p, alpha_rad, r, context, g, for_report: bool) -> Evaluation:
        checks = self.checks(entry, p, alpha_rad, r, context, g)
        if not self.estimates_rotation:
            return Evaluation(None, None, checks)
        beta = float(self.damping(r))
        spectrum = self.displacement_spectrum(entry, beta, context)
        estimate = estimate_rotation(spectrum, self.peak_ground_acceleration(entry, context), p,
                                     alpha_rad, beta, g, with_fixed_points=for_report)
        return Evaluation(estimate,
                          spectrum(STORED_SPECTRUM_PERIODS_S) if for_report else None, checks)

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

    def site_displacements(self, entries, damping: float):
        """For a procedure that reads only the site: the Sd of many records' sites at once, as
        ``of(index)``, the function of the periods that reads each on the design spectrum of
        ``entries[index]`` at damping β [-] with the operations of
        :meth:`displacement_spectrum`; None (the default) where it has no such form, and each
        site is then evaluated on its own."""
        return None


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



__all__ = ["CONVERGED", "EXACT_OVERTURNING", "EXACT_ROTATION", "EXACT_UPLIFT", "NOT_CONVERGED",
           "NO_UPLIFT", "OVERTURN", "SPECTRUM_PERIODS_S", "STORED_SPECTRUM_PERIODS_S", "Check",
           "Estimate", "Evaluation", "Procedure", "estimate_rotation"]
