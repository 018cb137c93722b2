"""The work of an audit, estimated before it starts (:mod:`audit.engine.shared.guards`
refuses or announces it): the exact solver's blocks and the oscillators of the spectra the
procedures read, per record."""

from __future__ import annotations

from audit.engine.shared import guards
from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_SIZES
from audit.engine.shared.grid import size_grid
from audit.engine.shared.runtime import Runtime
from audit.engine.run.settings import AuditSettings
from procedures.base import SPECTRUM_PERIODS_S

#: Damping ratios of the record spectra every audited record gets (Figures 5.x).
RECORD_SPECTRA = 3


def audit_cost(procedures, suite, settings: AuditSettings, runtime: Runtime) -> guards.Estimate:
    """The work of :func:`audit.engine.run.pipeline.run_audit`: every block solved once, twice
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
        guards.suite_motions(suite), settings.free_motion_s,
        blocks=sizes * alphas * ((3 if settings.robustness else 1) + len(settings.sensitivity)),
        oscillators=SPECTRUM_PERIODS_S.size * (RECORD_SPECTRA + alphas * len(procedures)),
        jobs=runtime.jobs, free_motion_option="solver.free_motion_s",
        settings=(guards.Setting("size_s", sizes, size_grid(*DEFAULT_SIZES).size),
                  guards.Setting("alpha_deg", alphas, len(DEFAULT_ALPHA_DEG))))


__all__ = ["audit_cost", "RECORD_SPECTRA"]
