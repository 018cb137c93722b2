"""An audit over a suite of records: every record's part, the suite statistics, the bottom line,
the reproduction checklist and the figure data — everything the report is drawn from.

:func:`run_audit` is the pipeline the command line and the Python API (:mod:`audit.api`) both
run; it returns an :class:`AuditRun`, which :mod:`audit.engine.results` saves and reads back.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from audit import G, __version__
from audit.engine.claims import evaluate_claims
from audit.engine.defaults import (DEFAULT_AGREE_BAND, DEFAULT_ALPHA_DEG, DEFAULT_FREE_MOTION_S,
                                   DEFAULT_ROBUSTNESS, DEFAULT_SCHEDULER, DEFAULT_SIZES)
from audit.engine.figure_data import design_spectra, mechanics, sensitivity_facts
from audit.engine.grid import size_grid
from audit.engine.partial import PartialStore
from audit.engine.record_audit import RecordAudit, audit_record, concat
from audit.engine.scheduler import computed_parts
from audit.engine.audit_run import AuditRun
from audit.engine.schemas import (CHECK_COLUMNS, HISTORY_COLUMNS, RESULT_COLUMNS, ROCKING_COLUMNS,
                                  SPECTRA_COLUMNS)
from audit.engine.ground_truth import parse_sensitivity
from audit.engine.settings import AuditSettings
from audit.physics.block import Restitution
from audit.engine.suite import bottom_line, suite_statistics, suite_summary
from audit.engine.verdicts import VERDICTS
from audit.errors import InputError


def record_summary(entry) -> dict:
    """Provenance of one record for ``summary.json``: facts, site, file, PGA/PGV recomputed."""
    motion, facts = entry.motion, entry.facts
    item = {"id": entry.id, "name": entry.name, "component": entry.component,
            "missing": entry.missing, "missing_reason": entry.missing_reason, "site": entry.site,
            "metadata": entry.metadata}
    if facts is not None:
        item["table_5_1"] = {"pga_g": facts.pga_g, "pgv_m_s": facts.pgv_ms,
                             "pulse_period_s": facts.pulse_period_s}
    if motion is not None:
        # absolute, so a moved summary.json or report still names the file
        source = Path(motion.source) if motion.source else None
        item.update(source=str(source.absolute()) if source and source.is_file()
                    else motion.source, sha256=motion.sha256, dt_s=motion.dt,
                    duration_s=motion.duration, pga_g=motion.pga_g, pgv_m_s=motion.pgv,
                    npts=int(motion.acceleration.size),
                    vertical_component=motion.vertical is not None)
    return item


def statistics(frame: pd.DataFrame) -> list[dict]:
    """Counts and approx/exact ratios per procedure, record and α."""
    stats = []
    for (procedure, record, alpha), group in frame.groupby(["procedure", "record", "alpha_deg"],
                                                          sort=False):
        counts = group["verdict"].value_counts()
        ratio = group["ratio"].replace([np.inf, -np.inf], np.nan).dropna()
        stats.append({
            "procedure": procedure, "record": record, "alpha_deg": float(alpha),
            "blocks": int(len(group)),
            "counts": {v: int(counts.get(v, 0)) for v in VERDICTS},
            "fragile": int(group["exact_fragile"].eq(True).sum()),
            "median_ratio": float(ratio.median()) if len(ratio) else None,
            "min_ratio": float(ratio.min()) if len(ratio) else None,
            "max_ratio": float(ratio.max()) if len(ratio) else None,
        })
    return stats


def combine(parts: list[RecordAudit], procedures, suite, settings: AuditSettings) -> AuditRun:
    """One :class:`AuditRun` from the per-record parts, in the suite's order, with the suite
    statistics, the bottom line and the figure data (the claims are added by
    :func:`run_audit`)."""
    def cat(name, columns):
        return concat([getattr(part, name) for part in parts if len(getattr(part, name))],
                      columns)

    results, checks = cat("results", RESULT_COLUMNS), cat("checks", CHECK_COLUMNS)
    suite_frame = suite_statistics(results)
    summary = {
        "version": __version__,
        "procedures": [{"name": proc.name, "title": proc.title, "reference": proc.reference,
                        "damping_law": proc.damping_law, "spectrum_source": proc.spectrum_source,
                        "figure_series": proc.figure_series} for proc in procedures],
        "records_source": suite.description,
        "pulse_idealised": suite.is_pulse_idealised,
        "records": [record_summary(entry) for entry in suite],
        "rejected_records": list(getattr(suite, "rejected", ())),
        "design_site": suite.design_site,
        "scaling": suite.scaling,
        "unauditable": [item for part in parts for item in part.unauditable],
        "grid": {"alpha_deg": list(settings.alpha_deg), "size_s": list(settings.size_s)},
        "settings": settings.described(),
        "statistics": statistics(results),
        "suite": suite_summary(suite_frame, {proc.name: proc.title for proc in procedures}),
        "bottom_line": bottom_line(results, checks, procedures),
        "histories": [item for part in parts for item in part.histories_meta],
        "mechanics": sensitivity_facts(),
    }
    return AuditRun(results, cat("spectra", SPECTRA_COLUMNS), cat("histories", HISTORY_COLUMNS),
                    cat("rocking", ROCKING_COLUMNS), cat("estimates_only", RESULT_COLUMNS),
                    summary, checks=checks, suite=suite_frame,
                    design_spectra=design_spectra(suite), mechanics=mechanics())


def run_audit(procedures, suite, alpha_deg=DEFAULT_ALPHA_DEG, sizes=None, jobs: int = 1,
              free_motion_s: float = DEFAULT_FREE_MOTION_S, progress=None, g: float = G,
              agree_band: float = DEFAULT_AGREE_BAND, robustness: float = DEFAULT_ROBUSTNESS,
              scheduler: str = DEFAULT_SCHEDULER, partial_dir=None, resume: bool = False,
              detail=(), claims: bool = True, restitution="housner", vertical: bool = False,
              friction: float | None = None, sensitivity=()) -> AuditRun:
    """Audit ``procedures`` on every record of ``suite`` over the (α, 2π/p) grid.

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
    alpha_deg : sequence of float
        Slendernesses [degrees].
    sizes : array, optional
        Block sizes 2π/p [s]; default 0.5 … 8.0 step 0.05.
    jobs : int
        ``local``: threads of the exact solver; ``dask``: worker processes of the LocalCluster.
    free_motion_s : float
        Free motion after each record, for the exact solver and the record spectra [s].
    progress : callable, optional
        ``progress(done, total, record_id, how)`` after each record (``how`` in words).
    g : float
        Acceleration of gravity [m/s²].
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    robustness : float
        ε of the fragility flag [-]; 0 turns it off.
    scheduler : str
        ``local``, ``dask`` or ``tcp://HOST:PORT`` (:mod:`audit.engine.scheduler`).
    partial_dir : str or Path, optional
        Folder for per-record results as they complete (:mod:`audit.engine.partial`).
    resume : bool
        Reuse the matching per-record results already in ``partial_dir``.
    detail : sequence of str
        Record ids whose per-record detail the report should show (``summary["detail"]``).
    claims : bool
        Check the claims of the reference report (``AuditRun.claims``).
    restitution, vertical, friction, sensitivity :
        The exact model's assumptions (:class:`~audit.engine.settings.AuditSettings`):
        impact model (``housner``, a fixed r, ``xFACTOR``), the records' vertical components,
        the base's friction coefficient μ [-] (None: not checked), and the alternative models
        (``restitution=x0.9``, ``vertical``) the verdicts' sensitivity is measured against.

    Returns
    -------
    AuditRun
        ``summary["resumed"]`` lists the records taken from ``partial_dir``.
    """
    sizes = size_grid(*DEFAULT_SIZES) if sizes is None else np.asarray(sizes, dtype=float)
    settings = AuditSettings(tuple(float(a) for a in alpha_deg), tuple(float(s) for s in sizes),
                             float(free_motion_s), float(agree_band), float(robustness), float(g),
                             str(Restitution.parse(restitution)), bool(vertical),
                             None if friction is None else float(friction),
                             parse_sensitivity(sensitivity), int(jobs))
    entries = list(suite)
    known = {entry.id for entry in entries}
    unknown = [record_id for record_id in detail if record_id not in known]
    if unknown:
        raise InputError(f"--detail: unknown record(s) {', '.join(unknown)} in "
                         f"{suite.description}")
    store = PartialStore(partial_dir, procedures, settings, resume) if partial_dir else None
    parts, resumed, where = computed_parts(audit_record, entries, procedures, settings, scheduler,
                                           store, resume, progress)
    run = combine(parts, procedures, suite, settings)
    run.summary.update(scheduler=where, resumed=resumed, detail=list(detail))
    if claims:
        run.claims = evaluate_claims(run, suite)
    return run


def compiles_first() -> bool:
    """Whether the rocking solver and the oscillator kernels the audit runs lack cached machine
    code, so that the first record waits for numba to compile them (once after installing)."""
    from audit.physics import oscillator, rocking
    from audit.physics.tiers import machine_code_cached
    return not (machine_code_cached(rocking._spectrum) and machine_code_cached(oscillator._peaks))


__all__ = ["run_audit", "combine", "AuditRun", "record_summary", "statistics", "compiles_first"]
