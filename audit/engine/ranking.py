"""Which blocks a procedure gets most wrong: the ranking the drawn time histories, the worst-cases
table and the bottom line's worst case all share (light: pandas only, no solver)."""

from __future__ import annotations

import pandas as pd

#: The worst blocks drawn as time histories, per procedure: (verdict, column ranked, largest
#: first?, reason). Missed overturnings rank by how small the procedure's rotation is.
WORST_CLASSES = (("unconservative", "ratio", False, "largest underestimate"),
                 ("missed-overturn", "approx_theta_rad", False, "missed overturning"),
                 ("conservative", "ratio", True, "largest overestimate"))


def rank_worst(rows: pd.DataFrame, column: str, largest: bool) -> pd.DataFrame:
    """``rows`` worst first by ``column``, blocks with a robust exact verdict before fragile ones
    (a missed overturning that a 3 % change of the record undoes is a weaker case)."""
    fragile = rows["exact_fragile"].eq(True)
    return rows.assign(_fragile=fragile).sort_values(
        ["_fragile", column], ascending=[True, not largest], kind="stable").drop(
        columns="_fragile")


def worst_case(rows: pd.DataFrame):
    """The block a procedure's bottom line names: a missed overturning where the procedure's
    rotation is smallest (robust before fragile), else the largest underestimate, else the
    largest overestimate; None when there is none."""
    order = sorted(WORST_CLASSES, key=lambda item: item[0] != "missed-overturn")
    for verdict, column, largest, _ in order:
        hits = rows[rows["verdict"] == verdict]
        if len(hits):
            return rank_worst(hits, column, largest).iloc[0]
    return None


__all__ = ["WORST_CLASSES", "rank_worst", "worst_case"]
