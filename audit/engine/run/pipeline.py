"""An audit over a suite of records: every record's part, the suite statistics, the bottom line,
the reproduction checklist and the figure data — everything the report is drawn from.

:func:`run_audit` is the pipeline the command line and the Python API (:mod:`audit.api`) both
run: each record's rows are written to the run's data files (:mod:`audit.engine.run.writer`) as
soon as its part is computed, while the next records are, in memory that does not grow with the
suite beyond a small term per record. :func:`audit_in_memory` writes them into a scratch folder and
reads the whole run back as an :class:`AuditRun`.
"""

from __future__ import annotations

import tempfile
from dataclasses import replace
from pathlib import Path

import pandas as pd

from audit.engine.shared import fields as check
from audit.engine.claims.checklist import claimed_records, evaluate_claims, load_claims
from audit.engine.shared.heap import return_freed_memory_promptly
from audit.engine.shared.partial import PartialStore
from audit.engine.run.record_audit import audit_record
from audit.engine.run.results import load_run
from audit.engine.run.writer import RunWriter
from audit.engine.shared.scheduler import computed_parts
from audit.engine.run.audit_run import AuditRun
from audit.engine.shared.schemas import CLAIM_COLUMNS
from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_ROBUSTNESS
from audit.engine.shared.runtime import Runtime
from audit.engine.run.settings import AuditSettings
from audit.errors import InputError


class _InOrder:
    """Hands each record's part to ``add(entry, part)`` in the suite's order.

    A local run computes the records in order; a Dask cluster hands them back as they complete,
    and a resumed run's reused parts come first. A part ahead of its turn waits on disk, so
    that memory holds one part at a time: in the run's kept parts (``kept``, where it is saved
    already), else in a scratch :class:`PartialStore` made when first needed.
    """

    def __init__(self, entries, add, kept, procedures, settings):
        self.entries, self.add, self.kept = entries, add, kept
        self.procedures, self.settings = procedures, settings
        self.next = 0
        self.waiting = set()
        self.scratch = None

    def __call__(self, index: int, part) -> None:
        if index != self.next:
            if self.kept is None:
                if self.scratch is None:
                    self.scratch = PartialStore(tempfile.mkdtemp(prefix="rocking-audit-parts-"),
                                                self.procedures, self.settings, resume=True)
                self.scratch.save(self.entries[index], part)
            self.waiting.add(index)
            return
        self.add(self.entries[index], part)
        self.next += 1
        while self.next in self.waiting:
            self.waiting.remove(self.next)
            entry = self.entries[self.next]
            self.add(entry, (self.scratch if self.kept is None else self.kept).load(entry))
            self.next += 1

    def remove(self) -> None:
        """Delete the scratch folder, if any."""
        if self.scratch is not None:
            self.scratch.remove()


def run_audit(procedures, suite, settings: AuditSettings, runtime: Runtime, folder, detail=(),
                claims: bool = True, progress=None) -> dict:
    """Audit ``procedures`` on every record of ``suite`` over the (α, 2π/p) grid and write the
    run's data files into ``folder``, each record's rows as soon as its part is computed (while
    the next records are), in memory that does not grow with the suite beyond a small term per
    record.

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
    settings : AuditSettings
        What is computed (:meth:`AuditSettings.parse`).
    runtime : Runtime
        How: threads or worker processes, the scheduler, the folder of parts kept as they
        complete for a resumed run (``partial_dir``), resuming, progress.
    folder : str or Path
        An existing folder (a staging folder, moved into place by the caller).
    detail : sequence of str
        Record ids whose per-record detail the report should show (``summary["detail"]``).
    claims : bool
        Check the claims of the reference report (``AuditRun.claims``).
    progress : audit.engine.shared.progress.Progress, optional
        Its bar (``done()``, where it has one) closed when the records are done, then told
        (``stage``) that the suite's files are being written.

    Returns
    -------
    dict
        ``summary.json``; ``summary["resumed"]`` lists the records taken from ``partial_dir``.
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
    kept = (None if runtime.partial_dir is None
            else PartialStore(runtime.partial_dir, procedures, settings, runtime.resume))
    checklist = load_claims() if claims else []  # read once: the records kept, then judged
    writer = RunWriter(Path(folder), procedures, claimed_records(checklist))
    in_order = _InOrder(entries, writer.add, kept, procedures, settings)
    try:
        _, resumed, where = computed_parts(audit_record, entries, procedures, settings,
                                           runtime.scheduler, kept, runtime.progress,
                                           consume=in_order)
    finally:
        writer.close()
        in_order.remove()
        if getattr(progress, "done", None) is not None:  # a bar: finished with the records
            progress.done()
    if progress is not None:
        progress.stage(f"writing the results of {len(entries)} records: the suite's "
                       f"statistics and the claims")
    summary = writer.summary(suite, settings, detail)
    summary.update(scheduler=where, resumed=resumed)
    writer.finish(summary, evaluate_claims(writer.kept_run(summary), suite, checklist)
                  if claims else pd.DataFrame(columns=CLAIM_COLUMNS))
    return summary


def audit_in_memory(procedures, suite, detail=(), claims: bool = True, *,
                    alpha_deg=DEFAULT_ALPHA_DEG, size_s=None,
                    robustness: float = DEFAULT_ROBUSTNESS, runtime=None) -> AuditRun:
    """The whole run of :func:`run_audit` on a grid, written and read back from its files into
    memory: for a test or a script, not for a suite of thousands of records.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    suite : records.RecordSuite
        The records.
    detail : sequence of str
        Record ids whose per-record detail the report should show.
    claims : bool
        Check the claims of the reference report.
    alpha_deg, size_s, robustness :
        As for :meth:`AuditSettings.parse` (the rest its defaults).
    runtime : audit.engine.shared.runtime.Runtime, optional
        How (:meth:`Runtime.parse <audit.engine.shared.runtime.Runtime.parse>`).
    """
    settings = AuditSettings.parse(alpha_deg=alpha_deg, size_s=size_s, robustness=robustness)
    runtime = Runtime.parse(runtime)
    with tempfile.TemporaryDirectory(prefix="rocking-audit-") as folder:
        run_audit(procedures, suite, settings, runtime, folder, detail, claims)
        return load_run(folder)


def compiles_first() -> bool:
    """Whether the kernels every audit runs, the rocking solver and the oscillator, lack current
    cached machine code, so that the first record waits for numba to compile them (once after
    installing or updating). The guidelines' own kernels compile beside them on a first run;
    one that a later run needs first (the fixed-point scan after ``run fema356``) takes
    seconds, and asking about it would announce a first run at every run of a command that
    never compiles it."""
    from audit.physics.spectrum_kernel import spectrum_peaks
    from audit.physics.rocking import kernel
    from audit.physics.tiers import machine_code_cached
    return not all(map(machine_code_cached, (kernel._spectrum, spectrum_peaks)))


__all__ = ["run_audit", "audit_in_memory", "AuditRun",
           "compiles_first"]
