"""Nanoseconds per Runge–Kutta step of the exact solver: today's step (one libm sin and cos, the
stages turned by angle addition) against the step it replaced (a libm sin and cos at each of
the four stages, kept in benchmarks/four_libm_step.py only), and one libm sin and cos on their
own for reference.

    python benchmarks/solver_step.py [--rounds 15] [--steps 2000000]

Both steps march the same block (p = 2 rad/s, α = 15°, h = 1/(40 p)) under the same sampled
ground motion (a sine of 1.5 g tan α, linear between samples; the pivot switches where θ
changes sign and the block is set back at rest where it would overturn, so it rocks
throughout). The three loops run in alternation in one process, rounds apart, and the medians
are printed with the load average. Each loop is timed by the CPU time of its thread, not the
wall clock, so that the other processes of a loaded machine do not count; the largest
difference of θ between the two marches shows they integrate the same motion to rounding.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit.physics.rocking.motion_equation import _SAMPLED, _rk4  # noqa: E402
from four_libm_step import rk4_four_libm  # noqa: E402


def _marcher(step):
    @numba.njit
    def march(acc, h, p2, alpha, g, theta_out):
        theta, omega, side = 0.0, 0.0, -1.0
        for i in range(acc.size - 1):
            t = i * h
            theta, omega = step(theta, omega, t, h, side, p2, alpha, g, _SAMPLED, acc[i],
                                (acc[i + 1] - acc[i]) / h, t, 0.0, 0.0, 0.0, 0.0)
            if side * theta < 0.0:
                side = -side
            if abs(theta) >= alpha:
                theta, omega = 0.0, 0.0
            theta_out[i] = theta
        return theta
    return march


_march_new = _marcher(_rk4)
_march_old = _marcher(rk4_four_libm)


@numba.njit
def _sincos(angles):
    total = 0.0
    for x in angles:
        total += math.sin(x) * math.cos(x)
    return total


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--steps", type=int, default=2_000_000)
    args = parser.parse_args()
    p, alpha, g = 2.0, math.radians(15.0), 9.81
    h = 1.0 / (40.0 * p)
    t = np.arange(args.steps + 1) * h
    acc = 1.5 * g * math.tan(alpha) * np.sin(2.0 * math.pi * t / 1.3)
    angles = np.linspace(-alpha, alpha, args.steps)  # the range φ = sα − θ takes
    theta_old, theta_new = np.empty(args.steps), np.empty(args.steps)
    work = {"four sin/cos pairs (before)": lambda: _march_old(acc, h, p * p, alpha, g, theta_old),
            "one sin/cos pair + angle addition": lambda: _march_new(acc, h, p * p, alpha, g,
                                                                    theta_new),
            "one libm sin and cos alone": lambda: _sincos(angles)}
    for run in work.values():
        run()  # compile
    times = {name: [] for name in work}
    loads = []
    for i in range(args.rounds):
        loads.append(os.getloadavg()[0])
        for name in (list(work) if i % 2 == 0 else list(work)[::-1]):
            begin = time.thread_time()
            work[name]()
            times[name].append((time.thread_time() - begin) / args.steps * 1e9)
    print(f"{args.steps} steps, {args.rounds} alternating rounds, load average "
          f"{min(loads):.2f}–{max(loads):.2f}; CPU ns per step (median, min–max):")
    for name, values in times.items():
        print(f"  {name:36s} {statistics.median(values):6.1f}  "
              f"({min(values):.1f}–{max(values):.1f})")
    old, new = (statistics.median(times[n]) for n in list(work)[:2])
    print(f"  ratio new/old {new / old:.3f}")
    print(f"largest |θ_new − θ_old| over the march: {np.max(np.abs(theta_new - theta_old)):.2e} "
          f"rad (α = {alpha:.4f} rad; {np.count_nonzero(theta_new)} steps rocking)")


if __name__ == "__main__":
    main()
