"""OpenQuake engine hazard-curve CSV exports (``hazard_curve-mean-SA(1.0)_N.csv``).

Layout, as the engine writes it (3.x):

* line 1: a ``#`` comment whose last field holds the metadata as ``key='value'`` pairs,
  among them ``investigation_time`` (T, years) and ``imt``;
* line 2: ``lon,lat,depth,poe-LEVEL,...``: the intensity levels [g] are in the column names
  (``depth`` is absent from older exports);
* one row per site: the probability of exceedance of each level in T.

The annual rate is λ = −ln(1 − poe)/T (Poisson; exact when the engine averaged rates,
``use_rates = true``). The engine orders sites by its own ids, so a site is matched by
``lon, lat`` (:func:`~records.hazard.curve.match_site`), never by row. The top levels can be
exactly 0 (kept: never exceeded); levels with poe = 1 exactly have no finite rate and are left
out; near poe = 1 values repeat (float32 rounding), a flat stretch of the curve.
"""

from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path

import numpy as np

from audit.errors import InputError
from records.hazard.curve import HazardCurve, match_site, number, read_text

_METADATA = re.compile(r"(\w+)=('[^']*'|[^,\s]+)")
_POE = "poe-"


def metadata(first_line: str) -> dict:
    """The ``key='value'`` pairs of an OpenQuake export's first line, as text."""
    return {key: value.strip("'") for key, value in _METADATA.findall(first_line)}


def is_openquake_csv(text: str) -> bool:
    """Whether ``text`` opens like an OpenQuake hazard-curve export."""
    first = text.split("\n", 1)[0]
    return first.startswith("#") and "investigation_time" in first


def read_openquake_curve(path, site=None) -> HazardCurve:
    """The hazard curve of one site from an OpenQuake hazard-curve CSV export.

    Parameters
    ----------
    path : str or pathlib.Path
    site : (float, float), optional
        Longitude, latitude [degrees] of the site, matched within
        :data:`~records.hazard.curve.SITE_TOLERANCE_DEG`; needed when the file holds several.

    Returns
    -------
    HazardCurve
        λ = −ln(1 − poe)/T [1/yr] at each level of the file [g].
    """
    path = Path(path)
    text = read_text(path)
    rows = list(csv.reader(io.StringIO(text)))
    if len(rows) < 3 or not is_openquake_csv(text):
        raise InputError(f"{path}: header: not an OpenQuake hazard-curve export (a '#' line "
                         "with investigation_time and imt, a line of column names, a row per "
                         "site)")
    meta = metadata(text.split("\n", 1)[0])
    for key in ("investigation_time", "imt"):
        if key not in meta:
            raise InputError(f"{path}: {key}: missing from the metadata line")
    try:
        years = float(meta["investigation_time"])
    except ValueError:
        years = math.nan
    if not (math.isfinite(years) and years > 0):
        raise InputError(f"{path}: investigation_time: expected years > 0, got "
                         f"'{meta['investigation_time']}'")
    header = [name.strip() for name in rows[1]]
    for name in ("lon", "lat"):
        if name not in header:
            raise InputError(f"{path}: {name}: no such column (columns: "
                             f"{', '.join(header[:4])}, ...)")
    poe_columns = [j for j, name in enumerate(header) if name.startswith(_POE)]
    if len(poe_columns) < 2:
        raise InputError(f"{path}: poe-LEVEL: expected a column per intensity level, found "
                         f"{len(poe_columns)}")
    levels = np.array([number(header[j][len(_POE):], path, header[j]) for j in poe_columns])
    body = []
    for line_no, row in enumerate(rows[2:], start=3):
        while row and not row[-1].strip():  # trailing empty fields are no data
            row = row[:-1]
        if not row:
            continue
        if len(row) != len(header):
            raise InputError(f"{path}: row {line_no}: {len(row)} fields, expected "
                             f"{len(header)} (lon, lat, ... and a poe per level, as the column "
                             "names)")
        body.append(row)
    lon, lat = header.index("lon"), header.index("lat")
    sites = [(number(row[lon], path, "lon"), number(row[lat], path, "lat")) for row in body]
    index = match_site(sites, site, str(path))
    row = body[index]
    where = f"{path}: site ({sites[index][0]:g}, {sites[index][1]:g})"
    poe = np.array([number(row[j], path, header[j]) for j in poe_columns])
    bad = np.flatnonzero(~((poe >= 0) & (poe <= 1)))
    if bad.size:
        raise InputError(f"{where}: {header[poe_columns[bad[0]]]}: a probability of exceedance "
                         f"must lie in [0, 1], got {poe[bad[0]]:g}")
    finite = poe < 1.0  # poe = 1: exceeded surely, no finite rate
    rates = -np.log1p(-poe[finite]) / years
    source = (f"{path.name}: OpenQuake ({meta.get('generated_by', 'engine')}), "
              f"{meta.get('kind', '')} curve of {meta['imt']}, site ({sites[index][0]:g}, "
              f"{sites[index][1]:g}), λ = −ln(1 − poe)/{years:g} yr")
    return HazardCurve.checked(meta["imt"], levels[finite], rates, source, sites[index], where)


__all__ = ["read_openquake_curve", "is_openquake_csv", "metadata"]
