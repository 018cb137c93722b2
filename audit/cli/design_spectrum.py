"""``python -m audit design-spectrum``: code design spectra."""

from __future__ import annotations

import sys

from audit.cli import options, outputs
from audit.api import DEFAULT_DESIGN_DAMPING_PCT, DEFAULT_DESIGN_PERIODS, sizes_text


def add_parser(sub):
    p = sub.add_parser("design-spectrum",
                       help="code design spectrum (FEMA 356, UBC 97, NTC 2018)")
    p.add_argument("code", choices=("fema356", "ubc97", "ntc2018"))
    p.add_argument("--sxs", type=options.POSITIVE, metavar="G", help="FEMA 356 S_XS [g]")
    p.add_argument("--sx1", type=options.POSITIVE, metavar="G", help="FEMA 356 S_X1 [g]")
    p.add_argument("--na", type=options.POSITIVE, default=1.0,
                   help="UBC 97 near-source factor N_a")
    p.add_argument("--nv", type=options.POSITIVE, default=1.0,
                   help="UBC 97 near-source factor N_v")
    p.add_argument("--ag", type=options.POSITIVE, metavar="G", help="NTC 2018 a_g on rock [g]")
    p.add_argument("--f0", type=options.POSITIVE, help="NTC 2018 amplification F0 [-]")
    p.add_argument("--tc-star", type=options.POSITIVE, metavar="S", help="NTC 2018 T_C* [s]")
    p.add_argument("--soil", default="A", choices=("A", "B", "C", "D", "E"),
                   help="NTC 2018 soil category (Tab. 3.2.IV)")
    p.add_argument("--topography", default="T1", choices=("T1", "T2", "T3", "T4"),
                   help="NTC 2018 topographic category (Tab. 3.2.V)")
    p.add_argument("--damping", default=",".join(f"{d:g}" for d in DEFAULT_DESIGN_DAMPING_PCT),
                   metavar="PCT,...", help="damping ratios [%%]")
    p.add_argument("--periods", default=sizes_text(DEFAULT_DESIGN_PERIODS),
                   metavar="START:STOP:STEP", help="periods [s]")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.api import Site, design_spectrum
    from audit.errors import InputError
    csv = outputs.checked(files={"--csv": args.csv})["--csv"]
    damping = options.damping_pct(args.damping)
    periods = options.time_grid(args.periods, "--periods", allow_zero=True)
    needs = {"fema356": ("--sxs", "--sx1"), "ntc2018": ("--ag", "--f0", "--tc-star"),
             "ubc97": ()}[args.code]
    absent = [flag for flag in needs if getattr(args, flag[2:].replace("-", "_")) is None]
    if absent:
        raise InputError(f"{', '.join(absent)}: {args.code} needs {', '.join(needs)}")
    site = {"fema356": lambda: Site(args.sxs, args.sx1),
            "ntc2018": lambda: Site(None, None, ntc=(args.ag, args.f0, args.tc_star, args.soil,
                                                     args.topography)),
            "ubc97": lambda: None}[args.code]()
    spectrum, columns = design_spectrum(args.code, periods, 100.0 * damping, site=site,
                                        near_source=(args.na, args.nv))
    if args.code == "ubc97":
        print(f"UBC 97: seismic zone 4, soil profile S_D, N_a = {args.na:g}, N_v = {args.nv:g} "
              f"(C_a = {spectrum.ca:.3f}, C_v = {spectrum.cv:.3f})", file=sys.stderr)
    outputs.write_csv(columns, csv)  # a dict of columns: no pandas for this command
    return 0
