"""A guideline's judgement of every object of a check under one record at the site: whether it
predicts overturning, the numbers it compares, and the bracket of the narrowest width it passes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from audit import G
from audit.engine.check_widths import guideline_bracket, overturns_at
from audit.physics.block import Restitution
from procedures.base import EXACT_OVERTURNING, OVERTURN
from procedures.overturning import predicts_overturning


@dataclass
class Judgement:
    """A procedure's answer for every object under one record at the site, arrays over objects.

    Attributes
    ----------
    overturns : numpy.ndarray of bool
        It predicts overturning.
    demand, capacity : numpy.ndarray
        The numbers it compares (+inf demand where its rotation estimate reaches α).
    width_low, width_high : numpy.ndarray
        Bracket of the narrowest width at the object's height it does not predict overturning
        for [m] (:func:`~audit.engine.check_widths.guideline_bracket`).
    quantity, unit : list of str
        What the numbers are, and their unit.
    """

    overturns: np.ndarray
    demand: np.ndarray
    capacity: np.ndarray
    width_low: np.ndarray
    width_high: np.ndarray
    quantity: list
    unit: list


def compared_numbers(evaluation, alpha_rad: float) -> tuple[str, str, float, float]:
    """(quantity, unit, demand, capacity) a procedure compares for one block: its rotation
    estimate against α [degrees], else its overturning check's demand and capacity."""
    if evaluation.estimate is not None:
        estimate = evaluation.estimate
        demand = (math.inf if estimate.outcome[0] == OVERTURN
                  else math.degrees(float(estimate.theta[0])))
        return "peak rotation θ against α", "deg", demand, math.degrees(alpha_rad)
    for check in evaluation.checks:
        if check.exact_event != EXACT_OVERTURNING:
            continue
        for demand, capacity, unit, scale in ((check.demand_m_s, check.capacity_m_s, "m/s", 1.0),
                                              (check.demand_m_s2, check.capacity_m_s2, "g", 1 / G),
                                              (check.demand_m, check.capacity_m, "m", 1.0)):
            first = float(np.ravel(demand)[0])
            if math.isfinite(first):
                return (f"{check.limit_state} check", unit, first * scale,
                        float(np.ravel(capacity)[0]) * scale)
    return "", "", math.nan, math.nan


def judge(procedure, entry, context, objects, restitution: Restitution, g: float) -> Judgement:
    """``procedure``'s :class:`Judgement` of every object under ``entry`` (scaled to the site)."""
    out = Judgement(np.zeros(len(objects), dtype=bool), *np.full((4, len(objects)), np.nan),
                    [], [])
    for i, obj in enumerate(objects):
        alpha = math.radians(obj.alpha_deg)
        evaluation = procedure.evaluate_for_verdict(
            entry, np.array([2.0 * math.pi / obj.size_s]), alpha, float(restitution.r(alpha)),
            context.on_demand(), g)
        out.overturns[i] = predicts_overturning(evaluation)[0]
        quantity, unit, out.demand[i], out.capacity[i] = compared_numbers(evaluation, alpha)
        out.quantity.append(quantity)
        out.unit.append(unit)
        out.width_low[i], out.width_high[i] = guideline_bracket(
            lambda width: overturns_at(procedure, entry, context, obj, width, restitution, g),
            obj, out.overturns[i])
    return out


def at_site(entry, context, intensity: float, site_im: float):
    """The record scaled to the site's intensity, and its context (the cached spectra scaled)."""
    factor = site_im / intensity
    scaled = replace(entry, motion=entry.motion.scaled(float(factor)))
    return scaled, context.scaled(scaled, float(factor))


__all__ = ["Judgement", "compared_numbers", "judge", "at_site"]
