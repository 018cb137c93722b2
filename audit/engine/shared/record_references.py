"""Records sent to a Dask worker by reference: the path, the reader and its settings, the file's
SHA-256 and a digest of the samples, instead of the samples themselves. The worker re-reads the
file and uses it only if both match (a scaled record never does); otherwise, and for pulses and
package records, the record travels by value (:mod:`audit.engine.shared.scheduler`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from pathlib import Path

from audit.engine.shared.partial import motion_digest
from audit.errors import InputError

#: Readers a worker can re-run from a motion's ``metadata["format"]``.
_READERS = ("peer-at2", "columns")


@dataclass(frozen=True)
class RecordReference:
    """A record sent by reference: everything but the samples, and how to read them back."""

    entry: object  # records.RecordEntry without its motion
    motion_fields: dict  # the GroundMotion's fields except ``acceleration``
    samples_digest: str


def by_reference(entry):
    """``entry`` as a :class:`RecordReference` when its file can be re-read, else ``entry``.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    """
    motion = entry.motion
    if (motion is None or motion.pulse is not None
            or motion.metadata.get("format") not in _READERS or not Path(motion.source).is_file()):
        return entry
    return RecordReference(replace(entry, motion=None),
                           {f.name: getattr(motion, f.name) for f in fields(motion)
                            if f.name != "acceleration"},
                           motion_digest(motion))


def resolve(item):
    """The :class:`RecordEntry` of ``item`` (re-read on a worker), or None if it cannot be.

    None when the file is not readable here, or its SHA-256 or samples differ from the ones
    the run was given (e.g. another file at that path, or a record scaled after reading).

    Parameters
    ----------
    item : records.RecordEntry or RecordReference
        A record, or a reference to one.
    """
    if not isinstance(item, RecordReference):
        return item
    from records import GroundMotion, read_at2, read_columns
    given = item.motion_fields
    try:
        if given["metadata"]["format"] == "peer-at2":
            motion = read_at2(given["source"])
        else:
            motion = read_columns(given["source"], given["metadata"]["column"], given["dt"],
                                  given["metadata"]["units"])
    except (InputError, OSError, KeyError):
        return None
    if motion.sha256 != given["sha256"] or motion_digest(motion) != item.samples_digest:
        return None
    return replace(item.entry, motion=GroundMotion(acceleration=motion.acceleration, **given))


__all__ = ["RecordReference", "by_reference", "resolve"]
