"""A progress line for long runs: on a terminal only, silent in CI and when piped."""

from __future__ import annotations

import os
import sys
import time


class Progress:
    """Counts steps of a run on one self-overwriting stderr line.

    Parameters
    ----------
    total : int
        Number of steps.
    label : str
        What is counted ("records").
    enabled : bool, optional
        Default: stderr is a terminal and the ``CI`` variable is not ``true``.
    """

    def __init__(self, total: int, label: str, enabled: bool | None = None):
        if enabled is None:
            enabled = sys.stderr.isatty() and os.environ.get("CI", "").lower() != "true"
        self.total, self.label, self.enabled = total, label, enabled
        self.count = 0
        self.start = time.perf_counter()

    def step(self, what: str = "") -> None:
        """Announce the next step (``what`` is being worked on)."""
        self.count += 1
        if self.enabled:
            width = 24
            filled = int(width * (self.count - 1) / max(self.total, 1))
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.count}/{self.total} "
                             f"{self.label}  {what:<28.28} {time.perf_counter() - self.start:5.1f} s")
            sys.stderr.flush()

    def done(self) -> None:
        """Finish the line."""
        if self.enabled:
            sys.stderr.write(f"\r{' ' * 78}\r")
            sys.stderr.flush()
