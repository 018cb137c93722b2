"""``python -m audit margins``: the design-level audit (fragility and collapse margins)."""

from __future__ import annotations

import math
import time
from pathlib import Path

from audit.cli import options
from audit.engine.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_JOBS, alpha_text)
from audit.errors import InputError

DEFAULT_OUT = "audit-out/margins"
DEFAULT_IM = "sa:1.0"


def add_parser(sub):
    p = sub.add_parser(
        "margins", help="fragility and collapse margins of blocks sized by each guideline",
        formatter_class=options.HelpWithDefaults,
        description="Scale the suite's records to a set of intensity levels (stripes), count "
                    "how many overturn each block exactly, fit a lognormal fragility, and say "
                    "where each guideline draws its line: its overturning intensity, the exact "
                    "probability of overturning there, and the FEMA P695 collapse margin ratio. "
                    "Writes stripes.csv, fragility.csv, capacity.csv, summary.json.")
    p.add_argument("procedure", help="registered procedure name ({registered}), or 'all'")
    options.add_records_option(p)
    p.add_argument("--im", default=DEFAULT_IM, metavar="pga|pgv|sa:T",
                   help="intensity measure: PGA [g], PGV [m/s] or the true 5 %%-damped "
                        "spectral acceleration at T [g]")
    p.add_argument("--stripes", metavar="IM,...",
                   help="intensity levels (unit of --im); default 24 levels, geometric, "
                        "0.2–5 × the site's design intensity (or the suite's median)")
    p.add_argument("--alpha", default=alpha_text(), metavar="DEG,...",
                   help="slendernesses [degrees]")
    p.add_argument("--sizes", default="0.5:8:0.25", metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s]")
    p.add_argument("--site", metavar="SXS,SX1",
                   help="FEMA 356 design site S_XS,S_X1 [g] of every record (the records' own "
                        "sites are replaced): the design intensity of the CMR")
    options.add_scaling_options(p)
    p.add_argument("--ntc-site", metavar="AG,F0,TC,SOIL,TOPO",
                   help="NTC 2018 site for every record (see 'run --help')")
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS, help="solver threads")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help="free motion after each record [s]")
    p.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="output directory")
    options.add_force_option(p)
    p.add_argument("--skip-bad-records", action="store_true",
                   help="audit the readable records and list the unreadable ones")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.cli.run import design_site
    from audit.engine.margins import (IntensityMeasure, margins_files, required_alpha,
                                      run_margins)
    from audit.engine.progress import Progress
    from audit.files import check_output_dir, write_files_atomically
    from procedures import get_procedures
    out_dir = check_output_dir(Path(args.out))
    im = IntensityMeasure.parse(args.im)
    levels = options.float_list(args.stripes, "--stripes") if args.stripes else None
    if levels is not None and not all(level > 0 for level in levels):
        raise InputError(f"--stripes: intensity levels must be positive, got '{args.stripes}'")
    procedures = get_procedures(args.procedure)
    sizes = options.sizes(args.sizes)
    alphas = options.alphas_deg(args.alpha)
    args.site_override = bool(args.site)  # one design site: the audit is of that site
    suite = design_site(args, options.suite(args))
    stripes = len(levels) if levels is not None else 24
    options.check_cost(args, [e.motion for e in suite if not e.missing], args.free_motion,
                       blocks=stripes * sizes.size * alphas.size)
    start = time.perf_counter()
    progress = Progress(len(suite), "record")
    progress.stage(f"exact fragility of {alphas.size * sizes.size} blocks on {len(suite)} "
                   f"records × {stripes} stripes of {im.name}; {', '.join(p.name for p in procedures)}"
                   " at the same stripes")
    try:
        margins = run_margins(procedures, suite, im, levels, alphas, sizes,
                              free_motion_s=args.free_motion, jobs=args.jobs, progress=progress)
    finally:
        progress.done()
    progress.stage("required slenderness for each size: α from 2° to 40°, 2° apart")
    margins.required_alpha = required_alpha(procedures, suite, sizes,
                                            free_motion_s=args.free_motion, jobs=args.jobs)
    write_files_atomically(out_dir, margins_files(margins))
    fragility = margins.fragility
    print(f"Fragility of {len(fragility)} blocks on {suite.description} "
          f"({time.perf_counter() - start:.1f} s)")
    if margins.summary["design_im"]:
        print(f"  median CMR {fragility['cmr'].median():.2f} (design {im.name} = "
              f"{margins.summary['design_im']:.3g} {im.unit})")
    print(f"  blocks with islands of survival above overturning: "
          f"{(fragility['records_with_islands'] > 0).mean():.0%}")
    for name, rows in margins.capacity.groupby("procedure", sort=False):
        print(f"  {name}: median exact P(overturn) where it draws its line "
              f"{rows['achieved_p_fit'].median():.2f}, its line / exact median "
              f"{rows['ratio_to_exact_median'].median():.2f}")
    exact = margins.required_alpha.set_index(["procedure", "size_s"])["required_alpha_deg"]
    for name in (p.name for p in procedures):
        below = [size for size in sizes
                 if exact.get((name, size), math.nan) < exact.get(("exact@0.10", size), math.nan)]
        print(f"  {name} accepts blocks more slender than the exact 10 % curve for "
              + (f"2π/p = {min(below):g}–{max(below):g} s ({len(below)} of {sizes.size} sizes)"
                 if below else "no size"))
    print(f"Wrote {out_dir}: stripes.csv, fragility.csv, capacity.csv, required_alpha.csv, "
          "summary.json")
    return 0
