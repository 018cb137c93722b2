"""``python -m audit floor-motion``: the motion of a floor of a linear building under a record."""

from __future__ import annotations

import sys

from audit.cli import options, outputs


def add_parser(sub):
    p = sub.add_parser(
        "floor-motion", help="the absolute acceleration of a floor of a linear building",
        formatter_class=options.HelpWithDefaults,
        description="Filters a record through a linear, classically damped building (modal "
                    "superposition, each mode solved exactly for the record linear between "
                    "samples) and writes the absolute acceleration of the floor at z/H as "
                    "time_s,acceleration_g; prints its PFA, PFV and the peak of its 5 %% "
                    "damped spectrum.")
    options.add_records_option(p)
    p.add_argument("--record", metavar="ID_OR_PATH", required=True,
                   help="record id of the suite, or a file")
    options.add_skip_bad_records_option(p)
    options.add_floor_options(p)
    p.set_defaults(floor=1.0)
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.add_argument("--json", action="store_true", help="print the peaks as JSON")
    p.set_defaults(func=run)


def run(args) -> int:
    import json

    import audit.api as api
    csv = outputs.checked(files={"--csv": args.csv},
                          inputs={"--record": args.record, "--records": args.records})["--csv"]
    result = api.floor_motion(args.record, options.floor(args), options.records(args))
    from audit.files import write_atomically
    if csv is not None:
        write_atomically({csv: result.csv()})
    else:
        sys.stdout.write(result.csv().decode())
    stream = sys.stdout if csv is not None else sys.stderr
    if args.json:
        print(json.dumps(result.as_dict()), file=stream)
    else:
        print(f"{result.motion.id} {result.floor['description']}: PFA = {result.pfa_g:.4g} g, "
              f"PFV = {result.pfv_m_s:.4g} m/s, peak of the 5 % spectrum "
              f"{result.spectrum_peak_g:.4g} g at T = {result.spectrum_peak_period_s:.3g} s",
              file=stream)
    if csv is not None:
        print(f"Wrote {result.motion.acceleration.size} rows to {args.csv}", file=sys.stderr)
    return 0
