"""Seismic hazard curves read from the tools that make them, one reader per source (like
pvlib's ``iotools``): OpenQuake engine CSV exports, USGS hazard service JSON, and a plain CSV
``im_g,annual_rate``. Each returns a :class:`HazardCurve` of annual rates of exceedance at one
site; :func:`read_hazard` picks the reader from the file.
"""

from __future__ import annotations

from pathlib import Path

from records.hazard.curve import SITE_TOLERANCE_DEG, HazardCurve, parse_imt
from records.hazard.openquake import is_openquake_csv, read_openquake_curve
from records.hazard.plain_csv import read_plain_curve
from records.hazard.usgs import read_usgs_curve


def read_hazard(path, site=None, imt: str | None = None,
                imt_field: str = "hazard.imt") -> HazardCurve:
    """The hazard curve in ``path``: USGS JSON (``.json``), an OpenQuake export (a CSV opening
    with its ``#`` metadata line) or a plain CSV.

    Parameters
    ----------
    path : str or pathlib.Path
    site : (float, float), optional
        Longitude, latitude [degrees]; chooses among the sites of an OpenQuake export and is
        checked against a USGS response's.
    imt : str, optional
        Chooses among the IMTs of a USGS response (``PGA``, ``SA(1.0)``).
    imt_field : str
        The argument ``imt`` came from (``hazard.imt``, or ``im`` whose IMT it is), for the
        message.
    """
    from records.hazard.curve import read_text
    path = Path(path)
    if path.suffix.lower() == ".json":
        return read_usgs_curve(path, imt, site, imt_field)
    if is_openquake_csv(read_text(path)):
        return read_openquake_curve(path, site)
    return read_plain_curve(path)


__all__ = ["HazardCurve", "read_hazard", "read_openquake_curve", "read_usgs_curve",
           "read_plain_curve", "parse_imt", "SITE_TOLERANCE_DEG"]
