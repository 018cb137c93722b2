"""``python -m audit report``: re-rendering a saved run's report."""

from __future__ import annotations

import sys
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
    from audit.api import REPORT_HTML, load_result
    result = load_result(args.results_dir)
    print(f"note: read the results in {args.results_dir}; rendering the report of "
          f"{len(result.summary['records'])} records, {result.blocks} blocks", file=sys.stderr)
    path = result.report(Path(args.results_dir) / REPORT_HTML)
    print(f"note: wrote {path} ({path.stat().st_size / 1e6:.1f} MB)", file=sys.stderr)
    return 0
