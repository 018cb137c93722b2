"""USGS hazard-curve web service responses (JSON).

Two layouts, both already **annual rates of exceedance** (no conversion):

* the static curve service (NSHM 2008/2014, e.g. the ``earthquake-hazard-tool``):
  ``response[]`` one entry per IMT, ``metadata.xvals`` (levels [g]), ``metadata.imt.value``
  (``PGA``, ``SA0P2``, ``SA1P0``), ``metadata.longitude/latitude``, and ``data[].yvals``;
* the dynamic services (nshmp-haz): ``metadata.xvalues`` and ``data[]`` one entry per source
  type, the total in the entry with ``component: "Total"``, its rates in ``yvalues``.
"""

from __future__ import annotations

import json
from pathlib import Path

from audit.errors import InputError
from records.hazard.curve import HazardCurve, match_site, parse_imt, read_text

TOTAL = "Total"


def read_usgs_curve(path, imt: str | None = None, site=None,
                    imt_field: str = "hazard.imt") -> HazardCurve:
    """The hazard curve of one IMT from a USGS hazard service response.

    Parameters
    ----------
    path : str or pathlib.Path
    imt : str, optional
        ``PGA``, ``SA(1.0)`` or ``SA1P0``; needed when the response holds several IMTs.
    site : (float, float), optional
        Longitude, latitude [degrees]; checked against the response's site when given.
    imt_field : str
        The argument that chose ``imt`` (``hazard.imt``, or ``im`` whose IMT it is), named
        when the response has no curve of it.

    Returns
    -------
    HazardCurve
    """
    path = Path(path)
    try:
        document = json.loads(read_text(path))
    except json.JSONDecodeError as exc:
        raise InputError(f"{path}: not valid JSON: {exc.msg} (line {exc.lineno})") from None
    entries = document.get("response") if isinstance(document, dict) else None
    if not isinstance(entries, list) or not entries:
        raise InputError(f"{path}: response: missing or empty; not a USGS hazard service answer")
    curves = [_entry(entry, path, k) for k, entry in enumerate(entries)]
    if imt is not None:
        wanted = parse_imt(imt, str(path))
        chosen = [c for c in curves if (c[0], c[1]) == wanted]
        if not chosen:
            chooser = ("hazard.imt" if imt_field == "hazard.imt"
                       else f"{imt_field} or hazard.imt")
            raise InputError(f"{path}: imt: no curve of {imt}, asked by {imt_field}; the "
                             f"response has {', '.join(sorted({c[2] for c in curves}))}: "
                             f"choose one of them with {chooser}", imt_field, "hazard.imt")
    elif len({(c[0], c[1]) for c in curves}) > 1:
        raise InputError(f"{path}: imt: the response holds curves of "
                         f"{', '.join(c[2] for c in curves)}; say which one with hazard.imt "
                         "or im", "hazard.imt", "im")
    else:
        chosen = curves
    sites = [c[3] for c in chosen]
    index = match_site(sites, site, str(path)) if site is not None or len(chosen) > 1 else 0
    kind, period, name, where_site, levels, rates, k, meta = chosen[index]
    where = f"{path}: response[{k}]"
    edition = meta.get("edition")
    source = (f"{path.name}: USGS hazard service"
              + (f", {edition.get('display', edition.get('value'))}"
                 if isinstance(edition, dict) else "")
              + f", {name}, site ({where_site[0]:g}, {where_site[1]:g})")
    vs30 = meta.get("vs30")
    if isinstance(vs30, dict):
        source += f", Vs30 {vs30.get('value')} m/s"
    return HazardCurve.checked(name, levels, rates, source, tuple(where_site), where)


def _entry(entry, path, k):
    """``(kind, period, imt text, (lon, lat), levels, rates, k, metadata)`` of one response
    entry."""
    where = f"{path}: response[{k}]"
    meta = entry.get("metadata") if isinstance(entry, dict) else None
    if not isinstance(meta, dict):
        raise InputError(f"{where}: metadata: missing")
    imt = meta.get("imt")
    name = imt.get("value") if isinstance(imt, dict) else imt
    if name is None:
        raise InputError(f"{where}: metadata.imt: missing")
    kind, period = parse_imt(name, where)
    levels = meta.get("xvals", meta.get("xvalues"))
    if not isinstance(levels, list):
        raise InputError(f"{where}: metadata.xvals: missing (nor xvalues)")
    row = _total_row(entry.get("data"), where)
    rates = row.get("yvals", row.get("yvalues"))
    if not isinstance(rates, list):
        raise InputError(f"{where}: data[].yvals: expected a list of annual rates (or "
                         f"yvalues), got {type(rates).__name__} {rates!r:.40}")
    lon = meta.get("longitude", row.get("longitude"))
    lat = meta.get("latitude", row.get("latitude"))
    try:
        site = (float(lon), float(lat))
    except (TypeError, ValueError):
        site = (float("nan"), float("nan"))
    text = "PGA" if kind == "PGA" else f"SA({float(period)})"
    try:
        levels = [float(v) for v in levels]
        rates = [float("nan") if v is None else float(v) for v in rates]
    except (TypeError, ValueError):
        raise InputError(f"{where}: xvals/yvals: expected numbers") from None
    return kind, period, text, site, levels, rates, k, meta


def _total_row(data, where: str) -> dict:
    """The entry of ``data`` holding the total hazard: the static service's one curve
    (``yvals``), or the dynamic services' entry with ``component: "Total"`` (each other entry
    is one source type's share of it, never the total: without the total, refused)."""
    if not isinstance(data, list) or not data:
        raise InputError(f"{where}: data: expected a non-empty list of curves, got "
                         f"{type(data).__name__} {data!r:.40}")
    for j, row in enumerate(data):
        if not isinstance(row, dict):
            raise InputError(f"{where}: data[{j}]: expected an object with its curve (yvals, or "
                             f"component and yvalues), got {type(row).__name__} {row!r:.40}")
    if any("component" in row or "yvalues" in row for row in data):
        totals = [row for row in data if row.get("component") == TOTAL]
        if not totals:
            found = ", ".join(str(row.get("component")) for row in data)
            raise InputError(f"{where}: data: no entry with component '{TOTAL}' (the total "
                             f"hazard; the response has {found}, each one source type's share)")
        return totals[0]
    if len(data) > 1:
        raise InputError(f"{where}: data: {len(data)} curves; a static-service response has "
                         "one per IMT")
    return data[0]


__all__ = ["read_usgs_curve"]
