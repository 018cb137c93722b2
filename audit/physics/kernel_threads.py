"""The threads that the compiled kernels' calls share: started when first needed and kept for
the process.

A solver call splits its blocks (or oscillators) into chunks, one per thread. Starting a pool of
threads for each call cost about a millisecond, a tenth of the solves of a stripe of one
far-field record, and the design-level audit makes thousands of calls. Idle threads are reused;
more start when calls overlap (records computed two at a time), each call's chunks all running
at once as with a pool of its own: the cap, :data:`MAX_THREADS`, is never the limit.
"""

from __future__ import annotations

import functools
import os
import threading
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the pool is made when a kernel first runs, not when the API is imported
    from concurrent.futures import ThreadPoolExecutor

#: Threads the calls of a process may hold at once (started only when none is idle).
MAX_THREADS = 1024
#: Name (prefix) of the pool's threads: idle for the process's life, never joined.
KERNEL_THREADS = "rocking-audit-kernel"


@functools.cache
def _pool() -> ThreadPoolExecutor:
    from concurrent.futures import ThreadPoolExecutor
    return ThreadPoolExecutor(MAX_THREADS, thread_name_prefix=KERNEL_THREADS)


#: Set by :func:`stop_kernels`: no chunk starts any more (the process is leaving).
_stopping = threading.Event()
#: Chunks running on the pool's threads, and the condition :func:`stop_kernels` waits on.
_running = {"count": 0}
_idle = threading.Condition()


def _counted(work, chunk):
    with _idle:
        if _stopping.is_set():  # queued before the stop: it never starts
            return None
        _running["count"] += 1
    try:
        return work(chunk)
    finally:
        with _idle:
            _running["count"] -= 1
            _idle.notify_all()


def run_chunks(work, chunks) -> None:
    """``work(chunk)`` for every chunk, each on a thread of the shared pool, returning when all
    are done. The caller waits interruptibly: after Ctrl-C or an error the chunks not yet
    started are cancelled, and a kernel already running finishes on its thread, unread
    (:func:`stop_kernels` waits for it). After :func:`stop_kernels`, KeyboardInterrupt: a
    thread computing a record beside the main one stops at its next call.
    ``work`` must not call :func:`run_chunks` itself: its chunks could wait for threads that
    all wait for them."""
    if _stopping.is_set():
        raise KeyboardInterrupt
    futures = [_pool().submit(_counted, work, chunk) for chunk in chunks]
    try:
        for future in futures:
            future.result()
    finally:
        for future in futures:
            future.cancel()
    if _stopping.is_set():
        raise KeyboardInterrupt


def stop_kernels(timeout_s: float | None = None) -> bool:
    """Start no more chunks and wait until none is running (at most ``timeout_s``): a process
    leaving after Ctrl-C must not tear down the interpreter, or free the arrays they read,
    under compiled kernels still running on other threads. Whether all have stopped."""
    _stopping.set()
    with _idle:
        return _idle.wait_for(lambda: _running["count"] == 0, timeout_s)


def _after_fork() -> None:
    global _stopping, _idle
    _pool.cache_clear()
    _stopping, _idle = threading.Event(), threading.Condition()
    _running["count"] = 0


# a forked process has none of its parent's threads: it starts its own
os.register_at_fork(after_in_child=_after_fork)


__all__ = ["run_chunks", "stop_kernels", "MAX_THREADS", "KERNEL_THREADS"]
