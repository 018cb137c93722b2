"""``python -m audit run``: the audit."""

from __future__ import annotations

import time
from pathlib import Path

from audit.cli import options

DEFAULT_OUT = "audit-out"


def add_parser(sub):
    p = sub.add_parser("run", help="audit a procedure (or all) and write the HTML report")
    p.add_argument("procedure", help="registered procedure name, or 'all'")
    options.add_records_option(p)
    p.add_argument("--alpha", default="10,15,20", metavar="DEG,...", help="slendernesses [degrees]")
    p.add_argument("--sizes", default="0.5:8:0.05", metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s]")
    p.add_argument("--out", metavar="DIR", help=f"output directory (default {DEFAULT_OUT}/PROCEDURE)")
    p.add_argument("--jobs", type=options.jobs, default=2,
                   help="threads for the exact solver and processes drawing the report (default 2)")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=10.0, metavar="S",
                   help="free motion after each record [s] (default 10)")
    options.add_force_option(p)
    p.add_argument("--skip-bad-records", action="store_true",
                   help="audit the readable records of a suite and list the unreadable ones "
                        "(default: stop at the first)")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.engine.progress import Progress
    from audit.engine.results import REPORT_HTML, save_run
    from audit.engine.runner import run_audit
    from procedures import get_procedures
    from reports import render_report
    from audit.engine.results import check_output_dir
    out_dir = check_output_dir(Path(args.out) if args.out else Path(DEFAULT_OUT) / args.procedure)
    procedures = get_procedures(args.procedure)
    sizes = options.sizes(args.sizes)
    alphas = options.alphas_deg(args.alpha)
    suite = options.suite(args)
    options.check_cost(args, [e.motion for e in suite if not e.missing], args.free_motion,
                       blocks=sizes.size * alphas.size,
                       oscillators=options.AUDIT_SPECTRA * (3 + alphas.size * len(procedures)))
    start = time.perf_counter()
    run = run_audit(procedures, suite, alphas, sizes, jobs=args.jobs,
                    free_motion_s=args.free_motion, progress=Progress(len(suite), "records"))
    computed = time.perf_counter() - start
    save_run(run, out_dir, lambda saved: render_report(saved, processes=args.jobs))
    total = time.perf_counter() - start
    print(f"Audited {', '.join(p.name for p in procedures)} on {suite.description}")
    for item in run.summary["unauditable"]:
        print(f"  not audited: {item['procedure']} × {item['record']}: {item['reason']}")
    counts = run.results["verdict"].value_counts()
    print("Verdicts: " + ", ".join(f"{v} {n}" for v, n in counts.items()))
    print(f"Wrote {out_dir / REPORT_HTML} and results.csv, summary.json "
          f"({computed:.1f} s computing, {total:.1f} s in all)")
    return 0
