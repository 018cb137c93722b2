"""``python -m audit atlas build|list|remove|check``: the exact-fragility atlas of a record set
on a floor (:mod:`audit.engine.atlas`), built once into the user cache."""

from __future__ import annotations

import json
import sys

from audit.cli import options
from audit.api import DEFAULT_CHECK_RECORDS, DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_JOBS


def _atlas_options(p):
    """What names an atlas: records, IM, floor, restitution, g, free motion."""
    p.add_argument("--records", metavar="NAME_OR_PATH", default=DEFAULT_CHECK_RECORDS,
                   help="record suite (see 'list'), manifest, file or folder")
    p.add_argument("--im", default=DEFAULT_IM, metavar="pga|pgv|sa:T",
                   help="intensity measure of the stripes")
    options.add_floor_options(p)
    options.add_restitution_option(p)
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S", help="free motion after each record [s]")


def build_command(build: dict) -> str:
    """The ``atlas build`` command line that builds the atlas a :class:`~audit.errors.NoAtlas`
    asked for (``build``: records as named, im, solver, floor)."""
    from audit.api import DEFAULT_RESTITUTION, Solver
    solver = build.get("solver") or Solver()
    command = f"python -m audit atlas build --records {build['records']} --im {build['im']}"
    if str(solver.restitution) != DEFAULT_RESTITUTION:
        command += f" --restitution {solver.restitution}"
    if solver.free_motion_s != DEFAULT_FREE_MOTION_S:
        command += f" --free-motion {solver.free_motion_s:g}"
    floor = build.get("floor")
    building = getattr(floor, "building", None)
    if building is not None and floor.z_over_h:
        command += (f" --floor {floor.z_over_h:g} --building {building.period_s:g}"
                    f" --building-model {building.model} --building-damping {building.damping:g}")
    return command


def add_parser(sub):
    p = sub.add_parser("atlas", help="build, list, remove or read the exact-fragility atlas of "
                                     "a record set on a floor (check's answers in seconds)",
                       description="The outcome of every record at every stripe of check's "
                                   "lattice for a grid of (α, 2π/p), kept in the user cache "
                                   "($ROCKING_AUDIT_ATLAS_DIR to choose another folder).")
    verbs = p.add_subparsers(dest="verb", required=True, metavar="build|list|remove|check")
    build = verbs.add_parser("build", help="build (or complete an interrupted build of) an atlas",
                             formatter_class=options.HelpWithDefaults)
    _atlas_options(build)
    build.add_argument("--scheduler", default="local", metavar="local|dask|tcp://HOST:PORT",
                       help="where records are computed: this process, a Dask LocalCluster "
                            "of --jobs worker processes, or an existing Dask cluster")
    build.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS,
                       help="solver threads, or worker processes with --scheduler dask")
    build.set_defaults(func=run_build)
    listing = verbs.add_parser("list", help="the atlases in the cache")
    listing.set_defaults(func=run_list)
    remove = verbs.add_parser("remove", help="remove an atlas by its key (or its first "
                                             "characters, as 'atlas list' shows them)")
    remove.add_argument("key")
    remove.set_defaults(func=run_remove)
    check = verbs.add_parser("check", help="exact P(overturn) at a site and the exact widths "
                                           "for P ≤ 10 %% and ≤ 50 %%, from the atlas",
                             formatter_class=options.HelpWithDefaults)
    check.add_argument("--block", action="append", metavar="WIDTHxHEIGHT",
                       help="an object by its full base width × full height [m]; repeat it")
    check.add_argument("--objects", metavar="FILE.csv",
                       help="an inventory: columns name,width_m,height_m")
    check.add_argument("--site", required=True, metavar="SXS,SX1",
                       help="FEMA 356 / ASCE 41 S_XS,S_X1 [g] at the hazard level assessed")
    _atlas_options(check)
    check.add_argument("--json", metavar="FILE", help="also write the answers as JSON")
    check.set_defaults(func=run_check)
    return p


def _keywords(args) -> dict:
    from audit.api import Solver
    return {"im": args.im, "solver": Solver(args.restitution, args.free_motion),
            "floor": options.floor(args)}


def run_build(args) -> int:
    from audit.api import Runtime, build_atlas
    done = build_atlas(args.records, scheduler=args.scheduler, progress=True,
                       runtime=Runtime(options.cap_jobs(args.jobs)), **_keywords(args))
    print(f"atlas of {done['records']} ({len(done['record_ids'])} records, {done['im']}, "
          f"{done['floor']}): {done['solves']} outcomes in {done['seconds']:.0f} s "
          f"({done['reused']} records reused), on {done['where']}", file=sys.stderr)
    return 0


def run_list(args) -> int:
    from audit.api import atlas_folder, list_atlases
    atlases = list_atlases()
    if not atlases:
        print(f"no atlas in {atlas_folder()}", file=sys.stderr)
    for a in atlases:
        p = a.provenance
        state = "complete" if a.complete else "incomplete (build again to complete it)"
        print(f"{a.key[:12]}  {p['records']} ({len(p.get('record_ids', []))} records)  "
              f"{p['im']}  {p['floor']}  restitution {p['restitution']}  "
              f"α {p['alpha_deg'][0]:g}–{p['alpha_deg'][-1]:g}° ×{len(p['alpha_deg'])}, "
              f"2π/p {p['size_s'][0]:g}–{p['size_s'][-1]:g} s ×{len(p['size_s'])}  "
              f"{a.size_bytes() / 1e6:.1f} MB  {state}")
    return 0


def run_remove(args) -> int:
    from audit.api import remove_atlas
    gone = remove_atlas(args.key)
    print(f"removed {', '.join(k[:12] for k in gone)}", file=sys.stderr)
    return 0


def run_check(args) -> int:
    from audit.api import atlas_check
    from audit.errors import InputError
    objects = list(args.block or [])
    if args.objects:
        from audit.api import read_objects
        objects += read_objects(args.objects)
    if not objects:
        raise InputError("give the objects: --block WIDTHxHEIGHT or --objects FILE.csv",
                         "--block")
    answers = atlas_check(objects, args.site, args.records, **_keywords(args))
    for a in answers:
        if a["p_overturn_at_site"] is None:
            print(f"{a['name']}: {a['outside']}")
            continue
        w = a["exact_required_width_m"]
        print(f"{a['name']}: P(overturn) at the site {a['p_overturn_at_site']['text']}; exact "
              f"width for P ≤ 10 %: {w['10%']:.3g} m, ≤ 50 %: {w['50%']:.3g} m")
    if args.json:
        from audit.files import write_file_atomically
        write_file_atomically(args.json, json.dumps(answers, indent=1).encode())
    return 0
