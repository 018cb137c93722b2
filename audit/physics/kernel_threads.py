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
from concurrent.futures import ThreadPoolExecutor

#: Threads the calls of a process may hold at once (started only when none is idle).
MAX_THREADS = 1024


@functools.cache
def _pool() -> ThreadPoolExecutor:
    return ThreadPoolExecutor(MAX_THREADS, thread_name_prefix="rocking-audit-kernel")


# a forked process has none of its parent's threads: it starts its own
os.register_at_fork(after_in_child=_pool.cache_clear)


def run_chunks(work, chunks) -> None:
    """``work(chunk)`` for every chunk, each on a thread of the shared pool, returning when all
    are done. The caller waits interruptibly: after Ctrl-C or an error the chunks not yet
    started are cancelled, and a kernel already running finishes on its thread, unread.
    ``work`` must not call :func:`run_chunks` itself: its chunks could wait for threads that
    all wait for them."""
    futures = [_pool().submit(work, chunk) for chunk in chunks]
    try:
        for future in futures:
            future.result()
    finally:
        for future in futures:
            future.cancel()


__all__ = ["run_chunks", "MAX_THREADS"]
