"""A hazard curve as a plain CSV file, for any other tool: columns ``im_g`` (levels [g]) and
``annual_rate`` (mean annual rate of exceedance [1/yr]), and a first comment line naming the
intensity measure, ``# imt=SA(1.0)`` (or ``PGA``): without it the curve could be integrated
with a fragility of another measure.

::

    # imt=SA(1.0)
    im_g,annual_rate
    0.05,0.021
    0.1,0.0087
    ...
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

from audit.errors import InputError
from records.hazard.curve import HazardCurve, number, read_text

COLUMNS = ("im_g", "annual_rate")
_IMT_LINE = re.compile(r"^#\s*imt\s*[=:]\s*(\S+)", re.I)


def read_plain_curve(path) -> HazardCurve:
    """The hazard curve of a plain CSV file (see the module).

    Returns
    -------
    HazardCurve
        ``site`` is None: the file does not say where.
    """
    path = Path(path)
    lines = read_text(path).splitlines()
    imt = next((m.group(1) for line in lines if (m := _IMT_LINE.match(line.strip()))), None)
    if imt is None:
        raise InputError(f"{path}: imt: no line '# imt=PGA' or '# imt=SA(T)' names the "
                         "intensity measure")
    body = [line for line in lines if line.strip() and not line.lstrip().startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(body))))
    header = [name.strip() for name in rows[0]] if rows else []
    for name in COLUMNS:
        if name not in header:
            raise InputError(f"{path}: {name}: no such column (expected columns "
                             f"{', '.join(COLUMNS)})")
    columns = [header.index(name) for name in COLUMNS]
    levels, rates = [], []
    for line_no, row in enumerate(rows[1:], start=2):
        if len(row) <= max(columns):
            raise InputError(f"{path}: row {line_no}: expected {len(header)} fields, got "
                             f"{len(row)}")
        levels.append(number(row[columns[0]], path, f"row {line_no}: im_g"))
        rates.append(number(row[columns[1]], path, f"row {line_no}: annual_rate"))
    return HazardCurve.checked(imt, levels, rates, f"{path.name}: plain CSV curve of {imt}",
                               None, str(path))


__all__ = ["read_plain_curve", "COLUMNS"]
