"""The work of an audit and of a design-level audit, estimated before it starts
(:mod:`audit.engine.shared.guards` refuses or announces it): the exact solver's blocks and the
oscillators of the spectra the procedures read, per record."""

from __future__ import annotations

import math

from audit.engine.shared import guards
from audit.engine.check.settings import CheckSettings
from audit.engine.shared.defaults import (DEFAULT_ALPHA_DEG, DEFAULT_MARGINS_SIZES, DEFAULT_SIZES,
                                   DEFAULT_STRIPES)
from audit.engine.shared.grid import size_grid
from audit.engine.design.settings import MarginsSettings
from audit.engine.shared.runtime import Runtime
from audit.engine.run.settings import AuditSettings
from procedures.base import SPECTRUM_PERIODS_S

#: Damping ratios of the record spectra every audited record gets (Figures 5.x).
RECORD_SPECTRA = 3
#: Slendernesses of the required-slenderness search per size, and its bisections
#: (:mod:`audit.engine.design.required_alpha`).
SEARCH_ALPHAS, SEARCH_BISECTIONS = 20, 8
#: A check reads its spectra on demand: periods an iteration of a procedure's rotation estimate
#: visits (an upper figure), and the widths a guideline's search tries beyond the object's own
#: (stepping out by 1.5× between 1 % and 99 % of the height, ≤ 11 steps, then ≤ 5 halvings).
ITERATION_PERIODS, GUIDELINE_TRIES = 10, 16


def _motions(suite) -> list:
    return [entry.motion for entry in suite if entry.motion is not None]


def audit_cost(procedures, suite, settings: AuditSettings, runtime: Runtime) -> guards.Estimate:
    """The work of :func:`audit.engine.run.suite_run.audit_suite`: every block solved once, twice
    more for the fragility flag (record × (1 ± ε)), once more per alternative model; the
    record's spectra and each procedure's at each slenderness.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    suite : records.RecordSuite
        The records.
    settings : AuditSettings
        The audit's settings (grid, free-motion time, fragility and sensitivity flags).
    runtime : Runtime
        How it runs (the number of jobs).
    """
    sizes, alphas = len(settings.size_s), len(settings.alpha_deg)
    return guards.estimate(
        _motions(suite), settings.free_motion_s,
        blocks=sizes * alphas * ((3 if settings.robustness else 1) + len(settings.sensitivity)),
        oscillators=SPECTRUM_PERIODS_S.size * (RECORD_SPECTRA + alphas * len(procedures)),
        jobs=runtime.jobs,
        settings=(guards.Setting("size_s", sizes, size_grid(*DEFAULT_SIZES).size),
                  guards.Setting("alpha_deg", alphas, len(DEFAULT_ALPHA_DEG))))


def margins_cost(procedures, suite, settings: MarginsSettings,
                 runtime: Runtime) -> guards.Estimate:
    """The work of :func:`audit.engine.design.pipeline.design_level_audit`: every block at every
    stripe, then the required-slenderness grid and its bisections; the spectra each procedure
    that reads the record's spectra (its rotation estimate) computes at each slenderness (once
    per record, scaled to every stripe) and at each of the search's.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    suite : records.RecordSuite
        The records.
    settings : MarginsSettings
        The design-level settings (stripes, grid, blocks, required-α search).
    runtime : Runtime
        How it runs (the number of jobs).
    """
    stripes = DEFAULT_STRIPES if settings.stripes is None else len(settings.stripes)
    sizes, alphas = len(settings.size_s), len(settings.alpha_deg)
    slendernesses = len({*settings.alpha_deg, *(b.alpha_deg for b in settings.blocks)})
    search = SEARCH_ALPHAS if settings.required else 0
    readers = sum(p.requires_motion and p.estimates_rotation for p in procedures)
    return guards.estimate(
        _motions(suite), settings.free_motion_s,
        blocks=(stripes * (sizes * alphas + len(settings.blocks))
                + (sizes * (SEARCH_ALPHAS + SEARCH_BISECTIONS) if settings.required else 0)),
        oscillators=SPECTRUM_PERIODS_S.size * (slendernesses + search) * readers,
        jobs=runtime.jobs,
        settings=(guards.Setting("stripes", stripes, DEFAULT_STRIPES),
                  guards.Setting("size_s", sizes, size_grid(*DEFAULT_MARGINS_SIZES).size),
                  guards.Setting("alpha_deg", alphas, len(DEFAULT_ALPHA_DEG)),
                  guards.Setting("blocks", len(settings.blocks), 0)))


def width_halvings() -> int:
    """Halvings (in ln w) of one bracket of the exact width search of
    :mod:`audit.engine.check.widths`: from the ratio between neighbouring scanned widths,
    (f_last/f_first)^(1/(count − 1)), down to 1 + WIDTH_TOLERANCE."""
    from audit.engine.check.widths import SCAN_FRACTIONS, SCAN_WIDTHS, WIDTH_TOLERANCE
    step = math.log(SCAN_FRACTIONS[1] / SCAN_FRACTIONS[0]) / (SCAN_WIDTHS - 1)
    return math.ceil(math.log2(step / math.log1p(WIDTH_TOLERANCE)))


def check_cost(procedures, suite, objects: int, settings: CheckSettings,
               runtime: Runtime) -> guards.Estimate:
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
    """
    # imported here: run and margins estimate their work without the check's modules
    from audit.engine.check.pipeline import LATTICE_EVERY, TARGETS
    from audit.engine.check.widths import SCAN_WIDTHS
    from audit.engine.shared.lattice import stripe_lattice
    stripes = stripe_lattice(LATTICE_EVERY).size + 1  # and the site's own
    targets = len(TARGETS) + (settings.hazard is not None)
    per_object = 1 + SCAN_WIDTHS + targets * width_halvings()
    per_object += len(procedures) if settings.hazard is not None else 0
    readers = sum(p.requires_motion for p in procedures)
    return guards.estimate(
        _motions(suite), settings.free_motion_s, blocks=stripes * objects * per_object,
        oscillators=ITERATION_PERIODS * (1 + GUIDELINE_TRIES) * readers * objects,
        jobs=runtime.jobs,
        settings=(guards.Setting("objects", objects, 0),))


__all__ = ["audit_cost", "margins_cost", "check_cost", "width_halvings"]
