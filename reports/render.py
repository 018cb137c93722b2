"""The self-contained HTML audit report, rendered from a saved :class:`~audit.engine.run.audit_run.AuditRun`.

Figures are plotly.js specifications drawn by the browser from data embedded in the page;
plotly.js itself is inlined once, so the page references nothing outside itself, opens offline
and can be attached to a design review. Nothing is drawn on the server.
"""

from __future__ import annotations

import math
from collections import defaultdict
from datetime import datetime, timezone

import numpy as np
import pandas as pd

from audit import G
from audit.engine.run.ranking import (LARGE_SUITE, WORST_CLASSES, WORST_ROWS, block_key,
                                  is_drawn, rank_worst)
from audit.engine.shared.schemas import GUIDE
from audit.engine.shared.verdicts import ROTATION_VERDICTS, UNSAFE_VERDICTS, VERDICTS, meanings
from reports.block_metres import describe_block
from reports.frame_rows import row_dicts
from reports.grid_figures import verdict_map_figure
from reports.history_figures import history_figure
from reports.html_parts import page_templates
from reports.outcome_words import describe_exact, describe_guideline
from reports.palette import CHECK_COLOURS, VERDICT_COLOURS
from reports.plots import to_json
from reports.spectra_figures import procedure_figure, response_and_rocking_figure
from reports.suite_sections import (CHECK_MEANING, checks_section, claims_section,
                                    mechanics_section, suite_section)

#: Colours of the guidelines' estimates in the time histories.
PROCEDURE_COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd")

VERDICT_MEANING = meanings(ROTATION_VERDICTS)
#: What the words of a guideline's estimate are made of (``describe_guideline``).
ESTIMATE_COLUMNS = ("procedure", "verdict", "alpha_deg", "approx_outcome", "approx_theta_rad",
                    "approx_period_s", "approx_cycle")
#: What a row of the worst-cases table is made of, and ranked by (``WORST_CLASSES``).
WORST_COLUMNS = (*ESTIMATE_COLUMNS, "record", "size_s", "exact_overturned", "exact_fragile",
                 "exact_theta_rad", "ratio")


class _Figures:
    """The figures of the page: a div id and a plotly spec each, in page order."""

    def __init__(self):
        self.specs = {}

    def add(self, figure_id: str, spec: dict) -> dict:
        self.specs[figure_id] = spec
        return {"id": figure_id, "height": spec["layout"]["height"]}


def _history_id(record, alpha, size) -> str:
    return f"th-{record}-{alpha:g}-{size:.2f}".replace(".", "_")


def _where(row, names) -> str:
    return (f"{names.get(row['record'], row['record'])}, α = {row['alpha_deg']:g}°, "
            f"2π/p = {row['size_s']:.2f} s "
            f"({describe_block(row['alpha_deg'], row['size_s'])})")


def _bottom_line(procedure: dict, line: dict, names: dict, band: float) -> dict:
    """One sentence per procedure from the engine's bottom line (``summary["bottom_line"]``)."""
    worst = line["worst"]
    worst_text = ""
    if worst is not None:
        worst_text = (f"{_where(worst, names)}: the guideline gives "
                      f"{describe_guideline(worst)}, the exact response "
                      f"{describe_exact(worst)} ({worst['verdict']})")
    return {**procedure, **line, "band_pct": 100.0 * band, "worst": worst_text,
            "worst_link": (_history_id(worst["record"], worst["alpha_deg"], worst["size_s"])
                           if worst is not None else None)}


def _estimates(match: pd.DataFrame, procedures) -> tuple[list, list]:
    """The guidelines' estimates for one block: lines to draw and words for the caption."""
    lines, words = [], []
    first = {}  # each procedure's row, in one pass over the block's few rows
    for row in row_dicts(match, ESTIMATE_COLUMNS):
        first.setdefault(row["procedure"], row)
    for colour, procedure in zip(PROCEDURE_COLOURS, procedures):
        row = first.get(procedure["name"])
        if row is None:
            continue
        words.append(f"{procedure['title']}: {describe_guideline(row)} ({row['verdict']})")
        if row["approx_outcome"] == "converged":
            lines.append((procedure["title"],
                          row["approx_theta_rad"] / math.radians(row["alpha_deg"]),
                          row["approx_period_s"], colour))
    return lines, words


def _by_record(frame: pd.DataFrame) -> dict:
    """The rows of each record, no rows (same columns) for any other: one pass, instead of a
    scan of the whole frame per figure."""
    return defaultdict(lambda: frame.iloc[:0], list(frame.groupby("record", sort=False)))


def _by_procedure(frame: pd.DataFrame) -> dict:
    """The rows of each procedure, no rows (same columns) for any other."""
    return defaultdict(lambda: frame.iloc[:0], list(frame.groupby("procedure", sort=False)))


def _at(frame: pd.DataFrame, meta: dict) -> np.ndarray:
    """Which rows of ``frame`` are the block of ``meta`` (its α and size as saved)."""
    return (np.isclose(frame["size_s"].to_numpy(), meta["size_s"])
            & np.isclose(frame["alpha_deg"].to_numpy(), meta["alpha_deg"]))


def _history_figure(pending, histories: dict, results: dict, meta, procedures, names) -> dict:
    """Figure of one drawn time history; ``histories`` and ``results`` by record."""
    rid = meta["record"]
    h = histories[rid]
    h = h[_at(h, meta)]
    match = results[rid]
    match = match[_at(match, meta)]
    lines, words = _estimates(match, procedures)
    exact = (f"overturns at t = {meta['overturn_time_s']:.2f} s" if meta.get("overturned")
             else f"peak θ/α = {meta['peak_rotation_ratio']:.3f}")
    figure = pending.add(_history_id(rid, meta["alpha_deg"], meta["size_s"]),
                         history_figure(h, meta, lines))
    figure["caption"] = (
        f"{names.get(rid, rid)}, α = {meta['alpha_deg']:g}°, 2π/p = {meta['size_s']:.2f} s "
        f"({meta['reason']}). Exact: {exact}. " + "; ".join(words) + ". Shaded spans are full "
        "rocking cycles (every second impact), to compare with the converged T(θ); the dashed "
        "grey line marks the end of the record.")
    figure["title"] = (f"{names.get(rid, rid)}, α = {meta['alpha_deg']:g}°, "
                       f"2π/p = {meta['size_s']:.2f} s")
    return figure


def _worst_cases(run, procedures, names, metas) -> list[dict]:
    """Per procedure and class, the worst blocks whose time history the run simulated (the run
    holds the rows of the records shown, which include those blocks; the totals are the
    whole suite's, from the bottom line)."""
    counts = {line["name"]: line["count"] for line in run.summary["bottom_line"]}
    # only drawn blocks can be listed: ranked after this cut, they keep their order (the
    # ranking is a stable sort) and the sort handles a few rows, not the whole suite
    drawn_rows = run.results.loc[is_drawn(run.results, metas), list(WORST_COLUMNS)]
    tables = []
    for procedure in procedures:
        rows = drawn_rows[drawn_rows["procedure"] == procedure["name"]]
        for verdict, column, largest, reason in WORST_CLASSES:
            hits = rows[rows["verdict"] == verdict]
            if len(hits):
                hits = rank_worst(hits, column, largest).head(WORST_ROWS)
            tables.append({"procedure": procedure, "reason": reason, "verdict": verdict,
                           "total": counts[procedure["name"]][verdict], "rows": [{
                               "where": _where(row, names), "exact": describe_exact(row),
                               "guideline": describe_guideline(row),
                               "ratio": row["ratio"], "fragile": row["exact_fragile"] is True,
                               "link": _history_id(row["record"], row["alpha_deg"],
                                                   row["size_s"]),
                               "key": block_key(row["record"], row["alpha_deg"], row["size_s"])}
                               for row in row_dicts(hits, WORST_COLUMNS)]})
    return tables


def _record_sections(run, procedures, pending, results, records, names, drawn,
                     by_record) -> list[dict]:
    summary = run.summary
    spectra_by, rocking_by = _by_record(run.spectra), _by_record(run.rocking)
    sections = []
    for record in records:
        rid, number = record["id"], record["number"]
        section = {"record": record, "number": number, "figures": [], "histories": [],
                   "unauditable": [u for u in summary["unauditable"] if u["record"] == rid]}
        # each procedure's rows and spectra split off once, not masked out per procedure
        rows = _by_procedure(by_record[1][rid])
        spectra = _by_procedure(spectra_by[rid])
        if not record["missing"]:
            response = spectra[""]
            rocking = rocking_by[rid]
            has_site = bool((record.get("site") or {}).get("sxs_g"))
            design = run.design_spectra[run.design_spectra["record"].isin(("", rid))]
            figure = pending.add(f"fig-5-{number}",
                                 response_and_rocking_figure(response, rocking, design))
            figure["caption"] = (
                f"Figure 5.{number} — {record['name']}: true response spectra Sd, Sv, Sa "
                f"(relative displacement, relative velocity, absolute acceleration; not "
                f"pseudo-spectra) for ξ = 5/10/15 % with the design spectra "
                f"{'of FEMA 356 (dashed, site parameters of Table 3.1) and ' if has_site else ''}"
                f"of UBC 97 (dotted, zone 4, soil S_D, 5 %) (left), and the exact rocking "
                f"spectra per α (right; × above the curves: the block overturns, one row of × "
                f"per α). Drag to zoom, double-click to reset.")
            section["figures"].append(figure)
        for procedure in procedures:
            prows = rows[procedure["name"]]
            if prows.empty:
                continue
            pspec = spectra[procedure["name"]]
            series = procedure["figure_series"] or "P"
            figure = pending.add(f"fig-{series}-{number}-{procedure['name']}",
                                 procedure_figure(prows, pspec, procedure["title"]))
            figure["caption"] = (
                f"Figure {series}.{number} — {procedure['title']} on {record['name']}: the "
                f"displacement spectrum the procedure reads at its β(α) (left), exact peak "
                f"rotation against the procedure's rotation (centre; a purple band spans the "
                f"branches of a cycle the iteration settles in, ○ marks a repelling fixed point), "
                f"the converged T(θ) of Eq. 8.1 (right); one row per α.")
            section["figures"].append(figure)
        section["histories"] = [
            _history_figure(pending, *by_record, meta=meta, procedures=procedures, names=names)
            for meta in run.summary.get("histories", [])
            if meta["record"] == rid and block_key(rid, meta["alpha_deg"], meta["size_s"]) not in drawn]
        sections.append(section)
    return sections


def render_report(run, generated: datetime | None = None) -> str:
    """The HTML report of an audit run, as one self-contained string.

    Parameters
    ----------
    run : audit.engine.run.audit_run.AuditRun
        Results of ``audit_in_memory`` or of ``audit.engine.run.results.load_run``.
    generated : datetime, optional
        Time stamp printed in the report (default: now, UTC).
    """
    from plotly.offline import get_plotlyjs
    pending = _Figures()
    summary = run.summary
    procedures = summary["procedures"]
    names = {r["id"]: r["name"] for r in summary["records"]}
    records = [dict(r, number=n) for n, r in enumerate(summary["records"], start=1)]
    # all of a small suite; of a large one, those asked for or the worst ones (most unsafe blocks)
    detailed = set(summary["detail_records"])
    detail = [r for r in records if r["id"] in detailed]
    large = len(records) > LARGE_SUITE
    detail_ids = {r["id"] for r in detail}
    band = summary.get("settings", {}).get("agree_band", 0.10)
    # records without a file still show the estimate of a procedure that needs none
    results = pd.concat([run.results, run.estimates_only], ignore_index=True)
    lines = {line["name"]: line for line in summary["bottom_line"]}
    bottom = [_bottom_line(p, lines[p["name"]], names, band) for p in procedures]
    metas = summary.get("histories", [])
    worst = _worst_cases(run, procedures, names, metas)
    shown = {row["key"] for table in worst for row in table["rows"]}
    by_record = _by_record(run.histories), _by_record(results)
    worst_histories = [_history_figure(pending, *by_record, meta=meta, procedures=procedures,
                                       names=names)
                       for meta in metas
                       if block_key(meta["record"], meta["alpha_deg"], meta["size_s"]) in shown]
    verdict_maps = []
    for procedure in procedures:
        rows = run.results[run.results["procedure"] == procedure["name"]]
        audited = [r["id"] for r in detail if (rows["record"] == r["id"]).any()]
        if audited:
            spec = verdict_map_figure(rows, audited, names, VERDICTS)
            present = spec.pop("present")
            figure = pending.add(f"verdict-map-{procedure['name']}", spec)
            fragile = rows[rows["exact_fragile"].eq(True) & rows["record"].isin(audited)]
            hinge = fragile["verdict"].isin(("both-overturn", "missed-overturn",
                                             "false-overturn")).sum()
            figure.update(procedure=procedure, present=present, fragile=len(fragile),
                          hinge=int(hinge))
            verdict_maps.append(figure)
    statistics = [dict(s, record_name=names.get(s["record"], s["record"]))
                  for s in summary["statistics"] if s["record"] in detail_ids]
    sections = _record_sections(run, procedures, pending, results, detail, names, shown,
                                by_record)
    html = page_templates().get_template("report.html.j2").render(
        summary=summary, procedures=procedures, bottom=bottom, worst=worst,
        worst_histories=worst_histories, verdict_maps=verdict_maps, sections=sections,
        mechanics=mechanics_section(run, pending), statistics=statistics, large=large,
        suite=suite_section(run, procedures, pending),
        checks=checks_section(run, names, pending, detail_ids), claims=claims_section(run),
        check_colours=CHECK_COLOURS, check_meaning=CHECK_MEANING,
        verdicts=VERDICTS, verdict_meaning=VERDICT_MEANING, verdict_colours=VERDICT_COLOURS,
        unsafe_verdicts=UNSAFE_VERDICTS, records=records, g=G, band_pct=100.0 * band,
        omitted=len(records) - len(detail), guide=GUIDE["results.csv"],
        specs={k: to_json(v) for k, v in pending.specs.items()},
        plotly_js=get_plotlyjs(),
        generated=(generated or datetime.now(timezone.utc)).strftime("%Y-%m-%d %H:%M UTC"))
    return html
