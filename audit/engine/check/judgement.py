"""A guideline's judgement of every object of a check under one record at the site: whether it
predicts overturning, the demand and capacity of each limit state it checks
(:mod:`audit.engine.check.limits`), and the bracket of the narrowest width it passes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from audit.engine.check.limits import limit_readings
from audit.engine.check.guideline_search import guideline_brackets, overturns_at
from audit.physics.block import Restitution
from procedures.overturning import predicts_overturning


@dataclass
class Judgement:
    """A procedure's answer for every object under one record at the site, arrays over objects.

    Attributes
    ----------
    overturns : numpy.ndarray of bool
        It predicts overturning.
    width_low, width_high : numpy.ndarray
        Bracket of the narrowest width at the object's height it does not predict overturning
        for [m] (:func:`~audit.engine.check.guideline_search.guideline_brackets`).
    readings : list
        Per object, the :class:`~audit.engine.check.limits.LimitReading` of each limit state.
    """

    overturns: np.ndarray
    width_low: np.ndarray
    width_high: np.ndarray
    readings: list


def judge(procedure, entry, context, objects, restitution: Restitution, g: float) -> Judgement:
    """``procedure``'s :class:`Judgement` of every object under ``entry`` (scaled to the site).

    Parameters
    ----------
    procedure : procedures.base.Procedure
        The guideline.
    entry : records.RecordEntry
        The record, scaled to the site.
    context : procedures.context.RecordContext
        Its spectra, scaled alike.
    objects : sequence of Block
        The objects checked.
    restitution : Restitution
        The impact model.
    g : float
        Acceleration of gravity [m/s²].
    """
    overturns, readings = np.zeros(len(objects), dtype=bool), []
    for i, obj in enumerate(objects):
        alpha = math.radians(obj.alpha_deg)
        evaluation = procedure.evaluate_for_verdict(
            entry, np.array([2.0 * math.pi / obj.size_s]), alpha, float(restitution.r(alpha)),
            context.on_demand(), g)
        overturns[i] = predicts_overturning(evaluation)[0]
        readings.append(limit_readings(evaluation, alpha))
    low, high = guideline_brackets(
        lambda which, widths: overturns_at(procedure, entry, context,
                                           [objects[k] for k in which], widths, restitution, g),
        objects, overturns)
    return Judgement(overturns, low, high, readings)


def at_site(entry, context, intensity: float, site_im: float):
    """The record scaled to the site's intensity, and its context (the cached spectra scaled).

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    context : procedures.context.RecordContext
        Its cached spectra.
    intensity : float
        The record's intensity as it stands (in the IM's unit, e.g. [g]).
    site_im : float
        The site's intensity, in the same unit.

    Returns
    -------
    tuple of (records.RecordEntry, procedures.context.RecordContext)
    """
    factor = site_im / intensity
    scaled = replace(entry, motion=entry.motion.scaled(float(factor)))
    return scaled, context.scaled(scaled, float(factor))


__all__ = ["Judgement", "judge", "at_site"]
