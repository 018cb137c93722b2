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

from audit.engine.run.ranking import WORST_CLASSES, worst_case
from audit.engine.shared.schemas import SUITE_COLUMNS, verdict_column
from audit.engine.shared.verdicts import (CHECK_VERDICTS, UNECONOMIC_CHECK_VERDICTS, UNECONOMIC_VERDICTS,
                                   UNSAFE_CHECK_VERDICTS, UNSAFE_VERDICTS, VERDICTS, names)

#: Percentiles of approx/exact written to ``suite.csv`` [%].
RATIO_PERCENTILES = (16, 50, 84)
_KEYS = ["procedure", "alpha_deg", "size_s"]


class SuiteStatistics:
    """:func:`suite_statistics` folded over the records one part at a time, so that a suite of
    thousands of records is never held whole: the verdict counts per group are summed as they
    come, and only the finite approx/exact ratios (for the percentiles) are kept, with their
    group number (12 bytes each); the rest of each part is dropped."""

    def __init__(self):
        self._groups = {}  # (procedure, α, size) → number, in order of first appearance
        self._counts = np.zeros((0, len(VERDICTS)), dtype=np.int64)  # group × verdict
        self._group, self._ratio = [], []

    def add(self, results: pd.DataFrame) -> "SuiteStatistics":
        """Fold ``results.csv`` rows (columns ``procedure, alpha_deg, size_s, verdict, ratio``).

        Parameters
        ----------
        results : pandas.DataFrame
            ``results.csv`` rows.
        """
        unknown = set(results["verdict"]) - set(VERDICTS)
        if unknown:
            raise ValueError(f"suite statistics: unknown verdicts {sorted(unknown)}")
        keys = zip(results["procedure"], results["alpha_deg"].astype(float),
                   results["size_s"].astype(float))
        group = np.fromiter((self._groups.setdefault(key, len(self._groups)) for key in keys),
                            dtype=np.int32, count=len(results))
        verdict = results["verdict"].map(VERDICT_CODE).to_numpy(dtype=np.int64)
        if len(self._groups) > len(self._counts):
            self._counts = np.vstack([self._counts, np.zeros(
                (len(self._groups) - len(self._counts), len(VERDICTS)), dtype=np.int64)])
        np.add.at(self._counts, (group, verdict), 1)
        ratio = results["ratio"].to_numpy(dtype=float)
        finite = np.isfinite(ratio)
        self._group.append(group[finite])
        self._ratio.append(ratio[finite])
        return self

    def frame(self) -> pd.DataFrame:
        """The table of :func:`suite_statistics` over every row folded so far."""
        if not self._groups:
            return pd.DataFrame(columns=SUITE_COLUMNS)
        records = self._counts.sum(axis=1)
        table = pd.DataFrame(list(self._groups), columns=_KEYS)
        table["records"] = records
        for code, v in enumerate(VERDICTS):
            table[verdict_column(v)] = self._counts[:, code] / records
        table["frac_unsafe"] = table[[verdict_column(v) for v in UNSAFE_VERDICTS]].sum(axis=1)
        grouped = pd.Series(np.concatenate(self._ratio)).groupby(np.concatenate(self._group))
        for q in RATIO_PERCENTILES:
            table[f"ratio_p{q}"] = grouped.quantile(q / 100.0).reindex(table.index)
        return table[SUITE_COLUMNS]


#: Each verdict's number: its place in :data:`~audit.engine.shared.verdicts.VERDICTS`.
VERDICT_CODE = {v: code for code, v in enumerate(VERDICTS)}


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
        Columns :data:`~audit.engine.shared.schemas.SUITE_COLUMNS`: ``records`` counted, the fraction
        of them in each verdict class (the fractions sum to 1), ``frac_unsafe`` (missed
        overturning + unconservative), and the 16th/50th/84th percentiles of approx/exact over
        the records where both survive (linear interpolation between order statistics; NaN
        where there is none). Groups keep the order of first appearance.
    """
    return SuiteStatistics().add(results).frame()


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


#: Where pure rocking stops being valid: results column → name in the bottom line (None there
#: when the flag was not checked: the column is empty).
_FLAGS = {"exact_slides": "slides", "exact_model_sensitive": "model_sensitive"}


class BottomLine:
    """:func:`bottom_line` folded over the records one part at a time: per procedure the verdict
    and flag counts, the finite ratios (for the median), the records seen, the check counts
    per limit state and the worst block so far (the worst of the worst is the suite's: the
    ranking is a stable sort, and the parts come in the suite's order)."""

    def __init__(self, procedures):
        self._lines = {p.name: {"count": dict.fromkeys(VERDICTS, 0), "ratios": [],
                                "records": set(), "worst": None, "checks": {}, "jumps": 0,
                                "flags": {flag: [0, 0, False] for flag in _FLAGS.values()}}
                       for p in procedures}

    def add(self, results: pd.DataFrame, checks: pd.DataFrame) -> "BottomLine":
        """Fold ``results.csv`` and ``checks.csv`` rows.

        Parameters
        ----------
        results : pandas.DataFrame
            ``results.csv`` rows.
        checks : pandas.DataFrame
            ``checks.csv`` rows.
        """
        # the counts of every procedure at once, by its number on each row: this runs in the
        # driver for each record, beside solver threads that wait for the GIL it holds
        lines = list(self._lines.values())
        procedure = _numbers(results["procedure"], self._lines)
        verdict = results["verdict"].map(VERDICT_CODE).to_numpy(dtype=float)
        ours = procedure >= 0
        if np.isnan(verdict[ours]).any():
            raise ValueError(f"bottom line: unknown verdicts "
                             f"{sorted(set(results['verdict'][ours & np.isnan(verdict)]))}")
        counts = _per_procedure(procedure, len(lines), verdict, len(VERDICTS))
        unsafe = results["verdict"].isin(UNSAFE_VERDICTS).to_numpy()
        jumps = _per_procedure(procedure, len(lines), results["exact_jumps"].eq(True).to_numpy())
        flags = {}
        for column, flag in _FLAGS.items():
            flagged = results[column].eq(True).to_numpy()
            flags[flag] = (_per_procedure(procedure, len(lines), flagged),
                           _per_procedure(procedure, len(lines), flagged & unsafe),
                           _per_procedure(procedure, len(lines),
                                          results[column].isin((True, False)).to_numpy()))
        ratio = results["ratio"].to_numpy(dtype=float)
        finite = np.isfinite(ratio)
        record = results["record"].to_numpy()
        check_procedure = _numbers(checks["procedure"], self._lines)
        check_record = checks["record"].to_numpy()
        # only the rows of a ranked class can be the worst case
        ranked = results["verdict"].isin([verdict for verdict, *_ in WORST_CLASSES]).to_numpy()
        candidates = dict(tuple(results[ranked].groupby("procedure", sort=False)))
        for i, (name, line) in enumerate(self._lines.items()):
            rows = procedure == i
            for value, n in zip(VERDICTS, counts[i].tolist()):
                line["count"][value] += n
            line["ratios"].append(ratio[rows & finite])
            line["records"].update(record[rows])
            line["records"].update(check_record[check_procedure == i])
            worst = worst_case(candidates.get(name, results.iloc[:0]))
            if worst is not None:  # the worst of (the worst so far, this part's): the same
                # block as ranking them all, since the ranking is a stable sort
                line["worst"] = worst if line["worst"] is None else worst_case(
                    pd.DataFrame([line["worst"], worst]))
            line["jumps"] += jumps[i]
            for flag, (flagged, flagged_unsafe, checked) in flags.items():
                tally = line["flags"][flag]
                tally[0] += flagged[i]
                tally[1] += flagged_unsafe[i]
                tally[2] |= bool(checked[i])
        # (limit state, verdict) pairs come in order of first appearance, so the limit states
        # do too
        for (name, state, value), n in checks.groupby(["procedure", "limit_state", "verdict"],
                                                      sort=False).size().items():
            if name in self._lines:
                tally = self._lines[name]["checks"].setdefault(
                    state, dict.fromkeys(names(CHECK_VERDICTS), 0))
                tally[value] += int(n)
        return self

    def lines(self) -> list[dict]:
        """The bottom line of every row folded so far (see :func:`bottom_line`)."""
        out = []
        for name, line in self._lines.items():
            count = line["count"]
            total = sum(count.values())
            unsafe = sum(count[v] for v in UNSAFE_VERDICTS)
            uneconomic = sum(count[v] for v in UNECONOMIC_VERDICTS)
            ratios = np.concatenate(line["ratios"]) if line["ratios"] else np.empty(0)
            worst = line["worst"]
            flags = {}
            for flag, (flagged, flagged_unsafe, checked) in line["flags"].items():
                flags[flag] = flagged if checked else None
                flags[f"{flag}_unsafe"] = flagged_unsafe if checked else None
            out.append({
                "name": name, "blocks": total, "records": len(line["records"]),
                "count": count, "pct": {v: 100.0 * n / total if total else 0.0
                                        for v, n in count.items()},
                "unsafe": unsafe, "uneconomic": uneconomic,
                "unsafe_pct": 100.0 * unsafe / total if total else 0.0,
                "uneconomic_pct": 100.0 * uneconomic / total if total else 0.0,
                "median_ratio": float(np.median(ratios)) if len(ratios) else None,
                "worst": None if worst is None else worst.to_dict(),
                "checks": [_check_line(state, tally) for state, tally in line["checks"].items()],
                "jumps": line["jumps"], **flags})
        return out


def _numbers(column: pd.Series, known) -> np.ndarray:
    """The position of each row's value among ``known`` (in its order), -1 where absent."""
    return column.map({name: i for i, name in enumerate(known)}).fillna(-1).to_numpy(
        dtype=np.int64)


def _per_procedure(procedure: np.ndarray, count: int, values: np.ndarray,
                   classes: int | None = None) -> np.ndarray:
    """Per procedure (rows numbered by :func:`_numbers`; -1 left out): the number of true
    ``values``, or with ``classes`` the rows of each class code ``values``, as ints."""
    ours = procedure >= 0
    if classes is None:
        return np.bincount(procedure[ours], weights=values[ours],
                           minlength=count).astype(np.int64).tolist()
    return np.bincount(procedure[ours] * classes + values[ours].astype(np.int64),
                       minlength=count * classes).reshape(count, classes)


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
        both survive), ``worst`` (the row of :func:`~audit.engine.run.ranking.worst_case`, or
        None), ``checks``: per limit state, ``limit_state, blocks, count`` (per check
        verdict), ``unsafe_pct`` (passed blocks the exact response exceeds, % of blocks) and
        ``uneconomic_pct``; and where pure rocking stops being valid, counted apart (their
        verdicts stay in ``count``): ``jumps``, ``slides`` and ``slides_unsafe`` (None without
        ``--friction``), ``model_sensitive`` and ``model_sensitive_unsafe`` (verdicts that change
        under an alternative ground-truth model; None without ``--sensitivity``).
    """
    return BottomLine(procedures).add(results, checks).lines()


def _check_line(state: str, count: dict) -> dict:
    blocks = sum(count.values())
    return {"limit_state": state, "blocks": blocks, "count": count,
            "unsafe_pct": 100.0 * sum(count[v] for v in UNSAFE_CHECK_VERDICTS) / blocks,
            "uneconomic_pct": 100.0 * sum(count[v] for v in UNECONOMIC_CHECK_VERDICTS) / blocks}


__all__ = ["suite_statistics", "suite_summary", "bottom_line", "SuiteStatistics",
           "BottomLine", "RATIO_PERCENTILES"]
