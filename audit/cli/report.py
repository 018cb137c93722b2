"""``python -m audit report``: re-rendering a saved run's report."""

from __future__ import annotations

from pathlib import Path



def add_parser(sub):
    p = sub.add_parser("report", help="re-render report.html from a run's saved results")
    p.add_argument("results_dir", metavar="RESULTS_DIR")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.engine.results import REPORT_HTML, load_run, write_files_atomically
    from reports import render_report
    run = load_run(args.results_dir)
    write_files_atomically(Path(args.results_dir), {REPORT_HTML: render_report(run).encode()})
    print(f"Wrote {Path(args.results_dir) / REPORT_HTML}")
    return 0
