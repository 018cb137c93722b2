"""``python -m audit margins``: the design-level audit (fragility and collapse margins)."""

from __future__ import annotations

import shutil
import sys

from audit.cli import options
from audit.api import (DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_JOBS,
                       DEFAULT_MARGINS_SIZES, DEFAULT_SITE_LEVEL, SITE_LEVELS,
                       alpha_text, sizes_text)
from audit.errors import InputError

DEFAULT_OUT = "audit-out/margins"
#: The files margins writes in its --out folder, and its parts' folder.
WRITES = ("margins.html", "stripes.csv", "fragility.csv", "capacity.csv", "required_alpha.csv",
          "scan.csv", "summary.json", "risk.csv", "risk_alpha.csv", "hazard.csv", ".partial")


def add_parser(sub):
    p = sub.add_parser(
        "margins", help="fragility and collapse margins of blocks sized by each guideline",
        formatter_class=options.HelpWithDefaults,
        description="Scale the suite's records to a set of intensity levels (stripes), count "
                    "how many overturn each block exactly, fit a lognormal fragility, and say "
                    "where each guideline draws its line: its overturning intensity, the exact "
                    "probability of overturning there, and the FEMA P695 collapse margin ratio. "
                    "Writes margins.html, stripes.csv, fragility.csv, capacity.csv, "
                    "required_alpha.csv, scan.csv and summary.json; with --hazard, each block's "
                    "annual rate of overturning at the site and the slenderness each size needs "
                    "for the risk target (risk.csv, risk_alpha.csv, hazard.csv).")
    p.add_argument("procedure", help="registered procedure name ({registered}), or 'all'")
    options.add_records_option(p)
    p.add_argument("--im", metavar="pga|pgv|sa:T",
                   help=f"intensity measure: PGA [g], PGV [m/s] or the 5 %%-damped "
                        f"pseudo-spectral acceleration ω²·S_d at T [g] (default: {DEFAULT_IM}, "
                        "or the --hazard file's IMT)")
    p.add_argument("--stripes", metavar="IM,...",
                   help="intensity levels (unit of --im); default the fixed lattice, 27 "
                        "levels 2^(k/4) from 0.0625 to 5.66 (whatever the site)")
    p.add_argument("--alpha", default=alpha_text(), metavar="DEG,...",
                   help="slendernesses [degrees]")
    p.add_argument("--size", default=sizes_text(DEFAULT_MARGINS_SIZES), metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s] (a comma list S,... too)")
    options.add_alias(p, "--sizes", "size")
    p.add_argument("--site", metavar="SXS,SX1",
                   help="FEMA 356 design site S_XS,S_X1 [g] of every record (the records' own "
                        "sites are replaced); its intensity is the CMR's denominator, taken as "
                        "the MCE's (FEMA P695) unless --level design")
    p.add_argument("--level", choices=tuple(SITE_LEVELS), default=DEFAULT_SITE_LEVEL,
                   help="hazard level of the --site values: mce (the CMR is over them) or "
                        "design (the CMR is over 1.5 × them, the MCE of ASCE 7)")
    options.add_scaling_options(p)
    options.add_floor_options(p)
    options.add_param_option(p)
    p.add_argument("--ntc-site", metavar="AG,F0,TC,SOIL,TOPO",
                   help="NTC 2018 site for every record (see 'run --help')")
    options.add_block_option(p)
    options.add_restitution_option(p)
    options.add_method_option(p, "sa:1.0")
    options.add_hazard_options(p)
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS,
                   help="solver threads, or worker processes with --scheduler dask")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help="free motion after each record [s]")
    p.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="output directory")
    options.add_scheduler_options(p)
    options.add_force_option(p)
    p.add_argument("--skip-bad-records", action="store_true",
                   help="audit the readable records and list the unreadable ones")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.api import PARTIAL_DIR, Hazard, Runtime, Solver, margins
    from audit.cli.outputs import checked
    out_dir = checked(folders={"--out": (args.out, WRITES)},
                      inputs={"--records": args.records, "--hazard": args.hazard})["--out"]
    out_dir_existed = out_dir.exists()
    values = {"alpha_deg": options.alphas_deg(args.alpha),
              "size_s": options.sizes(args.size, options.typed_flag(args, "size")),
              "blocks": args.block or ()}
    if not args.hazard and (args.site_location or args.hazard_imt):
        raise InputError(f"{'--site-location' if args.site_location else '--hazard-imt'}: read "
                         "on the --hazard file; no --hazard given")
    if args.stripes is not None:  # '' is refused, not taken for the default
        values["stripes"] = options.float_list(args.stripes, "--stripes")
    try:
        result = margins(args.procedure, options.records(args), im=args.im, params=args.param,
                         **values,
                         solver=Solver(args.restitution, free_motion_s=args.free_motion),
                         hazard=Hazard(args.hazard, imt=args.hazard_imt,
                                       location=args.site_location,
                                       risk_target=args.risk_target),
                         site=options.site(args), floor=options.floor(args),
                         runtime=Runtime(jobs=args.jobs, scheduler=args.scheduler,
                                         progress=True, force=args.force,
                                         partial_dir=out_dir / PARTIAL_DIR, resume=args.resume),
                         method=args.method)
    except KeyboardInterrupt:
        return options.interrupted(out_dir, out_dir_existed)
    result.write(out_dir)
    shutil.rmtree(out_dir / PARTIAL_DIR, ignore_errors=True)
    sys.stdout.write(result.summary_text())
    print(f"Wrote {out_dir / result.PAGE} and stripes.csv, fragility.csv, capacity.csv, "
          "required_alpha.csv, " + ("scan.csv, " if result.scan is not None else "")
          + "summary.json"
          + (", risk.csv, risk_alpha.csv, hazard.csv" if args.hazard else ""))
    return 0
