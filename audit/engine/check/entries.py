"""The guideline entries of one object in ``check.json``: one per (procedure, limit state), in
the shape every guideline of a check shares (``docs/check.md``), each verdict what its demand
against its capacity says (:mod:`audit.engine.check.limits`), beside the exact P at the site of
exceeding that same limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from audit.engine.check.limits import (MEDIAN, basis, p_exceed_at_site, suite_demand,
                                       suite_rule, verdict, wanted)

#: Relative precision of the width a mean-rule entry requires (1 %).
RULE_WIDTH_TOLERANCE = 0.01


def _number(value) -> float | None:
    return float(value) if value is not None and math.isfinite(value) else None


class GuidelineJudgement(NamedTuple):
    """One guideline's judgement of one object, what its entries are made of
    (:meth:`~audit.engine.check.guideline_widths.GuidelineWidths.of`).

    Attributes
    ----------
    proc : procedures.base.Procedure
        The guideline.
    judgements : list of audit.engine.check.judgement.Judgement
        One per record it judged (one for a procedure reading only the site).
    line : float
        Where on the stripes it turns to predicting overturning for half the records.
    width : float
        The narrowest width at which at most half the records predict overturning [m]: the
        required width of a median-rule entry.
    rule_widths : dict
        Required width [m] by limit state, of an entry whose suite rule is not the median.
    site_only : bool
        It reads only the site's design spectrum.
    """

    proc: object
    judgements: list
    line: float
    width: float
    rule_widths: dict
    site_only: bool


@dataclass(frozen=True)
class ExactRotations:
    """The object's exact response at the check's stripes: peak rotations and overturning
    (record, stripe), the stripes (the site's among them), the site's intensity and
    P(overturn) there, and which stripes the fragility is fitted on; the answers per limit found
    so far (one per limit rotation: guidelines share theirs). Rotations and overturning None
    where they are not solved (an atlas's object that no guideline judges short of overturning):
    then every limit is the object's α (``alpha_rad``) and its P(exceed) is P(overturn)."""

    theta_rad: np.ndarray | None
    overturned: np.ndarray | None
    levels: np.ndarray
    site_im: float
    p_overturn: float
    fitted: np.ndarray | None = None
    found: dict = field(default_factory=dict)
    alpha_rad: float | None = None

    def p_exceed(self, limit_rad: float) -> float:
        """Exact P at the site's intensity of the peak rotation reaching ``limit_rad`` (or
        overturning): :func:`~audit.engine.check.limits.p_exceed_at_site` of these rotations.

        Parameters
        ----------
        limit_rad : float
            The limit rotation [rad].
        """
        if self.theta_rad is None:
            # exceeding α is overturning; a limit short of it needs the rotations (not solved)
            if not limit_rad >= self.alpha_rad * (1.0 - 1e-12):
                raise ValueError(f"a limit of {limit_rad} rad, short of α, needs the exact "
                                 "rotations, which were not solved")
            return self.p_overturn
        if limit_rad not in self.found:
            self.found[limit_rad] = p_exceed_at_site(
                self.theta_rad, self.overturned, self.levels, self.site_im, limit_rad,
                self.p_overturn, self.fitted)
        return self.found[limit_rad]


def _blank(proc, limit_state: str) -> dict:
    return {"procedure": proc.title, "key": proc.name, "limit_state": limit_state,
            "verdict": "cannot judge", "demand": None, "capacity": None, "unit": None,
            "basis": None, "share_of_records_overturning": None, "factors": {},
            "anchorage_force_over_weight": None, "exact_p_exceed": None,
            "required_width_m": None, "quantity": None, "records_judged": 0,
            "guideline_im": None, "reason": None, "risk_p50": None, "spectrum_read": None}


def procedure_entries(guideline: GuidelineJudgement, b: int, exact: ExactRotations, chosen: str,
                      first_entry, risk_p50: float | None) -> list[dict]:
    """The entries of one procedure for object ``b`` (see the module).

    Parameters
    ----------
    guideline : GuidelineJudgement
        The guideline's judgement of the object: its judgements, its line on the stripes, its
        required widths, whether it reads only the site.
    b : int
        The object's index in the judgements.
    exact : ExactRotations
        The object's exact response at the stripes.
    chosen : str
        The limit state asked for (SLV, SLC or both).
    first_entry : records.RecordEntry
        The suite's first record, asked why the guideline cannot evaluate it when it judged none.
    risk_p50 : float or None
        P of overturning in 50 years at the required width [-], reported on a median-rule entry.
    """
    proc, judgements, line, width, rule_widths, site_only = guideline
    if not judgements:
        entry = _blank(proc, "overturning")
        entry["reason"] = (proc.unmet_requirements(first_entry)
                           or "it can evaluate no record of the suite")
        return [entry]
    share = float(np.mean([j.overturns[b] for j in judgements]))
    states = [r.limit_state for r in judgements[0].readings[b]]
    out = []
    for state in states:
        if not wanted(state, chosen):
            continue
        readings = [next(r for r in j.readings[b] if r.limit_state == state)
                    for j in judgements]
        rule = None if site_only else suite_rule(proc.name, len(readings))
        demands = np.array([r.demand for r in readings])
        settled = demands[~np.isnan(demands)]  # a rotation iteration may settle on none
        demand = suite_demand(settled, rule or MEDIAN) if settled.size else math.nan
        capacity = float(np.median([r.capacity for r in readings]))
        entry = _blank(proc, state)
        reasons = []
        if math.isinf(demand):
            reasons.append("its rotation estimate reaches α (overturning)"
                           + (" for at least half the records" if len(readings) > 1 else "")
                           + ": θ ≥ α")
        elif math.isnan(demand):
            reasons.append("its iteration settles on no rotation for any record")
        by_width = state in rule_widths or rule not in (None, MEDIAN)
        required = rule_widths.get(state, math.nan) if by_width else width
        if math.isinf(required):
            reasons.append("no width up to 0.99 × the height passes it (restrain the object)")
        entry.update(
            verdict="fails" if math.isinf(demand) else verdict(demand, capacity),
            demand=_number(demand), capacity=_number(capacity), unit=readings[0].unit,
            basis=basis(rule, len(readings), readings[0].unit) + (
                f"; {proc.basis_note}" if proc.basis_note else ""),
            share_of_records_overturning=share,
            exact_p_exceed=exact.p_exceed(readings[0].theta_limit_rad),
            required_width_m=_number(required), quantity=readings[0].quantity,
            factors=readings[0].factors,
            records_judged=len(readings), guideline_im=_number(line),
            reason="; ".join(reasons) or None,
            risk_p50=None if by_width else risk_p50, spectrum_read=proc.spectrum_read(first_entry))
        out.append(entry)
    return out


def rule_width(demand_capacity, obj, rule: str,
               tolerance: float = RULE_WIDTH_TOLERANCE) -> float:
    """The narrowest width at the object's height [m] whose suite demand (by ``rule``) is at
    most its capacity, bisected in ln w between 1 % and 99 % of the height (the demand taken
    as falling against the capacity as the width grows). ``demand_capacity(width)`` → the
    records' (demands, capacity) there. +inf where even 0.99 h fails.

    Parameters
    ----------
    demand_capacity : callable
        ``demand_capacity(width_m)`` → (each record's demand, the capacity) at that width, in the
        entry's unit.
    obj : Block
        The object; its height stays.
    rule : str
        How the records' demands are made one: ``mean``, ``median`` or ``max``.
    tolerance : float
        Relative precision of the width [-].
    """
    def passes(width: float) -> bool:
        demands, capacity = demand_capacity(width)
        return suite_demand(demands, rule) <= capacity

    low, high = 0.01 * obj.height_m, 0.99 * obj.height_m
    if not passes(high):
        return math.inf
    if passes(low):
        return low
    while high > low * (1.0 + tolerance):
        middle = math.sqrt(low * high)
        if passes(middle):
            high = middle
        else:
            low = middle
    return high


__all__ = ["procedure_entries", "rule_width", "ExactRotations", "GuidelineJudgement",
           "RULE_WIDTH_TOLERANCE"]
