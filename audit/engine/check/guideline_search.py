"""How a guideline's narrowest accepted width at an object's height is searched, record by
record and over the records.

Per record scaled to the site's intensity, the narrowest width c_r the guideline does not
predict overturning for (its answer is taken as monotone in width for one record); it accepts
a width when it predicts overturning for at most half the records it can evaluate, so its
required width is the ⌈n/2⌉-th smallest c_r. Each c_r is first bracketed by stepping out from
the object's width (:func:`guideline_brackets`); only the brackets that can hold that order
statistic are then halved (:func:`accepted_width`): each try of a procedure whose damping
depends on α (Priestley's β(r(α))) reads a new spectrum of the record.
"""

from __future__ import annotations

import math

import numpy as np

from procedures.overturning import overturning_predictions

#: Step of the guideline's search out from the object's width, as a ratio of widths, and the
#: relative precision of its bisection (2 %): each step of a procedure whose damping depends on
#: α (Priestley's β(r(α))) reads a new spectrum of the record.
GUIDELINE_STEP = 1.5
GUIDELINE_TOLERANCE = 0.02


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


__all__ = ["overturns_at", "guideline_brackets", "accepted_width", "GUIDELINE_STEP",
           "GUIDELINE_TOLERANCE"]
