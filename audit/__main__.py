"""``python -m audit``."""

import os
import signal
import sys


def _interrupted_starting(signum, frame):
    """Ctrl-C while the command line is read in, before the command's own handler
    (:mod:`audit.cli.interrupts`) is set: the same one line and exit status, not a traceback."""
    print("interrupted; nothing written", file=sys.stderr)
    sys.stderr.flush()
    os._exit(128 + signal.SIGINT)


signal.signal(signal.SIGINT, _interrupted_starting)
from audit.cli import main  # noqa: E402  (after the handler: its imports take ~0.5 s)

code = main()
# Every output is written, renamed into place and closed, and a Dask cluster is shut down,
# by now. Leave without the interpreter's teardown: it spends ~0.3 s freeing numba's compiled
# code and the run's arrays, and after Ctrl-C it would wait for solver threads still inside a
# compiled kernel, of which nothing is kept.
sys.stdout.flush()
sys.stderr.flush()
os._exit(code)
