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
from pathlib import Path

import numpy as np
import pandas as pd

from audit.errors import InputError
from audit.files import write_files_atomically
from audit.engine.csv_text import csv_bytes
from audit.engine.schemas import BOOLEAN_COLUMNS, RESULT_COLUMNS, column_guide
from audit.engine.audit_run import AuditRun

RESULTS_CSV = "results.csv"
SUMMARY_JSON = "summary.json"
SPECTRA_CSV = "spectra.csv"
HISTORIES_CSV = "histories.csv"
ROCKING_CSV = "rocking.csv"
ESTIMATES_ONLY_CSV = "estimates-only.csv"
CHECKS_CSV = "checks.csv"
SUITE_CSV = "suite.csv"
CLAIMS_CSV = "claims.csv"
DESIGN_SPECTRA_CSV = "design-spectra.csv"
MECHANICS_CSV = "mechanics.csv"
COLUMNS_JSON = "columns.json"
REPORT_HTML = "report.html"


def json_ready(value):
    """Plain JSON: NaN and inf become null, numpy scalars become Python numbers."""
    if isinstance(value, dict):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def _with_booleans(frame):
    """True/False in the boolean columns, empty only where undefined (NaN)."""
    frame = frame.copy()
    for column in BOOLEAN_COLUMNS:
        frame[column] = frame[column].map(
            lambda v: "" if v is None or (isinstance(v, float) and math.isnan(v)) else bool(v))
    return frame


def run_files(run: AuditRun) -> dict[str, bytes]:
    """The data files of a run, as bytes (``columns.json`` describes every column)."""
    return {
        RESULTS_CSV: csv_bytes(_with_booleans(run.results), "%.10g"),
        ESTIMATES_ONLY_CSV: csv_bytes(_with_booleans(run.estimates_only), "%.10g"),
        SUMMARY_JSON: json.dumps(json_ready(run.summary), indent=1, ensure_ascii=False).encode(),
        SPECTRA_CSV: csv_bytes(run.spectra, "%.8g"),
        HISTORIES_CSV: csv_bytes(run.histories, "%.7g"),
        ROCKING_CSV: csv_bytes(run.rocking, "%.10g"),
        CHECKS_CSV: csv_bytes(run.checks, "%.10g"),
        SUITE_CSV: csv_bytes(run.suite, "%.6g"),
        CLAIMS_CSV: run.claims.to_csv(index=False).encode(),
        DESIGN_SPECTRA_CSV: csv_bytes(run.design_spectra, "%.8g"),
        MECHANICS_CSV: csv_bytes(run.mechanics, "%.7g"),
        COLUMNS_JSON: json.dumps(column_guide(), indent=1, ensure_ascii=False).encode(),
    }


DATA_FILES = (RESULTS_CSV, ESTIMATES_ONLY_CSV, SUMMARY_JSON, SPECTRA_CSV, HISTORIES_CSV,
              ROCKING_CSV, CHECKS_CSV, SUITE_CSV, CLAIMS_CSV, DESIGN_SPECTRA_CSV, MECHANICS_CSV)


def load_run(run_dir: str | Path) -> AuditRun:
    """Read a run directory written by :func:`save_run`."""
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: not a directory of audit results")
    files = {}
    for name in DATA_FILES:
        if not (run_dir / name).is_file():
            raise InputError(f"{run_dir / name}: missing; is {run_dir} the output of 'audit run'?")
        files[name] = (run_dir / name).read_bytes()
    return parse_run(files, str(run_dir))


def _read_results(content: bytes, name: str, where: str) -> pd.DataFrame:
    keep_text = ("verdict", "approx_outcome", "approx_detail", "approx_fixed_points",
                 "approx_cycle")
    frame = pd.read_csv(io.BytesIO(content), keep_default_na=False,
                        na_values={c: [""] for c in RESULT_COLUMNS if c not in keep_text})
    missing = [c for c in RESULT_COLUMNS if c not in frame.columns]
    if missing:
        raise InputError(f"{where}/{name}: columns missing: {', '.join(missing)}")
    for column in BOOLEAN_COLUMNS:
        frame[column] = frame[column].map({True: True, False: False, "True": True,
                                           "False": False}).astype(object)
    frame["procedure"] = frame["procedure"].astype(str)
    return frame


def parse_run(files: dict[str, bytes], where: str = "results") -> AuditRun:
    """An :class:`AuditRun` from the bytes of its data files (the inverse of :func:`run_files`)."""
    try:
        summary = json.loads(files[SUMMARY_JSON].decode("utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}/{SUMMARY_JSON}: not valid JSON: {exc}") from None
    try:
        results = _read_results(files[RESULTS_CSV], RESULTS_CSV, where)
        estimates_only = _read_results(files[ESTIMATES_ONLY_CSV], ESTIMATES_ONLY_CSV, where)
        spectra = pd.read_csv(io.BytesIO(files[SPECTRA_CSV]), keep_default_na=False,
                              na_values={c: [""] for c in ("alpha_deg", "damping_pct", "period_s",
                                                           "sd_m", "sv_m_s", "sa_g")})
        histories = pd.read_csv(io.BytesIO(files[HISTORIES_CSV]))
        rocking = pd.read_csv(io.BytesIO(files[ROCKING_CSV]))
        checks = pd.read_csv(io.BytesIO(files[CHECKS_CSV]), keep_default_na=False,
                             na_values={c: [""] for c in ("alpha_deg", "size_s", "demand_m",
                                                          "capacity_m")})
        suite = pd.read_csv(io.BytesIO(files[SUITE_CSV]))
        claims = pd.read_csv(io.BytesIO(files[CLAIMS_CSV]), keep_default_na=False, dtype=str)
        design = pd.read_csv(io.BytesIO(files[DESIGN_SPECTRA_CSV]), keep_default_na=False,
                             na_values={c: [""] for c in ("damping_pct", "period_s", "sa_g",
                                                          "sd_m")})
        mechanics = pd.read_csv(io.BytesIO(files[MECHANICS_CSV]),
                                dtype={"figure": str, "series": str})
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}: cannot read the results: {exc}") from None
    spectra["procedure"] = spectra["procedure"].astype(str)
    design["record"] = design["record"].astype(str)
    return AuditRun(results, spectra, histories, rocking, estimates_only, summary, checks, suite,
                    claims, design, mechanics)


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
