"""The width each guideline requires at an object's height, searched for every object of a
check together (:class:`GuidelineWidths`): by the median of the records (the order statistic
of each record's narrowest accepted width, :func:`~audit.engine.check.guideline_search.accepted_width`),
and, for a guideline whose suite rule is another (NTC 2018's mean), the width whose suite
demand meets its capacity (:func:`~audit.engine.check.entries.rule_width`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from audit.engine.check.entries import GuidelineJudgement, rule_width
from audit.engine.check.limits import MEDIAN, limit_readings, suite_rule
from audit.engine.check.settings import CheckSettings
from audit.engine.check.guideline_search import accepted_width, overturns_at


@dataclass
class GuidelineWidths:
    """What the guidelines' width searches of a check read: the records' parts, each
    procedure's line on the stripes by block
    (:func:`~audit.engine.design.guideline_lines.guideline_lines`, as ``margins`` draws it), the answers of procedures that read only the site, the records scaled to the site
    (``site_context(i)``) and the settings; and the suite-rule widths found so far. A suite
    rule's width depends on the object's height alone (its search spans 1–99 % of the height),
    so the objects of one height share it, and a width's evaluation gives every limit state."""

    parts: list
    lines: dict
    site_judged: dict
    site_context: object
    settings: CheckSettings
    rule_widths: dict = field(default_factory=dict)
    readings: dict = field(default_factory=dict)

    def of(self, proc, b: int, obj) -> GuidelineJudgement:
        """The guideline's judgement of object ``b``: its judgements, its line on the stripes,
        its required width [m] by the median of the records, by limit state the width of an
        entry whose suite rule is another (:func:`~audit.engine.check.entries.rule_width`),
        whether it reads only the site.

        Parameters
        ----------
        proc : procedures.Procedure
        b : int
            The object's index in the check.
        obj : audit.engine.shared.blocks.Block
            The object.
        """
        parts, settings, site_context = self.parts, self.settings, self.site_context
        site_only = proc.name in self.site_judged
        records = ([0] if site_only else
                   [i for i, part in enumerate(parts) if proc.name in part.judged])
        mine = ([self.site_judged[proc.name]] if site_only
                else [parts[i].judged[proc.name] for i in records])
        line = float(self.lines[proc.name][b])
        width = math.nan
        if mine:
            def refine(which, widths):
                return [bool(overturns_at(proc, *site_context(records[k]), [obj], [w],
                                          settings.restitution, settings.g)[0])
                        for k, w in zip(which, widths)]
            width = accepted_width([j.width_low[b] for j in mine],
                                   [j.width_high[b] for j in mine], refine)
        rule_widths = {}
        rule = suite_rule(proc.name, len(records))
        # a site-only guideline has one demand, whatever its rule: the width where it meets its
        # capacity is the entry's (its line of overturning is not: NTC's SLV fails before d₀)
        if mine and rule != MEDIAN:
            for state in {r.limit_state for r in mine[0].readings[b]}:
                key = (proc.name, state, obj.height_m)
                if key not in self.rule_widths:
                    self.rule_widths[key] = rule_width(
                        lambda w, state=state: self._state_readings(proc, state, obj, w,
                                                                    records), obj, rule)
                rule_widths[state] = self.rule_widths[key]
        return GuidelineJudgement(proc, mine, line, width, rule_widths, site_only)

    def _state_readings(self, proc, state, obj, width_m, records):
        """The records' demands at limit state ``state`` of the object made ``width_m`` wide,
        and its capacity."""
        key = (proc.name, obj.height_m, width_m)
        if key not in self.readings:
            block = obj.with_width(width_m)
            alpha = math.radians(block.alpha_deg)
            p = np.array([2.0 * math.pi / block.size_s])
            restitution, g = self.settings.restitution, self.settings.g
            readings = []
            for i in records:
                entry, context = self.site_context(i)
                evaluation = proc.evaluate_for_verdict(entry, p, alpha,
                                                       float(restitution.r(alpha)),
                                                       context.on_demand(), g)
                readings += limit_readings(evaluation, alpha)
            self.readings[key] = readings
        mine = [r for r in self.readings[key] if r.limit_state == state]
        return [r.demand for r in mine], mine[0].capacity


__all__ = ["GuidelineWidths"]
