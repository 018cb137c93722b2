"""Speed and accuracy of the exact rocking solver against a plain solve_ivp implementation.

(a) :func:`audit.physics.reference.simulate_reference` — scipy ``solve_ivp`` with DOP853, rtol 1e-10,
    atol 1e-13, max_step = record dt, events for impacts, turning points and overturning — on a
    sample of blocks of the default grid;
(b) the project's :func:`audit.physics.rocking.rocking_spectrum` on the full default grid
    (α = 10, 15, 20°; 2π/p = 0.5 … 8 s step 0.05) of ``pacoima_dam_1971``;
then the whole seed suite's spectra. A sampled block counts as "near the overturning boundary"
when scaling the record by 0.99 or 1.01 changes whether it overturns.

    ROCKING_AUDIT_RECORDS=../shared/records/seed-suite.toml python benchmarks/rocking_spectrum.py
"""

import math
import time

import numpy as np

from audit.physics.block import RigidBlock
from audit.physics.reference import simulate_reference
from audit.physics.rocking import rocking_spectrum, simulate
from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_SIZES
from audit.engine.shared.grid import size_grid
from records import load_records


def main(record="pacoima_dam_1971", sample_count=18, jobs=2):
    suite = load_records()
    motion = suite.get(record).motion
    sizes = size_grid(*DEFAULT_SIZES)
    alphas = np.radians(DEFAULT_ALPHA_DEG)
    rocking_spectrum(motion, sizes[:2], alphas[:1])  # compile outside the timing

    start = time.perf_counter()
    spectrum = rocking_spectrum(motion, sizes, alphas, jobs=jobs)
    ours = (time.perf_counter() - start) / spectrum.theta_peak.size

    rng = np.random.default_rng(2026)
    picks = [(int(i), int(j)) for i, j in zip(rng.integers(0, alphas.size, sample_count),
                                              rng.integers(0, sizes.size, sample_count))]
    reference_time, worst, agree, compared, skipped = 0.0, 0.0, 0, 0, 0
    print(f"{'alpha':>5} {'2pi/p':>6} {'ours θ/α':>10} {'ref θ/α':>10} {'rel diff':>9}  overturn")
    for i, j in picks:
        block = RigidBlock.from_size(sizes[j], alphas[i])
        start = time.perf_counter()
        ref = simulate_reference(block, motion)
        reference_time += time.perf_counter() - start
        theta, over = spectrum.theta_peak[i, j], bool(spectrum.overturned[i, j])
        near = {simulate(block, motion.scaled(f)).overturned for f in (0.99, 1.01)} != {over}
        diff = abs(theta / ref["peak_rotation"] - 1) if ref["peak_rotation"] > 0 else 0.0
        if not over and not ref["overturned"] and theta < 0.9 * block.alpha:
            worst = max(worst, diff)
        if near:
            skipped += 1
        else:
            compared += 1
            agree += over == ref["overturned"]
        print(f"{math.degrees(alphas[i]):5.0f} {sizes[j]:6.2f} {theta / block.alpha:10.6f} "
              f"{ref['peak_rotation'] / block.alpha:10.6f} {diff:9.2e}  ours {over}, ref "
              f"{ref['overturned']}{' (within 1 % of the boundary)' if near else ''}")
    reference = reference_time / len(picks)
    print(f"\nsolve_ivp reference: {1e3 * reference:.1f} ms per block ({len(picks)} blocks)")
    print(f"rocking_spectrum:    {1e3 * ours:.3f} ms per block ({spectrum.theta_peak.size} blocks, "
          f"{jobs} threads)")
    print(f"speed ratio:         {reference / ours:.0f}x")
    print(f"largest relative difference of peak θ (surviving, θ < 0.9 α): {worst:.2e}")
    print(f"overturn classification agrees on {agree}/{compared} sampled blocks "
          f"({skipped} within 1 % of the boundary left out)")

    records = [entry.motion for entry in suite if entry.motion is not None]
    start = time.perf_counter()
    for m in records:
        rocking_spectrum(m, sizes, alphas, jobs=jobs)
    print(f"whole suite: {len(records)} records × {alphas.size} α × {sizes.size} sizes in "
          f"{time.perf_counter() - start:.2f} s")


if __name__ == "__main__":
    main()
