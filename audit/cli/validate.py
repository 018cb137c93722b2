"""``python -m audit validate``: the equivalent rigid block of shake-table specimens, fitted to
their outcomes and cross-validated by ground motion (a shell over :func:`audit.api.validate`)."""

from __future__ import annotations


from audit.cli import options
from audit.api import DEFAULT_FREE_MOTION_S, DEFAULT_JOBS

DEFAULT_OUT = "audit-out/validation"
#: The files validate writes in its --out folder.
WRITES = ("predictions.csv", "validation-*.csv", "validation.html")


def add_parser(sub):
    p = sub.add_parser(
        "validate", help="fit and cross-validate the rocking model against a shake-table campaign",
        formatter_class=options.HelpWithDefaults,
        description="Fit each specimen's equivalent 2-D rigid block (α, p, restitution factor) "
                    "by maximum likelihood of its observed outcomes under the exact solver (a "
                    "coarse grid, then fine grids along the region the outcomes allow; "
                    "profile-likelihood intervals; the alpha-p ridge where they do not identify "
                    "a parameter), "
                    "cross-validate it by ground motion against PGA, PGV and (PGA, PGV/PGA) "
                    "baselines and any peer-model columns, and predict the tests without an "
                    "outcome with a band over the parameters. Writes predictions.csv, "
                    "validation-fits.csv, validation-scores.csv, validation-tests.csv, "
                    "validation-ridge.csv and validation.html. Folder "
                    "format: docs/validation.md.")
    p.add_argument("folder", metavar="FOLDER", help="campaign folder: tests.csv and the motion "
                                                    "files it names")
    p.add_argument("--geometry", metavar="CSV",
                   help="geometric estimates (specimen, alpha_deg, p_rad_s, note) shown beside "
                        "the fit; default FOLDER/specimens.csv if present")
    p.add_argument("--folds", type=int, default=5,
                   help="cross-validation folds (whole ground motions per fold)")
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS, help="solver threads")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help="free rocking simulated after each motion [s]")
    p.add_argument("--band-pass", action="store_true",
                   help="rock the blocks under the motions band-passed 0.1-25 Hz (for records "
                        "that drift) instead of as recorded")
    p.add_argument("--out", default=DEFAULT_OUT, metavar="DIR", help="output folder")
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    from audit.api import validate
    from audit.errors import InputError
    from audit.cli.outputs import checked
    if args.folds < 2:
        raise InputError(f"--folds: must be at least 2, got {args.folds}")
    out_dir = checked(folders={"--out": (args.out, WRITES)},
                      inputs={"FOLDER": args.folder, "--geometry": args.geometry})["--out"]
    result = validate(args.folder, geometry=args.geometry, folds=args.folds, jobs=args.jobs,
                      free_motion_s=args.free_motion, band_pass=args.band_pass, progress=True)
    result.write(out_dir)
    print(f"{result.solves:,} exact simulations; wrote {out_dir / 'validation.html'} and the "
          "validation CSV files")
    return 0
