"""``python -m audit fragility``: a probabilistic procedure against the exact fragility."""

from __future__ import annotations

import sys

from audit.cli import options
from audit.api import DEFAULT_FRAGILITY_RECORDS, DEFAULT_PROBABILISTIC_PROCEDURE

#: The files fragility writes in its --out folder.
WRITES = ("fragility-*.csv", "fragility.html")


def add_parser(sub):
    p = sub.add_parser("fragility", help="audit a probabilistic procedure (femap58) against the "
                                         "exact overturning fragility by multiple PGV stripes",
                       description="Records default to the FEMA P695 far-field set "
                                   "(--records p695-far-field).")
    p.add_argument("--procedure", default=DEFAULT_PROBABILISTIC_PROCEDURE,
                   help="probabilistic procedure (see 'list')")
    options.add_records_option(p)
    options.add_skip_bad_records_option(p)
    options.add_floor_options(p)
    options.add_method_option(p, "pgv")
    p.add_argument("--out", required=True, metavar="DIR",
                   help="output folder: fragility-*.csv and fragility.html")
    p.add_argument("--pelicun", metavar="FILE",
                   help="also write the exact fragilities (median, beta in peak floor velocity) "
                        "in pelicun's FEMA P-58 damage library layout (CSV)")
    p.set_defaults(func=run, records=DEFAULT_FRAGILITY_RECORDS)
    return p


def run(args) -> int:
    from audit.api import FRAGILITY_HTML, fragility
    from audit.cli.outputs import checked
    from audit.files import write_file_atomically
    paths = checked(folders={"--out": (args.out, WRITES)}, files={"--pelicun": args.pelicun},
                    inputs={"--records": args.records})
    out_dir, pelicun = paths["--out"], paths["--pelicun"]
    result = fragility(args.procedure, options.records(args), progress=True,
                       floor=options.floor(args), method=args.method)
    pelicun_csv = result.pelicun_csv() if pelicun else None  # made before anything is written
    result.write(out_dir)
    if pelicun:
        write_file_atomically(pelicun, pelicun_csv)
    print(f"note: wrote {out_dir / FRAGILITY_HTML} and the fragility-*.csv files"
          + (f", and {pelicun} for pelicun" if pelicun else ""), file=sys.stderr)
    return 0
