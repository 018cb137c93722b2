"""The work of a design-level audit, estimated before it starts
(:mod:`audit.engine.shared.guards` refuses or announces it): the exact solver's blocks and the
oscillators of the spectra the procedures read, per record."""

from __future__ import annotations

from audit.engine.shared import guards
from audit.engine.shared.defaults import (DEFAULT_ALPHA_DEG, DEFAULT_MARGINS_SIZES,
                                          DEFAULT_STRIPES)
from audit.engine.shared.grid import size_grid
from audit.engine.shared.runtime import Runtime
from audit.engine.design.settings import MarginsSettings
from procedures.base import SPECTRUM_PERIODS_S

#: Slendernesses of the required-slenderness search per size, and its bisections
#: (:mod:`audit.engine.design.required_alpha`).
SEARCH_ALPHAS, SEARCH_BISECTIONS = 20, 8


def margins_cost(procedures, suite, settings: MarginsSettings,
                 runtime: Runtime) -> guards.Estimate:
    """The work of :func:`audit.engine.design.pipeline.run_margins`: every block at every
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
        guards.suite_motions(suite), settings.free_motion_s,
        blocks=(stripes * (sizes * alphas + len(settings.blocks))
                + (sizes * (SEARCH_ALPHAS + SEARCH_BISECTIONS) if settings.required else 0)),
        oscillators=SPECTRUM_PERIODS_S.size * (slendernesses + search) * readers,
        jobs=runtime.jobs, free_motion_option="solver.free_motion_s",
        settings=(guards.Setting("stripes", stripes, DEFAULT_STRIPES),
                  guards.Setting("size_s", sizes, size_grid(*DEFAULT_MARGINS_SIZES).size),
                  guards.Setting("alpha_deg", alphas, len(DEFAULT_ALPHA_DEG)),
                  guards.Setting("blocks", len(settings.blocks), 0)))


__all__ = ["margins_cost", "SEARCH_ALPHAS", "SEARCH_BISECTIONS"]
