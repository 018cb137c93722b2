"""Benchmark of ``audit check``: the far-field set at S_XS = 1.5 g, S_X1 = 0.9 g, every procedure,
one object (0.6 m × 1.8 m) and an inventory of N objects (widths and heights spread over
0.2–1.2 m × 0.6–3.0 m).

    python benchmarks/check.py [--objects 50] [--repeat 3] [--jobs 2] [--records p695-far-field]

A warm-up run on two records loads the compiled kernels first; then each case is run
``--repeat`` times, the cases alternating, and the medians printed: wall time and the process's
CPU time (all its threads), which a machine shared with other work inflates less. The exact part
alone (no procedure) is beside it, so the guidelines' share is the difference. Targets: one
object ≤ 20 s, 50 objects ≤ 5 min on 2 cores.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit.api import Site, design_suite  # noqa: E402
from audit.engine.check.pipeline import run_check  # noqa: E402
from audit.engine.shared.blocks import Block  # noqa: E402
from audit.engine.check.settings import CheckSettings  # noqa: E402
from audit.engine.shared.runtime import Runtime  # noqa: E402
from procedures import get_procedures  # noqa: E402
from records import load_records  # noqa: E402


def inventory(count: int) -> list[Block]:
    """``count`` objects, heights and slendernesses spread (seeded)."""
    rng = np.random.default_rng(32)
    heights = rng.uniform(0.6, 3.0, count)
    widths = heights * np.tan(np.radians(rng.uniform(8.0, 30.0, count)))
    return [Block.of_dimensions(float(w), float(h), name=f"object-{i + 1}") for i, (w, h)
            in enumerate(zip(widths, heights))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", default="p695-far-field")
    parser.add_argument("--objects", type=int, default=50)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    suite = design_suite(load_records(args.records),
                         site=Site(1.5, 0.9, override=True, scale_records=True))
    settings = CheckSettings.parse(im="sa:1.0")
    runtime = Runtime.parse(Runtime(jobs=args.jobs))
    every = get_procedures("all")
    cases = {"one object, every procedure": (every, [Block.of_dimensions(0.6, 1.8, name="0.6x1.8")]),
             "one object, exact only": ([], [Block.of_dimensions(0.6, 1.8, name="0.6x1.8")]),
             f"{args.objects} objects, every procedure": (every, inventory(args.objects))}
    two = replace(suite, entries=tuple(list(suite)[:2]))
    run_check(every, two, [Block.of_dimensions(0.5, 1.5, name="warm-up")], settings, runtime)
    wall = {name: [] for name in cases}
    cpu = {name: [] for name in cases}
    for _ in range(args.repeat):
        for name, (procedures, objects) in cases.items():
            begin, begin_cpu = time.perf_counter(), time.process_time()
            run_check(procedures, suite, objects, settings, runtime)
            wall[name].append(time.perf_counter() - begin)
            cpu[name].append(time.process_time() - begin_cpu)
            print(f"{name}: {wall[name][-1]:.1f} s wall, {cpu[name][-1]:.1f} s CPU", flush=True)
    print(f"{len(suite)} records, medians of {args.repeat}:")
    for name in cases:
        print(f"  {name}: {statistics.median(wall[name]):.1f} s wall, "
              f"{statistics.median(cpu[name]):.1f} s CPU")


if __name__ == "__main__":
    main()
