"""Verdict statistics across the records of a suite (``suite.csv``, ``summary["suite"]``).

The question a code committee asks is not "what happens under Pacoima" but "over a suite of
records consistent with the design, how often is the guideline unsafe, for which blocks, and by
how much". For every procedure × α × size the records audited are counted, each verdict class
as a fraction of them, and the approx/exact ratio where both survive as a median and a
16–84 % band.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from audit.engine.ranking import worst_case
from audit.engine.schemas import SUITE_COLUMNS, verdict_column
from audit.engine.verdicts import (CHECK_VERDICTS, UNECONOMIC_CHECK_VERDICTS, UNECONOMIC_VERDICTS,
                                   UNSAFE_CHECK_VERDICTS, UNSAFE_VERDICTS, VERDICTS, names)

#: Percentiles of approx/exact written to ``suite.csv`` [%].
RATIO_PERCENTILES = (16, 50, 84)
_KEYS = ["procedure", "alpha_deg", "size_s"]


def suite_statistics(results: pd.DataFrame) -> pd.DataFrame:
    """Verdict fractions and approx/exact percentiles per procedure × α × size.

    Parameters
    ----------
    results : pandas.DataFrame
        ``results.csv`` rows (columns ``procedure, alpha_deg, size_s, verdict, ratio``), one
        per record for each procedure × α × size.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`~audit.engine.schemas.SUITE_COLUMNS`: ``records`` counted, the fraction
        of them in each verdict class (the fractions sum to 1), ``frac_unsafe`` (missed
        overturning + unconservative), and the 16th/50th/84th percentiles of approx/exact over
        the records where both survive (linear interpolation between order statistics; NaN
        where there is none). Groups keep the order of first appearance.
    """
    if results.empty:
        return pd.DataFrame(columns=SUITE_COLUMNS)
    unknown = set(results["verdict"]) - set(VERDICTS)
    if unknown:
        raise ValueError(f"suite statistics: unknown verdicts {sorted(unknown)}")
    indicators = pd.DataFrame({verdict_column(v): (results["verdict"] == v).astype(float)
                               for v in VERDICTS})
    indicators[_KEYS] = results[_KEYS]
    indicators["ratio"] = results["ratio"].astype(float).replace([np.inf, -np.inf], np.nan)
    grouped = indicators.groupby(_KEYS, sort=False)
    table = grouped[[verdict_column(v) for v in VERDICTS]].mean()
    table.insert(0, "records", grouped.size())
    table["frac_unsafe"] = table[[verdict_column(v) for v in UNSAFE_VERDICTS]].sum(axis=1)
    for q in RATIO_PERCENTILES:
        table[f"ratio_p{q}"] = grouped["ratio"].quantile(q / 100.0)
    return table.reset_index()[SUITE_COLUMNS]


def suite_summary(suite: pd.DataFrame, titles: dict | None = None) -> list[dict]:
    """Per procedure and α: mean unsafe fraction, worst size, and a sentence to quote.

    Parameters
    ----------
    suite : pandas.DataFrame
        Output of :func:`suite_statistics`.
    titles : dict, optional
        Procedure name → title used in the sentence (default: the name).

    Returns
    -------
    list of dict
        ``procedure, alpha_deg, records, blocks, mean_unsafe, worst_size_s, worst_unsafe,
        sentence``; ``mean_unsafe`` is the unsafe fraction over every record × size (blocks
        weighted by their record count), ``worst_size_s`` the size 2π/p [s] with the largest
        unsafe fraction (the smallest such size on ties; None when never unsafe).
    """
    titles = titles or {}
    summary = []
    for (procedure, alpha), group in suite.groupby(["procedure", "alpha_deg"], sort=False):
        records = int(group["records"].max())
        counts = group["records"].to_numpy(dtype=float)
        unsafe = group["frac_unsafe"].to_numpy(dtype=float)
        mean_unsafe = float(np.sum(unsafe * counts) / np.sum(counts))
        worst = int(np.argmax(unsafe))
        worst_size = float(group["size_s"].iloc[worst]) if unsafe[worst] > 0 else None
        title = titles.get(procedure, procedure)
        over = f"over {records} record{'s' if records != 1 else ''}"
        sentence = (f"{over}, {title} is unsafe for {100 * mean_unsafe:.0f} % of blocks with "
                    f"α = {alpha:g}°, worst at 2π/p ≈ {worst_size:.3g} s "
                    f"({100 * unsafe[worst]:.0f} % of records)" if worst_size is not None else
                    f"{over}, {title} is never unsafe for blocks with α = {alpha:g}° "
                    f"(2π/p = {group['size_s'].min():g}–{group['size_s'].max():g} s)")
        summary.append({"procedure": procedure, "alpha_deg": float(alpha), "records": records,
                        "blocks": int(counts.sum()), "mean_unsafe": mean_unsafe,
                        "worst_size_s": worst_size, "worst_unsafe": float(unsafe[worst]),
                        "sentence": sentence})
    return summary


def bottom_line(results: pd.DataFrame, checks: pd.DataFrame, procedures) -> list[dict]:
    """Per procedure: how many blocks it gets wrong on each side, and its worst case.

    Parameters
    ----------
    results : pandas.DataFrame
        ``results.csv`` rows (blocks with an exact response).
    checks : pandas.DataFrame
        ``checks.csv`` rows.
    procedures : list of procedures.Procedure

    Returns
    -------
    list of dict
        ``name, blocks, records, count`` (per verdict), ``pct`` (per verdict, % of blocks),
        ``unsafe, uneconomic, unsafe_pct, uneconomic_pct, median_ratio`` (approx/exact where
        both survive), ``worst`` (the row of :func:`~audit.engine.ranking.worst_case`, or
        None), ``checks``: per limit state, ``limit_state, blocks, count`` (per check
        verdict), ``unsafe_pct`` (passed blocks the exact response exceeds, % of blocks) and
        ``uneconomic_pct``; and where pure rocking stops being valid, counted apart (their
        verdicts stay in ``count``): ``jumps``, ``slides`` and ``slides_unsafe`` (None without
        ``--friction``), ``model_sensitive`` and ``model_sensitive_unsafe`` (verdicts that change
        under an alternative ground-truth model; None without ``--sensitivity``).
    """
    lines = []
    for procedure in procedures:
        rows = results[results["procedure"] == procedure.name]
        mine = checks[checks["procedure"] == procedure.name]
        total = len(rows)
        counts = rows["verdict"].value_counts()
        count = {v: int(counts.get(v, 0)) for v in VERDICTS}
        unsafe = sum(count[v] for v in UNSAFE_VERDICTS)
        uneconomic = sum(count[v] for v in UNECONOMIC_VERDICTS)
        ratios = rows["ratio"].astype(float).replace([np.inf, -np.inf], np.nan).dropna()
        worst = worst_case(rows)
        unsafe_rows = rows["verdict"].isin(UNSAFE_VERDICTS)
        lines.append({
            "name": procedure.name, "blocks": total,
            "records": len(set(rows["record"]) | set(mine["record"])),
            "count": count, "pct": {v: 100.0 * n / total if total else 0.0
                                    for v, n in count.items()},
            "unsafe": unsafe, "uneconomic": uneconomic,
            "unsafe_pct": 100.0 * unsafe / total if total else 0.0,
            "uneconomic_pct": 100.0 * uneconomic / total if total else 0.0,
            "median_ratio": float(ratios.median()) if len(ratios) else None,
            "worst": None if worst is None else worst.to_dict(),
            "checks": _check_lines(mine),
            "jumps": int(rows["exact_jumps"].eq(True).sum()),
            **_flagged(rows, "exact_slides", "slides", unsafe_rows),
            **_flagged(rows, "exact_model_sensitive", "model_sensitive", unsafe_rows)})
    return lines


def _flagged(rows: pd.DataFrame, column: str, name: str, unsafe: pd.Series) -> dict:
    """Blocks flagged in ``column`` and the unsafe verdicts among them; None where the flag was
    not checked (the column is empty)."""
    flagged = rows[column].eq(True)
    checked = bool(rows[column].isin((True, False)).any())
    return {name: int(flagged.sum()) if checked else None,
            f"{name}_unsafe": int((flagged & unsafe).sum()) if checked else None}


def _check_lines(checks: pd.DataFrame) -> list[dict]:
    lines = []
    for state, rows in checks.groupby("limit_state", sort=False):
        counts = rows["verdict"].value_counts()
        count = {v: int(counts.get(v, 0)) for v in names(CHECK_VERDICTS)}
        lines.append({"limit_state": state, "blocks": len(rows), "count": count,
                      "unsafe_pct": 100.0 * sum(count[v] for v in UNSAFE_CHECK_VERDICTS)
                      / len(rows),
                      "uneconomic_pct": 100.0 * sum(count[v] for v in UNECONOMIC_CHECK_VERDICTS)
                      / len(rows)})
    return lines


__all__ = ["suite_statistics", "suite_summary", "bottom_line", "RATIO_PERCENTILES"]
