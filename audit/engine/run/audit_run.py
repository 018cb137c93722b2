"""What an audit run holds: the tables and the summary the files and the report are made of
(light: pandas only, so reading a run back and rendering its report load no solver)."""

from __future__ import annotations

from dataclasses import dataclass, field

import pandas as pd

from audit.engine.shared.schemas import (CHECK_COLUMNS, CLAIM_COLUMNS, DESIGN_SPECTRA_COLUMNS,
                                  HISTORY_COLUMNS, MECHANICS_COLUMNS, RESULT_COLUMNS,
                                  ROCKING_COLUMNS, SPECTRA_COLUMNS, SUITE_COLUMNS)


def _empty(columns):
    return field(default_factory=lambda: pd.DataFrame(columns=columns))


@dataclass
class AuditRun:
    """Everything an audit produced; the report is rendered from this alone.

    Attributes
    ----------
    results : pandas.DataFrame
        One row per procedure × record × α × size with an exact response (``results.csv``).
    spectra : pandas.DataFrame
        Record response spectra (procedure "") and the spectra each procedure read.
    histories : pandas.DataFrame
        Time histories of the representative and worst blocks.
    rocking : pandas.DataFrame
        Exact rocking spectra of every record with a file, whatever the procedures.
    estimates_only : pandas.DataFrame
        Estimates for records without a file (no exact response, no verdict).
    summary : dict
        Settings, records, unauditable records, per-record statistics, the suite's sentences
        and bottom line (``summary.json``).
    checks : pandas.DataFrame
        Limit-state checks, empty when no procedure makes any.
    suite : pandas.DataFrame
        Verdict statistics across the records.
    claims : pandas.DataFrame
        The reproduction checklist of the reference report.
    design_spectra, mechanics : pandas.DataFrame
        Figure data of Figures 5.x (design spectra) and 4.1, 7.1, 7.2
        (:mod:`audit.engine.run.figure_data`).
    """

    results: pd.DataFrame = _empty(RESULT_COLUMNS)
    spectra: pd.DataFrame = _empty(SPECTRA_COLUMNS)
    histories: pd.DataFrame = _empty(HISTORY_COLUMNS)
    rocking: pd.DataFrame = _empty(ROCKING_COLUMNS)
    estimates_only: pd.DataFrame = _empty(RESULT_COLUMNS)
    summary: dict = field(default_factory=dict)
    checks: pd.DataFrame = _empty(CHECK_COLUMNS)
    suite: pd.DataFrame = _empty(SUITE_COLUMNS)
    claims: pd.DataFrame = _empty(CLAIM_COLUMNS)
    design_spectra: pd.DataFrame = _empty(DESIGN_SPECTRA_COLUMNS)
    mechanics: pd.DataFrame = _empty(MECHANICS_COLUMNS)


__all__ = ["AuditRun"]
