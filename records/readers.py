"""What the strong-motion file readers share: one reader per format, PEER NGA ``.AT2``
(:mod:`records.at2_reader`) and column text files (:mod:`records.column_reader`).

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


#: Factor from each accepted unit name to m/s².
UNIT_FACTORS = {"g": G, "cm/s2": 0.01, "m/s2": 1.0}

# Spellings of the units found in file headers and comments, normalised to UNIT_FACTORS keys.
_UNIT_PATTERNS = (
    (re.compile(r"\bunits?\s+of\s+g\b|\bunits?\s*[:=]\s*g\b|\bin\s+g\b|[(\[]\s*g\s*[)\]]",
                re.I), "g"),
    (re.compile(r"cm\s*/\s*s(ec)?(\s*/\s*s(ec)?|\s*\^?\s*2|2)|\bgals?\b", re.I), "cm/s2"),
    (re.compile(r"\bm\s*/\s*s(ec)?(\s*/\s*s(ec)?|\s*\^?\s*2|2)", re.I), "m/s2"),
)


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


def checked_motion(motion: GroundMotion, units: str) -> GroundMotion:
    """The motion, unless its PGA shows that ``units`` cannot be right; a warning where the
    PGA is implausibly small for them."""
    if motion.pga_g > PLAUSIBLE_PGA_G:
        raise InputError(f"{motion.source}: units: read as '{units}', the PGA would be "
                         f"{motion.pga_g:.3g} g, beyond any recorded motion; are the units right?")
    if motion.pga_g < SMALL_PGA_G:
        warnings.warn(f"{motion.source}: units: read as '{units}', the PGA is only "
                      f"{motion.pga_g:.2g} g; are the units right?", InputWarning, stacklevel=3)
    return motion


def read_lines(path: Path) -> list[str]:
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


def parse_float(token: str, path: Path, line_no: int, name: str = "value") -> float:
    try:
        value = float(token.replace("D", "E").replace("d", "e"))
    except ValueError:
        raise InputError(f"{path}: line {line_no}: {name}: '{token}' is not a number") from None
    if not math.isfinite(value):
        raise InputError(f"{path}: line {line_no}: {name}: '{token}' is not finite")
    return value


def parse_floats(tokens: list[str], path: Path, numbered) -> np.ndarray:
    """The numbers of ``tokens``, parsed in one vectorised pass; only when one of them is not
    a finite number are they parsed one by one (``numbered()`` yields (token, line number)),
    so that the error names the first bad token and its line."""
    try:
        values = np.array(tokens, dtype=float)
        if np.all(np.isfinite(values)):
            return values
    except ValueError:  # e.g. Fortran exponents (1.0D+00) or a word
        pass
    return np.array([parse_float(token, path, line_no) for token, line_no in numbered()],
                    dtype=float)


def checked_dt(dt: float, path: Path) -> float:
    if not (math.isfinite(dt) and MIN_DT_S <= dt <= MAX_DT_S):
        raise InputError(f"{path}: dt: must be a positive number of seconds in [{MIN_DT_S:g}, "
                         f"{MAX_DT_S:g}], got {dt:g}")
    return dt


__all__ = ["sha256_of", "unit_factor", "units_in_text", "checked_motion", "read_lines",
           "parse_float", "parse_floats", "checked_dt", "UNIT_FACTORS", "MIN_DT_S", "MAX_DT_S",
           "PLAUSIBLE_PGA_G", "SMALL_PGA_G"]
