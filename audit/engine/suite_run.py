"""An audit over a suite of records: every record's part, the suite statistics, the bottom line,
the reproduction checklist and the figure data — everything the report is drawn from.

:func:`compute_suite` then :func:`write_suite` is the pipeline the command line and the Python
API (:mod:`audit.api`) both run: each record's part is stored on disk as it completes, then the
run's data files are written record by record (:mod:`audit.engine.run_writer`), in memory
that does not grow with the suite beyond a small term per record. :func:`run_audit` writes
them into a scratch folder and reads the whole run back as an :class:`AuditRun`.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import pandas as pd

from audit.engine import fields as check
from audit.engine.claims import claimed_records, evaluate_claims
from audit.engine.heap import return_freed_memory_promptly
from audit.engine.partial import PartialStore
from audit.engine.record_audit import audit_record
from audit.engine.results import load_run
from audit.engine.run_writer import RunWriter
from audit.engine.scheduler import computed_parts
from audit.engine.audit_run import AuditRun
from audit.engine.schemas import CLAIM_COLUMNS
from audit.engine.runtime import Runtime
from audit.engine.settings import AUDIT_FIELDS, AuditSettings
from audit.errors import InputError


@dataclass
class ComputedSuite:
    """Every record's part of an audit, kept on disk in ``store`` (not in memory) until
    :func:`write_suite` writes the run's files from them."""

    procedures: list
    suite: object
    settings: AuditSettings
    store: PartialStore
    resumed: list
    where: str
    detail: list
    claims: bool
    #: The store is this run's scratch (no ``partial_dir``): removed once written.
    scratch: bool


def compute_suite(procedures, suite, settings: AuditSettings, runtime: Runtime, detail=(),
                  claims: bool = True) -> ComputedSuite:
    """Audit ``procedures`` on every record of ``suite`` over the (α, 2π/p) grid, each record's
    part stored on disk as it completes (:func:`write_suite` then writes the run's files).

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
    settings : AuditSettings
        What is computed (:meth:`AuditSettings.parse`).
    runtime : Runtime
        How: threads or worker processes, the scheduler, the folder of parts kept as they
        complete (default a scratch folder removed by :func:`write_suite`), resuming, progress.
    detail : sequence of str
        Record ids whose per-record detail the report should show (``summary["detail"]``).
    claims : bool
        Check the claims of the reference report (``AuditRun.claims``).

    Returns
    -------
    ComputedSuite
    """
    return_freed_memory_promptly()  # the driver streams thousands of parts (heap.py)
    settings = replace(settings, jobs=runtime.jobs)
    detail = list(check.words("detail", detail))
    entries = list(suite)
    known = {entry.id for entry in entries}
    unknown = [record_id for record_id in detail if record_id not in known]
    if unknown:
        raise InputError(f"detail: unknown record(s) {', '.join(unknown)} in "
                         f"{suite.description}", "detail")
    scratch = runtime.partial_dir is None
    store = PartialStore(tempfile.mkdtemp(prefix="rocking-audit-parts-") if scratch
                         else runtime.partial_dir, procedures, settings, runtime.resume)
    try:
        _, resumed, where = computed_parts(audit_record, entries, procedures, settings,
                                           runtime.scheduler, store, runtime.resume,
                                           runtime.progress, keep=False)
    except BaseException:
        if scratch:
            store.remove()
        raise
    return ComputedSuite(list(procedures), suite, settings, store, resumed, where, detail,
                         claims, scratch)


def write_suite(computed: ComputedSuite, folder, progress=None) -> dict:
    """Write the data files of a computed audit into ``folder``, record by record, in memory
    that does not grow with the suite beyond a small term per record.

    Parameters
    ----------
    computed : ComputedSuite
    folder : str or Path
        An existing folder (a staging folder, moved into place by the caller).
    progress : audit.engine.progress.Progress, optional
        Told that the files are being written.

    Returns
    -------
    dict
        ``summary.json``; ``summary["resumed"]`` lists the records taken from ``partial_dir``.
    """
    entries = list(computed.suite)
    if progress is not None:
        progress.stage(f"writing the results of {len(entries)} records")
    writer = RunWriter(Path(folder), computed.procedures,
                       claimed_records() if computed.claims else ())
    try:
        for entry in entries:
            writer.add(entry, computed.store.load(entry))
    finally:
        writer.close()
    if computed.scratch:
        computed.store.remove()
    summary = writer.summary(computed.suite, computed.settings, computed.detail)
    summary.update(scheduler=computed.where, resumed=computed.resumed)
    writer.finish(summary, evaluate_claims(writer.kept_run(summary), computed.suite)
                  if computed.claims else pd.DataFrame(columns=CLAIM_COLUMNS))
    return summary


def run_audit(procedures, suite, detail=(), claims: bool = True, **values) -> AuditRun:
    """The whole run of :func:`compute_suite`, its settings and runtime given by their fields
    (``alpha_deg=…, sizes_s=…, jobs=…``), written and read back from its files into memory:
    for a test or a script, not for a suite of thousands of records."""
    settings = AuditSettings.parse(**{k: v for k, v in values.items() if k in AUDIT_FIELDS})
    runtime = Runtime.parse(**{k: v for k, v in values.items() if k not in AUDIT_FIELDS})
    computed = compute_suite(procedures, suite, settings, runtime, detail, claims)
    with tempfile.TemporaryDirectory(prefix="rocking-audit-") as folder:
        write_suite(computed, folder)
        return load_run(folder)


def compiles_first() -> bool:
    """Whether the rocking solver and the oscillator kernels the audit runs lack cached machine
    code, so that the first record waits for numba to compile them (once after installing)."""
    from audit.physics.peaks_between_samples import spectrum_peaks
    from audit.physics.rocking import kernel
    from audit.physics.tiers import machine_code_cached
    return not (machine_code_cached(kernel._spectrum) and machine_code_cached(spectrum_peaks))


__all__ = ["compute_suite", "write_suite", "ComputedSuite", "run_audit", "AuditRun",
           "compiles_first"]
