"""Ctrl-C stops a command wherever its main thread is: one line, exit status 130.

Python raises KeyboardInterrupt in whatever Python code the main thread runs when the signal
comes. Where that code is a callback called from C, the exception cannot reach the command: the
object-cache hooks that llvmlite calls through ctypes while numba compiles the solver or loads
it from its cache, or a finaliser. Python prints "Exception ignored …" and the command carries
on to exit 0. Such a lost interruption is caught by ``sys.unraisablehook`` and delivered again
from a helper thread until it lands in code that raises it.
"""

from __future__ import annotations

import _thread
import os
import signal
import sys
import threading
import time
from contextlib import contextmanager

#: Exit status of a run stopped by Ctrl-C (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130
#: How soon a lost interruption is delivered again [s].
REDELIVERY_S = 0.01
#: Longest wait for the threads still computing after Ctrl-C [s]: a compiled kernel runs to
#: its end (a chunk of blocks of one record), then its thread stops at its next call.
STOP_TIMEOUT_S = 60.0


def stop_threads(timeout_s: float = STOP_TIMEOUT_S) -> None:
    """After Ctrl-C, before the process leaves: no compiled kernel starts any more, and the
    threads still computing (kernels, records beside the main thread) are joined, so that the
    process never exits, or frees what they read, under a kernel running on another thread
    (that ended a run interrupted early in signal 11 instead of exit status 130). A second
    Ctrl-C stops the wait."""
    from audit.api import KERNEL_THREADS, stop_kernels
    deadline = time.monotonic() + timeout_s
    try:
        stop_kernels(timeout_s)
        for thread in threading.enumerate():
            if (thread is not threading.main_thread() and not thread.daemon
                    and not thread.name.startswith(KERNEL_THREADS)):
                thread.join(max(0.0, deadline - time.monotonic()))
    except KeyboardInterrupt:
        pass


@contextmanager
def interruptible():
    """SIGINT raises KeyboardInterrupt in the main thread of this process, and reliably so;
    a worker process forked meanwhile exits with :data:`EXIT_INTERRUPTED` (its main process
    reports the interruption, once). The previous handler and hook are restored on exit."""
    main_pid = os.getpid()
    state = {"lost": False, "active": True, "redelivery": None}

    def on_interrupt(signum, frame):
        if os.getpid() != main_pid:
            os._exit(EXIT_INTERRUPTED)
        if _runs(on_lost.__code__, frame):
            state["lost"] = True  # raised inside the hook it would be lost again
            return
        raise KeyboardInterrupt

    def redeliver():
        while state["active"]:
            time.sleep(REDELIVERY_S)
            if state["lost"]:
                state["lost"] = False
                _thread.interrupt_main(signal.SIGINT)

    def on_lost(unraisable):
        if os.getpid() != main_pid or not isinstance(unraisable.exc_value, KeyboardInterrupt):
            previous_hook(unraisable)
            return
        state["lost"] = True
        if state["redelivery"] is None:
            state["redelivery"] = threading.Thread(target=redeliver, daemon=True,
                                                   name="ctrl-c redelivery")
            state["redelivery"].start()

    previous_handler = signal.signal(signal.SIGINT, on_interrupt)
    previous_hook = sys.unraisablehook
    sys.unraisablehook = on_lost
    try:
        yield
    finally:
        state["active"] = False
        sys.unraisablehook = previous_hook
        signal.signal(signal.SIGINT, previous_handler)


def _runs(code, frame) -> bool:
    """Whether ``code`` is on the stack of ``frame``."""
    while frame is not None:
        if frame.f_code is code:
            return True
        frame = frame.f_back
    return False
