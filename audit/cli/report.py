"""``python -m audit report``: re-rendering a saved run's report."""

from __future__ import annotations

from pathlib import Path


def add_parser(sub):
    p = sub.add_parser("report", help="re-render report.html from a run's saved results",
                       description="Re-render report.html from the files an 'audit run' saved, "
                                   "without recomputing.")
    p.add_argument("results_dir", metavar="RESULTS_DIR",
                   help="output directory of 'audit run' (its --out): holds results.csv, "
                        "summary.json, spectra.csv, histories.csv, …; report.html is rewritten "
                        "there")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.engine.progress import Progress
    from audit.engine.results import REPORT_HTML, load_run
    from audit.files import write_files_atomically
    from reports import render_report
    # bad input fails here, before anything is said; only the rows of the records the report
    # shows are read
    run = load_run(args.results_dir, shown=True)
    blocks = sum(line["blocks"] for line in run.summary["bottom_line"])
    progress = Progress(0, "step")
    progress.stage(f"read the results in {args.results_dir}; rendering the report of "
                   f"{len(run.summary['records'])} records, {blocks} blocks")
    html = render_report(run).encode()
    write_files_atomically(Path(args.results_dir), {REPORT_HTML: html})
    progress.stage(f"wrote {Path(args.results_dir) / REPORT_HTML} ({len(html) / 1e6:.1f} MB)")
    return 0
