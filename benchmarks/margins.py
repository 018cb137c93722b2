"""Benchmark of the design-level audit: the far-field set at S_XS = 1.5 g, S_X1 = 0.9 g scaled to
the site, 3 α × 31 sizes (0.5:8:0.25), default stripes, every procedure.

    python benchmarks/margins.py [--records p695-far-field] [--jobs 2]

Prints the wall time of the exact stripes alone and with every procedure evaluated at the same
stripes (their difference is the guideline evaluation), exact solves per second, and the time to
write the files. Target: the whole audit within 5 minutes on a 2-core machine.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from audit.api import design_suite  # noqa: E402
from audit.engine.margins import IntensityMeasure, margins_files, run_margins  # noqa: E402
from audit.files import write_files_atomically  # noqa: E402
from procedures import get_procedures  # noqa: E402
from records import load_records  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", default="p695-far-field")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    suite = design_suite(load_records(args.records), (1.5, 0.9), True, True)
    sizes = np.arange(0.5, 8.001, 0.25)
    alphas = (10.0, 15.0, 20.0)
    im = IntensityMeasure.parse("sa:1.0")
    start = time.perf_counter()
    exact_only = run_margins([], suite, im, None, alphas, sizes, jobs=args.jobs)
    stripes_s = time.perf_counter() - start
    solves = len(exact_only.stripes)
    start = time.perf_counter()
    full = run_margins(get_procedures("all"), suite, im, None, alphas, sizes, jobs=args.jobs)
    full_s = time.perf_counter() - start
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as folder:
        write_files_atomically(Path(folder) / "m", margins_files(full))
    files_s = time.perf_counter() - start
    print(f"{len(suite)} records × {len(full.summary['levels'])} stripes × "
          f"{len(alphas) * sizes.size} blocks = {solves} exact solves")
    print(f"exact stripes alone: {stripes_s:.1f} s ({solves / stripes_s:.0f} solves/s)")
    print(f"with every procedure at the stripes: {full_s:.1f} s (guideline evaluation "
          f"{full_s - stripes_s:.1f} s); files {files_s:.1f} s; audit in all "
          f"{full_s + files_s:.1f} s (target ≤ 300 s)")


if __name__ == "__main__":
    main()
