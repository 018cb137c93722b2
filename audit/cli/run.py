"""``python -m audit run``: the audit."""

from __future__ import annotations

import time
from pathlib import Path

from audit.cli import options
from audit.errors import InputError

DEFAULT_OUT = "audit-out"


def _registered() -> str:
    """Names of the registered procedures, read from the entry points without loading them."""
    from importlib.metadata import entry_points
    return ", ".join(sorted(ep.name for ep in entry_points(group="rocking_audit.procedures")))


def add_parser(sub):
    import argparse

    class Defaults(argparse.ArgumentDefaultsHelpFormatter):
        """Shows each option's default, where it has one."""

        def _get_help_string(self, action):
            return action.help if action.default is None else super()._get_help_string(action)

    p = sub.add_parser("run", help="audit a procedure (or all) and write the HTML report",
                       formatter_class=Defaults,
                       description="Audit guideline procedures against the exact rocking "
                                   "response; writes report.html, results.csv, summary.json "
                                   "and the other files described in columns.json.")
    p.add_argument("procedure", help=f"registered procedure name ({_registered()}), or 'all'")
    options.add_records_option(p)
    p.add_argument("--alpha", default="10,15,20", metavar="DEG,...", help="slendernesses [degrees]")
    p.add_argument("--sizes", default="0.5:8:0.05", metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s]")
    p.add_argument("--out", metavar="DIR", help=f"output directory (default {DEFAULT_OUT}/PROCEDURE)")
    p.add_argument("--jobs", type=int, default=2, help="threads for the exact solver")
    p.add_argument("--free-motion", type=float, default=10.0, metavar="S",
                   help="free motion after each record [s]")
    p.add_argument("--agree-band", type=float, default=0.10, metavar="FRACTION",
                   help="verdict 'agrees' when both survive and |approx/exact − 1| ≤ FRACTION")
    p.add_argument("--robustness", type=float, default=0.03, metavar="EPSILON",
                   help="flag blocks whose exact overturning changes with the record scaled by "
                        "1 ± EPSILON (0 turns it off)")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.engine.progress import Progress
    from audit.engine.results import REPORT_HTML, save_run
    from audit.engine.runner import run_audit
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
    if out_dir.exists() and not out_dir.is_dir():  # fail before the computing, not after it
        raise InputError(f"--out {out_dir}: exists and is not a directory")
    progress = Progress(len(suite), "record")
    progress.stage(f"auditing {', '.join(p.name for p in procedures)} on {len(suite)} records")
    run = run_audit(procedures, suite, alphas, sizes, jobs=args.jobs,
                    free_motion_s=args.free_motion, progress=progress,
                    agree_band=args.agree_band, robustness=args.robustness)
    computed = time.perf_counter() - start
    progress.stage(f"writing the results and the report to {out_dir}")
    save_run(run, out_dir, render_report)
    total = time.perf_counter() - start
    print(f"Audited {', '.join(p.name for p in procedures)} on {suite.description}")
    for item in run.summary["unauditable"]:
        print(f"  not audited: {item['procedure']} × {item['record']}: {item['reason']}")
    counts = run.results["verdict"].value_counts()
    print("Verdicts: " + ", ".join(f"{v} {n}" for v, n in counts.items()))
    print(f"Wrote {out_dir / REPORT_HTML} and results.csv, summary.json "
          f"({computed:.1f} s computing, {total:.1f} s in all)")
    return 0
