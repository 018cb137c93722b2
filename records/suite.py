"""The record types every source produces: one record (:class:`RecordEntry`) and a suite of
them with a plain statement of where they came from (:class:`RecordSuite`)."""

from __future__ import annotations

from dataclasses import dataclass, field

from audit.errors import InputError
from records.catalogue import RecordFacts
from records.motion import GroundMotion
from records.sites import FEMA356_SITE_KEYS, NTC2018_SITE_KEYS

#: Keys a record's site may carry (FEMA 356 and NTC 2018).
SITE_FIELDS = (*FEMA356_SITE_KEYS, *NTC2018_SITE_KEYS)


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
        The FEMA 356 design site given to records without one (:func:`audit.engine.shared.sites.with_design_site`),
        JSON-ready; empty where none was given.
    scaling : dict
        The factors of :func:`audit.engine.shared.sites.scale_to_site`, JSON-ready; empty where unscaled.
    floor : dict
        Where the objects stand (:func:`audit.engine.shared.floors.on_floor`), JSON-ready, with each
        record's peak floor acceleration and velocity; empty on the ground.
    """

    entries: tuple[RecordEntry, ...]
    description: str
    is_pulse_idealised: bool = False
    design_site: dict = field(default_factory=dict)
    scaling: dict = field(default_factory=dict)
    floor: dict = field(default_factory=dict)
    #: Records left out by ``--skip-bad-records``: ``{"record", "file", "reason"}`` each.
    rejected: tuple = ()

    def __iter__(self):
        return iter(self.entries)

    def __len__(self):
        return len(self.entries)

    def __getitem__(self, key) -> RecordEntry:
        """The entry with this id (or at this position)."""
        if isinstance(key, int):
            return self.entries[key]
        return self.get(key)

    @property
    def ids(self) -> list[str]:
        """The records' ids, in order."""
        return [entry.id for entry in self.entries]

    def get(self, record_id: str) -> RecordEntry:
        """The entry with this id; InputError naming the ids there are."""
        for entry in self.entries:
            if entry.id == record_id:
                return entry
        raise InputError(f"record: unknown '{record_id}' in {self.description}; "
                         f"available: {', '.join(e.id for e in self.entries)}")


def counted_records(count: int, description: str) -> str:
    """``count`` records of a suite described as ``description``, in words: "44 records of the
    FEMA P695 far-field record set"; a description that itself begins with "records" is not
    repeated ("5 records of manifest suite.toml", not "5 records of records of manifest …")."""
    noun = "record" if count == 1 else "records"
    if description.startswith("records "):
        return f"{count} {noun} {description[len('records '):]}"
    return f"{count} {noun} of {description}"


def site_of(facts: RecordFacts | None, fields: dict) -> dict:
    """A record's site: its catalogue's FEMA 356 site (Table 3.1), then the given fields."""
    site = {}
    if facts is not None and facts.sxs_g is not None:
        site = {"site_class": facts.site_class, "sxs_g": facts.sxs_g, "sx1_g": facts.sx1_g}
    site.update({key: fields[key] for key in SITE_FIELDS if key in fields})
    return site
