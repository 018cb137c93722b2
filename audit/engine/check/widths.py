"""How wide an object of a given height must be for a target P(overturn) at the site: the exact
width.

Exact: the objects of one height and any width form a family; each member's multiple-stripe
fragility (the suite's records scaled to the check's stripes, a lognormal fitted to the counts)
gives P(overturn) at the site's intensity, P(w). The required width for a target is the
smallest width above which P(w) stays within the target on a scan of widths geometric from
:data:`SCAN_FRACTIONS` of the height, its last crossing then bisected (in ln w, every record
solved at each midpoint) to :data:`WIDTH_TOLERANCE`: a root of P(w) = target, not a point of
an α grid.

The width each guideline accepts is searched in
:mod:`audit.engine.check.guideline_search`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr

from audit.engine.design.lognormal_fit import lognormal_fits
from audit.engine.shared.scheduler import computed_parts
from audit.physics.rocking import RockingOptions, rocking_blocks

#: Widths scanned, as fractions of the height: the first and last, and how many in between.
SCAN_FRACTIONS = (0.03, 0.95)
SCAN_WIDTHS = 12
#: Relative precision of a required width (0.5 %).
WIDTH_TOLERANCE = 0.005
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
                          r=settings.restitution,
                          options=RockingOptions(settings.g, settings.free_motion_s),
                          jobs=settings.jobs,
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
        p = ndtr(np.log(site_im / medians) / betas)
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


__all__ = ["required_width", "exact_required_widths", "Family", "probability_at_site",
           "record_family", "FamilySettings", "SCAN_FRACTIONS", "SCAN_WIDTHS",
           "WIDTH_TOLERANCE"]
