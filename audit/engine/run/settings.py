"""What an audit computes, the same for every record of a run (and hashed for resumable runs)."""

from __future__ import annotations

from dataclasses import asdict, dataclass

from audit import G
from audit.engine.shared import fields as check
from audit.engine.shared.defaults import (DEFAULT_AGREE_BAND, DEFAULT_ALPHA_DEG, DEFAULT_FREE_MOTION_S,
                                   DEFAULT_RESTITUTION, DEFAULT_ROBUSTNESS, DEFAULT_SIZES)
from audit.engine.shared.grid import size_grid
from audit.engine.shared.ground_truth import GroundTruth, parse_sensitivity
from audit.physics.defaults import DEFAULT_REST_TOLERANCE, DEFAULT_STEPS_PER_RADIAN
from procedures.iteration import (CYCLE_TOLERANCE_RATIO, INITIAL_ROTATION_RATIO, MAX_CYCLE_LENGTH,
                                  MAX_ITERATIONS, TOLERANCE_RATIO)

#: Damping ratios of the record response spectra of Figures 5.x [-].
FIGURE_5_DAMPING = (0.05, 0.10, 0.15)
#: Samples kept per stored time history (about 2 per pixel of the report's figures).
HISTORY_POINTS = 2000


@dataclass(frozen=True)
class AuditSettings:
    """What a run computes, the same for every record.

    Build it with :meth:`parse`, which checks every field once.

    Attributes
    ----------
    alpha_deg : tuple of float
        Slendernesses [degrees].
    size_s : tuple of float
        Block sizes 2π/p [s].
    free_motion_s : float
        Free motion after each record, for the exact solver and the record spectra [s].
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    robustness : float
        ε of the fragility flag: exact spectra also at the record × (1 ± ε) [-]; 0 = off.
    g : float
        Acceleration of gravity [m/s²].
    restitution : str
        The exact solver's impact model (``housner``, a fixed r, or ``xFACTOR`` times Eq. 4.8;
        :class:`~audit.physics.block.Restitution`); the procedures read the same block's r.
    vertical : bool
        The exact solver includes the records' vertical components, where they have one.
    friction : float or None
        Friction coefficient μ of the base [-]: blocks whose pure-rocking response needs more
        are flagged ``exact_slides``; None: not checked.
    sensitivity : tuple of str
        Alternative ground-truth models, each an impact model or ``vertical``: the exact
        response is rerun under each and a verdict that changes is flagged
        ``exact_model_sensitive``.
    jobs : int
        Threads of the exact solver of one record: set by the engine from the run's
        :class:`~audit.engine.shared.runtime.Runtime` (not part of what is computed).
    """

    alpha_deg: tuple = DEFAULT_ALPHA_DEG
    size_s: tuple = tuple(size_grid(*DEFAULT_SIZES))
    free_motion_s: float = DEFAULT_FREE_MOTION_S
    agree_band: float = DEFAULT_AGREE_BAND
    robustness: float = DEFAULT_ROBUSTNESS
    g: float = G
    restitution: str = DEFAULT_RESTITUTION
    vertical: bool = False
    friction: float | None = None
    sensitivity: tuple = ()
    jobs: int = 1

    @classmethod
    def parse(cls, *, alpha_deg=DEFAULT_ALPHA_DEG, size_s=None, solver=None,
              agree_band: float = DEFAULT_AGREE_BAND, robustness: float = DEFAULT_ROBUSTNESS,
              friction: float | None = None, sensitivity=()) -> AuditSettings:
        """The settings of the given fields, each checked once (InputError naming the
        argument, or the solver's field: ``solver.restitution``); a field not given takes its
        default (:mod:`audit.engine.shared.defaults`).

        Parameters
        ----------
        alpha_deg : float or sequence of float
            Slendernesses [degrees], 0 < α < 45.
        size_s : float or sequence of float, optional
            Block sizes 2π/p [s], positive; default the grid of ``DEFAULT_SIZES``.
        solver : audit.engine.shared.solver.Solver, optional
            The exact solver's impact model, free motion, g and vertical motion
            (:meth:`Solver.parse <audit.engine.shared.solver.Solver.parse>`).
        agree_band, robustness :
            As the attributes: in [0, 1); in [0, 0.5).
        friction : float, optional
            Positive.
        sensitivity : str or sequence of str
        """
        from audit.engine.shared.solver import Solver
        solver = Solver.parse(solver, "run")
        return cls(
            alpha_deg=check.numbers("alpha_deg", alpha_deg,
                                    "slendernesses between 0 and 45 degrees", 0, 45,
                                    low_open=True, high_open=True),
            size_s=(tuple(float(s) for s in size_grid(*DEFAULT_SIZES)) if size_s is None
                    else check.numbers("size_s", size_s, "positive block sizes 2π/p in s", 0,
                                       low_open=True)),
            free_motion_s=solver.free_motion_s,
            agree_band=check.number("agree_band", agree_band, "a number in [0, 1)", 0, 1,
                                    high_open=True),
            robustness=check.number("robustness", robustness, "a number in [0, 0.5)", 0, 0.5,
                                    high_open=True),
            g=solver.g, restitution=str(solver.restitution), vertical=solver.vertical,
            friction=(None if friction is None else check.number(
                "friction", friction, "a positive friction coefficient μ", 0, low_open=True)),
            sensitivity=parse_sensitivity(check.words("sensitivity", sensitivity),
                                          "sensitivity"))

    @property
    def ground_truth(self) -> GroundTruth:
        """The exact model the run solves."""
        return GroundTruth(self.restitution, self.vertical)

    def as_dict(self) -> dict:
        """Plain values for ``summary.json`` (angles in degrees, sizes in s)."""
        values = asdict(self)
        values.pop("jobs")
        values.update(alpha_deg=list(self.alpha_deg), size_s=list(self.size_s),
                      sensitivity=list(self.sensitivity))
        return values

    def described(self) -> dict:
        """:meth:`as_dict` with the solver's and the iteration's fixed settings, for
        ``summary.json``."""
        return {**self.as_dict(),
                "steps_per_radian": DEFAULT_STEPS_PER_RADIAN,
                "rest_tolerance": DEFAULT_REST_TOLERANCE,
                "initial_rotation_ratio": INITIAL_ROTATION_RATIO,
                "tolerance_ratio": TOLERANCE_RATIO, "max_iterations": MAX_ITERATIONS,
                "max_cycle_length": MAX_CYCLE_LENGTH,
                "cycle_tolerance_ratio": CYCLE_TOLERANCE_RATIO,
                "figure_5_damping_pct": [100.0 * d for d in FIGURE_5_DAMPING]}


__all__ = ["AuditSettings", "FIGURE_5_DAMPING", "HISTORY_POINTS"]
