"""``python -m audit``."""

import os
import sys

from audit.cli import main

code = main()
# Every output is written, renamed into place and closed, and a Dask cluster is shut down,
# by now. Leave without the interpreter's teardown: it spends ~0.3 s freeing numba's compiled
# code and the run's arrays, and after Ctrl-C it would wait for solver threads still inside a
# compiled kernel, of which nothing is kept.
sys.stdout.flush()
sys.stderr.flush()
os._exit(code)
