"""The work of a check, estimated before it starts (:mod:`audit.engine.shared.guards` refuses
or announces it): the exact solver's blocks and the oscillators of the spectra the guidelines
read, per record."""

from __future__ import annotations

import math

from audit.engine.shared import guards
from audit.engine.shared.lattice import stripe_lattice
from audit.engine.shared.runtime import Runtime
from audit.engine.check.pipeline import LATTICE_EVERY, TARGETS
from audit.engine.check.settings import CheckSettings
from audit.engine.check.widths import SCAN_FRACTIONS, SCAN_WIDTHS, WIDTH_TOLERANCE

#: A check reads its spectra on demand: periods an iteration of a procedure's rotation estimate
#: visits (an upper figure), and the widths a guideline's search tries beyond the object's own
#: (stepping out by 1.5× between 1 % and 99 % of the height, ≤ 11 steps, then ≤ 5 halvings).
ITERATION_PERIODS, GUIDELINE_TRIES = 10, 16


def width_halvings() -> int:
    """Halvings (in ln w) of one bracket of the exact width search of
    :mod:`audit.engine.check.widths`: from the ratio between neighbouring scanned widths,
    (f_last/f_first)^(1/(count − 1)), down to 1 + WIDTH_TOLERANCE."""
    step = math.log(SCAN_FRACTIONS[1] / SCAN_FRACTIONS[0]) / (SCAN_WIDTHS - 1)
    return math.ceil(math.log2(step / math.log1p(WIDTH_TOLERANCE)))


def check_cost(procedures, suite, objects: int, settings: CheckSettings,
               runtime: Runtime, searched: int | None = None) -> guards.Estimate:
    """The work of :func:`audit.engine.check.pipeline.run_check`, per record: every object at every
    stripe, then its exact width search at its height (the scanned widths, and each target's
    bracket halved), each at every stripe; with a hazard curve, also the object at the width
    each guideline requires. Each procedure reading the record reads its spectrum at every
    object's damping, on demand: the periods its iteration visits, at the object's width and
    at each width the guideline's search tries.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The guidelines checked.
    suite : records.RecordSuite
        The records.
    objects : int
        Number of objects checked.
    settings : CheckSettings
        The check's settings (hazard, free-motion time).
    runtime : Runtime
        How it runs (the number of jobs).
    searched : int, optional
        Objects whose exact width search is solved; the others' reads an atlas
        (:mod:`audit.engine.check.atlas_side`). Every object when None.
    """
    stripes = stripe_lattice(LATTICE_EVERY).size + 1  # and the site's own
    targets = len(TARGETS) + (settings.hazard is not None)
    per_object = 1 + (len(procedures) if settings.hazard is not None else 0)
    search = SCAN_WIDTHS + targets * width_halvings()
    searched = objects if searched is None else searched
    readers = sum(p.requires_motion for p in procedures)
    return guards.estimate(
        guards.suite_motions(suite), settings.free_motion_s,
        blocks=stripes * (objects * per_object + searched * search),
        oscillators=ITERATION_PERIODS * (1 + GUIDELINE_TRIES) * readers * objects,
        jobs=runtime.jobs, free_motion_option="solver.free_motion_s",
        settings=(guards.Setting("objects", objects, 0),))


__all__ = ["check_cost", "width_halvings", "ITERATION_PERIODS", "GUIDELINE_TRIES"]
