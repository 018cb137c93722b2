"""Benchmark of ``audit check`` reading the atlas (its exact side; the guidelines judged
directly) against ``--method direct``: one object (0.6 m × 1.8 m) warm in a fresh process, an
inventory of N objects (widths 0.2–1.2 m, heights 0.6–3.0 m, uniform, seeded) against the
direct check of benchmarks/inventory_20.csv, alternating, at S_XS = 1.5 g, S_X1 = 0.9 g on the
far-field set; and ``audit atlas check`` (the exact side alone) for reference.

    python benchmarks/atlas_check.py [--inventory 200] [--large 10000] [--repeat 3]
                                     [--procedure all] [--before TREE]

``--before TREE`` (an earlier commit unpacked there: ``git archive COMMIT | tar -x -C TREE``)
times every case in both trees, alternating, the before/after of a change.

The atlas must be built (``python -m audit atlas build --records p695-far-field``). Every case
is the command line in a fresh process (warm: kernels compiled, records and atlas in the
cache); each case's median wall time, with the load average at its end. Targets (issue #58):
one object ≤ 3 s warm, N = 200 objects ≤ 0.5× the direct check of 20, 10,000 objects ≤ 5 min on
this 2-core machine.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
RECORDS = "p695-far-field"
SITE = "1.5,0.9"


def inventory_csv(count: int, folder: Path, seed: int = 58) -> Path:
    """``count`` objects as check's ``--objects`` file."""
    rng = np.random.default_rng(seed)
    height = rng.uniform(0.6, 3.0, count)
    width = np.minimum(rng.uniform(0.2, 1.2, count), 0.9 * height)
    path = folder / f"inventory_{count}.csv"
    path.write_text("name,width_m,height_m\n" + "".join(
        f"object {i},{w:.4f},{h:.4f}\n" for i, (w, h) in enumerate(zip(width, height))))
    return path


def timed(command: list[str], tree: str | None = None) -> float:
    """Wall time of ``audit COMMAND`` in a fresh process, importing ``tree``'s audit if given."""
    env = None if tree is None else {**os.environ, "PYTHONPATH": tree}
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "audit", *command], check=True, capture_output=True,
                   env=env, cwd=tree)
    return time.perf_counter() - start


def report(name: str, times: list[float]) -> None:
    print(f"{name}: median {statistics.median(times):.1f} s of {[round(t, 1) for t in times]}; "
          f"load {os.getloadavg()[0]:.1f}", flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inventory", type=int, default=200)
    parser.add_argument("--large", type=int, default=10000, help="0: not run")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--procedure", default="all", help="check's procedure argument")
    parser.add_argument("--before", metavar="TREE",
                        help="a copy of an earlier tree (git archive): each case timed there "
                             "too, alternating with this one")
    args = parser.parse_args()
    trees = {"": None} if args.before is None else {"before: ": args.before,
                                                     "after: ": str(HERE.parent)}
    # --force: the guard estimates the guidelines' side of 200 objects beyond 15 min
    check = ["check", args.procedure, "--site", SITE, "--records", RECORDS, "--force"]
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        one = {"one object, check (atlas)": check + ["--block", "0.6x1.8", "--method", "atlas"],
               "one object, check --method direct": check + ["--block", "0.6x1.8", "--method",
                                                             "direct"],
               "one object, atlas check (exact side alone)": [
                   "atlas", "check", "--block", "0.6x1.8", "--site", SITE, "--records", RECORDS]}
        objects = str(inventory_csv(args.inventory, folder))
        many = {f"{args.inventory} objects, check (atlas)": check + [
                    "--objects", objects, "--method", "atlas"],
                f"{args.inventory} objects, atlas check (exact side alone)": [
                    "atlas", "check", "--objects", objects, "--site", SITE, "--records",
                    RECORDS],
                "20 objects (benchmarks/inventory_20.csv), check --method direct": check + [
                    "--objects", str(HERE / "inventory_20.csv"), "--method", "direct"]}
        timed(check + ["--block", "0.5x1.5", "--method", "atlas"])  # warm-up
        for cases in (one, many):
            times = {tag + name: [] for name in cases for tag in trees}
            for _ in range(args.repeat):  # alternating
                for name, command in cases.items():
                    for tag, tree in trees.items():
                        times[tag + name].append(timed(command, tree))
            for name in times:
                report(name, times[name])
        if args.large:
            large = inventory_csv(args.large, folder)
            report(f"{args.large} objects, check (atlas)",
                   [timed(check + ["--objects", str(large), "--method", "atlas"])])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
