"""``python -m audit margins``: the design-level audit (fragility and collapse margins)."""

from __future__ import annotations

import math
import shutil
import time
from pathlib import Path

from audit.cli import options
from audit.cli.run import site_options
from audit.engine.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_JOBS,
                                   DEFAULT_MARGINS_SIZES, DEFAULT_SITE_LEVEL, SITE_LEVELS,
                                   alpha_text, sizes_text)
from audit.errors import InputError

DEFAULT_OUT = "audit-out/margins"


def add_parser(sub):
    p = sub.add_parser(
        "margins", help="fragility and collapse margins of blocks sized by each guideline",
        formatter_class=options.HelpWithDefaults,
        description="Scale the suite's records to a set of intensity levels (stripes), count "
                    "how many overturn each block exactly, fit a lognormal fragility, and say "
                    "where each guideline draws its line: its overturning intensity, the exact "
                    "probability of overturning there, and the FEMA P695 collapse margin ratio. "
                    "Writes margins.html, stripes.csv, fragility.csv, capacity.csv, "
                    "required_alpha.csv, scan.csv and summary.json; with --hazard, each block's "
                    "annual rate of overturning at the site and the slenderness each size needs "
                    "for the risk target (risk.csv, risk_alpha.csv, hazard.csv).")
    p.add_argument("procedure", help="registered procedure name ({registered}), or 'all'")
    options.add_records_option(p)
    p.add_argument("--im", metavar="pga|pgv|sa:T",
                   help=f"intensity measure: PGA [g], PGV [m/s] or the 5 %%-damped "
                        f"pseudo-spectral acceleration ω²·S_d at T [g] (default: {DEFAULT_IM}, "
                        "or the --hazard file's IMT)")
    p.add_argument("--stripes", metavar="IM,...",
                   help="intensity levels (unit of --im); default 24 levels, geometric, "
                        "0.2–5 × the site's design intensity (or the suite's median)")
    p.add_argument("--alpha", default=alpha_text(), metavar="DEG,...",
                   help="slendernesses [degrees]")
    p.add_argument("--sizes", default=sizes_text(DEFAULT_MARGINS_SIZES), metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s]")
    p.add_argument("--site", metavar="SXS,SX1",
                   help="FEMA 356 design site S_XS,S_X1 [g] of every record (the records' own "
                        "sites are replaced); its intensity is the CMR's denominator, taken as "
                        "the MCE's (FEMA P695) unless --level design")
    p.add_argument("--level", choices=tuple(SITE_LEVELS), default=DEFAULT_SITE_LEVEL,
                   help="hazard level of the --site values: mce (the CMR is over them) or "
                        "design (the CMR is over 1.5 × them, the MCE of ASCE 7)")
    options.add_scaling_options(p)
    p.add_argument("--ntc-site", metavar="AG,F0,TC,SOIL,TOPO",
                   help="NTC 2018 site for every record (see 'run --help')")
    options.add_block_option(p)
    options.add_restitution_option(p)
    options.add_hazard_options(p)
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS,
                   help="solver threads, or worker processes with --scheduler dask")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help="free motion after each record [s]")
    p.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="output directory")
    options.add_scheduler_options(p)
    options.add_force_option(p)
    p.add_argument("--skip-bad-records", action="store_true",
                   help="audit the readable records and list the unreadable ones")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.api import PARTIAL_DIR, margins
    from audit.files import check_output_dir
    from reports.margins_page import MARGINS_HTML
    out_dir = check_output_dir(Path(args.out))
    out_dir_existed = out_dir.exists()
    values = {"alpha_deg": options.alphas_deg(args.alpha),
              "sizes_s": options.sizes(args.sizes), "blocks": args.block or (),
              "restitution": args.restitution, "free_motion_s": args.free_motion,
              "site_level": args.level, "risk_target": args.risk_target}
    if args.im is not None:  # without it, the default or the hazard file's IMT
        values["im"] = args.im
    if args.hazard:
        values.update(hazard=args.hazard, site_location=options.site_location(args.site_location))
    elif args.site_location:
        raise InputError("--site-location: a site of the --hazard file; no --hazard given")
    if args.stripes is not None:  # '' is refused, not taken for the default
        values["stripes"] = options.float_list(args.stripes, "--stripes")
    site = site_options(args)
    del site["site_override"]  # one design site: the audit is of that site
    start = time.perf_counter()
    try:
        result = margins(args.procedure, options.suite(args), force=args.force, **values, **site,
                         jobs=args.jobs, scheduler=args.scheduler,
                         partial_dir=out_dir / PARTIAL_DIR, resume=args.resume, progress=True)
    except KeyboardInterrupt:
        return options.interrupted(out_dir, out_dir_existed)
    result.write(out_dir)
    shutil.rmtree(out_dir / PARTIAL_DIR, ignore_errors=True)
    _print_summary(result, time.perf_counter() - start)
    print(f"Wrote {out_dir / MARGINS_HTML} and stripes.csv, fragility.csv, capacity.csv, "
          "required_alpha.csv, scan.csv, summary.json"
          + (", risk.csv, risk_alpha.csv, hazard.csv" if args.hazard else ""))
    return 0


def _print_risk(result) -> None:
    hazard = result.summary["hazard"]
    print(f"  at the site ({hazard['source']}), target P {hazard['target_p50']:g} in 50 years:")
    for row in result.risk[result.risk["block_m"] != ""].itertuples():
        print(f"  block {row.block_m} m: λ_ov {row.annual_rate_fit:.3g}/yr, P in 50 years "
              f"{row.p50_fit:.3g} (stripe shares: {row.annual_rate_stripes:.3g}/yr); 90 % of "
              f"it from {row.im_low_90_g:.3g}–{row.im_high_90_g:.3g} g")


def _print_summary(result, seconds) -> None:
    fragility, summary = result.fragility, result.summary
    sizes = summary["grid"]["size_s"]
    print(f"Fragility of {len(fragility)} blocks on {summary['records_source']} in "
          f"{summary['scheduler']} ({seconds:.1f} s)"
          + (f"; reused {len(summary['resumed'])} records of an interrupted run"
             if summary["resumed"] else ""))
    if summary["design_im"]:
        print(f"  median CMR {fragility['cmr'].median():.2f} (over the MCE {summary['im']} = "
              f"{summary['mce_im']:.3g} {summary['im_unit']}; "
              f"{fragility['median_extrapolated'].sum()} medians beyond the stripes give bounds)")
    print(f"  blocks with islands of survival above overturning: "
          f"{(fragility['records_with_islands'] > 0).mean():.0%}")
    for name, rows in result.capacity.groupby("procedure", sort=False):
        if rows["achieved_p_fit"].isna().all():
            print(f"  {name}: draws no line (it can evaluate none of these records)")
            continue
        print(f"  {name}: median exact P(overturn) where it draws its line "
              f"{rows['achieved_p_fit'].median():.2f}, its line / exact median "
              f"{rows['ratio_to_exact_median'].median():.2f}")
    exact = result.required_alpha.set_index(["procedure", "size_s"])["required_alpha_deg"]
    drawn = set(result.required_alpha["procedure"])
    for name in (p["name"] for p in summary["procedures"] if p["name"] in drawn):
        below = [size for size in sizes
                 if exact.get((name, size), math.nan) < exact.get(("exact@0.10", size), math.nan)]
        print(f"  {name} accepts blocks more slender than the exact 10 % curve for "
              + (f"2π/p = {min(below):g}–{max(below):g} s ({len(below)} of {len(sizes)} sizes)"
                 if below else "no size"))
    for verdict in summary.get("acceptance", ()):
        print(f"  {verdict['procedure']} as a seismic system (FEMA P695): "
              f"{verdict['share_meeting_acmr20']:.0%} of the {verdict['blocks']} blocks it "
              f"sizes meet ACMR20 %; mean CMR {verdict['mean_cmr']:.2f} against ACMR10 % "
              f"{verdict['acmr10']:.2f}: {'passes' if verdict['passes'] else 'fails'}")
    if result.risk is not None:
        _print_risk(result)
