"""How a run is carried out, apart from what it computes: threads or worker processes, where
records are computed, progress, whether to start beyond the work's limits, the folder of parts
kept as they complete, resuming.

None of it changes a number of the results (:class:`~audit.engine.run.settings.AuditSettings` and
:class:`~audit.engine.design.settings.MarginsSettings` hold what does). Light: no scientific
import.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import DEFAULT_JOBS, DEFAULT_SCHEDULER
from audit.errors import InputError, field_name

LOCAL = "local"
DASK = "dask"

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
    progress : callable, True or None
        ``progress(done, total, record_id, how)`` after each record; True: a progress bar on
        standard error (the API draws it; the engine takes a callable or None).
    force : bool
        Start even when the work is estimated beyond the limits of
        :mod:`audit.engine.shared.guards`.
    partial_dir : Path or None
        Folder for per-record results as they complete (:mod:`audit.engine.shared.partial`), kept
        for a resumed run; None: none kept.
    resume : bool
        Reuse the matching per-record results already in ``partial_dir``.
    """

    jobs: int = DEFAULT_JOBS
    scheduler: object = DEFAULT_SCHEDULER
    progress: object = None
    force: bool = False
    partial_dir: Path | None = None
    resume: bool = False

    @classmethod
    def parse(cls, value=None, argument: str | None = "runtime") -> Runtime:
        """``value`` with every field checked once (InputError naming ``argument.field``, or
        the field alone where ``argument`` is None: a function's own keywords).

        Parameters
        ----------
        value : Runtime or None
            None: the defaults. ``progress`` may be True (a progress bar, which the caller
            draws) or False.
        argument : str or None
            The argument the runtime was given as, for the messages.
        """
        def name(field):
            return field_name(argument, field)

        if value is None:
            value = cls()
        if not isinstance(value, Runtime):
            raise InputError(f"{argument}: expected a Runtime(jobs, scheduler, progress, force, "
                             f"partial_dir, resume), got {value!r}", argument)
        scheduler = value.scheduler
        if isinstance(scheduler, str) or not hasattr(scheduler, "map"):
            scheduler = check_scheduler(scheduler, name("scheduler"))
        progress = check.callback(name("progress"), False if value.progress is None
                                  else value.progress, "progress(done, total, record_id, how)")
        partial = value.partial_dir
        resume = check.flag(name("resume"), value.resume)
        if resume and partial is None:
            raise InputError(f"{name('resume')}: needs {name('partial_dir')}, the folder of the "
                             "interrupted run's parts", name("resume"), name("partial_dir"))
        return cls(check.whole(name("jobs"), value.jobs, 1), scheduler, progress or None,
                   check.flag(name("force"), value.force),
                   None if partial is None else check.path(name("partial_dir"), partial,
                                                           "a folder"),
                   resume)

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


__all__ = ["Runtime", "check_scheduler", "LOCAL", "DASK"]
