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
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from audit import G
from audit.engine.claims import claimed_records, evaluate_claims
from audit.engine.heap import return_freed_memory_promptly
from audit.engine.defaults import (DEFAULT_AGREE_BAND, DEFAULT_ALPHA_DEG, DEFAULT_FREE_MOTION_S,
                                   DEFAULT_ROBUSTNESS, DEFAULT_SCHEDULER, DEFAULT_SIZES)
from audit.engine.grid import size_grid
from audit.engine.partial import PartialStore
from audit.engine.record_audit import audit_record
from audit.engine.results import load_run
from audit.engine.run_writer import RunWriter
from audit.engine.scheduler import computed_parts
from audit.engine.audit_run import AuditRun
from audit.engine.schemas import CLAIM_COLUMNS
from audit.engine.ground_truth import parse_sensitivity
from audit.engine.settings import AuditSettings
from audit.physics.block import Restitution
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


def compute_suite(procedures, suite, alpha_deg=DEFAULT_ALPHA_DEG, sizes=None, jobs: int = 1,
                  free_motion_s: float = DEFAULT_FREE_MOTION_S, progress=None, g: float = G,
                  agree_band: float = DEFAULT_AGREE_BAND,
                  robustness: float = DEFAULT_ROBUSTNESS, scheduler: str = DEFAULT_SCHEDULER,
                  partial_dir=None, resume: bool = False, detail=(), claims: bool = True,
                  restitution="housner", vertical: bool = False,
                  friction: float | None = None, sensitivity=()) -> ComputedSuite:
    """Audit ``procedures`` on every record of ``suite`` over the (α, 2π/p) grid, each record's
    part stored on disk as it completes (:func:`write_suite` then writes the run's files).

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
        Folder for per-record results as they complete (:mod:`audit.engine.partial`), kept
        for a resumed run; default a scratch folder removed by :func:`write_suite`.
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
    ComputedSuite
    """
    return_freed_memory_promptly()  # the driver streams thousands of parts (heap.py)
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
    scratch = partial_dir is None
    store = PartialStore(tempfile.mkdtemp(prefix="rocking-audit-parts-") if scratch
                         else partial_dir, procedures, settings, resume)
    try:
        _, resumed, where = computed_parts(audit_record, entries, procedures, settings,
                                           scheduler, store, resume, progress, keep=False)
    except BaseException:
        if scratch:
            store.remove()
        raise
    return ComputedSuite(list(procedures), suite, settings, store, resumed, where, list(detail),
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


def run_audit(procedures, suite, *args, **kwargs) -> AuditRun:
    """The whole run of :func:`compute_suite` (same arguments), written and read back from its
    files into memory: for a test or a script, not for a suite of thousands of records."""
    computed = compute_suite(procedures, suite, *args, **kwargs)
    with tempfile.TemporaryDirectory(prefix="rocking-audit-") as folder:
        write_suite(computed, folder)
        return load_run(folder)


def compiles_first() -> bool:
    """Whether the rocking solver and the oscillator kernels the audit runs lack cached machine
    code, so that the first record waits for numba to compile them (once after installing)."""
    from audit.physics import oscillator, rocking
    from audit.physics.tiers import machine_code_cached
    return not (machine_code_cached(rocking._spectrum) and machine_code_cached(oscillator._peaks))


__all__ = ["compute_suite", "write_suite", "ComputedSuite", "run_audit", "AuditRun",
           "compiles_first"]
