"""The Runge–Kutta step the exact solver took before issue 48 (a libm sin and cos at each of
its four stages), kept for the benchmarks alone, and the solver compiled again around any step,
so that the step before and today's can be measured and compared in one process
(``benchmarks/solver_step.py``, ``benchmarks/solver_fidelity.py``). Nothing in the product
imports this module.
"""

from __future__ import annotations

import math
import sys
import types
from pathlib import Path

import numba

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit.physics.rocking import kernel, motion_equation, spectrum  # noqa: E402
from audit.physics.rocking.motion_equation import _ground  # noqa: E402


@numba.njit(inline="always")
def _theta_acc_four_libm(theta, ug, uv, side, p2, alpha, g):
    phi = side * alpha - theta
    return -p2 * ((1.0 + uv / g) * math.sin(phi) + ug / g * math.cos(phi))


@numba.njit(nogil=True)
def rk4_four_libm(theta, omega, t, h, side, p2, alpha, g, kind, a0, slope, t0, amp, omega_p,
                  v0, vslope):
    """The step as it was at 1446a85: a libm sin and cos at each stage."""
    u1 = _ground(t, kind, a0, slope, t0, amp, omega_p)
    u2 = _ground(t + 0.5 * h, kind, a0, slope, t0, amp, omega_p)
    u3 = _ground(t + h, kind, a0, slope, t0, amp, omega_p)
    w1 = v0 + vslope * (t - t0)
    w2 = v0 + vslope * (t + 0.5 * h - t0)
    w3 = v0 + vslope * (t + h - t0)
    k1t = omega
    k1w = _theta_acc_four_libm(theta, u1, w1, side, p2, alpha, g)
    k2t = omega + 0.5 * h * k1w
    k2w = _theta_acc_four_libm(theta + 0.5 * h * k1t, u2, w2, side, p2, alpha, g)
    k3t = omega + 0.5 * h * k2w
    k3w = _theta_acc_four_libm(theta + 0.5 * h * k2t, u2, w2, side, p2, alpha, g)
    k4t = omega + h * k3w
    k4w = _theta_acc_four_libm(theta + h * k3t, u3, w3, side, p2, alpha, g)
    return (theta + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t),
            omega + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w))


def _compiled(function, namespace: dict):
    """``function`` (a kernel) compiled again with its global names looked up in ``namespace``."""
    f = function.py_func
    return numba.njit(nogil=True)(types.FunctionType(f.__code__, namespace, f.__name__,
                                                     f.__defaults__, f.__closure__))


def spectrum_with_step(step):
    """The product's many-block kernel (``kernel._spectrum``) compiled again, with the event
    location and the solver around it, so that every Runge–Kutta step is ``step``."""
    equation = {**vars(motion_equation), "_rk4": step}
    solver = {**vars(kernel), "_rk4": step}
    solver["_locate"] = _compiled(motion_equation._locate, equation)
    solver["_simulate"] = _compiled(kernel._simulate, solver)
    return _compiled(kernel._spectrum, solver)


class StepSwapped:
    """Within ``with StepSwapped(step):`` every ``rocking_blocks`` (and what calls it: the
    margins' stripes) solves with ``step``."""

    def __init__(self, step):
        self.kernel = spectrum_with_step(step)

    def __enter__(self):
        self.saved, spectrum._spectrum = spectrum._spectrum, self.kernel
        return self

    def __exit__(self, *exc):
        spectrum._spectrum = self.saved
