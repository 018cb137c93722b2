"""Progress of long runs on stderr, from tqdm: a bar on a terminal, one line per step otherwise
(CI logs, pipes), so a person always sees what the run is doing."""

from __future__ import annotations

import sys
import time

from tqdm import tqdm


class Progress:
    """Counts steps of a run and announces stages.

    Parameters
    ----------
    total : int
        Number of steps.
    label : str
        What is counted ("records").
    enabled : bool, optional
        Default True; False keeps the run silent (library use, tests).
    """

    def __init__(self, total: int, label: str, enabled: bool = True):
        self.total, self.label, self.enabled = total, label, enabled
        self.count = 0
        self.start = time.perf_counter()
        self.terminal = enabled and sys.stderr.isatty()
        self.bar = (tqdm(total=total, unit=label.rstrip("s") or "step", file=sys.stderr,
                         dynamic_ncols=True, leave=False) if self.terminal else None)

    def __call__(self, done: int, total: int, what: str, how: str = "") -> None:
        """``done`` of ``total`` steps are finished, the last being ``what`` (``how`` in words);
        the signature of :func:`audit.engine.run.pipeline.audit_in_memory`'s ``progress``."""
        self.count, self.total = done, total
        if self.bar is not None:
            if done < self.bar.n:  # a new pass over the same records
                self.bar.reset(total=total)
            self.bar.total = total
            self.bar.update(done - self.bar.n)
            self.bar.set_postfix_str(what)
        elif self.enabled:
            self.stage(f"{self.label} {done}/{total}: {what}" + (f" ({how})" if how else ""))

    def stage(self, text: str) -> None:
        """One line saying what the run does now, with the time elapsed.

        Parameters
        ----------
        text : str
            What the run does now.
        """
        if self.enabled:
            tqdm.write(f"[{time.perf_counter() - self.start:6.1f} s] {text}", file=sys.stderr)

    def done(self) -> None:
        """Finish the bar."""
        if self.bar is not None:
            self.bar.update(self.total - self.bar.n)
            self.bar.close()
            self.bar = None
