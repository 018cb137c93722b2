"""Where the records of an audit are computed: this process, or a Dask cluster.

The unit of work is :func:`~audit.engine.record_audit.audit_record` (one record, every procedure,
the whole grid); records are independent, so a suite spreads over workers with no other
communication. ``local`` runs them one after the other in this process (the exact solver
uses ``jobs`` threads); ``dask`` starts a ``dask.distributed`` LocalCluster of ``jobs``
single-threaded worker processes; ``tcp://HOST:PORT`` uses an existing Dask cluster. The
result of a record does not depend on where it was computed (the solver's threads only split
the grid), so every scheduler gives the same values.

Workers get a record by reference where they can read its file: the path, the reader and its
settings, the file's SHA-256 and a digest of the samples; the worker re-reads the file and
uses it only if both match (a scaled record never does). Otherwise, and for pulses and
package records, the record travels by value.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, fields, replace
from pathlib import Path

from audit.engine.partial import motion_digest
from audit.engine.record_audit import audit_record
from audit.errors import InputError

LOCAL = "local"
DASK = "dask"
#: Readers a worker can re-run from a motion's ``metadata["format"]``.
_READERS = ("peer-at2", "columns")


def check_scheduler(text: str) -> str:
    """``--scheduler``: ``local``, ``dask`` or a Dask scheduler address ``tcp://HOST:PORT``."""
    if text in (LOCAL, DASK):
        return text
    if text.startswith(("tcp://", "tls://")):
        host, _, port = text.split("://", 1)[1].rpartition(":")
        if host and port.isdigit():
            return text
    raise InputError(f"--scheduler: expected local, dask or tcp://HOST:PORT, got '{text}'")


@dataclass(frozen=True)
class RecordReference:
    """A record sent by reference: everything but the samples, and how to read them back."""

    entry: object  # records.RecordEntry without its motion
    motion_fields: dict  # the GroundMotion's fields except ``acceleration``
    samples_digest: str


def by_reference(entry):
    """``entry`` as a :class:`RecordReference` when its file can be re-read, else ``entry``."""
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


def timed_audit(item, procedures, settings):
    """Audit one record (entry or reference): ``(RecordAudit, seconds)``, or None if unresolved."""
    entry = resolve(item)
    if entry is None:
        return None
    start = time.perf_counter()
    part = audit_record(entry, procedures, settings)
    return part, time.perf_counter() - start


class LocalScheduler:
    """Records one after the other in this process; the solver uses ``settings.jobs`` threads."""

    description = "this process"

    def audit(self, entries, procedures, settings):
        """Yield ``(index, RecordAudit, seconds)`` for each entry, in order."""
        for index, entry in enumerate(entries):
            yield (index, *timed_audit(entry, procedures, settings))


class DaskScheduler:
    """Records as tasks of a Dask cluster, yielded as they complete.

    Parameters
    ----------
    client : distributed.Client
    description : str
    """

    def __init__(self, client, description: str):
        self.client, self.description = client, description
        #: Ids of the records sent by value (no file the workers could read back).
        self.by_value = []

    def audit(self, entries, procedures, settings):
        """Yield ``(index, RecordAudit, seconds)`` in order of completion.

        Each task runs the solver on one thread: the cluster's workers are the parallelism.
        A record sent by reference that a worker cannot read back is sent again by value.
        """
        from distributed import as_completed
        settings = replace(settings, jobs=1)
        procedures = self.client.scatter(list(procedures), broadcast=True)
        items = [by_reference(entry) for entry in entries]
        self.by_value += [entry.id for entry, item in zip(entries, items) if item is entry]
        futures = [self.client.submit(timed_audit, item, procedures, settings, pure=False)
                   for item in items]
        index_of = {future.key: index for index, future in enumerate(futures)}
        pending = as_completed(futures)
        for future in pending:
            index, outcome = index_of[future.key], future.result()
            future.release()
            if outcome is None:
                self.by_value.append(entries[index].id)
                retry = self.client.submit(timed_audit, entries[index], procedures, settings,
                                           pure=False)
                index_of[retry.key] = index
                pending.add(retry)
                continue
            yield (index, *outcome)


@contextmanager
def open_scheduler(spec: str, jobs: int):
    """The scheduler named by ``--scheduler`` (see :func:`check_scheduler`), closed on exit.

    Parameters
    ----------
    spec : str
        ``local``, ``dask`` or ``tcp://HOST:PORT``.
    jobs : int
        Worker processes of the ``dask`` LocalCluster (ignored otherwise).
    """
    spec = check_scheduler(spec)
    if spec == LOCAL:
        yield LocalScheduler()
        return
    try:
        import logging

        from distributed import Client, LocalCluster
    except ImportError:
        raise InputError(f"--scheduler {spec}: needs dask[distributed] "
                         "(pip install 'dask[distributed]')") from None
    if spec == DASK:
        with LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                          dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
                Client(cluster) as client:
            yield DaskScheduler(client, f"a Dask LocalCluster of {jobs} worker processes")
        return
    try:
        client = Client(spec, timeout="10s")
    except (OSError, TimeoutError) as exc:
        raise InputError(f"--scheduler {spec}: cannot connect: {exc}") from None
    with client:
        workers = len(client.scheduler_info()["workers"])
        yield DaskScheduler(client, f"the Dask cluster at {spec} ({workers} workers)")


__all__ = ["open_scheduler", "check_scheduler", "LocalScheduler", "DaskScheduler",
           "RecordReference", "by_reference", "resolve", "timed_audit"]
