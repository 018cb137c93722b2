"""Command-line interface: ``python -m audit COMMAND``, COMMAND one of list, check, rock,
spectrum, design-spectrum, floor-motion, run, margins, fragility, report, validate, pulse, atlas.

One module per command, each with ``add_parser(subparsers)`` and ``run(args)``; a command's
scientific imports happen inside its ``run``, so start-up and ``--help`` stay light. Angles are
typed in degrees and accelerations in g; everything inside is SI. Bad input is reported on one
line on stderr with exit status 2; Ctrl-C stops with one line and exit status 130.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import warnings

from audit import __version__
from audit.cli import (atlas, check, design_spectrum, floor_motion, fragility, listing, margins,
                       options, pulse, report, rock, run, spectrum, validate)
from audit.cli.flags import with_flags
from audit.cli.interrupts import EXIT_INTERRUPTED, interruptible, stop_threads
from audit.errors import InputError, InputWarning, NoAtlas

COMMANDS = (listing, check, rock, spectrum, design_spectrum, floor_motion, run, margins, fragility,
            report, validate, pulse, atlas)


#: A value that starts with a minus sign but is numbers, not an option: ``-118,34``,
#: ``-0.5``, ``-1e-3,2`` (argparse alone takes only ``-118`` or ``-0.5`` for a value).
_NUMBERS = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
                      r"(,\s*-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)*$")


class _Parser(argparse.ArgumentParser):
    """argparse with usage errors on one line (``error: COMMAND: what; see --help``), exit 2,
    and negative numbers and lists of numbers taken as values (``--site-location -118,34``):
    no option of the tool looks like a number. Its subcommands' parsers are of this class too
    (argparse makes them of the parent's class)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NUMBERS

    def error(self, message):
        message = " ".join(message.split())
        print(f"error: {self.prog}: {message} (see {self.prog} --help)", file=sys.stderr)
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="python -m audit",
        description="Audit seismic design-guideline procedures for rocking blocks against the "
                    "exact rocking response (Makris & Konstantinidis, PEER 2001/07).")
    parser.add_argument("--version", action="version", version=f"rocking-audit {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.add_parser(sub)
    return parser


def main(argv=None) -> int:
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:  # usage error (one line printed), --help or --version
        return exc.code if isinstance(exc.code, int) else 2
    with interruptible(), warnings.catch_warnings():
        # a user sees the tool's own warnings, one line each, never a library's deprecation
        # notices (Python hides those outside __main__ too; a test runner shows them)
        warnings.simplefilter("ignore", DeprecationWarning)
        warnings.simplefilter("ignore", PendingDeprecationWarning)
        warnings.simplefilter("always", InputWarning)
        warnings.showwarning = _one_line_warning
        code = _run(args)
        if code == EXIT_INTERRUPTED:
            stop_threads()
        return code


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    text = str(message)
    field = text.partition(":")[0]
    print(f"warning: {' '.join(with_flags(text, (field,)).split())}", file=sys.stderr)


def _run(args) -> int:
    try:
        if getattr(args, "jobs", None) is not None:
            args.jobs = options.cap_jobs(args.jobs)
        return args.func(args)
    except NoAtlas as exc:  # the atlas command that builds it, in the command line's words
        from audit.cli.atlas import build_command
        steps = [] if exc.build is None else [f"build it with '{build_command(exc.build)}'"]
        steps += ["use --method direct"] if exc.field == "method" else []
        asked = "atlas asked, but " if exc.field == "method" else ""
        print(f"error: {with_flags(exc.field, (exc.field,))}: {asked}{' '.join(exc.reason.split())}"
              + ("; " + ", or ".join(steps) if steps else ""), file=sys.stderr)
        return 2
    except InputError as exc:
        message = with_flags(str(exc), getattr(exc, "fields", ()))
        print(f"error: {' '.join(message.split())}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader of standard output (e.g. `| head`) has gone
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 0
    except OSError as exc:  # e.g. a folder without read permission
        where = exc.filename or ""
        print(f"error: {where}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted; nothing written", file=sys.stderr)
        return EXIT_INTERRUPTED


__all__ = ["main", "build_parser", "EXIT_INTERRUPTED"]
