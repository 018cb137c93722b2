"""How a run is carried out, apart from what it computes: threads or worker processes, where
records are computed, the folder of parts kept as they complete, resuming, progress.

None of it changes a number of the results (:class:`~audit.engine.run.settings.AuditSettings` and
:class:`~audit.engine.design.settings.MarginsSettings` hold what does). Light: no scientific
import.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import DEFAULT_JOBS, DEFAULT_SCHEDULER
from audit.errors import InputError

LOCAL = "local"
DASK = "dask"

#: The fields :meth:`Runtime.parse` takes, and their defaults.
RUNTIME_DEFAULTS = {"jobs": DEFAULT_JOBS, "scheduler": DEFAULT_SCHEDULER, "partial_dir": None,
                    "resume": False, "progress": None}
RUNTIME_FIELDS = tuple(RUNTIME_DEFAULTS)


def check_scheduler(text, field: str = "scheduler") -> str:
    """``local``, ``dask`` or a Dask scheduler address ``tcp://HOST:PORT``.

    Parameters
    ----------
    text : str
        What was given.
    field : str
        The argument's name, for the message.
    """
    if text in (LOCAL, DASK):
        return text
    if isinstance(text, str) and text.startswith(("tcp://", "tls://")):
        host, _, port = text.split("://", 1)[1].rpartition(":")
        if host and port.isdigit():
            return text
    raise InputError(f"{field}: expected local, dask or tcp://HOST:PORT, got {text!r}", field)


@dataclass(frozen=True)
class Runtime:
    """How a run is carried out.

    Attributes
    ----------
    jobs : int
        ``local``: threads of the exact solver; ``dask``: worker processes of the LocalCluster.
    scheduler : str
        ``local``, ``dask`` or ``tcp://HOST:PORT`` (:mod:`audit.engine.shared.scheduler`), or a
        scheduler already open (:func:`~audit.engine.shared.scheduler.open_scheduler`).
    partial_dir : Path or None
        Folder for per-record results as they complete (:mod:`audit.engine.shared.partial`), kept
        for a resumed run; None: none kept.
    resume : bool
        Reuse the matching per-record results already in ``partial_dir``.
    progress : callable or None
        ``progress(done, total, record_id, how)`` after each record.
    """

    jobs: int = DEFAULT_JOBS
    scheduler: object = DEFAULT_SCHEDULER
    partial_dir: Path | None = None
    resume: bool = False
    progress: object = None

    @classmethod
    def parse(cls, **values) -> Runtime:
        """The runtime of the given fields, each checked once (InputError naming it).

        Parameters
        ----------
        **values
            Fields of :data:`RUNTIME_FIELDS` by name (the rest take :data:`RUNTIME_DEFAULTS`).
        """
        check.unknown("the runtime", values, RUNTIME_FIELDS)
        value = {**RUNTIME_DEFAULTS, **values}
        scheduler = value["scheduler"]
        if isinstance(scheduler, str) or not hasattr(scheduler, "map"):
            scheduler = check_scheduler(scheduler)
        progress = value["progress"]
        if progress is not None and not callable(progress):
            raise InputError(f"progress: expected True, False or progress(done, total, "
                             f"record_id, how), got {progress!r}", "progress")
        partial = value["partial_dir"]
        resume = check.flag("resume", value["resume"])
        if resume and partial is None:
            raise InputError("resume: needs partial_dir, the folder of the interrupted run's "
                             "parts", "resume", "partial_dir")
        return cls(check.whole("jobs", value["jobs"], 1), scheduler,
                   None if partial is None else check.path("partial_dir", partial, "a folder"),
                   resume, progress)

    def report(self, done: int, total: int, record_id: str, how: str) -> None:
        """Tell :attr:`progress`, if any, that a record is done.

        Parameters
        ----------
        done, total : int
            Records done so far, and in all.
        record_id : str
            The record just done.
        how : str
            How, in words: ``computed in 2.1 s`` or ``reused from an interrupted run``.
        """
        if self.progress is not None:
            self.progress(done, total, record_id, how)


__all__ = ["Runtime", "RUNTIME_DEFAULTS", "RUNTIME_FIELDS", "check_scheduler", "LOCAL", "DASK"]
