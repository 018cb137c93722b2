"""Which blocks a procedure gets most wrong: the ranking the drawn time histories, the worst-cases
table and the bottom line's worst case all share, and which records the report shows (light:
pandas only, no solver)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from audit.engine.shared.verdicts import UNSAFE_VERDICTS

#: Above this many records the suite statistics come first and per-record detail is given only
#: for the records asked for (``summary["detail"]``) or the :data:`WORST_RECORDS` worst ones.
LARGE_SUITE = 10
WORST_RECORDS = 3
#: Rows per procedure and class in the worst-cases table.
WORST_ROWS = 5

#: The worst blocks drawn as time histories, per procedure: (verdict, column ranked, largest
#: first?, reason). Missed overturnings rank by how small the procedure's rotation is.
WORST_CLASSES = (("unconservative", "ratio", False, "largest underestimate"),
                 ("missed-overturn", "approx_theta_rad", False, "missed overturning"),
                 ("conservative", "ratio", True, "largest overestimate"))

#: Each ranked class's verdict → (column ranked, largest first?).
_RANKED = {verdict: (column, largest) for verdict, column, largest, _ in WORST_CLASSES}


def rank_worst(rows: pd.DataFrame, column: str, largest: bool) -> pd.DataFrame:
    """``rows`` worst first by ``column``, blocks with a robust exact verdict before fragile ones
    (a missed overturning that a 3 % change of the record undoes is a weaker case); NaN last,
    ties in the rows' order.

    Parameters
    ----------
    rows : pandas.DataFrame
        ``results.csv`` rows.
    column : str
        The column ranked by.
    largest : bool
        Whether the largest value is the worst.
    """
    return rows.take(_worst_first(rows["exact_fragile"].eq(True).to_numpy(),
                                  rows[column].to_numpy(dtype=float), largest))


def _worst_first(fragile: np.ndarray, value: np.ndarray, largest: bool) -> np.ndarray:
    """The order of :func:`rank_worst`, of the rows' fragility flags and ranked values."""
    missing = np.isnan(value)
    # numpy's lexsort is stable, as pandas' sort_values on these keys is, at a fraction of
    # its cost (the bottom line ranks every record's rows)
    return np.lexsort((np.where(missing, 0.0, -value if largest else value), missing, fragile))


def worst_positions(verdicts: np.ndarray, fragile: np.ndarray, values: np.ndarray, verdict: str,
                    largest: bool, count: int) -> np.ndarray:
    """Positions of the ``count`` worst rows of class ``verdict``, in :func:`rank_worst`'s order,
    from the rows' columns as arrays: no frame is indexed (a record's histories and its bottom
    line pick a few rows of each class).

    Parameters
    ----------
    verdicts, fragile, values : numpy.ndarray
        The rows' verdicts, exact fragility flags and ranked values.
    verdict : str
        The class.
    largest : bool
        Whether the largest value is the worst.
    count : int
        Rows wanted (fewer where the class has fewer).
    """
    hits = np.flatnonzero(verdicts == verdict)
    return hits[_worst_first(fragile[hits], values[hits], largest)[:count]]


def worst_case(rows: pd.DataFrame):
    """The block a procedure's bottom line names: a missed overturning where the procedure's
    rotation is smallest (robust before fragile), else the largest underestimate, else the
    largest overestimate; None when there is none.

    Parameters
    ----------
    rows : pandas.DataFrame
        One procedure's ``results.csv`` rows.

    Returns
    -------
    pandas.Series or None
    """
    order = sorted(WORST_CLASSES, key=lambda item: item[0] != "missed-overturn")
    verdicts = rows["verdict"].to_numpy()
    fragile = rows["exact_fragile"].eq(True).to_numpy()
    for verdict, column, largest, _ in order:
        # ranked on the columns' arrays: one row taken from the frame, not every hit
        first = worst_positions(verdicts, fragile, rows[column].to_numpy(dtype=float), verdict,
                                largest, 1)
        if first.size:
            return rows.iloc[first[0]]
    return None


def block_key(record, alpha_deg, size_s) -> tuple:
    """A block of a record, as the drawn time histories name it.

    Parameters
    ----------
    record : str
        The record's id.
    alpha_deg : float
        Slenderness α [degrees].
    size_s : float
        Size 2π/p [s].
    """
    return record, round(float(alpha_deg), 6), round(float(size_s), 6)


def is_drawn(results: pd.DataFrame, metas: list[dict]) -> np.ndarray:
    """Which rows of ``results`` are blocks whose time history was drawn (``metas``).

    Parameters
    ----------
    results : pandas.DataFrame
        ``results.csv`` rows.
    metas : list of dict
        The drawn histories (``record``, ``alpha_deg``, ``size_s``).
    """
    keys = {block_key(m["record"], m["alpha_deg"], m["size_s"]) for m in metas}
    return np.array([block_key(*key) in keys for key in zip(
        results["record"].tolist(), results["alpha_deg"].tolist(), results["size_s"].tolist())],
        dtype=bool)


class ShownRecords:
    """What the report shows of a large suite, folded over the records one part at a time: the
    records with the most unsafe blocks, and the worst drawn blocks of each procedure and class
    (the worst-cases table). The report then ranks the rows of those blocks' records again and
    finds the same blocks, with no need for the other records.

    Parameters
    ----------
    procedures : list of str
        Procedure names.
    """

    _COLUMNS = ["record", "alpha_deg", "size_s", "ratio", "approx_theta_rad", "exact_fragile"]

    def __init__(self, procedures):
        self._unsafe = {}  # record → unsafe blocks, in the suite's order
        self._worst = {(name, verdict): pd.DataFrame(columns=self._COLUMNS)
                       for name in procedures for verdict, *_ in WORST_CLASSES}

    def add(self, results: pd.DataFrame, metas: list[dict]) -> None:
        """Fold one record's ``results.csv`` rows and the time histories drawn for it.


        Parameters
        ----------
        results : pandas.DataFrame
            The record's ``results.csv`` rows.
        metas : list of dict
            Its drawn histories.
        """
        verdict = results["verdict"]
        for record in results["record"].to_numpy()[verdict.isin(UNSAFE_VERDICTS).to_numpy()]:
            self._unsafe[record] = self._unsafe.get(record, 0) + 1
        # only the drawn rows of the ranked classes can enter the table: they are picked from
        # the arrays, and the few of them taken from the frame once
        kept = verdict.isin(_RANKED).to_numpy().copy()
        kept[kept] = is_drawn(results.loc[kept, ["record", "alpha_deg", "size_s"]], metas)
        rows = results.loc[kept, ["procedure", "verdict", *self._COLUMNS]]
        for (name, verdict), hits in rows.groupby(["procedure", "verdict"], sort=False):
            if (name, verdict) in self._worst:
                column, largest = _RANKED[verdict]
                both = pd.concat([self._worst[name, verdict], hits[self._COLUMNS]],
                                 ignore_index=True)
                self._worst[name, verdict] = rank_worst(both, column, largest).head(WORST_ROWS)

    def worst_records(self) -> list[str]:
        """The :data:`WORST_RECORDS` records with the most unsafe blocks (suite order on ties)."""
        ranked = sorted(self._unsafe.items(), key=lambda item: -item[1])
        return [record for record, n in ranked[:WORST_RECORDS] if n]

    def table_blocks(self) -> list[list]:
        """``[record, α, size]`` of the blocks of the worst-cases table (each once)."""
        blocks = {block_key(*key): list(key) for frame in self._worst.values()
                  for key in zip(frame["record"], frame["alpha_deg"].astype(float),
                                 frame["size_s"].astype(float))}
        return list(blocks.values())


__all__ = ["WORST_CLASSES", "LARGE_SUITE", "WORST_RECORDS", "WORST_ROWS", "rank_worst",
           "worst_positions", "worst_case", "block_key", "is_drawn", "ShownRecords"]
