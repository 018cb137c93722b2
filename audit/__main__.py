"""``python -m audit``."""

import os
import sys

from audit.cli import EXIT_INTERRUPTED, main

code = main()
if code == EXIT_INTERRUPTED:
    # do not wait for solver threads still inside a compiled kernel: nothing of them is kept
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
sys.exit(code)
