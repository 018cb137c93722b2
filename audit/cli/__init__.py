"""Command-line interface: ``python -m audit {list,rock,spectrum,design-spectrum,run,report}``.

One module per command, each with ``add_parser(subparsers)`` and ``run(args)``; a command's
scientific imports happen inside its ``run``, so start-up and ``--help`` stay light. Angles are
typed in degrees and accelerations in g; everything inside is SI. Bad input is reported on one
line on stderr with exit status 2.
"""

from __future__ import annotations

import argparse
import sys

from audit import __version__
from audit.cli import design_spectrum, listing, report, rock, run, spectrum
from audit.errors import InputError

COMMANDS = (listing, rock, spectrum, design_spectrum, run, report)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m audit",
        description="Audit seismic design-guideline procedures for rocking blocks against the "
                    "exact rocking response (Makris & Konstantinidis, PEER 2001/07).")
    parser.add_argument("--version", action="version", version=f"rocking-audit {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.add_parser(sub)
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
