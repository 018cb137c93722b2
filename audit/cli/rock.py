"""``python -m audit rock``: exact rocking response of one block."""

from __future__ import annotations

import json
import math
import sys

from audit.cli import options, outputs
from audit.api import DEFAULT_FREE_MOTION_S, DEFAULT_RESTITUTION
from audit.errors import InputError


def add_parser(sub):
    p = sub.add_parser("rock", help="exact rocking response of one block")
    p.add_argument("--p", type=options.POSITIVE, metavar="RAD_PER_S",
                   help="frequency parameter p [rad/s]")
    p.add_argument("--size", type=options.POSITIVE, metavar="SECONDS", help="block size 2π/p [s]")
    p.add_argument("--alpha", type=options.number("must lie between 0 and 45 degrees", 0, 45,
                                                      low_open=True, high_open=True),
                   metavar="DEG", help="slenderness α [degrees]")
    p.add_argument("--block", metavar="WIDTHxHEIGHT",
                   help="the block by its full width × full height [m], e.g. 0.8x2.0, instead "
                        "of --p/--size and --alpha")
    p.add_argument("--r", type=options.number("must lie between 0 and 1", 0, 1),
                   help="coefficient of restitution (same as --restitution VALUE)")
    options.add_restitution_option(p)
    options.add_excitation_options(p)
    options.add_vertical_option(p)
    p.add_argument("--friction", type=options.POSITIVE, metavar="MU",
                   help="friction coefficient μ: mark the block as sliding when its pure-rocking "
                        "response needs more")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help=f"free motion simulated after the excitation [s] (default "
                                     f"{DEFAULT_FREE_MOTION_S:g})")
    options.add_alias(p, "--duration", "free_motion", options.NON_NEGATIVE)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw θ/α and θ' against time")
    p.add_argument("--history", metavar="FILE.csv",
                   help="write time_s, theta_rad, theta_dot_rad_s, ground_acc_g at every solver "
                        "output point (sampling grid, turning points, both sides of each impact)")
    options.add_floor_options(p)
    options.add_force_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    import audit.api as api
    paths = outputs.checked(files={"--plot": args.plot, "--history": args.history},
                            inputs={"--record": args.record, "--records": args.records})
    plot, history = paths["--plot"], paths["--history"]
    if args.r is not None and args.restitution != DEFAULT_RESTITUTION:
        raise InputError("give the impact model once: --r or --restitution, not both")
    restitution = args.r if args.r is not None else args.restitution
    if args.block is not None:
        if args.p is not None or args.size is not None or args.alpha is not None:
            raise InputError("--block: give the block once, by its dimensions or by --p/--size "
                             "and --alpha")
        block = api.Block.parse(args.block)
    else:
        if (args.p is None) == (args.size is None):
            raise InputError("give the block size: exactly one of --p RAD_PER_S or --size "
                             "SECONDS (or the block by --block WIDTHxHEIGHT)")
        if args.alpha is None:
            raise InputError("give the slenderness: --alpha DEG (or the block by --block "
                             "WIDTHxHEIGHT)")
        block = api.Block(alpha_deg=args.alpha,
                          size_s=args.size if args.size is not None else 2 * math.pi / args.p)
        # a size beyond the records is refused naming the flag typed (not --block)
        block = api.within_limits(block, f"--size {args.size:g}" if args.size is not None
                                  else f"--p {args.p:g}")
    response = api.rock(block, **options.motion(args),
                        solver=api.Solver(restitution, args.free_motion, vertical=args.vertical),
                        friction=args.friction, floor=options.floor(args),
                        runtime=api.Runtime(force=args.force))
    result = {**response.as_dict(),
              "width_m": block.width_m, "height_m": block.height_m,
              "vertical": args.vertical}
    files = {}
    if history:
        files[history] = response.history_csv()
    if plot:
        from audit.api import png_bytes
        files[plot] = png_bytes(response.plot(height_in=3.9))
    from audit.files import write_atomically
    write_atomically(files)  # all or nothing
    if history:
        print(f"History written to {args.history}", file=sys.stderr)
    if args.json:
        print(json.dumps(result))
        return 0
    print(response.summary_text(show_dimensions=args.block is not None), end="")
    if args.plot:
        print(f"Plot written to {args.plot}")
    return 0
