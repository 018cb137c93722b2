"""Synthetic shake-table campaigns whose truth is known, with outcomes from an *independent*
solver (scipy ``solve_ivp`` with events), written in the folder format records/campaign.py reads.

The solver integrates SPEC.md's Eq. 4.3 on the current pivot,

    θ'' = −p² { sin(s α − θ) + (üg/g) cos(s α − θ) },   s = ±1 the side rocked on,

with the ground acceleration read linearly between the samples written to the campaign (the
motion the tool reads), an event at θ = 0 (impact: θ' ← sqrt(r) θ', Eq. 4.6–4.8 with
r = (1 − 1.5 sin²α)²) and one at |θ| = α (overturned). The block starts at rest and uplifts
when |üg| > g tan α, a positive üg starting a negative rotation; after an impact too slow to
matter it rests until the ground can lift it again. Nothing of the project's solver is used.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp
from scipy.signal import butter, sosfiltfilt

G = 9.81
DT = 0.01
#: Free rocking after each record, in both solvers [s].
FREE_MOTION_S = 4.0
#: Below this angular velocity after an impact [rad/s per rad/s of p] the block is at rest.
_REST = 1e-4


def overturns(acc_g: np.ndarray, alpha_rad: float, p_rad_s: float, factor: float = 1.0,
              dt: float = DT, free_motion_s: float = FREE_MOTION_S) -> bool:
    """Whether the block (α, p, restitution ``factor`` × Eq. 4.8) overturns under the sampled
    ground acceleration ``acc_g`` [g] (read linearly between samples, zero after the record,
    then ``free_motion_s`` of free rocking)."""
    times = np.arange(acc_g.size) * dt
    end = times[-1] + free_motion_s
    r = factor * (1.0 - 1.5 * math.sin(alpha_rad) ** 2) ** 2
    lift = math.tan(alpha_rad)

    def ground(t):
        return np.interp(t, times, acc_g, right=0.0)

    def rhs(t, y, side):
        angle = side * alpha_rad - y[0]
        return (y[1], -p_rad_s ** 2 * (math.sin(angle) + ground(t) * math.cos(angle)))

    t = 0.0
    while True:
        # at rest: the first time the ground lifts the block (linear between samples)
        strong = np.flatnonzero((np.abs(acc_g) > lift) & (times >= t))
        if strong.size == 0:
            return False
        k = strong[0]
        if k > 0 and times[k - 1] >= t:
            a0, a1 = abs(acc_g[k - 1]), abs(acc_g[k])
            t = times[k - 1] + dt * (lift - a0) / (a1 - a0)
        else:
            t = max(t, times[k])
        side = -1.0 if acc_g[k] > 0 else 1.0
        y = (0.0, 0.0)
        while True:
            def impact(t, y, side=side):
                return y[0]
            impact.terminal, impact.direction = True, -side

            def topple(t, y, side=side):
                return side * y[0] - alpha_rad
            topple.terminal, topple.direction = True, 1.0
            sol = solve_ivp(rhs, (t, end), y, args=(side,), events=(impact, topple),
                            rtol=1e-7, atol=1e-10, max_step=4 * dt)
            if sol.t_events[1].size:
                return True
            if not sol.t_events[0].size:
                return False  # rocking through the end of the free motion
            t = float(sol.t_events[0][0])
            omega = math.sqrt(r) * float(sol.y_events[0][0][1])
            if abs(omega) < _REST * p_rad_s:
                break  # comes to rest; waits for the ground to lift it again
            side, y = -side, (0.0, omega)
            if t >= end:
                return False


def record(kind: int, period_s: float, rng) -> np.ndarray:
    """A table record [g, unit peak]: one-sine, one-cosine, a three-cycle enveloped burst or
    enveloped noise low-passed at 8 Hz; 0.5 s of rest before it and 0.5 s after."""
    if kind < 3:
        cycles = (1, 1, 3)[kind]
        t = np.arange(0.0, cycles * period_s, DT)
        phase = 2 * np.pi * t / period_s
        wave = (np.sin(phase), np.cos(phase),
                np.sin(phase) * np.sin(np.pi * t / (cycles * period_s)))[kind]
    else:
        t = np.arange(0.0, 6.0, DT)
        sos = butter(4, [0.3, 8.0], "bandpass", fs=1 / DT, output="sos")
        wave = sosfiltfilt(sos, rng.standard_normal(t.size)) * np.sin(np.pi * t / t[-1]) ** 2
    pad = np.zeros(int(round(0.5 / DT)))
    acc = np.concatenate((pad, wave, pad))
    return acc / np.max(np.abs(acc))


def write_campaign(folder: Path, alpha_deg: float, p_rad_s: float, *, seed: int,
                   records: int = 12, scales: int = 8, factor: float = 1.0,
                   heldout: int = 0, specimen: str = "spec") -> dict:
    """Write a campaign of ``records`` × ``scales`` tests of the block (α, p, factor) to
    ``folder``; ``heldout`` tests, drawn at random, get an empty outcome.

    The records mix the four kinds of :func:`record` with periods 0.3–2 s. Each is scaled to
    peaks of 1.02–3 × the uplift acceleration g tan α (log-spaced, jittered per record), so
    both outcomes are well represented.

    Returns
    -------
    dict
        ``outcome`` (every test's, bool), ``heldout`` (indices), ``tests`` (ids).
    """
    rng = np.random.default_rng(seed)
    (folder / "motions").mkdir(parents=True)
    alpha = math.radians(alpha_deg)
    rows, outcomes = [], []
    for i in range(records):
        base = record(i % 4, float(rng.uniform(0.3, 2.0)), rng)
        jitter = rng.uniform(0.9, 1.1)
        for level in np.geomspace(1.02, 3.0, scales) * jitter:
            test = f"T{len(rows):03d}"
            acc = np.round(base * level * math.tan(alpha), 5)
            pd.DataFrame({"time_s": np.round(np.arange(acc.size) * DT, 2),
                          "acc_g": acc}).to_csv(folder / "motions" / f"{test}.csv.gz",
                                                index=False)
            rows.append({"test": test, "ground_motion": f"rec{i}",
                         "motion_file": f"motions/{test}.csv.gz"})
            outcomes.append(overturns(acc, alpha, p_rad_s, factor))
    frame = pd.DataFrame(rows)
    outcome = np.array(outcomes)
    frame[f"{specimen}_overturned"] = outcome.astype(int).astype(object)
    hidden = rng.choice(len(rows), heldout, replace=False) if heldout else np.array([], int)
    frame.loc[hidden, f"{specimen}_overturned"] = ""
    frame.to_csv(folder / "tests.csv", index=False)
    return {"outcome": outcome, "heldout": hidden, "tests": frame["test"].to_numpy()}


__all__ = ["overturns", "record", "write_campaign", "FREE_MOTION_S", "DT"]
