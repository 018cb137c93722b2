"""``python -m audit spectrum``: rocking spectra or oscillator response spectra."""

from __future__ import annotations

from audit.cli import options
from audit.engine.defaults import DEFAULT_FREE_MOTION_S, DEFAULT_JOBS, alpha_text, sizes_text

#: Defaults of the response spectra: damping ratios [%] and oscillator periods [s].
DEFAULT_DAMPING_PCT = "5,10,15"
DEFAULT_PERIODS = "0.02:10:0.02"


def add_parser(sub):
    p = sub.add_parser("spectrum", help="rocking spectra (default) or oscillator response spectra")
    p.add_argument("--kind", choices=("rocking", "response"), default="rocking")
    options.add_excitation_options(p)
    p.add_argument("--alpha", default=alpha_text(), metavar="DEG,...",
                   help="slendernesses [degrees]")
    p.add_argument("--sizes", default=sizes_text(), metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s] (rocking)")
    p.add_argument("--damping", default=DEFAULT_DAMPING_PCT, metavar="PCT,...",
                   help="damping ratios [%%] (response)")
    p.add_argument("--periods", default=DEFAULT_PERIODS, metavar="START:STOP:STEP",
                   help="oscillator periods [s] (response)")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, metavar="S",
                   help=f"free motion after the record [s] (default: "
                        f"{DEFAULT_FREE_MOTION_S:g} for rocking, 0 for response spectra)")
    options.add_restitution_option(p)
    options.add_vertical_option(p)
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS, help="threads")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.add_argument("--plot", metavar="FILE.png", help="draw the spectra")
    options.add_force_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    import numpy as np
    csv = options.output_file(args.csv, "--csv")
    plot = options.output_file(args.plot, "--plot")
    if args.free_motion is None:
        args.free_motion = DEFAULT_FREE_MOTION_S if args.kind == "rocking" else 0.0
    if args.kind == "response":
        damping = options.damping_pct(args.damping)
        periods = options.time_grid(args.periods, "--periods", allow_zero=True)
        motion = options.motion(args)
        options.check_cost(args, [motion], args.free_motion,
                           oscillators=periods.size * damping.size, settings=(
                               ("--periods", periods.size,
                                options.values_in(DEFAULT_PERIODS, "--periods")),
                               ("--damping", damping.size,
                                options.values_in(DEFAULT_DAMPING_PCT, "--damping"))))
        from audit.physics.oscillator import response_spectra
        frame = response_spectra(motion, periods, damping, args.free_motion).to_frame()
        from reports.figures import draw_response_spectra as draw
    else:
        alphas = np.radians(options.alphas_deg(args.alpha))
        restitution = options.restitution(args)
        sizes = options.sizes(args.sizes)
        motion = options.vertical_motion(options.motion(args), args.vertical)
        options.check_cost(args, [motion], args.free_motion, blocks=sizes.size * alphas.size,
                           settings=options.grid_settings(sizes.size, alphas.size))
        from audit.physics.rocking import rocking_spectrum
        frame = rocking_spectrum(motion, sizes, alphas, restitution, free_motion_s=args.free_motion,
                                 jobs=args.jobs, vertical=args.vertical).to_frame()
        from reports.figures import draw_rocking_spectra as draw
    figure = ({plot: options.figure_png(lambda fig: draw(fig, frame, motion.id))}
              if plot else {})
    options.write_csv(frame, csv, figure)
    return 0
