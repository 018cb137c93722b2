"""Numba kernels run compiled, or in the interpreter while a process's work is small.

Before numba runs its first kernel in a process it loads its compiler context and the cached
machine code (~0.5 s; compiling on a cold cache takes ~5 s), while the interpreter runs the same
kernel code at ~1–10 µs per step. A single short simulation (``audit rock`` on a pulse, the
figures of ``audit report``) is therefore faster interpreted. :func:`tiered` picks: compiled
once any kernel of the package is loaded in the process, or once the estimated time of the
interpreted runs would exceed :data:`INTERPRETED_BUDGET_S`; interpreted otherwise. Both
execute the same code in IEEE double precision (the interpreter calls libm's ``sin``/``cos``, as
the compiled code does; no fast-math), so they agree to rounding.
"""

from __future__ import annotations

import functools
import math
import sys
import types

from numba.core.registry import CPUDispatcher

#: Estimated interpreted run time, summed over a process, before kernels run compiled [s]:
#: about what loading the compiled code costs.
INTERPRETED_BUDGET_S = 0.4

_interpreted_s = 0.0
_compiled_seen = False


@functools.cache
def interpreted(kernel: CPUDispatcher):
    """``kernel`` as a plain Python function whose calls to other kernels, of its module or of
    the modules it imports them from, are plain Python functions too: the same code, run by
    the interpreter."""
    return _plain(kernel, {})


def _plain(kernel: CPUDispatcher, namespaces: dict):
    """``kernel``'s Python function run in a copy of its module's namespace in which every
    kernel is plain too; ``namespaces`` holds the copies made so far, one per module."""
    f = kernel.py_func
    key = id(f.__globals__)
    if key not in namespaces:
        namespace = namespaces[key] = dict(f.__globals__)
        for name, value in list(namespace.items()):
            if isinstance(value, CPUDispatcher):
                namespace[name] = _plain(value, namespaces)
    return types.FunctionType(f.__code__, namespaces[key], f.__name__, f.__defaults__,
                              f.__closure__)


def _any_compiled() -> bool:
    """Whether a kernel of ``audit.physics`` has compiled code in this process (remembered once
    true: compiled code stays loaded, and the scan of the modules costs ~0.1 ms a call)."""
    global _compiled_seen
    _compiled_seen = _compiled_seen or any(
        isinstance(value, CPUDispatcher) and value.signatures
        for name, module in list(sys.modules.items()) if name.startswith("audit.physics.")
        for value in list(vars(module).values()))
    return _compiled_seen


def machine_code_cached(kernel: CPUDispatcher) -> bool:
    """Whether numba holds cached machine code of ``kernel`` on disk that is current (stamped
    with today's sources, :mod:`audit.physics.kernel_cache`), so that a run loads it (~0.5 s)
    rather than compiling it (seconds; the first run after installing or updating)."""
    try:  # numba reads its cache's index in its FunctionCache, not in a public API
        return bool(kernel._cache._cache_file._load_index())
    except AttributeError:  # another numba layout: say nothing rather than guess
        return True


def expect(interpreted_s: float) -> None:
    """Judge a batch of runs estimated to take ``interpreted_s`` [s] interpreted, all together:
    beyond the budget every later :func:`tiered` call runs compiled, so a batch too large to
    interpret (a suite's records on a floor) does not interpret its first runs before loading
    the compiled code anyway; within it, each run is counted as it comes."""
    global _interpreted_s
    if _interpreted_s + interpreted_s > INTERPRETED_BUDGET_S:
        _interpreted_s = math.inf


def tiered(kernel: CPUDispatcher, interpreted_s: float):
    """``kernel`` compiled, or interpreted for a run estimated to take ``interpreted_s`` [s]
    that way, while the process's interpreted runs stay within :data:`INTERPRETED_BUDGET_S`."""
    global _interpreted_s
    if _interpreted_s + interpreted_s > INTERPRETED_BUDGET_S or _any_compiled():
        return kernel
    _interpreted_s += interpreted_s
    return interpreted(kernel)


__all__ = ["INTERPRETED_BUDGET_S", "expect", "interpreted", "machine_code_cached", "tiered"]
