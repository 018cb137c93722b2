"""Record manifests: TOML files that list records, their files and formats, and their sites.

One ``[[record]]`` per record: ``id`` (a catalogue id gets the Table 5.1 facts and the FEMA 356
site of Table 3.1), ``file`` relative to the manifest, ``format`` (``peer-at2`` or
``columns``), for text files ``column`` (default 2 after a time column, else 1: see
:func:`records.column_reader.read_columns`), ``dt`` [s] and ``units`` (default: as the file states
them), a ``component`` in words, site fields, or ``missing = true`` for a record without a
file. A record's vertical component,
where it has one: ``vertical_file`` (same format, dt and units as ``file``; ``vertical_column``
for text files, default ``column``) and ``vertical_positive`` (``up``, the default, or ``down``
as in PEER's DWN files).
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

from audit.errors import InputError
from records.catalogue import SEED_CATALOGUE
from records.motion import GroundMotion
from records.sites import NTC2018_SOILS, NTC2018_TOPOGRAPHIES
from records.suite import SITE_FIELDS, RecordEntry, RecordSuite, site_of
from records.at2_reader import read_at2
from records.column_reader import read_columns
from records.readers import MAX_DT_S, MIN_DT_S, UNIT_FACTORS

#: Name of the built-in pulse-idealised suite.
FORMATS = ("peer-at2", "columns")
#: Site parameters a manifest entry may carry: FEMA 356 (Table 3.1) and NTC 2018 (§3.2).
_MANIFEST_FIELDS = {"id", "file", "format", "column", "dt", "units", "component", "missing",
                    "vertical_file", "vertical_column", "vertical_positive", *SITE_FIELDS}
#: Directions a vertical component's positive values may point.
VERTICAL_DIRECTIONS = ("up", "down")


def _check_field(fields: dict, key: str, where: str):
    """The value of ``key`` if it has the TOML type and range of :data:`_FIELD_RULES`."""
    value = fields[key]
    kind, check, expected = _FIELD_RULES[key]
    # TOML booleans are Python ints: a bool is only accepted where a bool is asked for
    if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
        raise InputError(f"{where}: {key}: expected {expected}, got {_toml_repr(value)}")
    if check is not None and not check(value):
        if isinstance(value, str) and value:  # a name not in the list
            raise InputError(f"{where}: {key}: unknown '{value}', expected {expected}")
        raise InputError(f"{where}: {key}: expected {expected}, got {_toml_repr(value)}")
    return value


def _toml_repr(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (list, dict)):
        return "an array" if isinstance(value, list) else "a table"
    return repr(value)


def _positive_finite(value) -> bool:
    return math.isfinite(value) and value > 0


#: TOML type, range check and description of every manifest field.
_FIELD_RULES = {
    "id": (str, bool, "a non-empty string"),
    "file": (str, bool, "a non-empty string (a path relative to the manifest)"),
    "format": (str, lambda v: v in FORMATS, f"one of {', '.join(FORMATS)}"),
    "column": (int, lambda v: v >= 1, "a whole number ≥ 1"),
    "dt": ((int, float), lambda v: MIN_DT_S <= v <= MAX_DT_S,
           f"a number of seconds in [{MIN_DT_S:g}, {MAX_DT_S:g}]"),
    "units": (str, lambda v: v in UNIT_FACTORS, f"one of {', '.join(UNIT_FACTORS)}"),
    "component": (str, None, "a string"),
    "vertical_file": (str, bool, "a non-empty string (a path relative to the manifest)"),
    "vertical_column": (int, lambda v: v >= 1, "a whole number ≥ 1"),
    "vertical_positive": (str, lambda v: v in VERTICAL_DIRECTIONS,
                          f"one of {', '.join(VERTICAL_DIRECTIONS)}"),
    "missing": (bool, None, "true or false"),
    "site_class": (str, None, "a string"),
    "sxs_g": ((int, float), _positive_finite, "a positive number of g"),
    "sx1_g": ((int, float), _positive_finite, "a positive number of g"),
    "ntc_ag_g": ((int, float), _positive_finite, "a positive number of g"),
    "ntc_f0": ((int, float), _positive_finite, "a positive number"),
    "ntc_tc_star_s": ((int, float), _positive_finite, "a positive number of seconds"),
    "ntc_soil": (str, lambda v: v in NTC2018_SOILS, f"one of {', '.join(NTC2018_SOILS)}"),
    "ntc_topography": (str, lambda v: v in NTC2018_TOPOGRAPHIES,
                       f"one of {', '.join(NTC2018_TOPOGRAPHIES)}"),
}


def _manifest_data(path: Path) -> dict:
    """The parsed TOML of a manifest; InputError for unreadable, non-UTF-8 or invalid files."""
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from None
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise InputError(f"{path}: encoding: UTF-16 text; save the manifest as UTF-8")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: encoding: not UTF-8 text (byte {exc.start + 1}); "
                         f"is it a binary file?") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not valid TOML: {exc}") from None


def load_manifest(path: str | Path, skip_bad: bool = False) -> RecordSuite:
    """Read a TOML manifest of records (schema of ``seed-suite.toml``).

    Paths are relative to the manifest. ``missing = true`` entries are kept, with no motion.
    Manifest entries may add FEMA 356 site parameters (``site_class``, ``sxs_g``, ``sx1_g``)
    and an NTC 2018 site (``ntc_ag_g``, ``ntc_f0``, ``ntc_tc_star_s``, ``ntc_soil``,
    ``ntc_topography``).
    Every field is checked for its TOML type and range. A record that cannot be read stops
    the load (the error names it and counts the other bad ones) unless ``skip_bad``, which
    keeps the readable records and lists the others in :attr:`RecordSuite.rejected`.
    """
    path = Path(path)
    data = _manifest_data(path)
    records = data.get("record")
    if isinstance(records, dict):
        raise InputError(f"{path}: record: written as a table [record]; each record must be an "
                         f"entry of an array of tables [[record]]")
    if not isinstance(records, list) or not records:
        raise InputError(f"{path}: no [[record]] entries")
    readers, seen = [], set()
    for number, fields in enumerate(records, start=1):
        where = f"{path}: record {number}"
        if not isinstance(fields, dict):
            raise InputError(f"{where}: expected a table [[record]], got {_toml_repr(fields)}")
        if "id" not in fields:
            raise InputError(f"{where}: id: missing")
        record_id = _check_field(fields, "id", where)
        where = f"{path}: record '{record_id}'"
        if record_id in seen:
            raise InputError(f"{where}: id: appears twice")
        seen.add(record_id)
        file = fields.get("file", "")
        readers.append((record_id, str(path.parent / file) if isinstance(file, str) else "",
                        lambda f=fields, w=where, i=record_id: _manifest_entry(path, f, w, i)))
    return collect(readers, f"records of manifest {path}", skip_bad)


def _manifest_entry(path: Path, fields: dict, where: str, record_id: str) -> RecordEntry:
    unknown = set(fields) - _MANIFEST_FIELDS
    if unknown:
        raise InputError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    for key in fields:
        _check_field(fields, key, where)
    facts = SEED_CATALOGUE.get(record_id)
    component = fields.get("component", "")
    site = site_of(facts, fields)
    if fields.get("missing", False):
        return RecordEntry(record_id, None, facts, component,
                           missing_reason=component or "no file", site=site)
    return RecordEntry(record_id, _read_entry(path.parent, fields, where, record_id),
                       facts, component, site=site)


def collect(readers, description: str, skip_bad: bool) -> RecordSuite:
    """A suite of the entries that ``readers`` (record, file, read) produce.

    Strict unless ``skip_bad``: the first bad record's error, with the count of the others.
    """
    entries, errors, rejected = [], [], []
    for record, file, read in readers:
        try:
            entries.append(read())
        except InputError as exc:
            errors.append(str(exc))
            reason = str(exc).removeprefix(f"{file}: ") if file else str(exc)
            rejected.append({"record": record, "file": file, "reason": reason})
    if errors and (not skip_bad or not entries):
        others = len(errors) - 1
        more = (f" ({others} other record(s) also bad; skip_bad audits the rest)"
                if others else "")
        raise InputError(f"{errors[0]}{more}", "skip_bad")
    return RecordSuite(tuple(entries), description, rejected=tuple(rejected))


def _read_entry(folder: Path, fields: dict, where: str, record_id: str) -> GroundMotion:
    if "file" not in fields:
        raise InputError(f"{where}: file: missing (or mark the record missing = true)")
    if "format" not in fields:
        raise InputError(f"{where}: format: missing, expected one of {', '.join(FORMATS)}")
    if fields["format"] == "peer-at2":
        ignored = {"column", "vertical_column", "dt", "units"} & set(fields)
        if ignored:
            raise InputError(f"{where}: {', '.join(sorted(ignored))}: not used by format "
                             f"peer-at2 (the AT2 header states them)")
    if "vertical_file" not in fields:
        unused = {"vertical_column", "vertical_positive"} & set(fields)
        if unused:
            raise InputError(f"{where}: {', '.join(sorted(unused))}: needs vertical_file")
    motion = _read_file(folder, fields, "file", fields.get("column"), where, record_id)
    if "vertical_file" not in fields:
        return motion
    up = _read_file(folder, fields, "vertical_file",
                    fields.get("vertical_column", fields.get("column")), where, record_id)
    return motion.with_vertical(up, down=fields.get("vertical_positive", "up") == "down")


def _read_file(folder: Path, fields: dict, key: str, column: int | None, where: str,
               record_id: str) -> GroundMotion:
    """The motion in the file of field ``key`` (``file`` or ``vertical_file``)."""
    file = folder / fields[key]
    if not file.is_file():
        raise InputError(f"{where}: {key}: {file} not found" if not file.exists()
                         else f"{where}: {key}: {file} is not a file")
    component = fields.get("component", "")
    if fields["format"] == "peer-at2":
        return read_at2(file, record_id, component)
    return read_columns(file, column, fields.get("dt"), fields.get("units"), record_id,
                        component)


