"""Command-line interface: ``python -m audit {list,rock,spectrum,design-spectrum,run,report}``.

Angles are typed in degrees and accelerations in g; everything inside is SI. Bad input is
reported on one line on stderr with exit status 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from audit import __version__
from audit.errors import InputError

DEFAULT_OUT = "audit-out"


def _float_list(text: str, option: str) -> list[float]:
    try:
        values = [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        raise InputError(f"{option}: expected comma-separated numbers, got '{text}'") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(f"{option}: expected comma-separated finite numbers, got '{text}'")
    return values


def _alphas_deg(text: str) -> np.ndarray:
    """Slendernesses typed in degrees, checked to lie in (0°, 45°)."""
    values = _float_list(text, "--alpha")
    for value in values:
        if not 0 < value < 45:
            raise InputError(f"--alpha: slenderness must lie between 0 and 45 degrees, got {value:g}")
    return np.array(values)


def _grid(text: str, option: str, allow_zero: bool = False) -> np.ndarray:
    """START:STOP:STEP (inclusive) or a comma list of times [s] given to ``option``."""
    from audit.runner import size_grid
    parts = text.split(":")
    low = "0 ≤ START" if allow_zero else "0 < START"
    try:
        numbers = [float(part) for part in parts]
    except ValueError:
        numbers = None
    if len(parts) == 3 and numbers is not None:
        start, stop, step = numbers
        if not ((start >= 0 if allow_zero else start > 0) and stop >= start and step > 0):
            raise InputError(f"{option}: need {low} ≤ STOP and STEP > 0, got '{text}'")
        return size_grid(start, stop, step)
    if len(parts) == 1:
        values = np.array(_float_list(text, option))
        if np.any(values < 0) or (not allow_zero and np.any(values == 0)):
            raise InputError(f"{option}: every value must be {'≥ 0' if allow_zero else '> 0'} s, "
                             f"got '{text}'")
        return values
    raise InputError(f"{option}: expected START:STOP:STEP or a comma list in seconds, got '{text}'")


def _sizes(text: str) -> np.ndarray:
    return _grid(text, "--sizes")


def _positive(value: float, option: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{option}: must be a positive number, got {value:g}")
    return value


def _suite(args):
    from records import load_records
    return load_records(args.records)


def _motion(args):
    """The excitation of ``rock``/``spectrum``: a record (id or file) or an analytic pulse."""
    from records import one_pulse, resolve_motion
    if args.pulse:
        if args.record:
            raise InputError("give either --record or --pulse, not both")
        if args.amplitude is None or args.pulse_period is None:
            raise InputError("--pulse needs --amplitude G and --pulse-period S")
        return one_pulse(args.pulse, args.amplitude, args.pulse_period)
    if not args.record:
        raise InputError("give the excitation: --record ID_OR_PATH, or --pulse cosine|sine")
    return resolve_motion(_suite(args), args.record).motion


def _add_records_option(parser):
    parser.add_argument("--records", metavar="PATH",
                        help="manifest (.toml), .AT2 or text file, or folder of .AT2 files; "
                             "default $ROCKING_AUDIT_RECORDS, else the built-in pulse-idealised suite")


def _add_excitation_options(parser):
    _add_records_option(parser)
    parser.add_argument("--record", metavar="ID_OR_PATH", help="record id of the suite, or a file")
    parser.add_argument("--pulse", choices=("cosine", "sine"), help="analytic one-cycle pulse")
    parser.add_argument("--amplitude", type=float, metavar="G", help="pulse amplitude a_p [g]")
    parser.add_argument("--pulse-period", type=float, metavar="S", help="pulse period T_p [s]")


def _plot_to(path: str, draw, height: float = 6.0) -> None:
    """Draw a matplotlib figure with ``draw(fig)`` and save it atomically to ``path``."""
    from reports.figures import save_figure
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    save_figure(draw, path, height=height)


def cmd_list(args) -> int:
    from procedures import available_procedures
    print("Procedures:")
    for name, cls in available_procedures().items():
        print(f"  {name:<16} {cls.title} — {cls.damping_law}; {cls.spectrum_source}")
    suite = _suite(args)
    print(f"\nRecords ({suite.description}):")
    for entry in suite:
        if entry.missing:
            state = f"MISSING: {entry.missing_reason}"
        else:
            m = entry.motion
            state = (f"PGA {m.pga_g:.3f} g, PGV {m.pgv:.2f} m/s, dt {m.dt:g} s, "
                     f"{m.duration:.1f} s — {m.source}")
        site = (f" [FEMA site {entry.site.get('site_class') or '?'}: S_XS {entry.site['sxs_g']:g} g, "
                f"S_X1 {entry.site['sx1_g']:g} g]" if entry.site.get("sxs_g") else "")
        print(f"  {entry.id:<20} {entry.name}: {state}{site}")
    return 0


def cmd_rock(args) -> int:
    from audit.block import RigidBlock
    from audit.rocking import simulate
    if (args.p is None) == (args.size is None):
        raise InputError("give the block size: exactly one of --p RAD_PER_S or --size SECONDS")
    alpha = math.radians(args.alpha)
    block = (RigidBlock(args.p, alpha, args.r) if args.p is not None
             else RigidBlock.from_size(args.size, alpha, args.r))
    motion = _motion(args)
    response = simulate(block, motion, free_motion_s=args.duration)
    result = {
        "record": motion.id, "p": block.p, "size_s": block.size_s, "alpha_deg": args.alpha,
        "r": block.r, "R_m": block.radius,
        "overturned": response.overturned,
        "overturn_time": None if math.isnan(response.overturn_time) else response.overturn_time,
        "peak_rotation": response.peak_rotation,
        "peak_rotation_ratio": response.peak_rotation_ratio,
        "peak_rotation_after_excitation": response.peak_rotation_after_excitation,
        "peak_angular_velocity": response.peak_angular_velocity,
        "impacts": response.n_impacts,
        "cycle_durations": response.cycle_durations.tolist(),
        "uplifted": response.uplifted,
    }
    if args.plot:
        from reports.figures import draw_time_histories
        _plot_to(args.plot, lambda fig: draw_time_histories(fig, [{
            "time": response.time, "theta_ratio": response.theta / block.alpha,
            "omega": response.omega,
            "title": f"{motion.id}: 2π/p = {block.size_s:.3g} s, α = {args.alpha:g}°",
            "rocking_span": (response.impact_times[0], response.impact_times[-1])
            if response.n_impacts else None,
            "cycle_starts": response.cycle_starts, "cycle_durations": response.cycle_durations,
            "excitation_end": motion.duration}]), height=3.9)
    if args.json:
        print(json.dumps(result))
        return 0
    state = (f"OVERTURNS at t = {response.overturn_time:.3f} s" if response.overturned
             else "survives" if response.uplifted else "does not uplift (PGA ≤ g tan α)")
    source = "" if motion.source in ("", "analytic pulse") else f" — {motion.source}"
    cycles = ", ".join(f"{d:.3f}" for d in response.cycle_durations[:8]) or "—"
    more = " …" if response.cycle_durations.size > 8 else ""
    print(f"Block p = {block.p:.4g} rad/s (2π/p = {block.size_s:.4g} s, R = {block.radius:.3g} m), "
          f"α = {args.alpha:g}°, r = {block.r:.4f}\n"
          f"Excitation: {motion.id}: {motion.component}{source}\n"
          f"Result: {state}\n"
          f"  peak |θ|                   {response.peak_rotation:.6g} rad = "
          f"{response.peak_rotation_ratio:.4f} α\n"
          f"  peak |θ| after excitation  "
          f"{response.peak_rotation_after_excitation / block.alpha:.4f} α\n"
          f"  peak |θ'|                  {response.peak_angular_velocity:.6g} rad/s\n"
          f"  impacts                    {response.n_impacts}\n"
          f"  full rocking cycles [s]    {cycles}{more}")
    if args.plot:
        print(f"Plot written to {args.plot}")
    return 0


def cmd_spectrum(args) -> int:
    motion = _motion(args)
    if args.free_motion is None:
        args.free_motion = 10.0 if args.kind == "rocking" else 0.0
    if args.kind == "response":
        from audit.oscillator import response_spectra
        damping = np.array(_float_list(args.damping, "--damping")) / 100.0
        periods = _grid(args.periods, "--periods", allow_zero=True)
        spectra = response_spectra(motion, periods, damping, args.free_motion)
        frame = spectra.to_frame()
        if args.plot:
            from reports.figures import draw_response_spectra
            _plot_to(args.plot, lambda fig: draw_response_spectra(fig, frame, motion.id))
    else:
        from audit.rocking import rocking_spectrum
        alphas = np.radians(_alphas_deg(args.alpha))
        spectrum = rocking_spectrum(motion, _sizes(args.sizes), alphas,
                                    free_motion_s=args.free_motion, jobs=args.jobs)
        frame = spectrum.to_frame()
        if args.plot:
            from reports.figures import draw_rocking_spectra
            _plot_to(args.plot, lambda fig: draw_rocking_spectra(fig, frame, motion.id))
    _write_csv(frame, args.csv)
    return 0


def _write_csv(frame, path):
    if path in (None, "-"):
        frame.to_csv(sys.stdout, index=False, float_format="%.8g")
        return
    from audit.results import write_files_atomically
    target = Path(path)
    write_files_atomically(target.parent if str(target.parent) else Path("."),
                           {target.name: frame.to_csv(index=False, float_format="%.8g").encode()})
    print(f"Wrote {len(frame)} rows to {path}", file=sys.stderr)


def cmd_design_spectrum(args) -> int:
    from audit.design_spectra import FEMA356Spectrum, UBC97Spectrum
    if args.code == "fema356":
        if args.sxs is None or args.sx1 is None:
            raise InputError("design-spectrum fema356 needs --sxs G and --sx1 G")
        spectrum = FEMA356Spectrum(args.sxs, args.sx1)
    else:
        spectrum = UBC97Spectrum(args.na, args.nv)
    periods = _grid(args.periods, "--periods", allow_zero=True)
    import pandas as pd
    frame = pd.concat([pd.DataFrame({
        "period_s": periods, "damping": d / 100.0,
        "sa_g": spectrum.acceleration(periods, d / 100.0),
        "sd": spectrum.displacement(periods, d / 100.0)})
        for d in _float_list(args.damping, "--damping")])
    _write_csv(frame, args.csv)
    return 0


def cmd_run(args) -> int:
    from audit.progress import Progress
    from audit.results import REPORT_HTML, save_run
    from audit.runner import run_audit
    from procedures import get_procedures
    from reports import render_report
    procedures = get_procedures(args.procedure)
    suite = _suite(args)
    sizes = _sizes(args.sizes)
    alphas = _alphas_deg(args.alpha)
    out_dir = Path(args.out) if args.out else Path(DEFAULT_OUT) / args.procedure
    start = time.perf_counter()
    run = run_audit(procedures, suite, alphas, sizes, jobs=args.jobs,
                    free_motion_s=args.free_motion, progress=Progress(len(suite), "records"))
    computed = time.perf_counter() - start
    save_run(run, out_dir, lambda saved: render_report(saved, processes=args.jobs))
    total = time.perf_counter() - start
    print(f"Audited {', '.join(p.name for p in procedures)} on {suite.description}")
    for item in run.summary["unauditable"]:
        print(f"  not audited: {item['procedure']} × {item['record']}: {item['reason']}")
    counts = run.results["verdict"].value_counts()
    print("Verdicts: " + ", ".join(f"{v} {n}" for v, n in counts.items()))
    print(f"Wrote {out_dir / REPORT_HTML} and results.csv, summary.json "
          f"({computed:.1f} s computing, {total:.1f} s in all)")
    return 0


def cmd_report(args) -> int:
    from audit.results import REPORT_HTML, load_run, write_files_atomically
    from reports import render_report
    run = load_run(args.results_dir)
    write_files_atomically(Path(args.results_dir), {REPORT_HTML: render_report(run).encode()})
    print(f"Wrote {Path(args.results_dir) / REPORT_HTML}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m audit",
        description="Audit seismic design-guideline procedures for rocking blocks against the "
                    "exact rocking response (Makris & Konstantinidis, PEER 2001/07).")
    parser.add_argument("--version", action="version", version=f"rocking-audit {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("list", help="registered procedures and the records of the record source")
    _add_records_option(p)
    p.set_defaults(func=cmd_list)

    p = sub.add_parser("rock", help="exact rocking response of one block")
    p.add_argument("--p", type=float, metavar="RAD_PER_S", help="frequency parameter p [rad/s]")
    p.add_argument("--size", type=float, metavar="SECONDS", help="block size 2π/p [s]")
    p.add_argument("--alpha", type=float, required=True, metavar="DEG", help="slenderness α [degrees]")
    p.add_argument("--r", type=float, help="coefficient of restitution (default Eq. 4.8)")
    _add_excitation_options(p)
    p.add_argument("--duration", type=float, default=10.0, metavar="S",
                   help="free motion simulated after the excitation [s] (default 10)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="draw θ/α and θ' against time")
    p.set_defaults(func=cmd_rock)

    p = sub.add_parser("spectrum", help="rocking spectra (default) or oscillator response spectra")
    p.add_argument("--kind", choices=("rocking", "response"), default="rocking")
    _add_excitation_options(p)
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
    p.set_defaults(func=cmd_spectrum)

    p = sub.add_parser("design-spectrum", help="code design spectrum (FEMA 356, UBC 97)")
    p.add_argument("code", choices=("fema356", "ubc97"))
    p.add_argument("--sxs", type=float, metavar="G", help="FEMA 356 S_XS [g]")
    p.add_argument("--sx1", type=float, metavar="G", help="FEMA 356 S_X1 [g]")
    p.add_argument("--na", type=float, default=1.0, help="UBC 97 near-source factor N_a")
    p.add_argument("--nv", type=float, default=1.0, help="UBC 97 near-source factor N_v")
    p.add_argument("--damping", default="5", metavar="PCT,...", help="damping ratios [%%]")
    p.add_argument("--periods", default="0:8:0.02", metavar="START:STOP:STEP", help="periods [s]")
    p.add_argument("--csv", metavar="FILE", help="CSV output (default: standard output)")
    p.set_defaults(func=cmd_design_spectrum)

    p = sub.add_parser("run", help="audit a procedure (or all) and write the HTML report")
    p.add_argument("procedure", help="registered procedure name, or 'all'")
    _add_records_option(p)
    p.add_argument("--alpha", default="10,15,20", metavar="DEG,...", help="slendernesses [degrees]")
    p.add_argument("--sizes", default="0.5:8:0.05", metavar="START:STOP:STEP",
                   help="block sizes 2π/p [s]")
    p.add_argument("--out", metavar="DIR", help=f"output directory (default {DEFAULT_OUT}/PROCEDURE)")
    p.add_argument("--jobs", type=int, default=2,
                   help="threads for the exact solver and processes drawing the report (default 2)")
    p.add_argument("--free-motion", type=float, default=10.0, metavar="S",
                   help="free motion after each record [s] (default 10)")
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("report", help="re-render report.html from a run's saved results")
    p.add_argument("results_dir", metavar="RESULTS_DIR")
    p.set_defaults(func=cmd_report)
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    if getattr(args, "jobs", 1) < 1:
        print("error: --jobs: must be at least 1", file=sys.stderr)
        return 2
    try:
        return args.func(args)
    except InputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # e.g. --out is a file, or a folder without write permission
        print(f"error: {exc.filename or ''}: {exc.strerror or exc}", file=sys.stderr)
        return 2


__all__ = ["main", "build_parser"]
