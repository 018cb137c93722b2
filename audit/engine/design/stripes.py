"""One record's part of the design-level audit (:mod:`audit.engine.design.margins`) and of a check: the
record scaled to every stripe, the exact response of every block there, and whether each
procedure predicts overturning (on the same scaled records, and on the site's design spectrum
scaled to the same level for one that reads a design spectrum).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from audit.engine.shared.blocks import BlockList
from audit.engine.shared.intensity import IntensityMeasure
from audit.physics.block import Restitution
from audit.physics.rocking import RockingOptions, rocking_blocks
from procedures.context import RecordContext
from procedures.overturning import overturning_predictions, site_predictions
from records.sites import scaled_site


def half_crossing(levels, fraction) -> float:
    """Where ``fraction`` first reaches 0.5 along ascending ``levels``, ln-interpolated; NaN if
    never.

    Parameters
    ----------
    levels : numpy.ndarray
        The stripes, ascending (e.g. [g]).
    fraction : numpy.ndarray
        The fraction at each stripe [-].
    """
    above = np.flatnonzero(fraction >= 0.5)
    if above.size == 0:
        return math.nan
    j = above[0]
    if j == 0 or fraction[j] == fraction[j - 1]:
        return float(levels[j])
    t = (0.5 - fraction[j - 1]) / (fraction[j] - fraction[j - 1])
    return float(np.exp(np.log(levels[j - 1]) + t * np.log(levels[j] / levels[j - 1])))


@dataclass(frozen=True)
class StripeSettings:
    """What every record's stripes depend on (and the key of a resumable part).

    Attributes
    ----------
    im : IntensityMeasure
    levels : tuple of float
        Stripes, ascending [unit of ``im``].
    design_im : float or None
        The site's design intensity [unit of ``im``]: design spectra are scaled by
        level / design_im (FEMA 356's, or an NTC 2018 site's own where it is the only one).
    blocks : audit.engine.shared.blocks.BlockList
    restitution : audit.physics.block.Restitution
    g, free_motion_s : float
        Gravity [m/s²], free motion after each record [s].
    jobs : int
        Solver threads of a task.
    exact : bool
        Solve the blocks exactly; False where their outcomes are read from an atlas instead
        (the procedures' predictions alone are computed, the exact arrays left empty).
    """

    im: IntensityMeasure
    levels: tuple
    design_im: float | None
    blocks: BlockList
    restitution: Restitution
    g: float
    free_motion_s: float
    jobs: int
    exact: bool = True

    def as_dict(self) -> dict:
        # ``exact`` only where False: the key of a direct part is what it always was
        return {"kind": "margins stripes", "im": self.im.name, "levels": list(self.levels),
                "design_im": self.design_im, "alpha_deg": self.blocks.alpha_deg.tolist(),
                "size_s": self.blocks.size_s.tolist(), "width_m": self.blocks.width_m.tolist(),
                "height_m": self.blocks.height_m.tolist(),
                "restitution": str(self.restitution), "g": self.g,
                "free_motion_s": self.free_motion_s, **({} if self.exact else {"exact": False})}


@dataclass
class RecordStripes:
    """One record's part of the design-level audit: arrays shaped (stripe, block).

    Attributes
    ----------
    record_id : str
    intensity : float
        The record's intensity as given [unit of the intensity measure].
    exact_overturned, exact_theta_rad : numpy.ndarray
    predicted : dict
        Per procedure name, whether it predicts overturning (False where it cannot evaluate).
    evaluated : dict
        Per procedure name, whether it could evaluate the record.
    """

    record_id: str
    intensity: float
    exact_overturned: np.ndarray
    exact_theta_rad: np.ndarray
    predicted: dict
    evaluated: dict


def _at_level(entry, base: RecordContext, level: float, intensity: float,
              settings: StripeSettings):
    """The record scaled to ``level`` and its context; its design spectrum scaled to the level
    too, where the site's design intensity is known."""
    factor = level / intensity
    site_factor = level / settings.design_im if settings.design_im else 1.0
    scaled = replace(entry, motion=entry.motion.scaled(factor),
                     site=scaled_site(entry.site, site_factor))
    return scaled, base.scaled(scaled, factor)


#: Relative width in level to which the step of a site-based procedure is located.
STEP_TOLERANCE = 1e-7


def locate_steps(procedure, entry, settings: StripeSettings, brackets: dict) -> dict:
    """Per block, the level at which a procedure that reads only the site's design spectrum
    turns from not predicting overturning (at its bracket's low end) to predicting it (at the
    high end): its answer is a step in intensity, located by bisection in ln(level) to
    :data:`STEP_TOLERANCE`, not at a point between the stripes.

    ``brackets`` maps a block's index to its (low, high) levels. The blocks of one slenderness
    are bisected together, each at its own level (one evaluation of them all per halving,
    :func:`~procedures.overturning.site_predictions`); each block's halvings are those of a
    bisection of it alone.

    Parameters
    ----------
    procedure : procedures.base.Procedure
        A procedure that reads only the site.
    entry : records.RecordEntry
        A record it evaluates.
    settings : StripeSettings
        The blocks, stripes and solver settings.
    brackets : dict
        Block index → (low, high) levels (e.g. [g]).

    Returns
    -------
    dict
        Block index → the level of its step.
    """
    blocks = settings.blocks
    intensity = settings.im.of_record(entry.motion, settings.free_motion_s)
    base = RecordContext(entry, settings.free_motion_s, settings.jobs)
    steps = {}
    for alpha_deg in dict.fromkeys(float(blocks.alpha_deg[b]) for b in brackets):
        mine = np.array([b for b in brackets if float(blocks.alpha_deg[b]) == alpha_deg])
        alpha = math.radians(alpha_deg)
        r = float(settings.restitution.r(alpha))
        p = 2.0 * math.pi / blocks.size_s[mine]
        low, high = (np.array([brackets[b][end] for b in mine], dtype=float) for end in (0, 1))
        while (open_ := np.flatnonzero(high / low > 1.0 + STEP_TOLERANCE)).size:
            middle = np.sqrt(low[open_] * high[open_])
            cases = [_at_level(entry, base, float(level), intensity, settings)
                     for level in middle]
            over = site_predictions(procedure, cases, p[open_], alpha, r, settings.g)
            high[open_[over]] = middle[over]
            low[open_[~over]] = middle[~over]
        steps.update(zip(mine.tolist(), np.sqrt(low * high).tolist()))
    return steps


#: Answers of procedures that read only the site (:meth:`~procedures.base.Procedure.reads_record`
#: false): one answer for every record of a suite, so each process computes it once.
_SITE_ANSWERS: dict = {}


def procedure_predictions(proc, cases, p, groups, g) -> np.ndarray:
    """:func:`~procedures.overturning.overturning_predictions`, kept across records for a
    procedure that reads only the (scaled) sites.

    Parameters
    ----------
    proc : procedures.base.Procedure
        The procedure.
    cases : list of tuple
        (record entry scaled to a level, its :class:`~procedures.context.RecordContext`) per level.
    p : numpy.ndarray
        Frequency parameter p of each block [rad/s].
    groups : list of tuple
        (α [rad], the indices of its blocks in ``p``, restitution r [-]) per slenderness.
    g : float
        Acceleration of gravity [m/s²].
    """
    if any(proc.reads_record(entry) for entry, _ in cases):
        return overturning_predictions(proc, cases, p, groups, g)
    # ``proc`` is kept with its answer, so its id is not reused while the answer is
    key = (id(proc), tuple(tuple(sorted(entry.site.items())) for entry, _ in cases),
           p.tobytes(), tuple((alpha, index.tobytes(), r) for alpha, index, r in groups), g)
    if key not in _SITE_ANSWERS:
        if len(_SITE_ANSWERS) >= 16:
            _SITE_ANSWERS.clear()
        _SITE_ANSWERS[key] = (proc, overturning_predictions(proc, cases, p, groups, g))
    return _SITE_ANSWERS[key][1].copy()


def record_stripes(entry, procedures, settings: StripeSettings,
                   context: RecordContext | None = None) -> RecordStripes:
    """The exact response and every procedure's prediction for one record scaled to each stripe
    (the unit of work of the design-level audit); ``context``, the record's spectra, when a
    caller reads them again after.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    settings : StripeSettings
        The blocks, stripes and solver settings.
    context : procedures.context.RecordContext, optional
        The record's spectra.
    """
    blocks, levels = settings.blocks, np.asarray(settings.levels, dtype=float)
    intensity = settings.im.of_record(entry.motion, settings.free_motion_s)
    factors = levels / intensity
    shape = (levels.size, len(blocks))
    exact_over, exact_theta = np.zeros(shape, dtype=bool), np.zeros(shape)
    groups = blocks.groups()
    alpha_rad = np.empty(len(blocks))
    for alpha, index in groups:
        alpha_rad[index] = alpha
    # every block at every stripe in one solver call, whatever its α: the threads share all
    # the record's solves, not a stripe's at a time
    if settings.exact:
        peaks = rocking_blocks(entry.motion, np.tile(blocks.size_s, levels.size),
                               np.tile(alpha_rad, levels.size), r=settings.restitution,
                               options=RockingOptions(settings.g, settings.free_motion_s),
                               jobs=settings.jobs, scale=np.repeat(factors, len(blocks)))
        exact_over[:], exact_theta[:] = (peaks.overturned.reshape(shape),
                                         peaks.theta_peak.reshape(shape))
    p = 2.0 * np.pi / blocks.size_s
    base = context or RecordContext(entry, settings.free_motion_s, settings.jobs)
    cases = [_at_level(entry, base, float(level), intensity, settings) for level in levels]
    alpha_groups = [(alpha, index, float(settings.restitution.r(alpha)))
                    for alpha, index in groups]
    predicted, evaluated = {}, {}
    for proc in procedures:
        predicted[proc.name] = np.zeros(shape, dtype=bool)
        mine = [j for j, (scaled, _) in enumerate(cases)
                if proc.unmet_requirements(scaled) is None]
        evaluated[proc.name] = bool(mine)
        if mine:
            predicted[proc.name][mine] = procedure_predictions(
                proc, [cases[j] for j in mine], p, alpha_groups, settings.g)
    return RecordStripes(entry.id, intensity, exact_over, exact_theta, predicted, evaluated)


__all__ = ["StripeSettings", "RecordStripes", "record_stripes", "procedure_predictions",
           "locate_steps", "half_crossing", "STEP_TOLERANCE"]
