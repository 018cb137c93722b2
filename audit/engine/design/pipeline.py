"""The design-level audit from start to end: the stripes (:mod:`audit.engine.design.margins`), the
required slenderness of each size (:mod:`audit.engine.design.required_alpha`), the fine amplitude
scans, on one scheduler, and the risk at the site where a hazard curve is given
(:mod:`audit.engine.design.margins_risk`)."""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import replace

from audit.engine.shared.defaults import DEFAULT_STRIPES
from audit.engine.design.margins import MarginsRun, margins_tables
from audit.engine.design.scans import amplitude_scans
from audit.engine.design.margins_risk import hazard_summary, hazard_table, margins_risk
from audit.engine.design.settings import MarginsSettings
from audit.engine.design.p695_acceptance import p695_acceptance
from audit.engine.design.required_alpha import required_alpha
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.scheduler import open_scheduler


def run_margins(procedures, suite, settings: MarginsSettings, runtime: Runtime,
                atlas=None) -> MarginsRun:
    """Everything of the design-level audit, its tables in a :class:`MarginsRun`.

    A ``runtime.progress`` with a ``stage(text)`` method (:class:`audit.engine.shared.progress.Progress`)
    is told each stage.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    suite : records.RecordSuite
        The records.
    settings : MarginsSettings
        The design-level settings.
    runtime : Runtime
        How it runs.
    atlas : audit.engine.atlas.fragility_read.AtlasReading, optional
        The atlas the blocks' exact fragilities are read from (at its stripes); the required
        slenderness, the acceptance and the guidelines stay direct, and no amplitude scan is
        made (:data:`~audit.engine.design.margins.MARGINS_NOT_ANSWERED`).
    """
    stage = getattr(runtime.progress, "stage", lambda text: None)
    blocks = len(settings.size_s) * len(settings.alpha_deg) + len(settings.blocks)
    stripes = (len(settings.stripes) if settings.stripes is not None
               else DEFAULT_STRIPES if atlas is None else atlas.levels.size)
    stage((f"exact fragility of {blocks} blocks on {len(suite)} records × {stripes} stripes of "
           f"{settings.im.name}" if atlas is None else
           f"exact fragility of {blocks} blocks read from the atlas {atlas.key[:12]} "
           f"({stripes} stripes of {settings.im.name})")
          + f"; {', '.join(p.name for p in procedures)} at the same stripes"
          + ("; then the required slenderness of each size" if settings.required else ""))
    with (open_scheduler(runtime.scheduler, runtime.jobs) if isinstance(runtime.scheduler, str)
          else nullcontext(runtime.scheduler)) as executor:
        on = replace(runtime, scheduler=executor)
        run = margins_tables(procedures, suite, settings, on, atlas)
        if settings.required:
            stage("required slenderness of each size: α from 2° to 40°, 2° apart, the exact "
                  "curves bisected")
            run.required_alpha = required_alpha(procedures, suite, settings,
                                                replace(on, partial_dir=None, resume=False))
            if run.summary["mce_im"]:
                stage("FEMA P695 acceptance: the exact fragility of the blocks each guideline "
                      "sizes, with the impact model × 0.9 and × 0.8 for the modelling "
                      "uncertainty")
                run.acceptance, run.summary["acceptance"] = p695_acceptance(
                    suite, settings, on, run.required_alpha)
    if atlas is None:  # it picks a record by its whole outcomes at the stripes
        run.scan = amplitude_scans(run, suite, settings, runtime)
    if settings.hazard is not None:
        run.risk, run.risk_alpha = margins_risk(run, settings.hazard, settings.risk_target)
        run.hazard = hazard_table(settings.hazard)
        run.summary["hazard"] = hazard_summary(settings.hazard, settings.risk_target)
    return run


__all__ = ["run_margins"]
