"""The files of an audit run (``results.csv``, ``summary.json`` and the figure data): their
names and formats, and reading them back.

A run directory holds everything the report is drawn from, so ``python -m audit report DIR``
re-renders it without recomputing. The files are written record by record by
:mod:`audit.engine.run.writer` into a staging folder beside the target and moved into place
only when all of them are complete (:func:`audit.files.staged_folder`): a failed run leaves no
partial output.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import orjson
import pandas as pd

from audit.errors import InputError
from audit.engine.shared.csv_text import csv_bytes
from audit.engine.shared.schemas import BOOLEAN_COLUMNS, GUIDE, RESULT_COLUMNS, column_guide
from audit.engine.run.audit_run import AuditRun
from audit.engine.run.ranking import block_key

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


def summary_bytes(summary: dict) -> bytes:
    """``summary.json``: UTF-8, indented, NaN and inf as null, numpy scalars as numbers (as
    :func:`audit.engine.shared.json_text.json_ready`), encoded by orjson in one pass without a
    copy of the summary: the summary of a suite of thousands of records holds every record's
    provenance, statistics and drawn histories.

    Parameters
    ----------
    summary : dict
        The run's summary.
    """
    return orjson.dumps(summary, option=orjson.OPT_INDENT_2 | orjson.OPT_SERIALIZE_NUMPY
                        | orjson.OPT_NON_STR_KEYS) + b"\n"


def _with_booleans(frame):
    """The texts True/False in the boolean columns, empty only where undefined (NaN, None);
    a column of bools is left as it is (written True/False)."""
    columns = {}
    for column in BOOLEAN_COLUMNS:
        values = frame[column].to_numpy()
        if values.dtype.kind != "b":  # True/False and NaN or None (not checked)
            values = np.where(pd.isna(values), "", values.astype(bool)).astype(object)
        columns[column] = values
    return frame.assign(**columns)


#: The tables of a run with a row per record × something: file → (:class:`AuditRun` attribute,
#: float format, booleans written as True/False). They are written record by record
#: (:mod:`audit.engine.run.writer`) and read back whole or for chosen records.
RECORD_TABLES = {
    RESULTS_CSV: ("results", "%.10g", True),
    ESTIMATES_ONLY_CSV: ("estimates_only", "%.10g", True),
    SPECTRA_CSV: ("spectra", "%.8g", False),
    HISTORIES_CSV: ("histories", "%.7g", False),
    ROCKING_CSV: ("rocking", "%.10g", False),
    CHECKS_CSV: ("checks", "%.10g", False),
    DESIGN_SPECTRA_CSV: ("design_spectra", "%.8g", False),
}


def table_bytes(frame: pd.DataFrame, name: str, header: bool = True) -> bytes:
    """CSV bytes of the rows of one of :data:`RECORD_TABLES`.

    Parameters
    ----------
    frame : pandas.DataFrame
        The rows.
    name : str
        The table's file name, a key of :data:`RECORD_TABLES`.
    header : bool
        Whether the first line names the columns.
    """
    _, float_format, booleans = RECORD_TABLES[name]
    return csv_bytes(_with_booleans(frame) if booleans else frame, float_format, header)


def suite_files(run: AuditRun) -> dict[str, bytes]:
    """The files of a run that hold the suite as a whole, as bytes.

    Parameters
    ----------
    run : AuditRun
        The run.

    Returns
    -------
    dict of str to bytes
        File name → contents.
    """
    return {
        SUMMARY_JSON: summary_bytes(run.summary),
        SUITE_CSV: csv_bytes(run.suite, "%.6g"),
        CLAIMS_CSV: run.claims.to_csv(index=False).encode(),
        MECHANICS_CSV: csv_bytes(run.mechanics, "%.7g"),
        COLUMNS_JSON: json.dumps(column_guide(), indent=1, ensure_ascii=False).encode(),
    }


DATA_FILES = (RESULTS_CSV, ESTIMATES_ONLY_CSV, SUMMARY_JSON, SPECTRA_CSV, HISTORIES_CSV,
              ROCKING_CSV, CHECKS_CSV, SUITE_CSV, CLAIMS_CSV, DESIGN_SPECTRA_CSV, MECHANICS_CSV)
#: Rows read at a time when only some records are kept.
_CHUNK_ROWS = 20_000


def read_summary(run_dir: str | Path) -> dict:
    """``summary.json`` of a run directory; InputError if it is not valid JSON.

    Parameters
    ----------
    run_dir : str or pathlib.Path
        The run's folder.
    """
    try:
        return json.loads((Path(run_dir) / SUMMARY_JSON).read_bytes())
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{run_dir}/{SUMMARY_JSON}: not valid JSON: {exc}") from None


def checked_summary(run_dir: Path) -> dict:
    """``summary.json`` of ``run_dir``, once the folder is found to hold every file of a run,
    each table with the columns of its schema.

    Parameters
    ----------
    run_dir : pathlib.Path
        The run's folder.
    """
    if not run_dir.is_dir():
        raise InputError(f"{run_dir}: not a directory of audit results")
    for name in DATA_FILES:
        if not (run_dir / name).is_file():
            raise InputError(f"{run_dir / name}: missing; is {run_dir} the output of 'audit run'?")
    summary = read_summary(run_dir)
    for name in DATA_FILES:
        if name in GUIDE:
            _check_columns(run_dir / name, name, run_dir)
    return summary


def load_run(run_dir: str | Path, shown: bool = False) -> AuditRun:
    """Read a run directory written by ``python -m audit run`` (or ``audit.api.run``).

    Parameters
    ----------
    run_dir : str or Path
    shown : bool
        Keep only the rows the report reads, reading the tables in chunks: results and time
        histories of ``summary["shown_records"]``, spectra, rocking spectra and checks of
        ``summary["detail_records"]`` (the records with a section), and of the summary's
        per-record ``statistics`` and ``histories``, those of these records. A report of a
        suite of thousands of records is drawn in bounded memory.
    """
    run_dir = Path(run_dir)
    summary = checked_summary(run_dir)
    files = {name: run_dir / name for name in DATA_FILES}
    where = str(run_dir)
    records = detailed = histories_kept = None
    if shown:
        absent = [key for key in ("detail_records", "worst_blocks", "shown_records")
                  if key not in summary]
        if absent:
            raise InputError(f"{where}/{SUMMARY_JSON}: no {absent[0]}; written by an older "
                             "version: run the audit again")
        records, detailed = set(summary["shown_records"]), set(summary["detail_records"])
        histories_kept = _histories_shown(detailed, summary["worst_blocks"])
        # dropped before the tables are read: a few kB a record of the suite
        summary["statistics"] = [s for s in summary["statistics"] if s["record"] in detailed]
        summary["histories"] = [h for h in summary["histories"] if h["record"] in records]
        if detailed >= {entry["id"] for entry in summary["records"]}:
            # every record has a section (a small suite): every row is read, at once
            records = detailed = histories_kept = None
    text = {"record": str}
    try:
        results = _read_results(files[RESULTS_CSV], records)
        estimates_only = _read_results(files[ESTIMATES_ONLY_CSV], records)
        spectra = _read(files[SPECTRA_CSV], detailed, keep_default_na=False, dtype=text,
                        na_values={c: [""] for c in ("alpha_deg", "damping_pct", "period_s",
                                                     "sd_m", "sv_m_s", "sa_g")})
        histories = _read(files[HISTORIES_CSV], histories_kept, dtype=text)
        rocking = _read(files[ROCKING_CSV], detailed, dtype=text)
        checks = _read(files[CHECKS_CSV], detailed, keep_default_na=False, dtype=text,
                       na_values={c: [""] for c in ("alpha_deg", "size_s", "demand_m",
                                                    "capacity_m")})
        suite = _read(files[SUITE_CSV], None)
        claims = _read(files[CLAIMS_CSV], None, keep_default_na=False, dtype=str)
        design = _read(files[DESIGN_SPECTRA_CSV], None if detailed is None else detailed | {""},
                       keep_default_na=False, dtype=text,
                       na_values={c: [""] for c in ("damping_pct", "period_s", "sa_g", "sd_m")})
        mechanics = _read(files[MECHANICS_CSV], None, dtype={"figure": str, "series": str})
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}: cannot read the results: {exc}") from None
    spectra["procedure"] = spectra["procedure"].astype(str)
    return AuditRun(results, spectra, histories, rocking, estimates_only, summary, checks, suite,
                    claims, design, mechanics)


def _check_columns(path: Path, name: str, run_dir: Path) -> None:
    """InputError naming the file where its header lacks a column of its schema (a file
    edited, or of another program), before any table is read."""
    try:
        header = pd.read_csv(path, nrows=0).columns
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: cannot read: {exc}") from None
    missing = [column for column in GUIDE[name] if column not in header]
    if missing:
        raise InputError(f"{path}: columns missing: {', '.join(missing)}; is {run_dir} the "
                         f"output of 'audit run'?")


def _read(path: Path, kept, **options) -> pd.DataFrame:
    """One CSV table: all of it (``kept`` None), or the rows of the records in the set ``kept``
    or those where ``kept(chunk)`` is true, read in chunks."""
    if kept is None:
        return pd.read_csv(path, **options)
    if not callable(kept):
        records = kept
        kept = lambda chunk: chunk["record"].isin(records)  # noqa: E731
    chunks = [chunk[kept(chunk)]
              for chunk in pd.read_csv(path, chunksize=_CHUNK_ROWS, **options)]
    return pd.concat(chunks, ignore_index=True) if chunks else pd.read_csv(path, **options)


def _histories_shown(detailed: set, worst_blocks: list):
    """Which history rows the report draws: all of the records with a section, and those of
    the worst-cases table's blocks."""
    worst = {block_key(*block) for block in worst_blocks}
    worst_records = {record for record, _, _ in worst}

    def kept(chunk: pd.DataFrame) -> pd.Series:
        shown = chunk["record"].isin(detailed)
        others = ~shown & chunk["record"].isin(worst_records)
        if others.any():  # each block of those records named once, not once per sample
            blocks = chunk.loc[others, ["record", "alpha_deg", "size_s"]]
            distinct = blocks.drop_duplicates()
            chosen = distinct[[block_key(*block) in worst
                               for block in distinct.itertuples(index=False)]]
            shown[others] = pd.MultiIndex.from_frame(blocks).isin(
                pd.MultiIndex.from_frame(chosen))
        return shown
    return kept


def _read_results(source, records) -> pd.DataFrame:
    keep_text = ("record", "verdict", "approx_outcome", "approx_detail", "approx_fixed_points",
                 "approx_cycle")
    frame = _read(source, records, keep_default_na=False, dtype={"record": str},
                  na_values={c: [""] for c in RESULT_COLUMNS if c not in keep_text})
    for column in BOOLEAN_COLUMNS:  # bool where every row has one, else object with NaN
        values = frame[column].map({True: True, False: False, "True": True, "False": False})
        frame[column] = values.astype(bool if values.notna().all() else object)
    frame["procedure"] = frame["procedure"].astype(str)
    return frame
