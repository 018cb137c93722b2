"""PEER NGA ``.AT2`` acceleration files (NGA-West1 and NGA-West2 layouts)."""

from __future__ import annotations

import re
from pathlib import Path

from audit.errors import InputError
from records.motion import GroundMotion
from records.readers import (checked_dt, checked_motion, parse_float, parse_floats, read_lines,
                             sha256_of, unit_factor, units_in_text)

_AT2_WEST2 = re.compile(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([-+0-9.EeDd]+)", re.I)
_AT2_WEST1 = re.compile(r"^\s*(\d+)\s+([-+0-9.EeDd]+)\s+NPTS\s*,\s*DT", re.I)


def read_at2(path: str | Path, record_id: str | None = None, component: str = "") -> GroundMotion:
    """Read a PEER NGA ``.AT2`` acceleration file (NGA-West1 and NGA-West2 layouts).

    Lines 1–3 are text (line 3 names the units), line 4 holds NPTS and DT either as
    ``NPTS=  4096, DT= .0100 SEC, ...`` (West2) or ``1991  0.0100  NPTS, DT`` (West1), then
    free-format values. The values are counted, not trusted to the layout, and the count
    must equal NPTS.

    Parameters
    ----------
    path : str or Path
        The ``.AT2`` file.
    record_id : str, optional
        Id of the motion; default is the file name without suffix.

    Returns
    -------
    GroundMotion
        üg [m/s²] at the file's DT [s].
    """
    path = Path(path)
    lines = read_lines(path)
    if len(lines) < 4:
        raise InputError(f"{path}: truncated header: an AT2 file has 4 header lines, found {len(lines)}")
    units = units_in_text(lines[2])
    if units is None:
        raise InputError(f"{path}: line 3: cannot tell the units from '{lines[2].strip()}'")
    match = _AT2_WEST2.search(lines[3]) or _AT2_WEST1.search(lines[3])
    if match is None:
        raise InputError(f"{path}: line 4: expected 'NPTS=..., DT=...' or '<npts> <dt> NPTS, DT', "
                         f"got '{lines[3].strip()}'")
    npts = int(match.group(1))
    dt = checked_dt(parse_float(match.group(2), path, 4, "DT"), path)
    data = lines[4:]
    values = parse_floats([token for line in data for token in line.split()], path,
                     lambda: ((token, line_no) for line_no, line in enumerate(data, start=5)
                              for token in line.split()))
    if len(values) != npts:
        raise InputError(f"{path}: NPTS: header says {npts} values, the file holds {len(values)}")
    return checked_motion(GroundMotion(
        id=record_id or path.stem,
        acceleration=values * unit_factor(units, str(path)),
        dt=dt,
        component=component or lines[1].strip(),
        source=str(path),
        sha256=sha256_of(path),
        metadata={"format": "peer-at2", "units": units, "npts": npts},
    ), units)


__all__ = ["read_at2"]
