"""Derive the golden audit values of ``seed_blocks.csv`` by a path independent of the tool.

- exact θ: :func:`audit.physics.reference.simulate_reference` (scipy ``solve_ivp``, DOP853, events),
  not the fast solver;
- Priestley's spectrum: ``scipy.signal.lsim`` (first-order hold) at each period the iteration
  asks for, not the tool's recurrence and interpolation;
- FEMA 356: the spectrum and Table 1-6 written out again from SPEC §6;
- the fixed-point iteration and the verdict written out again from SPEC §5 and the runner's
  definitions.

The blocks were chosen (from a run of the tool) to cover every verdict class on every available
record; only their values come from here. Run from the repository root:

    ROCKING_AUDIT_RECORDS=../shared/records/seed-suite.toml python tests/golden/make_golden.py
"""

import csv
import math
import sys
from pathlib import Path

import numpy as np
from scipy import signal

from audit.physics.block import RigidBlock
from audit.physics.reference import simulate_reference
from records import load_records

G = 9.81
FREE_MOTION_S = 10.0
BLOCKS = {  # record: [(procedure, α [deg], 2π/p [s]), ...]
    "pacoima_dam_1971": [("priestley1978", 20, 0.5), ("priestley1978", 20, 2.75),
                         ("priestley1978", 20, 5.0), ("priestley1978", 10, 5.8),
                         ("fema356", 10, 6.0), ("fema356", 20, 6.0), ("fema356", 15, 1.0)],
    "rinaldi_1994": [("priestley1978", 15, 2.0), ("priestley1978", 15, 6.0),
                     ("priestley1978", 15, 3.95),
                     ("priestley1978", 10, 4.0), ("fema356", 20, 7.5), ("fema356", 15, 4.0)],
    "sylmar_1994": [("priestley1978", 10, 6.0), ("priestley1978", 20, 5.0),
                    ("priestley1978", 10, 5.0), ("priestley1978", 10, 7.9),
                    ("fema356", 20, 5.0), ("fema356", 10, 8.0)],
    "erzincan_1992": [("priestley1978", 10, 4.0), ("priestley1978", 15, 6.5),
                      ("priestley1978", 20, 3.0)],
    "takatori_1995": [("priestley1978", 15, 6.0), ("priestley1978", 20, 7.0),
                      ("priestley1978", 10, 1.0), ("priestley1978", 15, 7.35),
                      ("priestley1978", 35, 3.0)],
}
SITES = {"pacoima_dam_1971": (1.59, 0.50), "rinaldi_1994": (1.56, 0.69),
         "sylmar_1994": (1.56, 0.80)}
TABLE_1_6 = [(0.02, 0.8, 0.8), (0.05, 1.0, 1.0), (0.10, 1.3, 1.2), (0.20, 1.8, 1.5),
             (0.30, 2.3, 1.7), (0.40, 2.7, 1.9), (0.50, 3.0, 2.0)]


def fema_sd(period, beta, sxs, sx1):
    betas, bs, b1 = zip(*TABLE_1_6)
    b_s, b_1 = float(np.interp(beta, betas, bs)), float(np.interp(beta, betas, b1))
    t_s = sx1 * b_s / (sxs * b_1)
    t_0 = 0.2 * t_s
    if period < t_0:
        sa = sxs * ((5 / b_s - 2) * period / t_s + 0.4)
    elif period <= t_s:
        sa = sxs / b_s
    else:
        sa = sx1 / (b_1 * period)
    return sa * G * period ** 2 / (4 * math.pi ** 2)


def lsim_sd(motion, period, beta):
    if period == 0:
        return 0.0
    acc = np.concatenate((motion.acceleration, np.zeros(int(round(FREE_MOTION_S / motion.dt)))))
    t = np.arange(acc.size) * motion.dt
    w = 2 * math.pi / period
    system = signal.lti([[0, 1], [-w * w, -2 * beta * w]], [[0], [1]], [[1, 0]], [[0]])
    _, y, _ = signal.lsim(system, -acc, t, interp=True)
    return float(np.max(np.abs(y)))


def iterate(sd, p, alpha):
    """SPEC §5 steps 2–6 with θ₀/α = 0.1, |Δθ|/α ≤ 1e-6, at most 2000 iterations."""
    radius = 3 * G / (4 * p ** 2)
    x = 0.1
    for i in range(1, 2001):
        period = 4 / p * math.acosh(1 / (1 - x))
        new = sd(period) / (radius * math.cos(alpha)) / alpha
        if new >= 1:
            return "overturn", math.nan, i
        if abs(new - x) <= 1e-6:
            return "converged", new * alpha, i
        x = new
    return "not-converged", math.nan, 2000


def verdict(exact, outcome, approx):
    if outcome == "no-uplift" and exact["n_impacts"] == 0 and exact["peak_rotation"] == 0:
        return "no-uplift"
    if outcome == "not-converged":
        return "not-converged"
    if exact["overturned"]:
        return "both-overturn" if outcome == "overturn" else "missed-overturn"
    if outcome == "overturn":
        return "false-overturn"
    return "conservative" if approx >= exact["peak_rotation"] else "unconservative"


def main(out=Path(__file__).with_name("seed_blocks.csv")):
    suite = load_records()
    rows = []
    for record, blocks in BLOCKS.items():
        motion = suite.get(record).motion
        for procedure, alpha_deg, size in blocks:
            alpha = math.radians(alpha_deg)
            block = RigidBlock.from_size(size, alpha)
            r = (1 - 1.5 * math.sin(alpha) ** 2) ** 2
            exact = simulate_reference(block, motion, FREE_MOTION_S)
            if procedure == "priestley1978" and motion.pga <= G * math.tan(alpha):
                beta, outcome, approx, iterations = -0.34 * math.log(r), "no-uplift", 0.0, 0
            elif procedure == "priestley1978":
                beta = -0.34 * math.log(r)
                cache = {}  # a 2-cycle asks for the same two periods again and again
                outcome, approx, iterations = iterate(
                    lambda t: cache.setdefault(t, lsim_sd(motion, t, beta)), block.p, alpha)
            else:
                beta = 0.4 * (1 - math.sqrt(r))
                outcome, approx, iterations = iterate(
                    lambda t: fema_sd(t, beta, *SITES[record]), block.p, alpha)
            rows.append({"record": record, "procedure": procedure, "alpha_deg": alpha_deg,
                         "size_s": size, "exact_theta": exact["peak_rotation"],
                         "exact_overturned": exact["overturned"], "approx_theta": approx,
                         "approx_outcome": outcome, "verdict": verdict(exact, outcome, approx)})
            print(rows[-1], file=sys.stderr)
    with open(out, "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=list(rows[0]))
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.8g}" if isinstance(v, float) else v) for k, v in row.items()})


if __name__ == "__main__":
    main()
