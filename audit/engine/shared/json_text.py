"""Plain JSON of a summary: what every workflow's ``summary.json`` is written through."""

from __future__ import annotations

import math

import numpy as np


def json_ready(value):
    """Plain JSON: NaN and inf become null, numpy scalars become Python numbers.

    Parameters
    ----------
    value : object
        A dict, list, tuple or scalar, nested.
    """
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


__all__ = ["json_ready"]
