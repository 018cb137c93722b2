"""A run's files written record by record, with everything the suite needs as a whole folded
as the records pass: the driver never holds a suite of thousands of records at once.

Each record's part (:class:`~audit.engine.run.record_audit.RecordAudit`) arrives in the suite's
order; its rows are appended to the CSV files (the same bytes as the whole table written at
once, :func:`~audit.engine.run.results.table_bytes`) and dropped. What stays grows by a small term
per record: the suite statistics' finite ratios with their block
(:class:`~audit.engine.run.suite.SuiteStatistics`), the bottom line's finite ratios
(:class:`~audit.engine.run.suite.BottomLine`), each record's summary and per-α statistics, the
report's worst candidates (:class:`~audit.engine.run.ranking.ShownRecords`), and the parts of the
few records the reference report's claims name (those claims read them).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from audit import __version__
from audit.engine.run.audit_run import AuditRun
from audit.engine.shared.floors import suite_floor
from audit.engine.run.figure_data import (mechanics, sensitivity_facts, site_design_spectra,
                                      ubc97_design_spectrum)
from audit.engine.run.ranking import LARGE_SUITE, ShownRecords
from audit.engine.run.record_audit import concat
from audit.engine.run.results import (DESIGN_SPECTRA_CSV, RECORD_TABLES, suite_files, table_bytes)
from audit.engine.shared.schemas import GUIDE
from audit.engine.run.suite import VERDICT_CODE, BottomLine, SuiteStatistics, suite_summary
from audit.engine.shared.verdicts import VERDICTS
from procedures.parameters import parameters_used


def record_summary(entry) -> dict:
    """Provenance of one record for ``summary.json``: facts, site, file, PGA/PGV recomputed.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    """
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
    """Counts and approx/exact ratios per procedure, record and α (groups in order of first
    appearance).

    Parameters
    ----------
    frame : pandas.DataFrame
        ``results.csv`` rows.
    """
    # one pass over the columns for every group, not a dozen pandas calls per group: a record
    # holds tens of groups, and this ran in the driver while the solver waited for the GIL
    grouped = frame.groupby(["procedure", "record", "alpha_deg"], sort=False)
    group = grouped.ngroup().to_numpy()
    keys = grouped.size()
    size = len(keys)
    code = frame["verdict"].map(VERDICT_CODE).to_numpy(dtype=float)
    known = ~np.isnan(code)
    counts = np.bincount(group[known] * len(VERDICTS) + code[known].astype(np.int64),
                         minlength=size * len(VERDICTS)).reshape(size, len(VERDICTS))
    fragile = np.bincount(group, weights=frame["exact_fragile"].eq(True).to_numpy(),
                          minlength=size)
    ratio = frame["ratio"].to_numpy(dtype=float)
    finite = np.isfinite(ratio)
    spread = (pd.Series(ratio[finite]).groupby(group[finite]).agg(["median", "min", "max"])
              .reindex(range(size)).to_numpy())
    stats = []
    for g, ((procedure, record, alpha), blocks) in enumerate(keys.items()):
        median, low, high = spread[g].tolist()
        stats.append({
            "procedure": procedure, "record": record, "alpha_deg": float(alpha),
            "blocks": int(blocks),
            "counts": dict(zip(VERDICTS, counts[g].tolist())),
            "fragile": int(fragile[g]),
            "median_ratio": None if np.isnan(median) else float(median),
            "min_ratio": None if np.isnan(low) else float(low),
            "max_ratio": None if np.isnan(high) else float(high),
        })
    return stats


class RunWriter:
    """The files of one run in ``folder``, fed one record at a time.

    Parameters
    ----------
    folder : Path
        An existing, empty folder (a staging folder: the caller moves the files into place).
    procedures : list of procedures.Procedure
    kept_records : set of str
        Records whose whole part is kept in memory (:meth:`kept_run`): those the claims read.
    """

    def __init__(self, folder: Path, procedures, kept_records=frozenset()):
        self.folder = Path(folder)
        self.procedures = procedures
        self.kept_records = set(kept_records)
        self._files = {name: open(self.folder / name, "wb") for name in RECORD_TABLES}
        for name, stream in self._files.items():
            stream.write((",".join(GUIDE[name]) + "\n").encode())
        self._files[DESIGN_SPECTRA_CSV].write(
            table_bytes(ubc97_design_spectrum(), DESIGN_SPECTRA_CSV, header=False))
        self.suite_statistics = SuiteStatistics()
        self.bottom_line = BottomLine(procedures)
        self.shown = ShownRecords([p.name for p in procedures])
        self.statistics, self.unauditable, self.histories = [], [], []
        self.kept = []

    def add(self, entry, part) -> None:
        """Append one record's rows and fold them into the suite's statistics.

        Parameters
        ----------
        entry : records.RecordEntry
            The record.
        part : RecordAudit
            Its part of the audit.
        """
        self._files[DESIGN_SPECTRA_CSV].write(
            table_bytes(site_design_spectra(entry), DESIGN_SPECTRA_CSV, header=False))
        for name, (attribute, *_) in RECORD_TABLES.items():
            if name != DESIGN_SPECTRA_CSV:
                self._files[name].write(table_bytes(getattr(part, attribute), name,
                                                    header=False))
        self.suite_statistics.add(part.results)
        self.bottom_line.add(part.results, part.checks)
        self.shown.add(part.results, part.histories_meta)
        self.statistics += statistics(part.results)
        self.unauditable += part.unauditable
        self.histories += part.histories_meta
        if entry.id in self.kept_records:
            self.kept.append(part)

    def close(self) -> None:
        """Close the CSV files (the tables are complete) and compute ``suite.csv``."""
        for stream in self._files.values():
            stream.close()
        self.suite_frame = self.suite_statistics.frame()

    def summary(self, suite, settings, detail) -> dict:
        """``summary.json`` of the run (its records, statistics, bottom line and which records
        the report shows).

        Parameters
        ----------
        suite : records.RecordSuite
            The records.
        settings : AuditSettings
            The audit's settings.
        detail : sequence of str
            Record ids whose per-record detail the report should show; the worst records when empty
            (every record of a small suite).
        """
        ids = [entry.id for entry in suite]
        worst = self.shown.worst_records()
        detailed = set(ids) if len(ids) <= LARGE_SUITE else set(detail or worst)
        blocks = self.shown.table_blocks()
        shown = detailed | {record for record, *_ in blocks}
        return {
            "version": __version__,
            "procedures": [{"name": p.name, "title": p.title, "reference": p.reference,
                            "damping_law": p.damping_law, "spectrum_source": p.spectrum_source,
                            "figure_series": p.figure_series,
                            **({"parameters": parameters_used(p)} if type(p).parameters else {})}
                           for p in self.procedures],
            "records_source": suite.description,
            "pulse_idealised": suite.is_pulse_idealised,
            "records": [record_summary(entry) for entry in suite],
            "rejected_records": list(getattr(suite, "rejected", ())),
            "design_site": suite.design_site,
            "scaling": suite.scaling,
            "floor": suite_floor(suite),
            "unauditable": self.unauditable,
            "grid": {"alpha_deg": list(settings.alpha_deg), "size_s": list(settings.size_s)},
            "settings": settings.described(),
            "statistics": self.statistics,
            "suite": suite_summary(self.suite_frame,
                                   {p.name: p.title for p in self.procedures}),
            "bottom_line": self.bottom_line.lines(),
            "histories": self.histories,
            "mechanics": sensitivity_facts(),
            "detail": list(detail),
            "worst_records": worst,
            # the report's sections: every record of a small suite, else those asked for or
            # the worst ones; the blocks of its worst-cases table; the records whose rows it
            # reads (both)
            "detail_records": [record for record in ids if record in detailed],
            "worst_blocks": blocks,
            "shown_records": [record for record in ids if record in shown],
        }

    def kept_run(self, summary: dict) -> AuditRun:
        """An :class:`AuditRun` of the kept records' rows and the whole run's summary.

        Parameters
        ----------
        summary : dict
            The whole run's summary (:meth:`summary`).
        """
        def cat(name):
            return concat([getattr(part, name) for part in self.kept
                           if len(getattr(part, name))], GUIDE[_FILE_OF[name]])
        return AuditRun(cat("results"), cat("spectra"), cat("histories"), cat("rocking"),
                        cat("estimates_only"), summary, checks=cat("checks"),
                        suite=self.suite_frame)

    def finish(self, summary: dict, claims) -> None:
        """Write the files of the suite as a whole.

        Parameters
        ----------
        summary : dict
            The whole run's summary.
        claims : pandas.DataFrame
            The claims checklist (``claims.csv``).
        """
        run = AuditRun(summary=summary, suite=self.suite_frame, claims=claims,
                       mechanics=mechanics())
        for name, content in suite_files(run).items():
            (self.folder / name).write_bytes(content)


_FILE_OF = {attribute: name for name, (attribute, *_) in RECORD_TABLES.items()}


__all__ = ["RunWriter", "record_summary", "statistics"]
