"""``python -m audit fragility``: a probabilistic procedure against the exact fragility."""

from __future__ import annotations

import tempfile
from pathlib import Path

from audit.cli import options

#: Page of the audit, rendered from its saved CSV files.
FRAGILITY_HTML = "fragility.html"


def add_parser(sub):
    p = sub.add_parser("fragility", help="audit a probabilistic procedure (femap58) against the "
                                         "exact overturning fragility by multiple PGV stripes",
                       description="Records default to the FEMA P695 far-field set "
                                   "(--records p695-far-field).")
    p.add_argument("--procedure", default="femap58", help="probabilistic procedure (see 'list')")
    options.add_records_option(p)
    p.add_argument("--out", required=True, metavar="DIR",
                   help="output folder: fragility-*.csv and fragility.html")
    p.set_defaults(func=run, records="p695-far-field")
    return p


def run(args) -> int:
    from audit.engine.fragility_audit import audit_procedure
    from audit.engine.progress import Progress
    from audit.errors import InputError
    from audit.files import check_output_dir, write_files_atomically
    from procedures.registry import available_procedures
    from reports.fragility_page import render_fragility_page
    found = available_procedures(probabilistic=True)
    if args.procedure not in found:
        raise InputError(f"--procedure: unknown '{args.procedure}', available: "
                         f"{', '.join(found)}")
    out_dir = check_output_dir(Path(args.out))
    suite = options.suite(args)
    entries = [entry for entry in suite.entries if entry.motion is not None]
    if not entries:
        raise InputError(f"--records: '{args.records}' has no record with a motion")
    procedure = found[args.procedure]()
    progress = Progress(0, "step")
    progress.stage(f"{procedure.title}: exact overturning of its components under "
                   f"{len(entries)} records scaled to each PGV stripe")
    tables = audit_procedure(procedure, [e.id for e in entries], [e.motion for e in entries])
    files = {name: table.to_csv(index=False).encode() for name, table in tables.items()}
    # the page is drawn from the files as saved, then everything is written together
    with tempfile.TemporaryDirectory() as saved:
        write_files_atomically(saved, files)
        files[FRAGILITY_HTML] = render_fragility_page(
            saved, f"{procedure.title} against the exact fragility ({args.records})").encode()
    write_files_atomically(out_dir, files)
    progress.stage(f"wrote {out_dir / FRAGILITY_HTML} and the fragility-*.csv files")
    return 0
