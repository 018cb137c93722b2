"""Suite-scale audit: the local scheduler against a Dask cluster, on one suite of records.

Every registered procedure on every record of the suite over the default grid (α = 10, 15, 20°;
2π/p = 0.5 … 8 s step 0.05), computed and written (the data files and the report, as
``python -m audit run`` writes them) by one of three modes:

- ``local``: in one process, the solver on ``--workers`` threads (``--scheduler local``);
- ``dask``: on a Dask cluster as an operator runs one, the scheduler and ``--workers``
  single-threaded workers each a process of its own (``distributed``'s SubprocessCluster),
  reached at its ``tcp://`` address (``--scheduler tcp://HOST:PORT``);
- ``localcluster``: ``--scheduler dask``, the run's own LocalCluster, whose scheduler lives in
  the driver's process (its start-up is in the wall time; its workers' memory is not asked).

Each mode runs in a fresh child process, after a warm-up that loads the compiled solver, so its
peak memory is its own: ``resource.getrusage`` maxrss of the child (the driver), and of each
Dask worker and the scheduler (asked before the cluster closes). Reports wall time, time per
record and per block, the size of a record's results and of the run's files, and a projection
for the ~21,000 NGA-West2 components.
Every mode runs with one BLAS thread (``--blas-threads``), as Dask's nanny starts its workers, so
that a difference of BLAS settings is never measured as a Dask speed-up (the oscillator's
coefficients are closed-form now; no BLAS call remains on the hot path).

    python benchmarks/suite.py                       # FEMA P695 far-field, --site 1.5,0.9
    python benchmarks/suite.py --enlarge 440 --procedures priestley1978,fema356,ntc2018
    python benchmarks/suite.py --records ../shared/records/seed-suite.toml \\
        --records ../shared/records/extras.toml --repeat 2

The default suite ``p695-far-field`` (44 components) needs the FEMA P695 suites; where the
records package does not provide it, the benchmark says so and uses the seed and extra records.
``--enlarge N`` stands in for a database no one ships: every component at several scale factors
(geometric, 0.5–2) and both polarities, N records in all, each a distinct motion.
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

#: The shared records folder: that of $ROCKING_AUDIT_RECORDS, else ../shared/records.
SHARED = Path(os.environ.get("ROCKING_AUDIT_RECORDS") or Path(__file__).resolve().parents[2]
              / "shared" / "records" / "seed-suite.toml").parent
FALLBACK = [str(SHARED / "seed-suite.toml"), str(SHARED / "extras.toml")]
NGA_WEST2_COMPONENTS = 21_000
#: Dask's nanny starts workers with these at 1; the local mode gets the same (--blas-threads).
BLAS_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
MODES = ("local", "dask", "localcluster")


def load_suite(sources, site):
    """The records of every source in one suite, with the design site applied where possible."""
    from audit.errors import InputError
    from records import RecordSuite, load_records
    suites = []
    for source in sources:
        try:
            suites.append(load_records(source))
        except InputError as exc:
            if sources == FALLBACK:
                raise
            print(f"# {source}: not available here ({exc}); using {', '.join(FALLBACK)}",
                  file=sys.stderr)
            return load_suite(FALLBACK, site)
    entries = tuple(entry for suite in suites for entry in suite if not entry.missing)
    suite = RecordSuite(entries, " + ".join(s.description for s in suites))
    if site:
        try:
            from audit.engine.shared.sites import with_design_site
        except ImportError:
            print("# --site: this records package cannot set a design site; records keep their own",
                  file=sys.stderr)
        else:
            suite = with_design_site(suite, *site)
    return suite


def enlarged(suite, size: int):
    """``size`` records from the suite's components, each at one of ⌈size / (2 × components)⌉
    scale factors (geometric, 0.5–2) in one of both polarities."""
    from dataclasses import replace

    from records import RecordSuite
    per_polarity = -(-size // (2 * len(suite)))
    factors = np.geomspace(0.5, 2.0, per_polarity) if per_polarity > 1 else np.array([1.0])
    entries = [replace(entry, id=f"{entry.id}@{sign * factor:+.3f}",
                       motion=entry.motion.scaled(sign * factor))
               for factor in factors for sign in (1, -1) for entry in suite]
    return RecordSuite(tuple(entries[:size]), f"{suite.description}, enlarged to {size} "
                       f"records ({per_polarity} scale factors × 2 polarities)")


def max_rss_kb() -> int:
    """Peak resident memory of this process [kB] (Linux ``ru_maxrss``)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def measure(mode, sources, site, workers, size, procedure_names):
    """One timed audit in this process (run as a child): a JSON line on stdout."""
    import tempfile

    from audit.api import Runtime
    from audit.api import run as run_api
    from audit.engine.shared.heap import return_freed_memory_promptly
    from audit.engine.run.record_audit import audit_record
    from audit.engine.run.settings import AuditSettings
    from procedures import get_procedures
    return_freed_memory_promptly()  # as a run does, before this benchmark's cluster threads start
    suite = load_suite(sources, site)
    if size:
        suite = enlarged(suite, size)
    procedures = [procedure for name in procedure_names.split(",")
                  for procedure in get_procedures(name.strip())]
    warm = AuditSettings(alpha_deg=(15.0,), size_s=(2.0,))
    audit_record(suite.entries[0], procedures, warm)   # compiled solver loaded before timing
    seconds, worker_rss = {}, []

    def progress(done, total, record_id, how):
        seconds[record_id] = float(how.split()[-2])
        print(f"#   [{done}/{total}] {record_id}: {how}", file=sys.stderr, flush=True)

    out_dir = Path(tempfile.mkdtemp(prefix="suite-benchmark-")) / "out"
    start = time.perf_counter()
    cluster_start, scheduler_rss = 0.0, None
    if mode in ("local", "localcluster"):
        summary = run_api(procedures, suite, out_dir=out_dir, runtime=Runtime(
            jobs=workers, progress=progress,
            scheduler="local" if mode == "local" else "dask")).summary
        wall = time.perf_counter() - start
    else:
        import logging

        from distributed import Client
        from distributed.deploy.subprocess import SubprocessCluster
        with SubprocessCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None,
                               silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
            client.wait_for_workers(workers)
            client.run(audit_record, suite.entries[0], procedures, warm)
            cluster_start = time.perf_counter() - start
            start = time.perf_counter()
            summary = run_api(procedures, suite, out_dir=out_dir, runtime=Runtime(
                jobs=workers, progress=progress, scheduler=cluster.scheduler_address)).summary
            wall = time.perf_counter() - start
            worker_rss = list(client.run(max_rss_kb).values())
            scheduler_rss = client.run_on_scheduler(max_rss_kb)
    part = audit_record(suite.entries[0], procedures, AuditSettings())
    blocks = (sum(not item["missing"] for item in summary["records"])
              * len(summary["grid"]["alpha_deg"]) * len(summary["grid"]["size_s"]))
    files_mb = sum(path.stat().st_size for path in out_dir.iterdir()) / 2**20
    shutil.rmtree(out_dir.parent)
    print(json.dumps({
        "mode": mode, "suite": suite.description, "records": len(suite), "blocks": blocks,
        "procedures": [p.name for p in procedures],
        "wall_s": wall, "cluster_start_s": cluster_start, "record_s": seconds,
        "self_maxrss_mb": max_rss_kb() / 1024,
        "worker_maxrss_mb": [rss / 1024 for rss in worker_rss],
        "scheduler_maxrss_mb": scheduler_rss and scheduler_rss / 1024,
        "record_result_mb": len(pickle.dumps(part)) / 2**20, "files_mb": files_mb,
        "duration_s": statistics.mean(e.motion.duration for e in suite),
    }), flush=True)


def child(mode, args):
    command = [sys.executable, __file__, "--child", mode, "--workers", str(args.workers),
               "--enlarge", str(args.enlarge), "--procedures", args.procedures]
    command += [item for source in args.records for item in ("--records", source)]
    command += ["--site", args.site] if args.site else []
    blas = {name: str(args.blas_threads) for name in BLAS_VARIABLES} if args.blas_threads else {}
    done = subprocess.run(command, capture_output=True, text=True, env={**os.environ, **blas})
    if done.returncode:
        sys.exit(f"{mode} run failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", action="append", metavar="SUITE",
                        help="suite name or path, repeatable (default p695-far-field)")
    parser.add_argument("--site", default="1.5,0.9", metavar="SXS,SX1",
                        help="FEMA 356 design site [g] ('' for none; default 1.5,0.9)")
    parser.add_argument("--workers", type=int, default=2, help="threads / Dask workers")
    parser.add_argument("--repeat", type=int, default=1, help="runs of each mode (medians)")
    parser.add_argument("--blas-threads", type=int, default=1,
                        help="BLAS threads of both modes, as Dask workers have (0: leave unset)")
    parser.add_argument("--enlarge", type=int, default=0, metavar="N",
                        help="audit N records made of the suite's components scaled and "
                             "reversed (0: the suite as it is)")
    parser.add_argument("--procedures", default="all", help="procedures audited ('all' or "
                                                             "names, comma-separated)")
    parser.add_argument("--modes", default="local,dask",
                        help="comma-separated, of local, dask, localcluster (default local,dask)")
    parser.add_argument("--child", choices=MODES, help=argparse.SUPPRESS)
    args = parser.parse_args()
    args.records = args.records or ["p695-far-field"]
    site = [float(v) for v in args.site.split(",")] if args.site else None
    if args.child:
        return measure(args.child, args.records, site, args.workers, args.enlarge,
                       args.procedures)

    runs = {mode: [] for mode in args.modes.split(",")}
    for _ in range(args.repeat):
        for mode in runs:       # side by side, alternating
            runs[mode].append(child(mode, args))
    first = next(iter(runs.values()))[0]
    print(f"suite: {first['suite']}")
    print(f"{first['records']} records (mean length {first['duration_s']:.1f} s), "
          f"{first['blocks']} exact blocks, {', '.join(first['procedures'])}, "
          f"{args.workers} workers/threads, {args.repeat} run(s) each, medians, "
          f"BLAS threads {args.blas_threads or 'unset'}")
    print(f"{'mode':<12} {'wall s':>8} {'s/record':>9} {'ms/block':>9} {'core-s/rec':>11} "
          f"{'driver MB':>10} {'workers MB':>14} {'scheduler MB':>13}")
    per_record_cost = {}
    for mode, items in runs.items():
        wall = statistics.median(item["wall_s"] for item in items)
        cost = statistics.median(s for item in items for s in item["record_s"].values())
        per_record_cost[mode] = cost
        workers = ", ".join(f"{rss:.0f}" for rss in items[-1]["worker_maxrss_mb"]) or "-"
        scheduler = items[-1]["scheduler_maxrss_mb"]
        scheduler = f"{scheduler:.0f}" if scheduler else "in driver" if mode != "local" else "-"
        print(f"{mode:<12} {wall:8.1f} {wall / first['records']:9.2f} "
              f"{1000 * wall / first['blocks']:9.2f} {cost:11.2f} "
              f"{max(i['self_maxrss_mb'] for i in items):10.0f} {workers:>14} {scheduler:>13}")
    if runs.get("dask"):
        print(f"dask cluster start-up "
              f"{statistics.median(i['cluster_start_s'] for i in runs['dask']):.1f} s (not in the "
              "wall time)")
    print(f"a record's results pickled: {first['record_result_mb']:.2f} MB; the run's files "
          f"(CSV, JSON, report): {first['files_mb']:.0f} MB")
    # one record on one single-threaded worker (or one core of the local run)
    cost = next(per_record_cost[mode] for mode in ("dask", "localcluster", "local")
                if mode in per_record_cost)
    print(f"\nprojection, {NGA_WEST2_COMPONENTS} NGA-West2 components at the default grid, "
          f"{cost:.1f} core-s per record (records of ~{first['duration_s']:.0f} s):")
    for workers in (2, 16, 64, 256, 1024):
        minutes = NGA_WEST2_COMPONENTS * cost / workers / 60
        print(f"  {workers:5d} Dask workers: {minutes:8.1f} min ({minutes / 60:.2f} h)")
    print(f"  disk for every record's stored part while the run goes: "
          f"~{NGA_WEST2_COMPONENTS * first['record_result_mb'] / 1024:.0f} GB; the driver "
          "writes the files record by record (see the maxrss column across suite sizes)")


if __name__ == "__main__":
    main()
