"""Benchmark of check's answers read from the atlas (``python -m audit atlas check``): one
object (0.6 m × 1.8 m) warm, and inventories of N objects (widths 0.2–1.2 m, heights
0.6–3.0 m, uniform, seeded), at S_XS = 1.5 g, S_X1 = 0.9 g on the far-field set.

    python benchmarks/atlas_check.py [--objects 200,10000] [--repeat 3]

The atlas must be built (``python -m audit atlas build --records p695-far-field``). Each case's
median wall time, with the load average at its end. Targets (issue #58): one object ≤ 3 s warm,
10,000 objects ≤ 5 min on this 2-core machine; the 200-object inventory against the direct
check of 20 objects (benchmarks/check.py).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit.api import atlas_check  # noqa: E402

RECORDS = "p695-far-field"
SITE = (1.5, 0.9)


def inventory(count: int, seed: int = 58) -> list:
    rng = np.random.default_rng(seed)
    height = rng.uniform(0.6, 3.0, count)
    width = np.minimum(rng.uniform(0.2, 1.2, count), 0.9 * height)
    return [(f"object {i}", float(w), float(h)) for i, (w, h) in enumerate(zip(width, height))]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--objects", default="200,10000")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    # one object as a user runs it: a fresh process, the command line (warm: kernels compiled,
    # records and atlas in the cache)
    command = [sys.executable, "-m", "audit", "atlas", "check", "--block", "0.6x1.8",
               "--site", ",".join(map(str, SITE)), "--records", RECORDS]
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    print(f"one object, command line: median {statistics.median(times):.2f} s of "
          f"{[round(t, 2) for t in times]}; load {os.getloadavg()[0]:.1f}")
    atlas_check(inventory(2), SITE, RECORDS)  # loads the records' digest and the atlas once
    for count in (int(c) for c in args.objects.split(",")):
        objects = inventory(count)
        times = []
        for _ in range(args.repeat if count <= 1000 else 1):
            start = time.perf_counter()
            answers = atlas_check(objects, SITE, RECORDS)
            times.append(time.perf_counter() - start)
        outside = sum(a["p_overturn_at_site"] is None for a in answers)
        print(f"{count} objects ({outside} outside the atlas): median {statistics.median(times):.1f} s of "
              f"{[round(t, 1) for t in times]}; load {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
