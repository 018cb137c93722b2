"""``python -m audit rock``: exact rocking response of one block."""

from __future__ import annotations

import io
import json
import math
import sys

from audit.cli import options
from audit.engine.defaults import DEFAULT_FREE_MOTION_S
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
    p.add_argument("--duration", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help=f"free motion simulated after the excitation [s] (default "
                                     f"{DEFAULT_FREE_MOTION_S:g})")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw θ/α and θ' against time")
    p.add_argument("--history", metavar="FILE.csv",
                   help="write time_s, theta_rad, theta_dot_rad_s, ground_acc_g at every solver "
                        "output point (sampling grid, turning points, both sides of each impact)")
    options.add_force_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.physics.block import RigidBlock
    from audit.physics.rocking import simulate
    plot = options.output_file(args.plot, "--plot")
    history = options.output_file(args.history, "--history")
    if args.r is not None and args.restitution != "housner":
        raise InputError("give the impact model once: --r or --restitution, not both")
    r = args.r if args.r is not None else options.restitution(args)
    named = None
    if args.block is not None:
        from audit.engine.blocks import parse_blocks
        if args.p is not None or args.size is not None or args.alpha is not None:
            raise InputError("--block: give the block once, by its dimensions or by --p/--size "
                             "and --alpha")
        blocks = parse_blocks([args.block])
        if len(blocks) != 1:
            raise InputError(f"--block: rock takes one block, got '{args.block}'")
        named = blocks[0]
        block = RigidBlock.from_dimensions(named.width_m / 2, named.height_m / 2, r)
        args.alpha = math.degrees(block.alpha)
    else:
        if (args.p is None) == (args.size is None):
            raise InputError("give the block size: exactly one of --p RAD_PER_S or --size "
                             "SECONDS (or the block by --block WIDTHxHEIGHT)")
        if args.alpha is None:
            raise InputError("give the slenderness: --alpha DEG (or the block by --block "
                             "WIDTHxHEIGHT)")
        alpha = math.radians(args.alpha)
        block = (RigidBlock(args.p, alpha, r) if args.p is not None
                 else RigidBlock.from_size(args.size, alpha, r))
    motion = options.vertical_motion(options.motion(args), args.vertical)
    options.check_cost(args, [motion], args.duration, blocks=1, free_motion_option="--duration")
    response = simulate(block, motion, free_motion_s=args.duration, vertical=args.vertical)
    from audit.engine.ground_truth import slides
    friction = response.required_friction
    sliding = None if args.friction is None else bool(slides(friction, args.friction))
    result = {
        "record": motion.id, "p": block.p, "size_s": block.size_s, "alpha_deg": args.alpha,
        "r": block.r, "restitution": f"{r:g}" if args.r is not None else str(r),
        "R_m": block.radius, "block_m": named.label if named else None,
        "overturned": response.overturned,
        "overturn_time": None if math.isnan(response.overturn_time) else response.overturn_time,
        "peak_rotation": response.peak_rotation,
        "peak_rotation_ratio": response.peak_rotation_ratio,
        "peak_rotation_after_excitation": response.peak_rotation_after_excitation,
        "peak_rotation_free_vibration": None if math.isnan(response.peak_rotation_free_vibration)
        else response.peak_rotation_free_vibration,
        "peak_angular_velocity": response.peak_angular_velocity,
        "impacts": response.n_impacts,
        "cycle_durations": response.cycle_durations.tolist(),
        "uplifted": response.uplifted,
        "required_friction": None if math.isinf(friction) else friction,
        "jumps": response.jumps, "friction": args.friction, "slides": sliding,
        "vertical": args.vertical,
    }
    outputs = {}
    if history:
        outputs[history] = history_csv(response, motion)
    if plot:
        from reports.figures import draw_time_histories
        outputs[plot] = options.figure_png(lambda fig: draw_time_histories(fig, [{
            "time": response.time, "theta_ratio": response.theta / block.alpha,
            "omega": response.omega,
            "title": f"{motion.id}: 2π/p = {block.size_s:.3g} s, α = {args.alpha:g}°",
            "rocking_span": (response.impact_times[0], response.impact_times[-1])
            if response.n_impacts else None,
            "cycle_starts": response.cycle_starts, "cycle_durations": response.cycle_durations,
            "excitation_end": motion.duration}]), height=3.9)
    from audit.files import write_atomically
    write_atomically(outputs)  # all or nothing
    if history:
        print(f"History written to {args.history}", file=sys.stderr)
    if args.json:
        print(json.dumps(result))
        return 0
    state = (f"OVERTURNS at t = {response.overturn_time:.3f} s" if response.overturned
             else "survives" if response.uplifted else "does not uplift (PGA ≤ g tan α)")
    source = "" if motion.source in ("", "analytic pulse") else f" — {motion.source}"
    # after overturning there is no "after the excitation"
    after = ("n/a" if response.overturned
             else f"{response.peak_rotation_after_excitation / block.alpha:.4f} α")
    free = ("n/a" if math.isnan(response.peak_rotation_free_vibration)
            else f"{response.peak_rotation_free_vibration / block.alpha:.4f} α (largest turning point)")
    cycles = ", ".join(f"{d:.3f}" for d in response.cycle_durations[:8]) or "—"
    more = " …" if response.cycle_durations.size > 8 else ""
    print((f"Block {named.label} m (width × height): " if named else "Block ")
          + f"p = {block.p:.4g} rad/s (2π/p = {block.size_s:.4g} s, R = {block.radius:.3g} m), "
          f"α = {args.alpha:g}°, r = {block.r:.4f}\n"
          f"Excitation: {motion.id}: {motion.component}{source}\n"
          f"Result: {state}\n"
          f"  peak |θ|                   {response.peak_rotation:.6g} rad = "
          f"{response.peak_rotation_ratio:.4f} α\n"
          f"  peak |θ| after excitation  {after}\n"
          f"  free-vibration peak |θ|    {free}\n"
          f"  peak |θ'|                  {response.peak_angular_velocity:.6g} rad/s\n"
          f"  impacts                    {response.n_impacts}\n"
          f"  full rocking cycles [s]    {cycles}{more}\n"
          f"  required friction |H|/V    "
          f"{'n/a (jumps: V < 0)' if response.jumps else f'{friction:.4f}'} (tan α = {math.tan(block.alpha):.4f})"
          + ("" if sliding is None else f"\n  {'with μ = ' + format(args.friction, 'g'):<27}"
             f"{'SLIDES: pure rocking does not apply' if sliding else 'rocks without sliding'}"))
    if args.plot:
        print(f"Plot written to {args.plot}")
    return 0


def history_csv(response, motion) -> bytes:
    """The response at every solver output point as CSV bytes.

    Columns ``time_s, theta_rad, theta_dot_rad_s, ground_acc_g``; an impact appears twice at
    its time (θ' before, then after); nothing after overturning.
    """
    import numpy as np

    from audit import G
    time, theta, omega = response.history()
    table = np.column_stack((time, theta, omega, motion.acceleration_at(time) / G))
    text = io.StringIO()
    np.savetxt(text, table, fmt="%.10g", delimiter=",", comments="",
               header="time_s,theta_rad,theta_dot_rad_s,ground_acc_g")
    return text.getvalue().encode()
