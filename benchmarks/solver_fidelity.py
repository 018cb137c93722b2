"""The fidelity contract of issue 48 on the far-field margins grid: the overturning outcomes of
today's solver against those of the step it replaced (``benchmarks/four_libm_step.py``), with
every outcome that changed shown to be knife-edge.

    python benchmarks/solver_fidelity.py [--records p695-far-field] [--jobs 2] [--first N]
        [--out fidelity.npz] [--from fidelity.npz]

The grid is the one ``margins all --records p695-far-field --site 1.5,0.9 --scale-to-site``
solves for its stripes (the default stripes, α and sizes: 98,208 outcomes), computed as that
command computes it (:func:`audit.engine.design.margins.margins_stripes`, no procedure), once with each
step. An outcome that changed is knife-edge when the step it replaced changes it too under a
relative change of the record's scale factor of at most 1e-6: the smallest such change (of 25
from 1e-12 to 1e-6, even in ln, each way; outcomes this close to their edge flip back and forth
in it, so a coarser search can miss them) is printed for each. ``--from`` takes the outcomes of
an earlier run's ``--out`` instead of solving the grid again; ``--first N`` scales only N
records to the site (FEMA P695 scales the set as a whole), so its outcomes are not the grid's.
Both solvers are the product's kernels, the one compiled again around the old step; that this
recompilation gives the product's answers bit for bit with today's step is checked first, on
the first record.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from four_libm_step import StepSwapped, rk4_four_libm  # noqa: E402

from audit.api import Site, design_suite  # noqa: E402
from audit.engine.shared.blocks import BlockList  # noqa: E402
from audit.engine.design.margins import margins_stripes  # noqa: E402
from audit.engine.design.settings import MarginsSettings  # noqa: E402
from audit.engine.shared.runtime import Runtime  # noqa: E402
from audit.physics.rocking import motion_equation, rocking_blocks  # noqa: E402
from records import load_records  # noqa: E402

#: Relative changes of the scale factor tried, smallest first, each way.
WIDTHS = np.logspace(-12.0, -6.0, 25)


def flip_width(entry, factor: float, size_s: float, alpha_rad: float, outcome: bool,
               settings) -> float:
    """The smallest relative change of ``factor`` among :data:`WIDTHS` that changes whether the
    block overturns under the current solver; NaN if none does."""
    for width in WIDTHS:
        for sign in (-1.0, 1.0):
            peaks = rocking_blocks(entry.motion.scaled(factor * (1.0 + sign * width)),
                                   [size_s], [alpha_rad], r=settings.restitution, g=settings.g,
                                   free_motion_s=settings.free_motion_s)
            if bool(peaks.overturned[0]) != outcome:
                return sign * float(width)
    return math.nan


def solved_grid(suite, settings, runtime) -> dict:
    """The grid's outcomes and peaks with today's step and with the step before, after checking
    that the recompiled solver gives the product's answers bit for bit on the first record."""
    first = replace(suite, entries=suite.entries[:1])
    product = margins_stripes([], first, settings, runtime)
    with StepSwapped(motion_equation._rk4):
        rebuilt = margins_stripes([], first, settings, runtime)
    assert np.array_equal(product.exact_theta_rad, rebuilt.exact_theta_rad), \
        "the recompiled solver does not reproduce the product's"
    new = margins_stripes([], suite, settings, runtime)
    with StepSwapped(rk4_four_libm):
        old = margins_stripes([], suite, settings, runtime)
    return {"new_overturned": new.exact_overturned, "old_overturned": old.exact_overturned,
            "new_theta": new.exact_theta_rad, "old_theta": old.exact_theta_rad,
            "levels": np.asarray(new.settings.levels), "intensities": new.intensities,
            "records": np.array([e.id for e in new.entries])}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", default="p695-far-field")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--first", type=int, help="only the suite's first N records")
    parser.add_argument("--out", type=Path, default=Path("fidelity.npz"))
    parser.add_argument("--from", dest="earlier", type=Path,
                        help="the outcomes of an earlier run (its --out)")
    args = parser.parse_args()
    records = load_records(args.records)
    if args.first:
        records = replace(records, entries=records.entries[:args.first])
    suite = design_suite(records, site=Site(1.5, 0.9, override=True, scale_records=True))
    settings = MarginsSettings.parse()
    print(f"load average {os.getloadavg()[0]:.1f}", flush=True)
    grid = (dict(np.load(args.earlier)) if args.earlier
            else solved_grid(suite, settings, Runtime.parse(Runtime(jobs=args.jobs))))
    entries = {entry.id: entry for entry in suite}
    blocks = BlockList.of(settings.alpha_deg, settings.size_s, settings.blocks)
    alpha_rad = np.radians(blocks.alpha_deg)
    levels, new_over, old_over = grid["levels"], grid["new_overturned"], grid["old_overturned"]
    changed = np.argwhere(new_over != old_over)
    print(f"{len(grid['records'])} records × {levels.size} stripes × {len(blocks)} blocks = "
          f"{new_over.size} outcomes (load average {os.getloadavg()[0]:.1f})")
    both_survive = ~new_over & ~old_over & (grid["old_theta"] > 0)
    relative = np.abs(grid["new_theta"][both_survive] / grid["old_theta"][both_survive] - 1)
    print(f"peak θ of the {both_survive.sum()} rocking survivors: relative change median "
          f"{np.median(relative):.1e}, 99.9th percentile {np.quantile(relative, 0.999):.1e}, "
          f"largest {relative.max():.1e}")
    print(f"outcomes changed: {len(changed)} of {new_over.size}")
    widths = []
    with StepSwapped(rk4_four_libm):
        for r, j, b in changed:
            record_id = str(grid["records"][r])
            factor = float(levels[j] / grid["intensities"][r])
            width = flip_width(entries[record_id], factor, float(blocks.size_s[b]),
                               float(alpha_rad[b]), bool(old_over[r, j, b]), settings)
            widths.append(width)
            print(f"  {record_id} stripe {levels[j]:.4g} (× {factor:.6g}) α = "
                  f"{blocks.alpha_deg[b]:g}° 2π/p = {blocks.size_s[b]:g} s: overturned "
                  f"{bool(old_over[r, j, b])} → {bool(new_over[r, j, b])}; the step before "
                  f"flips at a relative change of the factor of {width:+.1e}", flush=True)
    widths = np.array(widths)
    print(f"knife-edge (flips under ≤ 1e-6 with the step before): "
          f"{np.isfinite(widths).sum()} of {len(changed)}")
    np.savez_compressed(args.out, **{**grid, "changed": changed, "flip_width": widths})


if __name__ == "__main__":
    main()
