"""``python -m audit check``: one or many objects at one site, the answer an engineer acts on."""

from __future__ import annotations

import sys
import time

from audit.cli import options
from audit.api import (DEFAULT_CHECK_RECORDS, DEFAULT_FREE_MOTION_S, DEFAULT_IM,
                       DEFAULT_JOBS)
from audit.errors import InputError

#: The files check writes in its --out folder.
WRITES = ("check.json", "check.csv", "check.html")


def add_parser(sub):
    p = sub.add_parser(
        "check", help="does an object pass each guideline at a site; its exact P(overturn) and "
                      "the width it needs",
        formatter_class=options.HelpWithDefaults,
        description="For each object (a block in metres) at one FEMA 356 / ASCE 41 site: each "
                    "guideline's verdict with the numbers it compares, the exact probability of "
                    "overturning at the site's intensity (multiple-stripe fragility, bootstrap "
                    "band over records), and the base width each guideline requires at the "
                    "object's height against the exact width for P(overturn) ≤ 10 % and "
                    "≤ 50 %. The site's S_XS, S_X1 are those of the hazard level you assess "
                    "(e.g. BSE-1E or BSE-2E): every number is at that level. With --hazard, "
                    "also each object's mean annual rate of overturning and P in 50 years from "
                    "the site's hazard curve, the P in 50 years of the object as each guideline "
                    "sizes it, and the exact width for the risk target. With --out, writes "
                    "check.json, check.csv and check.html.")
    p.add_argument("--block", action="append", metavar="WIDTHxHEIGHT",
                   help="an object by its full base width × full height [m] (of the box of its "
                        "centre of mass), e.g. 0.6x1.8; repeat it for several")
    p.add_argument("--objects", metavar="FILE.csv",
                   help="an inventory: columns name,width_m,height_m (or name,alpha_deg,size_s "
                        "for objects described that way), one object a row")
    p.add_argument("--alpha", metavar="DEG,...",
                   help="with --size: objects by slenderness [degrees], every --size each")
    p.add_argument("--size", metavar="S,... or START:STOP:STEP",
                   help="with --alpha: sizes 2π/p [s]")
    p.add_argument("--site", metavar="SXS,SX1",
                   help="FEMA 356 / ASCE 41 design spectral accelerations S_XS,S_X1 [g] at the "
                        "hazard level assessed (required): the site's intensity")
    p.add_argument("--ntc-site", metavar="AG,F0,TC,SOIL,TOPO",
                   help="NTC 2018 site as for 'run', its values those of the --limit-state's "
                        "return period (with 'both', read for SLV and SLC alike): NTC 2018 then "
                        "reads its code spectrum S_De and EN 1998-1 its a_g·S_S·S_T; the "
                        "records stay the exact answer's")
    p.add_argument("procedure", nargs="?", default="all",
                   help="registered procedure name ({registered}), or 'all'")
    p.add_argument("--records", metavar="NAME_OR_PATH", default=DEFAULT_CHECK_RECORDS,
                   help="record suite (see 'list'), manifest, file or folder; each record is "
                        "scaled to the site's intensity and to a fixed lattice of stripes, "
                        "0.0625–5.66 g")
    options.add_record_file_options(p)
    p.add_argument("--im", default=None, metavar="pga|sa:T",
                   help=f"intensity measure (default {DEFAULT_IM}, or the --hazard file's IMT): "
                        "the 5 %%-damped pseudo-spectral acceleration ω²·S_d at T [g] (the site's "
                        "intensity: its design spectrum at T; S_X1 at 1 s) or PGA (0.4 S_XS)")
    p.add_argument("--limit-state", default="both", metavar="SLV|SLC|both",
                   help="the limit state the --site values are for, of a guideline that names "
                        "its own (NTC 2018: SLV, d ≤ 0.4 d₀; SLC, d ≤ 0.6 d₀); 'both' reports "
                        "each")
    options.add_hazard_options(p)
    p.add_argument("--return-period", type=options.number("must be more than 1 year", 1.0,
                                                          low_open=True),
                   metavar="YEARS", help="with --hazard: the site's intensity for the exact "
                   "answer is the hazard curve's at this return period (e.g. 2475); --site "
                   "stays the design spectrum the guidelines read")
    p.add_argument("--poe", metavar="P",
                   help="with --hazard: as --return-period, by the probability of exceedance "
                        "in 50 years (e.g. 2%%, or 0.02)")
    p.add_argument("--friction", type=options.POSITIVE, metavar="MU",
                   help="friction coefficient μ of the objects' base: which mode governs, "
                        "sliding (tan α > μ, or records whose rocking needs more than μ) or "
                        "rocking; without it, no sliding is assumed and the friction the "
                        "records need is given")
    options.add_floor_options(p)
    options.add_param_option(p)
    p.add_argument("--mass", type=options.POSITIVE, metavar="KG",
                   help="the mass of each object [kg]: the anchorage forces of the component "
                        "provisions it fails also in kN")
    p.add_argument("--guideline-spectrum", default="ground", choices=("ground", "floor"),
                   help="on a floor, the spectrum FEMA 356 reads: the ground's design spectrum "
                        "of --site as its text is written (default), or the floor's response "
                        "spectrum (the median of the floor motions at the site, as S_XS, S_X1); "
                        "its entry gives its verdict on the other too")
    options.add_restitution_option(p)
    p.add_argument("--method", choices=("atlas", "direct"), default=None,
                   help="where the exact side (fragility, P at the site, exact widths, risk) "
                        "comes from: the atlas of --records on this floor ('audit atlas "
                        "build'), each answer with its error there, or solved; default: the "
                        "atlas where one is built, else solved. P at the other standard IM: "
                        "its own atlas where one is built ('atlas build --im pga' beside "
                        "sa:1), unless direct. The guidelines are judged directly either way")
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS,
                   help="solver threads, or worker processes with --scheduler dask")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help="free motion after each record [s]")
    p.add_argument("--out", metavar="DIR", help="write check.json, check.csv, check.html here")
    options.add_force_option(p)
    p.add_argument("--scheduler", default="local", metavar="local|dask|tcp://HOST:PORT",
                   help="where records are computed")
    p.add_argument("--skip-bad-records", action="store_true",
                   help="check with the readable records and list the unreadable ones")
    p.set_defaults(func=run)


def objects_of(args) -> list:
    """Every object of ``--block``, ``--objects`` and ``--alpha``/``--size``, checked."""
    from audit.api import object_by_slenderness, parse_block_text, read_objects
    objects = []
    for text in args.block or ():
        objects += parse_block_text(text, "--block")
    if args.objects:
        objects += read_objects(args.objects, "--objects")
    if bool(args.alpha) != bool(args.size):
        raise InputError("--alpha and --size go together: objects by slenderness and size")
    if args.alpha:
        for alpha in options.float_list(args.alpha, "--alpha"):
            for size in options.sizes(args.size):
                name = f"α={alpha:g}°, 2π/p={size:g} s"
                objects.append(object_by_slenderness(name, alpha, size, f"--alpha/--size {name}"))
    if not objects:
        raise InputError("check: give the objects: --block WIDTHxHEIGHT, --objects FILE.csv or "
                         "--alpha DEG --size S")
    seen = set()
    for obj in objects:  # one pass: an inventory may hold tens of thousands of objects
        if obj.name in seen:
            raise InputError(f"check: object '{obj.name}' is given twice")
        seen.add(obj.name)
    return objects


def run(args) -> int:
    from audit.api import Hazard, Runtime, Solver, check
    from audit.cli.outputs import checked
    if not args.site:
        raise InputError("--site: required, S_XS,S_X1 [g] of the hazard level assessed "
                         "(e.g. --site 1.5,0.9)")
    out_dir = checked(folders={"--out": (args.out, WRITES)},
                      inputs={"--records": args.records, "--objects": args.objects,
                              "--hazard": args.hazard}).get("--out")
    site = options.site(args)
    objects = objects_of(args)
    if args.guideline_spectrum == "floor" and not args.floor:
        raise InputError("--guideline-spectrum floor: reads the floor's response spectrum; the "
                         "objects stand on the ground (give --floor Z/H and --building T1)")
    start = time.perf_counter()
    if not args.hazard:
        for flag in ("site_location", "hazard_imt", "return_period", "poe"):
            if getattr(args, flag) is not None:
                raise InputError(f"--{flag.replace('_', '-')}: read on the --hazard file; no "
                                 "--hazard given")
    result = check(objects, site, procedures=args.procedure, records=options.records(args),
                   im=args.im, friction=args.friction, params=args.param, mass_kg=args.mass,
                   guideline_spectrum=args.guideline_spectrum,
                   hazard=Hazard(args.hazard, imt=args.hazard_imt,
                                 location=args.site_location, return_period=args.return_period,
                                 poe=args.poe, risk_target=args.risk_target),
                   floor=options.floor(args),
                   solver=Solver(args.restitution, free_motion_s=args.free_motion),
                   runtime=Runtime(jobs=args.jobs, scheduler=args.scheduler, progress=True,
                                   force=args.force),
                   method=args.method)
    if out_dir is not None:
        result.write(out_dir)
    print(f"done in {time.perf_counter() - start:.1f} s", file=sys.stderr)
    sys.stdout.write(result.summary_text())
    if out_dir is not None:
        print(f"Wrote {out_dir / 'check.html'}, check.json and check.csv")
    return 0
