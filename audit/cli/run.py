"""``python -m audit run``: the audit."""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path

from audit.cli import options
from audit.errors import InputError

DEFAULT_OUT = "audit-out"


def add_parser(sub):
    p = sub.add_parser("run", help="audit a procedure (or all) and write the HTML report")
    p.add_argument("procedure", help="registered procedure name, or 'all'")
    options.add_records_option(p)
    p.add_argument("--alpha", default="10,15,20", metavar="DEG,...", help="slendernesses [degrees]")
    p.add_argument("--sizes", default="0.5:8:0.05", metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s]")
    p.add_argument("--out", metavar="DIR", help=f"output directory (default {DEFAULT_OUT}/PROCEDURE)")
    p.add_argument("--jobs", type=int, default=2,
                   help="threads for the exact solver and processes drawing the report (default 2)")
    p.add_argument("--free-motion", type=float, default=10.0, metavar="S",
                   help="free motion after each record [s] (default 10)")
    p.add_argument("--agree-band", type=float, default=0.10, metavar="FRACTION",
                   help="verdict 'agrees' when both survive and |approx/exact − 1| ≤ FRACTION "
                        "(default 0.10)")
    p.add_argument("--robustness", type=float, default=0.03, metavar="EPSILON",
                   help="flag blocks whose exact overturning changes with the record scaled by "
                        "1 ± EPSILON (default 0.03; 0 turns it off)")
    p.add_argument("--scheduler", default="local", metavar="local|dask|tcp://HOST:PORT",
                   help="where records are audited: this process (default), a Dask LocalCluster "
                        "of --jobs worker processes, or an existing Dask cluster")
    p.add_argument("--resume", action="store_true",
                   help="reuse the per-record results that an interrupted run left in OUT/.partial")
    p.add_argument("--detail", metavar="ID,...", help="records whose detail the report shows")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.engine.partial import PARTIAL_DIR
    from audit.engine.results import REPORT_HTML, save_run
    from audit.engine.runner import run_audit
    from audit.engine.scheduler import check_scheduler
    from procedures import get_procedures
    from reports import render_report
    procedures = get_procedures(args.procedure)
    suite = options.suite(args)
    sizes = options.sizes(args.sizes)
    alphas = options.alphas_deg(args.alpha)
    out_dir = Path(args.out) if args.out else Path(DEFAULT_OUT) / args.procedure
    start = time.perf_counter()
    if not (0 <= args.agree_band < 1):
        raise InputError(f"--agree-band: must lie in [0, 1), got {args.agree_band:g}")
    if not (0 <= args.robustness < 0.5):
        raise InputError(f"--robustness: must lie in [0, 0.5), got {args.robustness:g}")
    detail = [item.strip() for item in (args.detail or "").split(",") if item.strip()]
    try:
        run = run_audit(procedures, suite, alphas, sizes, jobs=args.jobs,
                        free_motion_s=args.free_motion, progress=_progress_line,
                        agree_band=args.agree_band, robustness=args.robustness,
                        scheduler=check_scheduler(args.scheduler),
                        partial_dir=out_dir / PARTIAL_DIR, resume=args.resume, detail=detail)
    except KeyboardInterrupt:
        print(f"interrupted: the records done are kept in {out_dir / PARTIAL_DIR}; "
              "the same command with --resume completes the run", file=sys.stderr)
        return 130
    computed = time.perf_counter() - start
    save_run(run, out_dir, lambda saved: render_report(saved, processes=args.jobs))
    shutil.rmtree(out_dir / PARTIAL_DIR, ignore_errors=True)
    total = time.perf_counter() - start
    print(f"Audited {', '.join(p.name for p in procedures)} on {suite.description} "
          f"in {run.summary['scheduler']}"
          + (f"; reused {len(run.summary['resumed'])} records of an interrupted run"
             if run.summary["resumed"] else ""))
    for item in run.summary["unauditable"]:
        print(f"  not audited: {item['procedure']} × {item['record']}: {item['reason']}")
    counts = run.results["verdict"].value_counts()
    print("Verdicts: " + ", ".join(f"{v} {n}" for v, n in counts.items()))
    print(f"Wrote {out_dir / REPORT_HTML} and results.csv, summary.json "
          f"({computed:.1f} s computing, {total:.1f} s in all)")
    return 0


def _progress_line(done: int, total: int, record_id: str, how: str) -> None:
    """One line on stderr per completed record."""
    print(f"[{done}/{total}] {record_id}: {how}", file=sys.stderr, flush=True)
