"""CSV text of the output tables, the bytes pandas' ``to_csv(index=False, float_format=...)``
writes, about three times faster.

pandas formats every cell through its generic formatter (a NaN test and a Python call per
value), which took half a second of a seed-suite audit; here each column is turned into its
texts in one list comprehension and the rows joined once. A test checks byte equality with
pandas on every kind of cell the tables hold.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from pandas.api.types import infer_dtype

_QUOTE_IF = (",", '"', "\n", "\r")


def _cell(value, float_format: str) -> str:
    """One cell of an object column as pandas writes it."""
    kind = type(value)
    if value is None or (kind is float and value != value):
        return ""
    if kind is str:
        if any(mark in value for mark in _QUOTE_IF):
            return '"' + value.replace('"', '""') + '"'
        return value
    if kind is float:
        return float_format % value
    return str(value)


def _column(values, float_format: str) -> list[str]:
    kind = values.dtype.kind
    if kind == "f":
        # the tables repeat their values (grid coordinates, one exact response under every
        # procedure, rest and overturning fills): each distinct one is formatted once, told
        # apart by its bits so that -0.0 stays "-0"
        codes, distinct = pd.factorize(np.ascontiguousarray(values, dtype=np.float64)
                                       .view(np.int64))
        texts = ["" if x != x else float_format % x
                 for x in distinct.view(np.float64).tolist()]
        return np.asarray(texts, dtype=object)[codes].tolist()
    if kind in "iu":
        return list(map(str, values.tolist()))
    if kind == "b":
        return ["True" if x else "False" for x in values.tolist()]
    if infer_dtype(values, skipna=True) == "string":
        # text columns repeat a few values (record ids, verdicts): each distinct one is
        # formatted once; code -1 (None, NaN) takes the empty text appended last
        codes, distinct = pd.factorize(values)
        texts = [_cell(x, float_format) for x in distinct] + [""]
        return np.asarray(texts, dtype=object)[codes].tolist()
    return [_cell(x, float_format) for x in values.tolist()]


def csv_bytes(frame: pd.DataFrame, float_format: str, header: bool = True) -> bytes:
    """``frame`` as CSV (header unless ``header`` is false, no index, floats by ``float_format`` such as ``"%.10g"``,
    empty cells for NaN and None, fields quoted only where they hold a comma, quote or line
    break), UTF-8.

    Parameters
    ----------
    frame : pandas.DataFrame
        The table.
    float_format : str
        ``%``-format of floats, e.g. ``"%.10g"``.
    header : bool
        Whether the first line names the columns.
    """
    columns = [_column(frame[name].to_numpy(), float_format) for name in frame.columns]
    rows = "\n".join(map(",".join, zip(*columns))) + "\n" if columns and len(frame) else ""
    if header:
        rows = ",".join(_cell(str(name), float_format) for name in frame.columns) + "\n" + rows
    return rows.encode()


__all__ = ["csv_bytes"]
