"""``python -m audit spectrum``: rocking spectra or oscillator response spectra."""

from __future__ import annotations

from audit.cli import options


def add_parser(sub):
    p = sub.add_parser("spectrum", help="rocking spectra (default) or oscillator response spectra")
    p.add_argument("--kind", choices=("rocking", "response"), default="rocking")
    options.add_excitation_options(p)
    p.add_argument("--alpha", default="10,15,20", metavar="DEG,...", help="slendernesses [degrees]")
    p.add_argument("--sizes", default="0.5:8:0.05", metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s] (rocking)")
    p.add_argument("--damping", default="5,10,15", metavar="PCT,...",
                   help="damping ratios [%%] (response)")
    p.add_argument("--periods", default="0.02:10:0.02", metavar="START:STOP:STEP",
                   help="oscillator periods [s] (response)")
    p.add_argument("--free-motion", type=float, metavar="S",
                   help="free motion after the record [s] (default: 10 for rocking, "
                        "0 for response spectra)")
    p.add_argument("--jobs", type=int, default=2, help="threads")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.add_argument("--plot", metavar="FILE.png", help="draw the spectra")
    p.set_defaults(func=run)


def run(args) -> int:
    import numpy as np
    motion = options.motion(args)
    if args.free_motion is None:
        args.free_motion = 10.0 if args.kind == "rocking" else 0.0
    if args.kind == "response":
        from audit.physics.oscillator import response_spectra
        damping = np.array(options.float_list(args.damping, "--damping")) / 100.0
        periods = options.time_grid(args.periods, "--periods", allow_zero=True)
        spectra = response_spectra(motion, periods, damping, args.free_motion)
        frame = spectra.to_frame()
        if args.plot:
            from reports.figures import draw_response_spectra
            options.plot_to(args.plot, lambda fig: draw_response_spectra(fig, frame, motion.id))
    else:
        from audit.physics.rocking import rocking_spectrum
        alphas = np.radians(options.alphas_deg(args.alpha))
        spectrum = rocking_spectrum(motion, options.sizes(args.sizes), alphas,
                                    free_motion_s=args.free_motion, jobs=args.jobs)
        frame = spectrum.to_frame()
        if args.plot:
            from reports.figures import draw_rocking_spectra
            options.plot_to(args.plot, lambda fig: draw_rocking_spectra(fig, frame, motion.id))
    options.write_csv(frame, args.csv)
    return 0
