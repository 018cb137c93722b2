"""``python -m audit design-spectrum``: code design spectra."""

from __future__ import annotations

import sys

from audit.cli import options
from audit.errors import InputError


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
    p.add_argument("--damping", default="5", metavar="PCT,...", help="damping ratios [%%]")
    p.add_argument("--periods", default="0:8:0.02", metavar="START:STOP:STEP", help="periods [s]")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.set_defaults(func=run)


def run(args) -> int:
    csv = options.output_file(args.csv, "--csv")
    damping = options.damping_pct(args.damping)
    periods = options.time_grid(args.periods, "--periods", allow_zero=True)
    from audit.physics.design_spectra import FEMA356Spectrum, NTC2018Spectrum, UBC97Spectrum
    if args.code == "fema356":
        if args.sxs is None or args.sx1 is None:
            raise InputError("design-spectrum fema356 needs --sxs G and --sx1 G")
        spectrum = FEMA356Spectrum(args.sxs, args.sx1)
    elif args.code == "ntc2018":
        if args.ag is None or args.f0 is None or args.tc_star is None:
            raise InputError("design-spectrum ntc2018 needs --ag G, --f0 F0 and --tc-star S")
        spectrum = NTC2018Spectrum(args.ag, args.f0, args.tc_star, args.soil, args.topography)
    else:
        spectrum = UBC97Spectrum(args.na, args.nv)
        print(f"UBC 97: seismic zone 4, soil profile S_D, N_a = {args.na:g}, N_v = {args.nv:g} "
              f"(C_a = {spectrum.ca:.3f}, C_v = {spectrum.cv:.3f})", file=sys.stderr)
    import numpy as np
    options.write_csv({  # a dict of columns: no pandas for this command
        "period_s": np.tile(periods, damping.size),
        "damping_pct": np.repeat(100.0 * damping, periods.size),
        "sa_g": np.concatenate([spectrum.acceleration(periods, d) for d in damping]),
        "sd_m": np.concatenate([spectrum.displacement(periods, d) for d in damping])}, csv)
    return 0
