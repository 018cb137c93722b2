"""Each guideline judged by its own acceptance criterion: one entry of ``check.json`` per
(procedure, limit state), whose verdict is what its demand against its capacity says.

Per record scaled to the site, a procedure's evaluation gives one :class:`LimitReading` per
limit state it checks (:func:`limit_readings`):

* a displacement, velocity or acceleration check of its own (NTC 2018's SLV, d_dem(T_SLV) ≤
  0.4 d₀, and SLC, ≤ 0.6 d₀; Housner's energy check, S_v < S_v,cr), read as it is. The
  uplift check (NTC's SLD) says nothing about overturning or damage and is left out, and a
  linear check the text refines by a displacement one of the same limit state (NTC's
  SLV-linear) gives way to it. Where a check passes on a rule besides demand ≤ capacity
  (NTC's SLV passes where SLD does: the block does not uplift, a_g,SLD governs, §C8.7.1.2.1.8)
  its demand is the block's, 0: the block does not move;
* else its rotation estimate θ against α ("overturning"), +inf where the estimate reaches α.
  Neither Priestley, Evison & Carr (1978) nor FEMA 356 as the project has them (through Makris
  & Konstantinidis 2001, §8 and §9) states a capacity below α.

A procedure reading only the site's design spectrum gives one reading for every record. A
procedure reading each record gives one per record, made one demand by its rule for a suite
(:data:`SUITE_RULES`): NTC 2018 takes the mean of the records' effects with at least
:data:`NTC_MEAN_RECORDS` records and the largest with fewer (NTC 2018 §7.3.5, the rule the
Circolare's §C8.7.1.2.1.9 applies to a local mechanism's peak displacements; known here
second-hand, from the project's reference notes); the others the suite's median, the
⌈n/2⌉-th smallest demand (Housner's S_v,cr is the velocity at which a block overturns with
about 50 % probability; Priestley's paper reads one spectrum and gives no rule for a suite).
The share of records whose own demand exceeds the capacity stays beside it, as information.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from audit import G
from audit.engine.shared.defaults import BOTH, LIMIT_STATES
from procedures.base import EXACT_UPLIFT, OVERTURN
#: A linear check the text refines by a displacement check of the named limit state.
SUPERSEDED = {"SLV-linear": "SLV"}
#: How a procedure reading each record makes the records' demands one (default MEDIAN).
MEAN, MEDIAN = "mean", "median"
SUITE_RULES = {"ntc2018": MEAN}
#: Fewest records whose mean effect NTC 2018 §7.3.5 accepts (the largest below it).
NTC_MEAN_RECORDS = 7


@dataclass(frozen=True)
class LimitReading:
    """One limit state of a procedure for one block under one record.

    Attributes
    ----------
    limit_state : str
    demand, capacity : float
        In ``unit`` (+inf demand where a rotation estimate reaches α).
    unit : str
        ``deg``, ``m``, ``m/s`` or ``g``.
    theta_limit_rad : float
        Exact peak rotation at and above which the exact response exceeds this limit [rad]
        (α for overturning).
    quantity : str
        What is compared, in words.
    factors : dict
        Named factors of the check, e.g. the period the demand was read at (``T_LS_s``).
    """

    limit_state: str
    demand: float
    capacity: float
    unit: str
    theta_limit_rad: float
    quantity: str
    factors: dict = field(default_factory=dict)


def _first(values) -> float:
    return float(np.ravel(values)[0])


def limit_readings(evaluation, alpha_rad: float) -> list[LimitReading]:
    """The :class:`LimitReading` of each limit state ``evaluation`` (one block) checks (see the
    module).

    Parameters
    ----------
    evaluation : procedures.base.Evaluation
        The procedure's evaluation of one block.
    alpha_rad : float
        The block's slenderness α [rad] (the rotation limit where a check states none).
    """
    readings = []
    states = {check.limit_state for check in evaluation.checks}
    for check in evaluation.checks:
        if check.exact_event == EXACT_UPLIFT or SUPERSEDED.get(check.limit_state) in states:
            continue
        for demand, capacity, unit, scale, words in (
                (check.demand_m, check.capacity_m, "m", 1.0, "displacement demand"),
                (check.demand_m_s, check.capacity_m_s, "m/s", 1.0, "velocity demand"),
                (check.demand_m_s2, check.capacity_m_s2, "g", 1.0 / G, "acceleration demand")):
            demand, capacity = _first(demand) * scale, _first(capacity) * scale
            if not (math.isfinite(demand) and math.isfinite(capacity)):
                continue
            if bool(np.ravel(check.passes)[0]) and demand > capacity:
                demand = 0.0  # passes on its other rule: the block does not uplift
            limit, period = _first(check.theta_limit_rad), _first(check.period_s)
            readings.append(LimitReading(
                check.limit_state, demand, capacity, unit,
                limit if math.isfinite(limit) else alpha_rad,
                f"{words} against {check.limit_state} capacity",
                {"T_LS_s": period} if math.isfinite(period) else {}))
            break
    if evaluation.estimate is not None and not any(r.unit == "m" for r in readings):
        estimate = evaluation.estimate
        theta = (math.inf if estimate.outcome[0] == OVERTURN
                 else math.degrees(_first(estimate.theta)))
        readings.insert(0, LimitReading("overturning", theta, math.degrees(alpha_rad), "deg",
                                        alpha_rad, "peak rotation θ against α"))
    return readings


def wanted(limit_state: str, chosen: str) -> bool:
    """Whether an entry of ``limit_state`` is reported when ``chosen`` (SLV, SLC or both).

    Parameters
    ----------
    limit_state : str
        The entry's limit state (``SLV``, ``SLC``, or another procedure's).
    chosen : str
        The limit states asked for: ``SLV``, ``SLC`` or ``both``.
    """
    return chosen == BOTH or limit_state not in LIMIT_STATES or limit_state == chosen


def suite_rule(key: str, records: int) -> str:
    """How procedure ``key`` makes ``records`` records' demands one: mean, median or max.

    Parameters
    ----------
    key : str
        The procedure's name.
    records : int
        Number of records.
    """
    rule = SUITE_RULES.get(key, MEDIAN)
    return "max" if rule == MEAN and records < NTC_MEAN_RECORDS else rule


def suite_demand(demands, rule: str) -> float:
    """The records' demands made one by ``rule`` (mean, max, or median: the ⌈n/2⌉-th smallest,
    so a demand of +inf counts as any other).

    Parameters
    ----------
    demands : array_like of float
        Each record's demand.
    rule : str
        ``mean``, ``median`` or ``max``.
    """
    values = np.sort(np.asarray(demands, dtype=float))
    if rule == MEAN:
        return float(values.mean())
    if rule == "max":
        return float(values[-1])
    return float(values[math.ceil(values.size / 2) - 1])


def basis(rule: str | None, records: int, unit: str) -> str:
    """How an entry's verdict follows from its demand and capacity, in one sentence.

    Parameters
    ----------
    rule : str or None
        ``mean``, ``median`` or ``max``; None for an entry that reads only the design spectrum.
    records : int
        Number of records.
    unit : str
        Unit of the entry's demand (``deg`` for a rotation).
    """
    compare = ("passes when θ stays below α (no overturning)" if unit == "deg"
               else "passes when the demand is at most the capacity")
    if rule is None:
        return f"reads only the site's design spectrum (one demand for every record); {compare}"
    how = {MEAN: f"the mean of the {records} records' demands (NTC 2018 §7.3.5: the mean "
                 f"effect of at least {NTC_MEAN_RECORDS} records)",
           "max": f"the largest of the {records} records' demands (NTC 2018 §7.3.5: fewer "
                  f"than {NTC_MEAN_RECORDS} records)",
           MEDIAN: f"the median of the {records} records' demands (the ⌈n/2⌉-th smallest: it "
                   "passes when at most half the records exceed the capacity)"}[rule]
    return f"applied record by record; the demand is {how}; {compare}"


def verdict(demand: float, capacity: float) -> str:
    """What demand against capacity says (NaN either: cannot judge).

    Parameters
    ----------
    demand, capacity : float
        In the same unit.
    """
    if math.isnan(demand) or math.isnan(capacity):
        return "cannot judge"
    return "passes" if demand <= capacity else "fails"


def p_exceed_at_site(theta_rad, overturned, levels, site_im: float, limit_rad: float,
                     p_overturn: float, fitted=None) -> float:
    """Exact P at the site's intensity of the peak rotation reaching ``limit_rad`` (or
    overturning), from the records' exact peaks at the stripes (shaped (record, stripe)), by the
    rule of P(overturn) at the site (:mod:`audit.engine.design.site_probability`): the lognormal
    fitted to the lattice stripes' counts (its maximum by Fisher scoring,
    :func:`~audit.engine.design.lognormal_fit.lognormal_fits`), unless the count at the site's
    own stripe rejects it (the rule reads no band, so none is drawn). A limit no record reaches short of overturning is P(overturn)
    itself; exceeding a limit ≤ α includes overturning, so the answer is at least
    ``p_overturn`` even where the two estimates cross.

    Parameters
    ----------
    theta_rad : array_like of float
        Exact peak rotations [rad], shaped (record, stripe).
    overturned : array_like of bool
        Whether each record overturns the block at each stripe, shaped alike.
    levels : array_like of float
        The stripes' intensities (in the IM's unit, e.g. [g]), the site's among them.
    site_im : float
        The site's intensity, in the same unit.
    limit_rad : float
        The limit rotation [rad].
    p_overturn : float
        P(overturn) at the site [-], the least the answer can be.
    fitted : array_like of bool, optional
        Which stripes the lognormal is fitted on (the lattice's); every one when None.
    """
    from audit.engine.check.widths import probability_at_site
    from audit.engine.design.site_probability import site_probability
    overturned = np.asarray(overturned, dtype=bool)
    exceeded = overturned | (np.asarray(theta_rad) >= limit_rad)
    if np.array_equal(exceeded, overturned):
        return p_overturn
    levels = np.asarray(levels, dtype=float)
    fitted = np.ones(levels.size, dtype=bool) if fitted is None else np.asarray(fitted)
    model = float(probability_at_site(exceeded[:, fitted, None], levels[fitted], site_im)[0])
    site = int(np.argmin(np.abs(levels - site_im)))
    at = site_probability(model, None, int(exceeded[:, site].sum()), exceeded.shape[0])
    return max(at.p, p_overturn)


__all__ = ["LimitReading", "limit_readings", "wanted", "suite_rule", "suite_demand", "basis",
           "verdict", "p_exceed_at_site", "LIMIT_STATES", "BOTH", "SUITE_RULES", "MEAN",
           "MEDIAN", "NTC_MEAN_RECORDS", "SUPERSEDED"]
