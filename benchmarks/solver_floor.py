"""The least wall time a command can take on this machine with its compiled solves unchanged:
the CPU time spent inside the solver threads (the rocking solver's and the oscillators' chunks,
all run through :func:`audit.physics.kernel_threads.run_chunks`) divided by the cores.

    python benchmarks/solver_floor.py -- margins all --site 1.5,0.9 --scale-to-site \\
        --records p695-far-field
    python benchmarks/solver_floor.py -- run all --records $ROCKING_AUDIT_RECORDS

The command runs in this process, in an empty temporary folder (its outputs are discarded).
No rearrangement of the rest of the work (Python, files, report) can bring its wall time below
the floor, however well it overlaps with the solves: only fewer solves or cheaper ones can. The
guidelines' own compiled iterations run on the record threads, not in these chunks, and are not
counted, so the floor is a lower bound.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import threading
import time
from collections import Counter
from pathlib import Path

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit.cli import main as audit_main  # noqa: E402
from audit.physics import kernel_threads, response_spectra  # noqa: E402
from audit.physics.rocking import spectrum  # noqa: E402

#: Modules that call the shared threads, by what their chunks solve.
CALLERS = {spectrum: "rocking solver", response_spectra: "oscillators"}


def counted(chunk_cpu_s: Counter, lock: threading.Lock, name: str):
    """``run_chunks`` adding each chunk's CPU time (its thread's) to ``chunk_cpu_s[name]``."""
    def run_chunks(work, chunks):
        def timed(chunk):
            begin = time.thread_time()
            try:
                return work(chunk)
            finally:
                with lock:
                    chunk_cpu_s[name] += time.thread_time() - begin
        return kernel_threads.run_chunks(timed, chunks)
    return run_chunks


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("command", nargs=argparse.REMAINDER,
                        help="the audit command and its options, after --")
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    cores = len(os.sched_getaffinity(0))
    chunk_cpu_s, lock = Counter(), threading.Lock()
    for module, name in CALLERS.items():
        module.run_chunks = counted(chunk_cpu_s, lock, name)
    with tempfile.TemporaryDirectory(prefix="solver-floor-") as folder:
        os.chdir(folder)
        wall, cpu = time.perf_counter(), time.process_time()
        code = audit_main(command)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    if code:
        raise SystemExit(f"the command exited with status {code}")
    solves = sum(chunk_cpu_s.values())
    print(f"wall: {wall:.1f} s")
    print(f"process CPU: {cpu:.1f} s")
    for name, seconds in chunk_cpu_s.most_common():
        print(f"{name} CPU: {seconds:.1f} s")
    print(f"solver floor: {solves / cores:.1f} s ({solves:.1f} s of solver CPU on {cores} "
          f"cores, {solves / cores / wall:.0%} of the wall time)")


if __name__ == "__main__":
    main()
