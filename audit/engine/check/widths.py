"""How wide an object of a given height must be: the exact width for a target P(overturn) at
the site, and the width each guideline accepts.

Exact: the objects of one height and any width form a family; each member's multiple-stripe
fragility (the suite's records scaled to the check's stripes, a lognormal fitted to the counts)
gives P(overturn) at the site's intensity, P(w). The required width for a target is the
smallest width above which P(w) stays within the target on a scan of widths geometric from
:data:`SCAN_FRACTIONS` of the height, its last crossing then bisected (in ln w, every record
solved at each midpoint) to :data:`WIDTH_TOLERANCE`: a root of P(w) = target, not a point of
an α grid.

Guideline: per record scaled to the site's intensity, the narrowest width c_r the guideline does
not predict overturning for (its answer is taken as monotone in width for one record); it accepts
a width when it predicts overturning for at most half the records it can evaluate, so its
required width is the ⌈n/2⌉-th smallest c_r. Each c_r is first bracketed by stepping out from
the object's width (:func:`guideline_brackets`); only the brackets that can hold that order
statistic are then halved (:func:`accepted_width`): each try of a procedure whose damping
depends on α (Priestley's β(r(α))) reads a new spectrum of the record.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import norm

from audit.engine.design.lognormal_fit import lognormal_fits
from audit.engine.shared.scheduler import computed_parts
from audit.physics.rocking import rocking_blocks
from procedures.overturning import overturning_predictions

#: Widths scanned, as fractions of the height: the first and last, and how many in between.
SCAN_FRACTIONS = (0.03, 0.95)
SCAN_WIDTHS = 12
#: Relative precision of a required width (0.5 %).
WIDTH_TOLERANCE = 0.005
#: Step of the guideline's search out from the object's width, as a ratio of widths, and the
#: relative precision of its bisection (2 %): each step of a procedure whose damping depends on
#: α (Priestley's β(r(α))) reads a new spectrum of the record.
GUIDELINE_STEP = 1.5
GUIDELINE_TOLERANCE = 0.02
#: Blocks (each solved at every stripe) from which a pass of the width search reports each
#: record done: a long inventory's passes take minutes, a few objects' a moment.
PROGRESS_BLOCKS = 1000


@dataclass(frozen=True)
class FamilySettings:
    """Blocks given one by one (``size_s[i]``, ``alpha_deg[i]``) at every stripe of a check.

    ``intensity`` holds each record's intensity (record id, value), so each record is scaled to
    the stripes exactly as for the object's own fragility.
    """

    size_s: tuple
    alpha_deg: tuple
    levels: tuple
    intensity: tuple
    restitution: object
    g: float
    free_motion_s: float
    jobs: int


def record_family(entry, procedures, settings: FamilySettings) -> np.ndarray:
    """Exact overturning of the blocks of ``settings`` under one record scaled to each stripe,
    shaped (stripe, block): one solver call for every block at every stripe, so that a
    bisection's one or two blocks still keep every thread busy.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    procedures : list
        Unused (none: the exact solver alone), for the scheduler's ``task(entry, procedures,
        settings)``.
    settings : FamilySettings
        The blocks, stripes and solver settings.
    """
    intensity = dict(settings.intensity)[entry.id]
    levels, blocks = len(settings.levels), len(settings.size_s)
    factors = np.array([level / intensity for level in settings.levels])
    return rocking_blocks(entry.motion, np.tile(settings.size_s, levels),
                          np.tile(np.radians(settings.alpha_deg), levels),
                          r=settings.restitution, g=settings.g,
                          free_motion_s=settings.free_motion_s, jobs=settings.jobs,
                          scale=np.repeat(factors, blocks)).overturned.reshape(levels, blocks)


def probability_at_site(overturned, levels, site_im: float) -> np.ndarray:
    """P(overturn) at ``site_im`` of each block's fitted fragility; ``overturned`` is shaped
    (record, stripe, block).

    Parameters
    ----------
    overturned : numpy.ndarray of bool
        Outcomes shaped (record, stripe, block).
    levels : array_like of float
        The stripes [g].
    site_im : float
        The site's intensity [g].
    """
    counts = overturned.sum(axis=0).T  # (block, stripe)
    medians, betas = lognormal_fits(levels, overturned.shape[0], counts)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = norm.cdf(np.log(site_im / medians) / betas)
    return np.where(np.isinf(medians), 0.0, np.where(medians == 0.0, 1.0, p))


def required_width(measure, heights_m, targets, scan=SCAN_FRACTIONS, count=SCAN_WIDTHS,
                   tolerance=WIDTH_TOLERANCE) -> np.ndarray:
    """The smallest width above which the measure stays ≤ each target, per height (see the
    module).

    Parameters
    ----------
    measure : callable
        ``measure(heights_m, widths_m)`` → what each target limits (P(overturn) at the site, or
        P in 50 years) for each (height, width) pair (arrays of one length), shaped (pair,) when
        one measure serves every target or (pair, target); the expensive step: called once for
        the scan and once per halving, with every open bracket together.
    heights_m : array
        Heights of the families [m].
    targets : sequence of float
        Target probabilities [-].
    scan, count, tolerance :
        Scanned widths (fractions of the height, first and last, and how many) and the
        relative precision of the answer.

    Returns
    -------
    numpy.ndarray
        Shaped (height, target) [m]: the narrowest scanned width where the measure is already
        within the target there; NaN where it exceeds the target still at the widest.
    """
    heights = np.asarray(heights_m, dtype=float)
    fractions = np.geomspace(scan[0], scan[1], count)
    widths = heights[:, None] * fractions[None, :]

    def measured(h, w):
        values = np.asarray(measure(h, w), dtype=float)
        return np.broadcast_to(values.reshape(len(w), -1), (len(w), len(targets)))

    p = measured(np.repeat(heights, count), widths.ravel()).reshape(*widths.shape, len(targets))
    pairs = [(h, t) for h in range(heights.size) for t in range(len(targets))]
    low = np.full(len(pairs), np.nan)
    high = np.full(len(pairs), np.nan)
    for k, (h, t) in enumerate(pairs):
        over = np.flatnonzero(p[h, :, t] > targets[t])
        if over.size == 0:
            high[k] = widths[h, 0]
        elif over[-1] < count - 1:
            low[k], high[k] = widths[h, over[-1]], widths[h, over[-1] + 1]
    limit = np.array([targets[t] for _, t in pairs])
    height_of = np.array([heights[h] for h, _ in pairs])
    target_of = np.array([t for _, t in pairs])
    while True:
        open_ = np.flatnonzero(np.isfinite(low) & (high / low > 1.0 + tolerance))
        if not open_.size:
            break
        middle = np.sqrt(low[open_] * high[open_])
        values = measured(height_of[open_], middle)[np.arange(open_.size), target_of[open_]]
        above = values > limit[open_]
        low[open_[above]] = middle[above]
        high[open_[~above]] = middle[~above]
    return high.reshape(heights.size, len(targets))


@dataclass(frozen=True)
class Family:
    """The records of a check, ready to solve any object of any width at every stripe.

    Attributes
    ----------
    entries : list of records.RecordEntry
    levels : numpy.ndarray
        The check's stripes [unit of its intensity measure].
    intensity : dict
        Each record's intensity (record id → value), so each is scaled to the stripes exactly
        as for the object's own fragility.
    settings : audit.engine.check.settings.CheckSettings
    jobs : int
    scheduler :
        An open scheduler (:func:`~audit.engine.shared.scheduler.open_scheduler`).
    progress : callable, optional
        ``progress(done, total, record_id, how)`` after each record of a pass of
        :data:`PROGRESS_BLOCKS` blocks or more.
    """

    entries: list
    levels: np.ndarray
    intensity: dict
    settings: object
    jobs: int
    scheduler: object
    progress: object = None

    def overturned(self, heights_m, widths_m) -> np.ndarray:
        """Exact overturning of the block of each (height, width) pair [m] under every record at
        every stripe, shaped (record, stripe, block).

        Parameters
        ----------
        heights_m, widths_m : array_like of float
            Full height and full base width of each block [m].
        """
        from audit.engine.shared.blocks import Block
        g = self.settings.g
        blocks = [Block.of_dimensions(w, h, g=g) for h, w in zip(heights_m, widths_m)]
        work = FamilySettings(tuple(b.size_s for b in blocks),
                              tuple(b.alpha_deg for b in blocks), tuple(self.levels),
                              tuple(self.intensity.items()), self.settings.restitution, g,
                              self.settings.free_motion_s, self.jobs)
        parts, _, _ = computed_parts(record_family, self.entries, [], work, self.scheduler,
                                     progress=(self.progress if len(blocks) >= PROGRESS_BLOCKS
                                               else None))
        return np.stack(parts)


def exact_required_widths(family: Family, heights_m, targets, measure,
                          solved: list | None = None) -> np.ndarray:
    """:func:`required_width` of the exact fragility: ``measure(overturned, levels)`` → what
    each target limits, per block (shaped (block,) or (block, target)), from the records'
    outcomes at the stripes (:meth:`Family.overturned`); widths [m] shaped (height, target).
    Every solve is appended to ``solved`` as (heights, widths, outcomes (record, stripe,
    block)), for the family fit (:mod:`audit.engine.check.width_family`).

    Parameters
    ----------
    family : Family
        The records, ready to solve.
    heights_m : array_like of float
        The objects' full heights [m].
    targets : sequence of float
        The limits of the measure (e.g. P(overturn) at the site [-]).
    measure : callable
        ``measure(overturned, levels)`` → the measure per block.
    solved : list, optional
        Where each solve is appended.
    """
    def measured(heights, widths):
        overturned = family.overturned(heights, widths)
        if solved is not None:
            solved.append((np.asarray(heights, dtype=float), np.asarray(widths, dtype=float),
                           overturned))
        return measure(overturned, family.levels)

    return required_width(measured, heights_m, targets)


def overturns_at(procedure, entry, context, objects, widths_m, restitution,
                 g: float) -> np.ndarray:
    """Whether ``procedure`` predicts overturning for each object made as wide as its entry of
    ``widths_m`` under ``entry`` (a record scaled to the site, ``context`` its spectra), all in
    one evaluation: each object's answer is that of an evaluation of it alone.

    Parameters
    ----------
    procedure : procedures.base.Procedure
        The guideline.
    entry : records.RecordEntry
        The record, scaled to the site.
    context : procedures.context.RecordContext
        Its spectra.
    objects : sequence of Block
        The objects; their heights stay.
    widths_m : sequence of float
        Full base width tried for each [m].
    restitution : Restitution
        The impact model.
    g : float
        Acceleration of gravity [m/s²].

    Returns
    -------
    numpy.ndarray of bool
        One answer per object.
    """
    blocks = [obj.with_width(float(width)) for obj, width in zip(objects, widths_m)]
    alpha = [math.radians(block.alpha_deg) for block in blocks]
    # the verdict alone: the iteration reads the record's spectrum at each α's damping only
    # where it goes (a new damping at every width tried)
    return overturning_predictions(
        procedure, [(entry, context.on_demand())],
        np.array([2.0 * math.pi / block.size_s for block in blocks]),
        [(a, np.array([k]), float(restitution.r(a))) for k, a in enumerate(alpha)], g)[0]


def guideline_brackets(overturns, objects, object_overturns) -> tuple[np.ndarray, np.ndarray]:
    """Per object, widths (low, high) [m] at its height with ``overturns`` at low and not at
    high, high/low ≤ :data:`GUIDELINE_STEP`: stepped out from the object's width (whose answer
    is its ``object_overturns``). (0.99 h, +inf) when it predicts overturning up to 0.99 × the
    height; (0, 0.01 h) when it predicts none down to 1 % of the height. The objects step
    together, each through the widths it would try alone, one call of ``overturns`` per step.

    Parameters
    ----------
    overturns : callable
        ``overturns(indices, widths_m)`` → whether the guideline predicts overturning for those
        objects at those widths.
    objects : sequence of Block
        The objects.
    object_overturns : array_like of bool
        The guideline's answer at each object's own width.
    """
    heights = np.array([obj.height_m for obj in objects], dtype=float)
    lowest, highest = 0.01 * heights, 0.99 * heights
    up = np.asarray(object_overturns, dtype=bool)
    # the width last found overturning (going up) or not (going down)
    reached = np.array([obj.width_m for obj in objects], dtype=float)
    low, high = np.full(heights.size, np.nan), np.full(heights.size, np.nan)
    ended_up = up & ~(reached < highest)
    low[ended_up], high[ended_up] = highest[ended_up], math.inf
    ended_down = ~up & ~(reached > lowest)
    low[ended_down], high[ended_down] = 0.0, lowest[ended_down]
    open_ = np.flatnonzero(~(ended_up | ended_down))
    while open_.size:
        going_up = up[open_]
        tried = np.where(going_up, np.minimum(reached[open_] * GUIDELINE_STEP, highest[open_]),
                         np.maximum(reached[open_] / GUIDELINE_STEP, lowest[open_]))
        over = np.asarray(overturns(open_, tried), dtype=bool)
        found = going_up != over  # up: not overturning at last; down: overturning at last
        done = open_[found]
        low[done] = np.where(going_up[found], reached[done], tried[found])
        high[done] = np.where(going_up[found], tried[found], reached[done])
        reached[open_] = tried
        more = open_[~found]
        ended_up = up[more] & ~(reached[more] < highest[more])
        low[more[ended_up]], high[more[ended_up]] = highest[more[ended_up]], math.inf
        ended_down = ~up[more] & ~(reached[more] > lowest[more])
        low[more[ended_down]], high[more[ended_down]] = 0.0, lowest[more[ended_down]]
        open_ = more[~(ended_up | ended_down)]
    return low, high


def accepted_width(low, high, refine, tolerance: float = GUIDELINE_TOLERANCE) -> float:
    """The narrowest width a guideline accepts over records: the ⌈n/2⌉-th smallest of the
    records' narrowest widths c_r (it accepts w when at most half the records have c_r > w),
    each known within its bracket (low_r, high_r]. Only the brackets that straddle the
    order statistic's own bracket are halved (``refine(records, widths)`` → whether each record
    predicts overturning at its width), until it is known to ``tolerance``; +inf when that
    record predicts overturning at every width.

    Parameters
    ----------
    low, high : array_like of float
        Each record's bracket of its narrowest accepted width [m].
    refine : callable
        ``refine(records, widths)`` → whether each of those records predicts overturning at its
        width.
    tolerance : float
        Relative precision of the width [-].
    """
    low, high = np.array(low, dtype=float), np.array(high, dtype=float)
    k = math.ceil(low.size / 2) - 1
    while True:
        bound_low, bound_high = np.sort(low)[k], np.sort(high)[k]
        if not math.isfinite(bound_high) or bound_high <= bound_low * (1.0 + tolerance):
            return float(bound_high)
        straddle = np.flatnonzero((high > bound_low) & (low < bound_high)
                                  & (high > low * (1.0 + tolerance)) & (low > 0.0)
                                  & np.isfinite(high))
        if not straddle.size:
            return float(bound_high)
        middle = np.sqrt(low[straddle] * high[straddle])
        over = np.asarray(refine(straddle, middle), dtype=bool)
        low[straddle[over]] = middle[over]
        high[straddle[~over]] = middle[~over]


__all__ = ["required_width", "exact_required_widths", "Family", "overturns_at", "guideline_brackets",
           "accepted_width", "probability_at_site",
           "record_family", "FamilySettings", "SCAN_FRACTIONS", "SCAN_WIDTHS",
           "WIDTH_TOLERANCE"]
