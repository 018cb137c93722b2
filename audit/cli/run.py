"""``python -m audit run``: the audit."""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path

from audit.cli import options
from audit.api import (DEFAULT_AGREE_BAND, DEFAULT_FREE_MOTION_S, DEFAULT_JOBS,
                       DEFAULT_ROBUSTNESS, alpha_text, sizes_text)

DEFAULT_OUT = "audit-out"
#: The files a run writes in its --out folder (audit.engine.run.results), and its parts' folder.
WRITES = ("report.html", "columns.json", "*.csv", "summary.json", ".partial")


def add_parser(sub):
    p = sub.add_parser("run", help="audit a procedure (or all) and write the HTML report",
                       formatter_class=options.HelpWithDefaults,
                       description="Audit guideline procedures against the exact rocking "
                                   "response; writes report.html, results.csv, summary.json "
                                   "and the other files described in columns.json.")
    p.add_argument("procedure", help="registered procedure name ({registered}), or 'all'")
    options.add_records_option(p)
    p.add_argument("--alpha", default=alpha_text(), metavar="DEG,...",
                   help="slendernesses [degrees]")
    p.add_argument("--size", default=sizes_text(), metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s] (a comma list S,... too)")
    options.add_alias(p, "--sizes", "size")
    p.add_argument("--out", metavar="DIR", help=f"output directory (default {DEFAULT_OUT}/PROCEDURE)")
    p.add_argument("--jobs", type=options.jobs, default=DEFAULT_JOBS,
                   help="threads of the exact solver, or worker processes with --scheduler dask")
    p.add_argument("--free-motion", type=options.NON_NEGATIVE, default=DEFAULT_FREE_MOTION_S,
                   metavar="S",
                   help="free motion after each record [s]")
    p.add_argument("--agree-band", type=options.number("must lie in [0, 1)", 0, 1, high_open=True),
                   default=DEFAULT_AGREE_BAND, metavar="FRACTION",
                   help="verdict 'agrees' when both survive and |approx/exact − 1| ≤ FRACTION")
    p.add_argument("--robustness", type=options.number("must lie in [0, 0.5)", 0, 0.5,
                                                       high_open=True),
                   default=DEFAULT_ROBUSTNESS, metavar="EPSILON",
                   help="flag blocks whose exact overturning changes with the record scaled by "
                        "1 ± EPSILON (0 turns it off)")
    p.add_argument("--site", metavar="SXS,SX1",
                   help="FEMA 356 design site S_XS,S_X1 [g] (§1.6) for every record without one")
    p.add_argument("--site-override", action="store_true",
                   help="with --site: also replace the sites records carry (Table 3.1)")
    options.add_scaling_options(p)
    p.add_argument("--ntc-site", metavar="AG,F0,TC,SOIL,TOPO",
                   help="NTC 2018 site for every record: a_g [g], F0, T_C* [s], soil category "
                        "(A–E), topography (T1–T4), e.g. 0.25,2.4,0.3,B,T1; NTC 2018 then reads "
                        "its demand off this code spectrum instead of the record's")
    options.add_floor_options(p)
    options.add_param_option(p)
    options.add_restitution_option(p)
    options.add_ground_truth_options(p)
    options.add_force_option(p)
    p.add_argument("--skip-bad-records", action="store_true",
                   help="audit the readable records of a suite and list the unreadable ones "
                        "(default: stop at the first)")
    options.add_scheduler_options(p)
    p.add_argument("--detail", metavar="ID,...", help="records whose detail the report shows")
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.api import PARTIAL_DIR, REPORT_HTML, Runtime, Solver
    from audit.api import run as run_api
    from audit.cli.outputs import checked
    out = Path(args.out) if args.out else Path(DEFAULT_OUT) / args.procedure
    out_dir = checked(folders={"--out": (out, WRITES)}, inputs={"--records": args.records})["--out"]
    out_dir_existed = out_dir.exists()
    grid = {"alpha_deg": options.alphas_deg(args.alpha),
            "size_s": options.sizes(args.size, options.typed_flag(args, "size"))}
    site = options.site(args)
    start = time.perf_counter()
    try:
        result = run_api(args.procedure, options.records(args), params=args.param,
                         out_dir=out_dir, **grid,
                         solver=Solver(args.restitution, free_motion_s=args.free_motion,
                                       vertical=args.vertical),
                         agree_band=args.agree_band, robustness=args.robustness,
                         friction=args.friction, sensitivity=args.sensitivity or (), site=site,
                         floor=options.floor(args),
                         runtime=Runtime(jobs=args.jobs, scheduler=args.scheduler,
                                         progress=True, force=args.force,
                                         partial_dir=out_dir / PARTIAL_DIR, resume=args.resume),
                         detail=[item.strip() for item in (args.detail or "").split(",")
                                 if item.strip()])
    except KeyboardInterrupt:
        return options.interrupted(out_dir, out_dir_existed)
    shutil.rmtree(out_dir / PARTIAL_DIR, ignore_errors=True)
    total = time.perf_counter() - start
    sys.stdout.write(result.summary_text())
    print(f"Wrote {out_dir / REPORT_HTML} and results.csv, summary.json "
          f"in {total:.1f} s")
    return 0
