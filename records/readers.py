"""Readers for strong-motion files: PEER NGA ``.AT2`` and column text files.

Both return a :class:`~records.motion.GroundMotion` in SI units. Every malformed input raises
:class:`~audit.errors.InputError` with a message that names the file and the problem.
"""

from __future__ import annotations

import hashlib
import math
import re
import warnings
from pathlib import Path

import numpy as np

from audit import G
from audit.errors import InputError, InputWarning
from records.motion import GroundMotion

#: No strong-motion record exceeds ~4.4 g; a larger PGA means the declared units are wrong.
PLAUSIBLE_PGA_G = 6.0
#: A record this weak rocks nothing; below it the declared units are probably wrong (warning).
SMALL_PGA_G = 0.005
#: Sampling steps accepted from files and manifests [s]: 10 kHz to 1 Hz.
MIN_DT_S, MAX_DT_S = 1e-4, 1.0

#: A time column is uniform where every time lies within this fraction of a step of the uniform
#: grid from its first to its last time (files print times to a few digits).
TIME_TOLERANCE = 0.01
#: A first column is a time column where it rises on this share of the steps between its
#: first TIME_SNIFF_LINES data lines (an acceleration column rises on about half of them).
TIME_COLUMN_RISING = 0.9
TIME_SNIFF_LINES = 100

#: Factor from each accepted unit name to m/s².
UNIT_FACTORS = {"g": G, "cm/s2": 0.01, "m/s2": 1.0}

# Spellings of the units found in file headers and comments, normalised to UNIT_FACTORS keys.
_UNIT_PATTERNS = (
    (re.compile(r"\bunits?\s+of\s+g\b|\bunits?\s*[:=]\s*g\b|\bin\s+g\b|[(\[]\s*g\s*[)\]]",
                re.I), "g"),
    (re.compile(r"cm\s*/\s*s(ec)?(\s*/\s*s(ec)?|\s*\^?\s*2|2)|\bgals?\b", re.I), "cm/s2"),
    (re.compile(r"\bm\s*/\s*s(ec)?(\s*/\s*s(ec)?|\s*\^?\s*2|2)", re.I), "m/s2"),
)
_AT2_WEST2 = re.compile(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([-+0-9.EeDd]+)", re.I)
_AT2_WEST1 = re.compile(r"^\s*(\d+)\s+([-+0-9.EeDd]+)\s+NPTS\s*,\s*DT", re.I)
_DT_COMMENT = re.compile(r"\bdt\s*=\s*([0-9.]+(?:[eE][-+]?\d+)?)", re.I)
_NPTS_COMMENT = re.compile(r"\bnpts\s*=\s*(\d+)", re.I)


def sha256_of(path: Path) -> str:
    """Hex SHA-256 of a file's bytes (provenance of a record)."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def unit_factor(units: str, where: str) -> float:
    """Factor from ``units`` ("g", "cm/s2", "m/s2") to m/s²; InputError naming ``where``."""
    try:
        return UNIT_FACTORS[units]
    except KeyError:
        raise InputError(f"{where}: units: unknown '{units}', expected one of "
                         f"{', '.join(UNIT_FACTORS)}") from None


def units_in_text(text: str) -> str | None:
    """The acceleration unit that a header or comment line states, or None."""
    for pattern, units in _UNIT_PATTERNS:
        if pattern.search(text):
            return units
    return None


def _checked(motion: GroundMotion, units: str) -> GroundMotion:
    """The motion, unless its PGA shows that ``units`` cannot be right; a warning where the
    PGA is implausibly small for them."""
    if motion.pga_g > PLAUSIBLE_PGA_G:
        raise InputError(f"{motion.source}: units: read as '{units}', the PGA would be "
                         f"{motion.pga_g:.3g} g, beyond any recorded motion; are the units right?")
    if motion.pga_g < SMALL_PGA_G:
        warnings.warn(f"{motion.source}: units: read as '{units}', the PGA is only "
                      f"{motion.pga_g:.2g} g; are the units right?", InputWarning, stacklevel=3)
    return motion


def _read_text(path: Path) -> list[str]:
    try:
        raw = Path(path).read_bytes()
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except IsADirectoryError:
        raise InputError(f"{path}: is a folder, expected a record file") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from None
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise InputError(f"{path}: encoding: UTF-16 text; save the record as ASCII or UTF-8")
    if b"\0" in raw:
        raise InputError(f"{path}: not a text file (it holds NUL bytes); is it binary?")
    text = raw.decode("utf-8", errors="replace")
    if not text.strip():
        raise InputError(f"{path}: file is empty")
    return text.splitlines()


def _parse_float(token: str, path: Path, line_no: int, name: str = "value") -> float:
    try:
        value = float(token.replace("D", "E").replace("d", "e"))
    except ValueError:
        raise InputError(f"{path}: line {line_no}: {name}: '{token}' is not a number") from None
    if not math.isfinite(value):
        raise InputError(f"{path}: line {line_no}: {name}: '{token}' is not finite")
    return value


def _floats(tokens: list[str], path: Path, numbered) -> np.ndarray:
    """The numbers of ``tokens``, parsed in one vectorised pass; only when one of them is not
    a finite number are they parsed one by one (``numbered()`` yields (token, line number)),
    so that the error names the first bad token and its line."""
    try:
        values = np.array(tokens, dtype=float)
        if np.all(np.isfinite(values)):
            return values
    except ValueError:  # e.g. Fortran exponents (1.0D+00) or a word
        pass
    return np.array([_parse_float(token, path, line_no) for token, line_no in numbered()],
                    dtype=float)


def _check_dt(dt: float, path: Path) -> float:
    if not (math.isfinite(dt) and MIN_DT_S <= dt <= MAX_DT_S):
        raise InputError(f"{path}: dt: must be a positive number of seconds in [{MIN_DT_S:g}, "
                         f"{MAX_DT_S:g}], got {dt:g}")
    return dt


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
    lines = _read_text(path)
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
    dt = _check_dt(_parse_float(match.group(2), path, 4, "DT"), path)
    data = lines[4:]
    values = _floats([token for line in data for token in line.split()], path,
                     lambda: ((token, line_no) for line_no, line in enumerate(data, start=5)
                              for token in line.split()))
    if len(values) != npts:
        raise InputError(f"{path}: NPTS: header says {npts} values, the file holds {len(values)}")
    return _checked(GroundMotion(
        id=record_id or path.stem,
        acceleration=values * unit_factor(units, str(path)),
        dt=dt,
        component=component or lines[1].strip(),
        source=str(path),
        sha256=sha256_of(path),
        metadata={"format": "peer-at2", "units": units, "npts": npts},
    ), units)


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
    lines = _read_text(path)
    if column is not None and (not isinstance(column, int) or isinstance(column, bool)
                               or column < 1):
        raise InputError(f"{path}: column: must be a whole number ≥ 1, got {column!r}")
    comments = " ".join(line for line in lines if line.lstrip()[:1] in ("%", "#"))
    timed = column != 1 and _opens_with_time(lines)
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
    for line_no, line in enumerate(lines, start=1):
        tokens = line.split()
        if not tokens or tokens[0][0] in "%#":
            continue
        if len(tokens) < column:
            raise InputError(f"{path}: line {line_no}: column {column} missing "
                             f"(the line has {len(tokens)})")
        texts.append(tokens[column - 1])
        line_nos.append(line_no)
        if timed:
            times.append(tokens[0])
    values = _floats(texts, path, lambda: zip(texts, line_nos))
    if not values.size:
        raise InputError(f"{path}: no data lines")
    if timed:
        step = _uniform_step(times, line_nos, path)
        if dt is not None and abs(float(dt) - step) > TIME_TOLERANCE * step:
            raise InputError(f"{path}: dt: {float(dt):g} s given, the time column steps "
                             f"{step:g} s")
        dt = step if dt is None else dt
    dt = _check_dt(float(dt), path)
    npts = _NPTS_COMMENT.search(comments)
    if npts is not None and int(npts.group(1)) != len(values):
        raise InputError(f"{path}: npts: header says {npts.group(1)} values, the file holds {len(values)}")
    return _checked(GroundMotion(
        id=record_id or path.stem,
        acceleration=values * factor,
        dt=dt,
        component=component or f"column {column}",
        source=str(path),
        sha256=sha256_of(path),
        metadata={"format": "columns", "units": units, "column": column},
    ), units)


def _opens_with_time(lines: list[str]) -> bool:
    """Whether the file's first column is a time column: its first :data:`TIME_SNIFF_LINES`
    data lines hold two or more numbers each, and the first number rises on at least
    :data:`TIME_COLUMN_RISING` of the steps between them (an acceleration column rises on
    about half)."""
    firsts = []
    for line in lines:
        tokens = line.split()
        if not tokens or tokens[0][0] in "%#":
            continue
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
    times = _floats(texts, path, lambda: zip(texts, line_nos))
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
