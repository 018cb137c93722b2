"""Saving and loading an audit run: ``results.csv``, ``summary.json`` and the figure data.

A run directory holds everything the report is drawn from, so ``python -m audit report DIR``
re-renders it without recomputing. Files are written to a temporary directory beside the
target and moved into place only when all of them are complete: a failed run leaves no partial
output.
"""

from __future__ import annotations

import io
import json
import math
import os
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from audit.errors import InputError
from audit.engine.runner import RESULT_COLUMNS, AuditRun

RESULTS_CSV = "results.csv"
SUMMARY_JSON = "summary.json"
SPECTRA_CSV = "spectra.csv"
HISTORIES_CSV = "histories.csv"
ROCKING_CSV = "rocking.csv"
REPORT_HTML = "report.html"


def _json_ready(value):
    """Plain JSON: NaN and inf become null, numpy scalars become Python numbers."""
    if isinstance(value, dict):
        return {str(k): _json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(v) for v in value]
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


#: Start of this run: staging folders older than it, of processes no longer alive, are stale.
_RUN_STARTED = time.time()


def _staging_prefix(out_dir: Path) -> str:
    return f".{out_dir.name}-staging-"


def _writable(folder: Path, what: str, path: Path) -> None:
    """InputError unless a folder can be created in ``folder`` (tried, then removed): the
    permission bits say nothing for root or on a read-only file system."""
    try:
        os.rmdir(tempfile.mkdtemp(prefix=f".{path.name}-probe-", dir=folder))
    except OSError as exc:
        raise InputError(f"{what}: {path}: folder {folder} is not writable "
                         f"({exc.strerror})") from None


def _writable_ancestor(path: Path, what: str) -> None:
    """InputError unless the nearest existing ancestor of ``path`` is a writable folder."""
    ancestor = path.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise InputError(f"{what}: {path}: {ancestor} is a file, not a folder")
    _writable(ancestor, what, path)


def check_output_dir(out_dir: str | Path, what: str = "--out") -> Path:
    """``out_dir`` if it can receive a run's files: a writable folder, or one that can be made.

    Called before any computation, so a bad output path costs nothing; ``what`` names the
    option in the one-line InputError.
    """
    out_dir = Path(out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        raise InputError(f"{what}: {out_dir} is a file, expected a folder")
    _writable_ancestor(out_dir, what)
    if out_dir.is_dir():
        _writable(out_dir, what, out_dir)
    return out_dir


def check_output_file(path: str | Path, what: str) -> Path:
    """``path`` if a file can be written there: not a folder, in a writable or creatable one."""
    text = str(path)
    path = Path(path)
    if path.is_dir() or text.endswith(("/", os.sep)):
        raise InputError(f"{what}: {text} is a folder, expected a file name")
    _writable_ancestor(path, what)
    return path


def clean_stale_staging(out_dir: Path) -> None:
    """Remove staging folders of ``out_dir`` left by a run that was killed while saving.

    Only folders named with this tool's staging prefix, older than the current run, whose
    process is no longer alive.
    """
    prefix = _staging_prefix(out_dir)
    if not out_dir.parent.is_dir():
        return
    for folder in out_dir.parent.glob(prefix + "*"):
        pid = folder.name[len(prefix):].split("-")[0]
        if not (folder.is_dir() and pid.isdigit() and folder.stat().st_mtime < _RUN_STARTED):
            continue
        try:
            os.kill(int(pid), 0)
            continue  # its process still runs
        except ProcessLookupError:
            shutil.rmtree(folder, ignore_errors=True)
        except PermissionError:
            continue


def write_files_atomically(out_dir: str | Path, files: dict[str, bytes]) -> None:
    """Write ``files`` (name → content) into ``out_dir``, all or nothing.

    Everything is written into a staging folder next to ``out_dir`` first (named
    ``.NAME-staging-PID-…``; stale ones of killed runs are removed here); each file is then
    moved into place with an atomic rename. Files of ``out_dir`` that are not in ``files`` are
    left alone. An OS error names ``out_dir``, never the staging folder.
    """
    out_dir = check_output_dir(out_dir, "output folder")
    clean_stale_staging(out_dir)
    try:
        out_dir.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f"{_staging_prefix(out_dir)}{os.getpid()}-",
                                        dir=out_dir.parent))
    except OSError as exc:
        raise InputError(f"{out_dir}: cannot write: {exc.strerror}") from None
    try:
        for name, content in files.items():
            (staging / name).write_bytes(content)
        out_dir.mkdir(exist_ok=True)
        for name in files:
            if (out_dir / name).is_dir():
                raise InputError(f"{out_dir / name}: is a folder, cannot be replaced by a file")
            os.replace(staging / name, out_dir / name)
    except OSError as exc:
        raise InputError(f"{out_dir}: cannot write: {exc.strerror}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def run_files(run: AuditRun) -> dict[str, bytes]:
    """The data files of a run, as bytes."""
    results = run.results.copy()
    for column in ("exact_overturned", "approx_overturned", "exact_uplifted"):
        results[column] = results[column].map(
            lambda v: "" if v is None or (isinstance(v, float) and math.isnan(v)) else bool(v))
    return {
        RESULTS_CSV: results.to_csv(index=False, float_format="%.10g").encode(),
        SUMMARY_JSON: json.dumps(_json_ready(run.summary), indent=1, ensure_ascii=False).encode(),
        SPECTRA_CSV: run.spectra.to_csv(index=False, float_format="%.8g").encode(),
        HISTORIES_CSV: run.histories.to_csv(index=False, float_format="%.7g").encode(),
        ROCKING_CSV: run.rocking.to_csv(index=False, float_format="%.10g").encode(),
    }


def load_run(run_dir: str | Path) -> AuditRun:
    """Read a run directory written by :func:`save_run`."""
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: not a directory of audit results")
    files = {}
    for name in (RESULTS_CSV, SUMMARY_JSON, SPECTRA_CSV, HISTORIES_CSV, ROCKING_CSV):
        if not (run_dir / name).is_file():
            raise InputError(f"{run_dir / name}: missing; is {run_dir} the output of 'audit run'?")
        files[name] = (run_dir / name).read_bytes()
    return parse_run(files, str(run_dir))


def parse_run(files: dict[str, bytes], where: str = "results") -> AuditRun:
    """An :class:`AuditRun` from the bytes of its data files (the inverse of :func:`run_files`)."""
    try:
        summary = json.loads(files[SUMMARY_JSON].decode("utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}/{SUMMARY_JSON}: not valid JSON: {exc}") from None
    keep_text = ("verdict", "approx_outcome", "approx_detail")
    try:
        results = pd.read_csv(io.BytesIO(files[RESULTS_CSV]), keep_default_na=False,
                              na_values={c: [""] for c in RESULT_COLUMNS if c not in keep_text})
        spectra = pd.read_csv(io.BytesIO(files[SPECTRA_CSV]), keep_default_na=False,
                              na_values={c: [""] for c in ("alpha_deg", "damping", "period_s",
                                                           "sd", "sv", "sa")})
        histories = pd.read_csv(io.BytesIO(files[HISTORIES_CSV]))
        rocking = pd.read_csv(io.BytesIO(files[ROCKING_CSV]))
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}: cannot read the results: {exc}") from None
    missing = [c for c in RESULT_COLUMNS if c not in results.columns]
    if missing:
        raise InputError(f"{where}/{RESULTS_CSV}: columns missing: {', '.join(missing)}")
    for column in ("exact_overturned", "approx_overturned", "exact_uplifted"):
        results[column] = results[column].map({True: True, False: False, "True": True,
                                               "False": False}).astype(object)
    results["procedure"] = results["procedure"].astype(str)
    spectra["procedure"] = spectra["procedure"].astype(str)
    return AuditRun(results, spectra, histories, rocking, summary)


def save_run(run: AuditRun, out_dir: str | Path, render) -> AuditRun:
    """Write a run's data files and its report, rendered from exactly what is saved.

    Parameters
    ----------
    run : AuditRun
    out_dir : str or Path
    render : callable
        ``render(run) -> str``, the HTML report.

    Returns
    -------
    AuditRun
        The run as saved (and as ``python -m audit report`` will read it back).
    """
    files = run_files(run)
    saved = parse_run(files, str(out_dir))
    files[REPORT_HTML] = render(saved).encode("utf-8")
    write_files_atomically(out_dir, files)
    return saved
