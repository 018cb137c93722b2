"""Column text files of a strong-motion record: accelerations alone, or time and acceleration,
with the step and units stated in the file or given."""

from __future__ import annotations

import numbers
import re
from pathlib import Path

import numpy as np

from audit.errors import InputError
from records.motion import GroundMotion
from records.readers import (UNIT_FACTORS, checked_dt, checked_motion, parse_floats, read_lines,
                             sha256_of, unit_factor, units_in_text)

#: A time column is uniform where every time lies within this fraction of a step of the uniform
#: grid from its first to its last time (files print times to a few digits).
TIME_TOLERANCE = 0.01
#: A first column is a time column where it rises on this share of the steps between its
#: first TIME_SNIFF_LINES data lines (an acceleration column rises on about half of them).
TIME_COLUMN_RISING = 0.9
TIME_SNIFF_LINES = 100
_DT_COMMENT = re.compile(r"\bdt\s*=\s*([0-9.]+(?:[eE][-+]?\d+)?)", re.I)
_NPTS_COMMENT = re.compile(r"\bnpts\s*=\s*(\d+)", re.I)


def read_columns(path: str | Path, column: int | None = None, dt: float | None = None,
                 units: str | None = None, record_id: str | None = None,
                 component: str = "") -> GroundMotion:
    """Read one column of a whitespace-separated text file of accelerations.

    Lines starting with ``%`` or ``#`` are comments; CRLF endings, tabs, repeated
    separators and exponents like ``e-001`` are accepted. Where ``dt`` or ``units`` are not
    given they are taken from the file: ``dt`` from a time column or the comments
    (``dt = 0.005``), ``units`` from the comments (``cm/sec^2``, ``units: g``); a
    ``npts = N`` comment is checked against the count.

    A time column is the first column of a file of two or more, where it increases from line
    to line (an acceleration column does not); it is not read as accelerations. Its step
    (last − first time)/(samples − 1) is the time step, and every time must lie on that
    uniform grid within :data:`TIME_TOLERANCE` of a step, or within the rounding of the times'
    printed decimals where that is coarser; a ``dt`` given must agree with the step within
    :data:`TIME_TOLERANCE`.

    Parameters
    ----------
    path : str or Path
        The text file.
    column : int, optional
        1-based column of the accelerations; default 2 after a time column, else 1.
    dt : float, optional
        Time step [s].
    units : {"g", "cm/s2", "m/s2"}, optional
        Units of the values.

    Returns
    -------
    GroundMotion
        üg [m/s²] at step ``dt`` [s].
    """
    path = Path(path)
    lines = read_lines(path)
    if column is not None and (not isinstance(column, numbers.Integral) or isinstance(column, bool)
                               or column < 1):
        raise InputError(f"{path}: column: must be a whole number ≥ 1, got {column!r}")
    rows, header = _data_rows(lines, path)
    # an uncommented header line of names may state the units or the step, as a comment does
    comments = " ".join([line for line in lines if line.lstrip()[:1] in ("%", "#")] + [header])
    timed = column != 1 and _opens_with_time([tokens for _, tokens in rows])
    column = column or (2 if timed else 1)
    if dt is None and not timed:
        found = _DT_COMMENT.search(comments)
        if found is None:
            raise InputError(f"{path}: dt: not stated in the file (no time column, no "
                             f"'dt = …' comment); give dt, the time step [s]")
        try:
            dt = float(found.group(1))
        except ValueError:
            raise InputError(f"{path}: dt: '{found.group(1)}' in the comments is not a number") from None
    if units is None:
        units = units_in_text(comments)
        if units is None:
            raise InputError(f"{path}: units: not stated in the file; give units "
                             f"({', '.join(UNIT_FACTORS)})")
    factor = unit_factor(units, str(path))
    texts, times, line_nos = [], [], []
    for line_no, tokens in rows:
        if len(tokens) < column:
            raise InputError(f"{path}: line {line_no}: column {column} missing "
                             f"(the line has {len(tokens)})")
        texts.append(tokens[column - 1])
        line_nos.append(line_no)
        if timed:
            times.append(tokens[0])
    values = parse_floats(texts, path, lambda: zip(texts, line_nos))
    if not values.size:
        raise InputError(f"{path}: no data lines")
    if timed:
        step = _uniform_step(times, line_nos, path)
        if dt is not None and abs(float(dt) - step) > TIME_TOLERANCE * step:
            raise InputError(f"{path}: dt: {float(dt):g} s given, the time column steps "
                             f"{step:g} s")
        dt = step if dt is None else dt
    dt = checked_dt(float(dt), path)
    npts = _NPTS_COMMENT.search(comments)
    if npts is not None and int(npts.group(1)) != len(values):
        raise InputError(f"{path}: npts: header says {npts.group(1)} values, the file holds {len(values)}")
    return checked_motion(GroundMotion(
        id=record_id or path.stem,
        acceleration=values * factor,
        dt=dt,
        component=component or f"column {column}",
        source=str(path),
        sha256=sha256_of(path),
        metadata={"format": "columns", "units": units, "column": column},
    ), units)


def _is_number(token: str) -> bool:
    try:
        float(token.replace("D", "E").replace("d", "e"))
    except ValueError:
        return False
    return True


def _data_rows(lines: list[str], path: Path) -> tuple[list, str]:
    """(line number, fields) of every data line, and the text of an uncommented header line
    of names before them (``time_s acc_g``: no field of it is a number), which is not data.
    Fields are separated by whitespace, or by commas where the data's decimals are points (a
    CSV file); commas without a decimal point anywhere could be decimal commas: refused."""
    data = [(line_no, line) for line_no, line in enumerate(lines, start=1)
            if line.strip() and line.lstrip()[0] not in "%#"]
    header = ""
    if len(data) > 1 and not any(_is_number(field)
                                 for field in re.split(r"[,\s]+", data[0][1].strip())):
        header = data.pop(0)[1]
    commas = [(line_no, line) for line_no, line in data if "," in line]
    if commas and not any("." in line for _, line in data):
        line_no, line = commas[0]
        raise InputError(f"{path}: line {line_no}: '{line.strip()[:40]}' has commas and no "
                         "decimal point: decimal commas? write decimals with points and "
                         "separate columns by spaces, tabs or commas")
    return [(line_no, [field.strip() for field in line.split(",")] if commas else line.split())
            for line_no, line in data], header


def _opens_with_time(rows: list[list[str]]) -> bool:
    """Whether the file's first column is a time column: its first :data:`TIME_SNIFF_LINES`
    data rows hold two or more numbers each, and the first number rises on at least
    :data:`TIME_COLUMN_RISING` of the steps between them (an acceleration column rises on
    about half)."""
    firsts = []
    for tokens in rows:
        if len(tokens) < 2:
            return False
        firsts.append(tokens[0])
        if len(firsts) == TIME_SNIFF_LINES:
            break
    try:
        first = np.array(firsts, dtype=float)
    except ValueError:
        return False
    return (first.size >= 2 and bool(np.all(np.isfinite(first)))
            and np.mean(np.diff(first) > 0) >= TIME_COLUMN_RISING)


def _uniform_step(texts: list[str], line_nos: list[int], path: Path) -> float:
    """The step [s] of a time column (its ``texts`` on lines ``line_nos``); InputError naming
    the first line where the times stop increasing or leave the uniform grid by more than
    :data:`TIME_TOLERANCE` of a step."""
    times = parse_floats(texts, path, lambda: zip(texts, line_nos))
    steps = np.diff(times)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0)) + 1
        raise InputError(f"{path}: line {line_nos[i]}: time: {texts[i]} s does not come after "
                         f"{texts[i - 1]} s; a time column must increase")
    step = float(times[-1] - times[0]) / (times.size - 1)
    off = np.abs(times - (times[0] + step * np.arange(times.size)))
    tolerance = TIME_TOLERANCE * step
    if np.any(off > tolerance):
        # times printed to d decimals are each off by up to half a unit, and so are the first
        # and last that fix the grid: up to one unit of the last decimal in all
        decimals = max((len(text) - text.index(".") - 1 for text in texts
                        if "." in text and not any(c in text for c in "eEdD")), default=0)
        tolerance = max(tolerance, 10.0 ** -decimals * (1 + 1e-9))
    if np.any(off > tolerance):
        i = int(np.argmax(off > tolerance))
        raise InputError(f"{path}: line {line_nos[i]}: time: {texts[i]} s is {off[i]:.3g} s "
                         f"off the uniform step {step:.6g} s of the time column (more than "
                         f"{TIME_TOLERANCE:.0%} of a step and the rounding of its digits); "
                         f"resample the record to a constant step")
    return step


__all__ = ["read_columns", "TIME_TOLERANCE", "TIME_COLUMN_RISING", "TIME_SNIFF_LINES"]
