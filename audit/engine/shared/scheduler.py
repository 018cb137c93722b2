"""Where the records of an audit are computed: this process, or a Dask cluster.

The unit of work is one record, a task the workflow hands in (an audit's record: every
procedure, the whole grid; a design-level audit's: a record's stripes; a check's: a record's
part); records are independent, so a suite spreads over workers with no other
communication. ``local`` runs them in this process, two at a time, handed back in order (the
exact solver uses ``jobs`` threads); ``dask`` starts a ``dask.distributed`` LocalCluster of ``jobs``
single-threaded worker processes; ``tcp://HOST:PORT`` uses an existing Dask cluster. The
result of a record does not depend on where it was computed (the solver's threads only split
the grid), so every scheduler gives the same values.

Workers get a record by reference where they can read its file
(:mod:`audit.engine.shared.record_references`), otherwise by value.
"""

from __future__ import annotations

import time
from collections import deque
from concurrent.futures import CancelledError, ThreadPoolExecutor
from contextlib import contextmanager, nullcontext
from dataclasses import replace

from audit.engine.shared.record_references import by_reference, resolve
from audit.engine.shared.runtime import DASK, LOCAL, check_scheduler
from audit.errors import InputError


def timed(task, item, *args):
    """``task(entry, *args)`` on one record (entry or reference): ``(part, seconds)``, or None
    if the reference cannot be resolved.

    Parameters
    ----------
    task : callable
        ``task(entry, *args)``, the work on one record.
    item : records.RecordEntry or RecordReference
        The record, or a reference re-read here.
    *args
        The task's other arguments.
    """
    entry = resolve(item)
    if entry is None:
        return None
    start = time.perf_counter()
    part = task(entry, *args)
    return part, time.perf_counter() - start


#: Records a local run computes at once: the next one starts while the last is finished, so
#: that one record's Python work (guidelines' iterations, rows, files), which holds the GIL,
#: runs beside the other's compiled kernels, which release it.
RECORDS_IN_FLIGHT = 2
#: Records a local run may have computed ahead of the one the caller waits for: a thread whose
#: record finished before an earlier one (or while the caller writes the last) starts the next
#: at once instead of idling, and memory holds at most this many parts more.
RECORDS_AHEAD = 2


class LocalScheduler:
    """Records in this process, two at a time and handed back in order (up to
    :data:`RECORDS_AHEAD` computed ahead of their turn); the solver uses ``settings.jobs``
    threads."""

    description = "this process"
    #: Solver threads of a task: None keeps the settings' ``jobs``.
    solver_threads = None

    def map(self, task, entries, *args):
        """Yield ``(index, task(entry, *args), seconds)`` for each entry, in order.

        Parameters
        ----------
        task : callable
            ``task(entry, *args)``, the work on one record.
        entries : sequence of records.RecordEntry or RecordReference
            The records.
        *args
            The task's other arguments.
        """
        pool = ThreadPoolExecutor(RECORDS_IN_FLIGHT)
        window = RECORDS_IN_FLIGHT + RECORDS_AHEAD  # queued ones start as a thread frees
        try:
            futures = deque(pool.submit(timed, task, entry, *args)
                            for entry in entries[:window])
            for index in range(len(entries)):
                done = futures.popleft().result()
                if index + window < len(entries):
                    futures.append(pool.submit(timed, task, entries[index + window], *args))
                yield (index, *done)
        finally:  # on an interrupt or an error nothing waits for the records still queued
            pool.shutdown(wait=False, cancel_futures=True)


#: Times a record whose task the Dask scheduler cancelled (a lost worker took an argument it
#: needed) is sent again before the run gives up.
RESUBMITS = 3
#: Records queued or running per worker thread of a Dask cluster: enough that a worker never
#: waits for the driver, few enough that the records sent by value stay a small, fixed term.
TASKS_PER_THREAD = 2


class DaskScheduler:
    """Records as tasks of a Dask cluster, yielded as they complete.

    Parameters
    ----------
    client : distributed.Client
    description : str
    """

    #: Each task runs the solver on one thread: the cluster's workers are the parallelism.
    solver_threads = 1

    def __init__(self, client, description: str):
        self.client, self.description = client, description
        #: Ids of the records sent by value (no file the workers could read back).
        self.by_value = []

    def map(self, task, entries, *args):
        """Yield ``(index, task(entry, *args), seconds)`` in order of completion.

        ``args`` (procedures, settings) are scattered once to every worker. Records are
        submitted as earlier ones complete, :data:`TASKS_PER_THREAD` per worker thread of the
        cluster as it is then (so a cluster that grows gets more): a record sent by value is
        held by the scheduler only while queued or running, and the driver's memory does not
        grow with the suite. A record sent by reference that a worker cannot read back is sent
        again by value. A worker lost mid-run: the Dask scheduler gives its tasks to the other
        workers (up to ``distributed.scheduler.allowed-failures`` deaths per task), but a task
        whose scattered argument was lost with it is cancelled, so the arguments are scattered
        again and the record sent again (up to :data:`RESUBMITS` times); ``retries=`` would only
        re-run a task that raised, which for a deterministic record raises again
        (tests/cli/test_dask_cluster.py).

        Parameters
        ----------
        task : callable
            ``task(entry, *args)``, the work on one record.
        entries : sequence of records.RecordEntry or RecordReference
            The records.
        *args
            The task's other arguments.
        """
        from distributed import as_completed
        # an empty list (the check's width search has no procedures) has nothing to scatter;
        # keys of their own (hash=False): the same procedures scattered by an earlier call
        # would share its key, and its release lose them under this call's tasks
        given = args

        def scattered():
            return [arg if isinstance(arg, list) and not arg
                    else self.client.scatter(arg, broadcast=True, hash=False) for arg in given]

        args = scattered()
        waiting = iter(enumerate(entries))
        cancelled = {}
        index_of = {}
        pending = as_completed()

        def submit(index, item):
            future = self.client.submit(timed, task, item, *args, pure=False)
            index_of[future.key] = index
            pending.add(future)

        def send(index, entry):
            item = by_reference(entry)
            if item is entry:
                self.by_value.append(entry.id)
            submit(index, item)

        def fill():
            threads = max(1, sum(self.client.nthreads().values()))
            for index, entry in waiting:
                send(index, entry)
                if pending.count() >= TASKS_PER_THREAD * threads:
                    return

        fill()
        for future in pending:
            index = index_of.pop(future.key)
            try:
                outcome = future.result()
            except CancelledError:
                # the scheduler forgot the task: a worker lost mid-run can take the only copy
                # of a scattered argument with it, and what depends on it is cancelled, not
                # rerun; scattered again, the record is sent again
                cancelled[index] = cancelled.get(index, 0) + 1
                if cancelled[index] > RESUBMITS:
                    raise
                args = scattered()
                send(index, entries[index])
                continue
            future.release()
            if outcome is None:
                self.by_value.append(entries[index].id)
                submit(index, entries[index])
            else:
                yield (index, *outcome)
            fill()


@contextmanager
def side_thread():
    """One worker thread for Python work (holding the GIL) to run beside the caller's compiled
    solves (which release it), not after them with a core idle. On exit, after Ctrl-C or an
    error too, nothing waits for it: what is still queued is dropped."""
    pool = ThreadPoolExecutor(1)
    try:
        yield pool
    finally:
        pool.shutdown(wait=False, cancel_futures=True)


@contextmanager
def open_scheduler(spec: str, jobs: int):
    """The scheduler named by ``spec`` (see :func:`check_scheduler`), closed on exit.

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
        raise InputError(f"scheduler {spec}: needs dask[distributed] "
                         "(pip install 'dask[distributed]')", "scheduler") from None
    if spec == DASK:
        with LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                          dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
                Client(cluster) as client:
            yield DaskScheduler(client, f"a Dask LocalCluster of {jobs} worker processes")
        return
    try:
        client = Client(spec, timeout="10s")
    except (OSError, TimeoutError) as exc:
        raise InputError(f"scheduler {spec}: cannot connect: {exc}", "scheduler") from None
    with client:
        workers = len(client.scheduler_info()["workers"])
        yield DaskScheduler(client, f"the Dask cluster at {spec} ({workers} workers)")


def _with_jobs(settings, jobs: int):
    """``settings`` with ``jobs`` solver threads: a dataclass with a ``jobs`` field, or one that
    says how (:meth:`~audit.engine.check.record_part.CheckWork.with_jobs`, whose threads are
    its stripes')."""
    with_jobs = getattr(settings, "with_jobs", None)
    return with_jobs(jobs) if with_jobs is not None else replace(settings, jobs=jobs)


def computed_parts(task, entries, procedures, settings, scheduler: str, store=None,
                   progress=None, consume=None):
    """``task(entry, procedures, settings)`` of every entry, where ``scheduler`` says, each part
    stored as it completes and reused from ``store`` when resuming.

    Parameters
    ----------
    task : callable
        The unit of work of one record (module level, so that Dask can send it).
    entries : list of records.RecordEntry
    procedures : list of procedures.Procedure
    settings : dataclass with ``jobs``
        The run's settings (their ``jobs`` also sizes a ``dask`` LocalCluster).
    scheduler : str or LocalScheduler or DaskScheduler
        ``local``, ``dask`` or ``tcp://HOST:PORT`` (opened for this call and closed), or a
        scheduler already open (:func:`open_scheduler`), for several calls.
    store : audit.engine.shared.partial.PartialStore, optional
        Where each part is kept as it completes; with its ``resume``, the matching parts
        already there are reused.
    progress : callable, optional
        ``progress(done, total, record_id, how)`` after each record.
    consume : callable, optional
        ``consume(index, part)`` of each part as it completes or is reused (not in order on a
        Dask cluster; reused ones first), which is then dropped: a suite of thousands of
        records is never held whole, and ``parts`` is None. Default: return the parts.

    Returns
    -------
    parts : list or None
        One per entry, in order.
    resumed : list of str
        Ids of the records whose parts came from ``store``.
    description : str
        Where the parts were computed.
    """
    progress = progress or (lambda done, total, record_id, how: None)
    parts = [None] * len(entries)

    def take(index, part):
        if consume is not None:
            consume(index, part)
        parts[index] = part if consume is None else True  # True: done, not held

    for i, entry in enumerate(entries):
        if store and store.resume and (part := store.load(entry)) is not None:
            take(i, part)
    resumed = [entry.id for entry, part in zip(entries, parts) if part is not None]
    for count, record_id in enumerate(resumed, start=1):
        progress(count, len(entries), record_id, "reused from an interrupted run")
    todo = [i for i, part in enumerate(parts) if part is None]
    with (open_scheduler(scheduler, settings.jobs) if isinstance(scheduler, str)
          else nullcontext(scheduler)) as executor:
        threads = executor.solver_threads
        task_settings = settings if threads is None else _with_jobs(settings, threads)
        for count, (k, part, seconds) in enumerate(
                executor.map(task, [entries[i] for i in todo], list(procedures), task_settings),
                start=len(resumed) + 1):
            if store:
                store.save(entries[todo[k]], part)
            progress(count, len(entries), entries[todo[k]].id, f"computed in {seconds:.1f} s")
            take(todo[k], part)
    return (parts if consume is None else None), resumed, executor.description


__all__ = ["computed_parts", "open_scheduler", "check_scheduler", "LocalScheduler", "DaskScheduler",
           "side_thread", "timed"]
