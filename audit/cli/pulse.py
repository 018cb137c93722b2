"""``python -m audit pulse``: the velocity pulse of each record of a suite."""

from __future__ import annotations

import sys

from audit.cli import options, outputs


def add_parser(sub):
    p = sub.add_parser(
        "pulse", help="velocity pulse of each record (Shahi & Baker 2014) and its "
                      "Mavroeidis-Papageorgiou fit",
        description="Classifies each record of the suite as pulse-like or not with Shahi & "
                    "Baker's (2014) algorithm (the record's two horizontal components where the "
                    "suite has both, e.g. the FEMA P695 sets; else its one component), and "
                    "fits a Mavroeidis & Papageorgiou (2003) pulse to the extracted pulse. "
                    "One CSV row per record. Results are cached in the user cache folder.")
    options.add_records_option(p)
    options.add_skip_bad_records_option(p)
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="each record's velocity with the extracted pulse and the fit over it")
    p.set_defaults(func=run)


def run(args) -> int:
    import audit.api as api
    paths = outputs.checked(files={"--csv": args.csv, "--plot": args.plot},
                            inputs={"--records": args.records})
    csv, plot = paths["--csv"], paths["--plot"]
    frame, figure = api.record_pulses(options.records(args), plot=plot is not None)
    files = {}
    if plot is not None and figure is not None:
        files[plot] = api.png_bytes(figure)
    outputs.write_csv(frame, csv, files)
    if plot is not None:
        print(f"Plot written to {args.plot}" if figure is not None
              else "No record with a motion: no plot written", file=sys.stderr)
    return 0
