"""Side by side: one command run from two checkouts (a baseline commit and the change) in
alternation, repeated; wall time (and the children's CPU time) of each run, medians and the
ratio change/baseline, with the machine's load average beside every run.

    git worktree add --detach ../base 1a046c4
    python benchmarks/compare.py --baseline ../base --repeat 5 -- \\
        python -m audit run all --records $ROCKING_AUDIT_RECORDS
    python benchmarks/compare.py --baseline ../base --repeat 2 --stages -- \\
        python {change}/benchmarks/margins.py

Each run is a fresh process in an empty folder, with ``PYTHONPATH`` the checkout's (so the
same script measures either tree); ``{change}`` in the command is this checkout. With
``--stages`` the lines ``name: N s`` a benchmark prints (benchmarks/margins.py's breakdown) are
collected and compared too. ``--keep DIR`` keeps each side's last output folder, to compare the
files the two trees wrote; ``--identical`` (with ``--keep``) then says whether every file is
the same bytes on both sides, the report's "generated" time stamp aside — for a change that
must not alter any output, measured against its parent commit:

    git worktree add --detach ../parent HEAD~1
    python benchmarks/compare.py --baseline ../parent --keep /tmp/both --identical -- \\
        python -m audit run all --records $ROCKING_AUDIT_RECORDS --out out
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CHANGE = Path(__file__).resolve().parents[1]
#: ``stage: 12.3 s`` in a benchmark's output.
STAGE = re.compile(r"([A-Za-zα ]+?):? (\d+(?:\.\d+)?) s\b")
#: The time stamp of a page (``generated 2026-11-27 16:13 UTC``): the one difference allowed.
STAMP = re.compile(rb"generated \d{4}-\d\d-\d\d \d\d:\d\d UTC")


def run_once(tree: Path, command: list[str], keep: Path | None) -> dict:
    folder = Path(tempfile.mkdtemp(prefix="compare-"))
    env = {**os.environ, "PYTHONPATH": str(tree)}
    command = [part.replace("{change}", str(CHANGE)) for part in command]
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    begin = time.perf_counter()
    done = subprocess.run(command, cwd=folder, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - begin
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode:
        sys.exit(f"{tree}: {' '.join(command)} failed ({done.returncode}):\n{done.stderr}")
    stages = {name.strip(): float(value) for name, value in STAGE.findall(done.stdout)}
    if keep is not None:
        shutil.rmtree(keep, ignore_errors=True)
        shutil.copytree(folder, keep)
    shutil.rmtree(folder, ignore_errors=True)
    return {"wall": wall, "cpu": (after.ru_utime + after.ru_stime)
            - (before.ru_utime + before.ru_stime), "load": load, "stages": stages}


def differing_files(base: Path, change: Path) -> list[str]:
    """Files (relative paths) present on one side only or with other bytes, time stamps aside."""
    names = {p.relative_to(side).as_posix() for side in (base, change) for p in side.rglob("*")
             if p.is_file()}
    return sorted(name for name in names
                  if not ((base / name).is_file() and (change / name).is_file())
                  or STAMP.sub(b"", (base / name).read_bytes())
                  != STAMP.sub(b"", (change / name).read_bytes()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", type=Path, required=True, help="baseline checkout")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--stages", action="store_true")
    parser.add_argument("--keep", type=Path, help="keep each side's last output in DIR/{baseline,change}")
    parser.add_argument("--identical", action="store_true",
                        help="with --keep: check that both sides wrote the same files")
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    if args.identical and args.keep is None:
        parser.error("--identical needs --keep DIR")
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    trees = {"baseline": args.baseline.resolve(), "change": CHANGE}
    runs = {name: [] for name in trees}
    for i in range(args.repeat):
        # alternate which goes first, so a trend in the machine's load favours neither
        for name in (("baseline", "change") if i % 2 == 0 else ("change", "baseline")):
            keep = args.keep / name if args.keep else None
            result = run_once(trees[name], command, keep)
            runs[name].append(result)
            print(f"run {i + 1} {name:8s} wall {result['wall']:7.2f} s  cpu {result['cpu']:7.2f} s"
                  f"  load {result['load']:5.2f}  {result['stages'] or ''}", flush=True)
    print(f"\n{' '.join(command)}\nmedians of {args.repeat} alternating runs (load average "
          f"{min(r['load'] for v in runs.values() for r in v):.1f}–"
          f"{max(r['load'] for v in runs.values() for r in v):.1f}):")
    rows = [("wall", lambda r: r["wall"]), ("cpu", lambda r: r["cpu"])]
    if args.stages:
        names = [n for n in runs["baseline"][0]["stages"] if n in runs["change"][0]["stages"]]
        rows += [(name, lambda r, n=name: r["stages"][n]) for name in names]
    for label, value in rows:
        base = statistics.median(value(r) for r in runs["baseline"])
        change = statistics.median(value(r) for r in runs["change"])
        print(f"  {label:40s} baseline {base:8.2f} s  change {change:8.2f} s  "
              f"ratio {change / base if base else float('nan'):.3f}")
    if args.identical:
        differing = differing_files(args.keep / "baseline", args.keep / "change")
        files = sum(1 for p in (args.keep / "change").rglob("*") if p.is_file())
        print("outputs: " + (f"differ: {', '.join(differing)}" if differing else
                             f"all {files} files identical (time stamps aside)"))


if __name__ == "__main__":
    main()
