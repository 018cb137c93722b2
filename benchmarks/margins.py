"""Benchmark of the design-level audit: the far-field set at S_XS = 1.5 g, S_X1 = 0.9 g scaled to
the site, 3 α × 31 sizes (0.5:8:0.25), default stripes, every procedure.

    python benchmarks/margins.py [--records p695-far-field] [--jobs 2] [--first N]

Prints the split of the audit as ``python -m audit margins`` runs it: the stripes with every
procedure evaluated at them, the required-α searches, FEMA P695's acceptance of the blocks each
guideline sizes, the fine amplitude scans, and the files with margins.html; the exact stripes
alone are timed once more on their own so that the guideline evaluation is the difference.
Target: the whole audit within 5 minutes on a 2-core machine.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit.api import MarginsResult, Site, design_suite  # noqa: E402
from audit.engine.design.margins import margins_tables  # noqa: E402
from audit.engine.design.scans import amplitude_scans  # noqa: E402
from audit.engine.design.settings import MarginsSettings  # noqa: E402
from audit.engine.design.p695_acceptance import p695_acceptance  # noqa: E402
from audit.engine.shared.runtime import Runtime  # noqa: E402
from audit.engine.design.required_alpha import required_alpha  # noqa: E402
from audit.files import write_files_atomically  # noqa: E402
from procedures import get_procedures  # noqa: E402
from records import load_records  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", default="p695-far-field")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--first", type=int, help="only the suite's first N records (a quicker "
                        "side-by-side of the stages on a loaded machine)")
    args = parser.parse_args()
    records = load_records(args.records)
    if args.first:
        records = replace(records, entries=records.entries[:args.first])
    suite = design_suite(records, site=Site(1.5, 0.9, override=True, scale_records=True))
    settings = MarginsSettings.parse(im="sa:1.0", alpha_deg=(10.0, 15.0, 20.0),
                                     size_s=np.arange(0.5, 8.001, 0.25))
    runtime = Runtime.parse(Runtime(jobs=args.jobs))
    procedures = get_procedures("all")
    timed = {}

    def timing(name, work):
        begin = time.perf_counter()
        value = work()
        timed[name] = time.perf_counter() - begin
        return value

    exact_only = timing("exact stripes alone", lambda: margins_tables(
        [], suite, settings, runtime))
    full = timing("stripes", lambda: margins_tables(procedures, suite, settings, runtime))
    full.required_alpha = timing("required α", lambda: required_alpha(
        procedures, suite, settings, runtime))
    full.acceptance, full.summary["acceptance"] = timing(
        "P695 acceptance", lambda: p695_acceptance(suite, settings, runtime, full.required_alpha))
    full.scan = timing("scans", lambda: amplitude_scans(full, suite, settings, runtime))
    with tempfile.TemporaryDirectory() as folder:
        timing("files and report", lambda: write_files_atomically(
            Path(folder) / "m", MarginsResult(full).files()))
    solves = len(exact_only.stripes)
    audit_s = sum(v for k, v in timed.items() if k != "exact stripes alone")
    print(f"{len(suite)} records × {len(full.summary['levels'])} stripes × "
          f"{len(settings.alpha_deg) * len(settings.size_s)} blocks = {solves} exact solves")
    print(f"exact stripes alone: {timed['exact stripes alone']:.1f} s "
          f"({solves / timed['exact stripes alone']:.0f} solves/s)")
    print(f"stripes with every procedure: {timed['stripes']:.1f} s (guideline evaluation "
          f"{timed['stripes'] - timed['exact stripes alone']:.1f} s); required α "
          f"{timed['required α']:.1f} s; P695 acceptance {timed['P695 acceptance']:.1f} s; "
          f"scans {timed['scans']:.1f} s; files and report "
          f"{timed['files and report']:.1f} s")
    print(f"the audit in all: {audit_s:.1f} s (target ≤ 300 s)")

if __name__ == "__main__":
    main()
