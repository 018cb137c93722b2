"""Parsing and checking of the options shared by several commands, and writing their outputs.

Light on purpose: importing this module loads numpy and the project's error type, nothing else,
so ``--help`` and option errors cost no scientific import.
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path

import numpy as np

from audit.errors import InputError


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
    values = float_list(text, "--alpha")
    for value in values:
        if not 0 < value < 45:
            raise InputError(f"--alpha: slenderness must lie between 0 and 45 degrees, got {value:g}")
    return np.array(values)


def time_grid(text: str, option: str, allow_zero: bool = False) -> np.ndarray:
    """START:STOP:STEP (inclusive) or a comma list of times [s] given to ``option``."""
    from audit.engine.grid import size_grid
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
        values = np.array(float_list(text, option))
        if np.any(values < 0) or (not allow_zero and np.any(values == 0)):
            raise InputError(f"{option}: every value must be {'≥ 0' if allow_zero else '> 0'} s, "
                             f"got '{text}'")
        return values
    raise InputError(f"{option}: expected START:STOP:STEP or a comma list in seconds, got '{text}'")


def sizes(text: str) -> np.ndarray:
    """Block sizes 2π/p [s] of ``--sizes``."""
    return time_grid(text, "--sizes")


def positive(value: float, option: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{option}: must be a positive number, got {value:g}")
    return value


def suite(args):
    """The record suite of ``--records`` (or its defaults)."""
    from records import ENV_VARIABLE, load_records
    # absolute, so the files an audit writes name the records wherever they are read from
    path = args.records or os.environ.get(ENV_VARIABLE)
    return load_records(os.path.abspath(path) if path else None)


def motion(args):
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
    return resolve_motion(suite(args), args.record).motion


def add_records_option(parser):
    parser.add_argument("--records", metavar="PATH",
                        help="manifest (.toml), .AT2 or text file, or folder of .AT2 files; "
                             "default $ROCKING_AUDIT_RECORDS, else the built-in pulse-idealised suite")


def add_excitation_options(parser):
    add_records_option(parser)
    parser.add_argument("--record", metavar="ID_OR_PATH", help="record id of the suite, or a file")
    parser.add_argument("--pulse", choices=("cosine", "sine"), help="analytic one-cycle pulse")
    parser.add_argument("--amplitude", type=float, metavar="G", help="pulse amplitude a_p [g]")
    parser.add_argument("--pulse-period", type=float, metavar="S", help="pulse period T_p [s]")


def plot_to(path: str, draw, height: float = 6.0) -> None:
    """Draw a matplotlib figure with ``draw(fig)`` and save it atomically to ``path``."""
    from reports.figures import save_figure
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    save_figure(draw, path, height=height)


def write_csv(frame, path):
    """``frame`` as CSV to ``path`` (atomically) or to standard output for None or ``-``."""
    if path in (None, "-"):
        frame.to_csv(sys.stdout, index=False, float_format="%.8g")
        return
    from audit.engine.results import write_files_atomically
    target = Path(path)
    write_files_atomically(target.parent if str(target.parent) else Path("."),
                           {target.name: frame.to_csv(index=False, float_format="%.8g").encode()})
    print(f"Wrote {len(frame)} rows to {path}", file=sys.stderr)
