"""The driver's heap while a suite streams through it.

Each record's part is thousands of small allocations (DataFrame blocks of a few kB) that are
freed once the part is written. glibc's malloc keeps freed memory until the free space at the
top of its heap exceeds ``M_TRIM_THRESHOLD`` (128 kB, raised dynamically up to 32 MB as large
blocks are freed), so over thousands of records the resident size creeps up with memory the
process no longer uses. A fixed 64 kB threshold returns it as it is freed — the setting Dask
gives its own workers (``distributed.nanny.pre-spawn-environ``, ``MALLOC_TRIM_THRESHOLD_``).
Measured on 440 records of the enlarged far-field suite: peak growth over 44 records 103 kB a
record instead of 134 kB.

glibc also gives each new thread an arena of its own (up to 8 per core). With ``--scheduler
dask`` the driver's Dask threads (the client's event loop, which receives every record's part,
and the LocalCluster's scheduler) allocate in arenas of their own, and the driver's peak grew
faster with the suite than the local scheduler's. One arena for the whole process: measured with
``--scheduler dask`` on the enlarged far-field suite, peak growth from 44 to 264 records 114 kB
a record instead of 164 kB (local: 114 kB), and no change of the local scheduler's wall time
(44 records, 3 runs each). A thread that allocated before the call keeps its own arena, so it
is made before a scheduler starts.
"""

from __future__ import annotations

import ctypes

#: glibc's mallopt parameter number of M_TRIM_THRESHOLD (malloc.h).
_M_TRIM_THRESHOLD = -1
#: glibc's mallopt parameter number of M_ARENA_MAX (malloc.h).
_M_ARENA_MAX = -8
#: Free memory at the top of the heap above which it is returned to the system [bytes].
TRIM_THRESHOLD_BYTES = 64 * 1024
#: Heaps (arenas) the process's threads share.
ARENAS = 1


def return_freed_memory_promptly() -> bool:
    """Set glibc's trim threshold to :data:`TRIM_THRESHOLD_BYTES` and its arenas to
    :data:`ARENAS` for this process; False (and nothing done) where the C library is not glibc."""
    try:  # the symbols the process already has: glibc's on Linux
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return False
    trimmed = mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD_BYTES)
    shared = mallopt(_M_ARENA_MAX, ARENAS)
    return bool(trimmed and shared)


__all__ = ["return_freed_memory_promptly", "TRIM_THRESHOLD_BYTES", "ARENAS"]
