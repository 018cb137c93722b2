"""``python -m audit spectrum``: rocking spectra or oscillator response spectra."""

from __future__ import annotations

import sys

from audit.cli import options, outputs
from audit.api import (DEFAULT_DAMPING_PCT, DEFAULT_FREE_MOTION_S, DEFAULT_JOBS,
                       DEFAULT_PERIODS, DEFAULT_RESPONSE_FREE_MOTION_S, alpha_text,
                       sizes_text)


def add_parser(sub):
    p = sub.add_parser("spectrum", help="rocking spectra (default) or oscillator response spectra")
    p.add_argument("--kind", choices=("rocking", "response"), default="rocking")
    options.add_excitation_options(p)
    p.add_argument("--alpha", default=alpha_text(), metavar="DEG,...",
                   help="slendernesses [degrees]")
    p.add_argument("--size", default=sizes_text(), metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s] (a comma list S,... too; rocking)")
    options.add_alias(p, "--sizes", "size")
    p.add_argument("--damping", default=",".join(f"{d:g}" for d in DEFAULT_DAMPING_PCT),
                   metavar="PCT,...",
                   help="damping ratios [%%] (response)")
    p.add_argument("--periods", default=sizes_text(DEFAULT_PERIODS), metavar="START:STOP:STEP",
                   help="oscillator periods [s] (response)")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, metavar="S",
                   help=f"free motion after the record [s] (default: "
                        f"{DEFAULT_FREE_MOTION_S:g} for rocking, 0 for response spectra)")
    options.add_restitution_option(p)
    options.add_vertical_option(p)
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS, help="threads")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.add_argument("--plot", metavar="FILE.png", help="draw the spectra")
    options.add_floor_options(p)
    options.add_force_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    import audit.api as api
    paths = outputs.checked(files={"--csv": args.csv, "--plot": args.plot},
                            inputs={"--record": args.record, "--records": args.records})
    csv, plot = paths["--csv"], paths["--plot"]
    if args.free_motion is None:
        args.free_motion = (DEFAULT_FREE_MOTION_S if args.kind == "rocking"
                            else DEFAULT_RESPONSE_FREE_MOTION_S)
    if args.kind == "response":
        damping = options.damping_pct(args.damping)
        periods = options.time_grid(args.periods, "--periods", allow_zero=True)
        frame = api.response_spectra(**options.motion(args), periods_s=periods,
                                     damping_pct=100.0 * damping, free_motion_s=args.free_motion,
                                     floor=options.floor(args),
                                     runtime=api.Runtime(force=args.force))
    else:
        alphas = options.alphas_deg(args.alpha)
        sizes = options.sizes(args.size, options.typed_flag(args, "size"))
        frame = api.rocking_spectrum(**options.motion(args), size_s=sizes, alpha_deg=alphas,
                                     solver=api.Solver(args.restitution, args.free_motion,
                                                       vertical=args.vertical),
                                     floor=options.floor(args),
                                     runtime=api.Runtime(args.jobs, force=args.force))
    if frame.attrs["floor"]["building_model"]:
        print(f"Spectra of the floor motion {frame.attrs['floor']['description']}",
              file=sys.stderr)
    figure = {}
    if plot:  # matplotlib is loaded only for a figure
        figure = {plot: api.png_bytes(api.spectra_figure(frame, args.kind,
                                                         frame.attrs.get("record", "")))}
    outputs.write_csv(frame, csv, figure)
    return 0
