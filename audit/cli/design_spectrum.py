"""``python -m audit design-spectrum``: code design spectra."""

from __future__ import annotations

import sys

from audit.cli import options
from audit.errors import InputError


def add_parser(sub):
    p = sub.add_parser("design-spectrum", help="code design spectrum (FEMA 356, UBC 97)")
    p.add_argument("code", choices=("fema356", "ubc97"))
    p.add_argument("--sxs", type=float, metavar="G", help="FEMA 356 S_XS [g]")
    p.add_argument("--sx1", type=float, metavar="G", help="FEMA 356 S_X1 [g]")
    p.add_argument("--na", type=float, default=1.0, help="UBC 97 near-source factor N_a")
    p.add_argument("--nv", type=float, default=1.0, help="UBC 97 near-source factor N_v")
    p.add_argument("--damping", default="5", metavar="PCT,...", help="damping ratios [%%]")
    p.add_argument("--periods", default="0:8:0.02", metavar="START:STOP:STEP", help="periods [s]")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.physics.design_spectra import FEMA356Spectrum, UBC97Spectrum
    if args.code == "fema356":
        if args.sxs is None or args.sx1 is None:
            raise InputError("design-spectrum fema356 needs --sxs G and --sx1 G")
        spectrum = FEMA356Spectrum(args.sxs, args.sx1)
    else:
        spectrum = UBC97Spectrum(args.na, args.nv)
        print(f"UBC 97: seismic zone 4, soil profile S_D, N_a = {args.na:g}, N_v = {args.nv:g} "
              f"(C_a = {spectrum.ca:.3f}, C_v = {spectrum.cv:.3f})", file=sys.stderr)
    periods = options.time_grid(args.periods, "--periods", allow_zero=True)
    import pandas as pd
    frame = pd.concat([pd.DataFrame({
        "period_s": periods, "damping_pct": d,
        "sa_g": spectrum.acceleration(periods, d / 100.0),
        "sd_m": spectrum.displacement(periods, d / 100.0)})
        for d in options.float_list(args.damping, "--damping")])
    options.write_csv(frame, args.csv)
    return 0
