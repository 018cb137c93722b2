"""Benchmark of ``margins`` and ``fragility`` read from the atlas (``--method atlas``) against
their direct solve, on the far-field set on the ground, alternating the two, medians:

* ``margins fema356`` on a grid of blocks (α 10, 15, 20° × 2π/p 0.5–8 s every 0.25 s: 93
  blocks, the default grid), S_XS = 1.5 g, S_X1 = 0.9 g, without the required slenderness
  (direct in both); the atlas's fits against the direct ones on its 14 stripes (the
  interpolation's difference) and on the direct audit's 27 (what a user sees change);
* ``fragility femap58`` (9 components with a block), the atlas's 14 PGV stripes against the
  direct 19.

    python benchmarks/atlas_fragility.py [--repeat 2] [--skip-margins]

The atlases must be built (``python -m audit atlas build --records p695-far-field`` and the
same with ``--im pgv``). Wall times of the API calls in this process (warm: one call of each
first), the load average after each.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.append(str(Path(__file__).resolve().parents[1]))

import audit.api as api  # noqa: E402
from audit.engine.shared.lattice import stripe_lattice  # noqa: E402

RECORDS = "p695-far-field"
SITE = (1.5, 0.9)
GRID = {"alpha_deg": (10.0, 15.0, 20.0), "size_s": tuple(np.arange(0.5, 8.0001, 0.25))}


def timed(call):
    start = time.perf_counter()
    result = call()
    return time.perf_counter() - start, result, os.getloadavg()[0]


def alternate(calls: dict, repeat: int) -> dict:
    """Each call ``repeat`` times, alternating; a warm-up of each first."""
    results = {name: call() for name, call in calls.items()}  # warm: kernels, records
    times = {name: [] for name in calls}
    for _ in range(repeat):
        for name, call in calls.items():
            seconds, results[name], load = timed(call)
            times[name].append(seconds)
            print(f"  {name}: {seconds:.1f} s (load {load:.1f})", flush=True)
    return {name: (statistics.median(t), results[name]) for name, t in times.items()}


def differences(atlas, direct, median: str, beta: str) -> str:
    ratio = np.abs(atlas[median] / direct[median] - 1.0)
    dbeta = np.abs(atlas[beta] - direct[beta])
    return (f"|median ratio − 1| median {np.nanmedian(ratio):.4f}, largest {np.nanmax(ratio):.4f}; "
            f"|Δβ| median {np.nanmedian(dbeta):.4f}, largest {np.nanmax(dbeta):.4f}")


def curve(row, levels):
    """The lognormal fragility of a ``fragility.csv`` row at ``levels``."""
    from scipy.stats import norm
    return norm.cdf(np.log(levels / row["median"]) / row["beta"])


def fragility_same_stripes(levels):
    """``fragility femap58``'s components table solved directly at ``levels`` [m/s]."""
    from audit.engine.fragility.pipeline import COMPONENTS_CSV, run_fragility
    from audit.engine.fragility.settings import FragilitySettings
    from procedures.registry import available_procedures
    from records import load_records
    entries = [e for e in load_records(RECORDS) if e.motion is not None]
    return run_fragility(available_procedures(probabilistic=True)["femap58"](),
                         [e.id for e in entries], [e.motion for e in entries],
                         FragilitySettings(levels_m_s=tuple(levels)))[COMPONENTS_CSV]


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--skip-margins", action="store_true")
    args = parser.parse_args()
    print("fragility femap58:")
    done = alternate({"atlas": lambda: api.fragility("femap58", RECORDS, method="atlas"),
                      "direct": lambda: api.fragility("femap58", RECORDS, method="direct")},
                     args.repeat)
    for name, (seconds, _) in done.items():
        print(f"fragility {name}: median {seconds:.2f} s")
    atlas, direct = done["atlas"][1].table, done["direct"][1].table
    print("  atlas (14 stripes) vs direct (19):",
          differences(atlas, direct, "exact_median_m_s", "exact_beta"))
    same = fragility_same_stripes(stripe_lattice(2).tolist())
    print("  atlas vs direct on the same 14 PGV stripes:",
          differences(atlas, same, "exact_median_m_s", "exact_beta"))
    print(atlas[["component", "exact_median_m_s", "exact_beta", "atlas_error"]]
          .merge(direct[["component", "exact_median_m_s", "exact_beta"]], on="component",
                 suffixes=("_atlas", "_direct")).to_string(index=False))
    if args.skip_margins:
        return 0
    common = dict(site=SITE, required=False, **GRID)
    print("margins fema356, 93 blocks:")
    done = alternate({"atlas": lambda: api.margins("fema356", RECORDS, method="atlas", **common),
                      "direct": lambda: api.margins("fema356", RECORDS, method="direct",
                                                    **common)}, args.repeat)
    for name, (seconds, _) in done.items():
        print(f"margins {name}: median {seconds:.1f} s")
    atlas, direct = done["atlas"][1].fragility, done["direct"][1].fragility
    same = api.margins("fema356", RECORDS, method="direct",
                       stripes=tuple(stripe_lattice(2).tolist()), **common).fragility
    print("  atlas vs direct on the same 14 stripes:", differences(atlas, same, "median", "beta"))
    levels = stripe_lattice(2)
    gap = np.array([np.max(np.abs(curve(a, levels) - curve(s, levels)))
                    for (_, a), (_, s) in zip(atlas.iterrows(), same.iterrows())])
    worst = int(np.nanargmax(np.abs(atlas["median"] / same["median"] - 1.0)))
    print(f"  P along the curve (at the 14 stripes), |atlas − direct|: median {np.median(gap):.4f}, "
          f"largest {gap.max():.4f}; beyond the stated error at {np.sum(gap > atlas['atlas_error'])}"
          f" of {gap.size} blocks; largest median difference at α {atlas['alpha_deg'][worst]:g}°, "
          f"2π/p {atlas['size_s'][worst]:g} s (θ {atlas['median'][worst]:.3f} against "
          f"{same['median'][worst]:.3f} g)")
    print("  atlas (14) vs direct (27):", differences(atlas, direct, "median", "beta"))
    print("  stated error along the curves: median ±%.3f, largest ±%.3f"
          % (atlas["atlas_error"].median(), atlas["atlas_error"].max()))
    few = [(10.0, 1.0), (15.0, 2.0), (20.0, 4.0), (15.0, 6.0)]
    for alpha, size in few:
        pick = lambda t: t[(t["alpha_deg"] == alpha) & (np.isclose(t["size_s"], size))].iloc[0]
        a, s, d = pick(atlas), pick(same), pick(direct)
        print(f"  α {alpha:g}°, 2π/p {size:g} s: atlas θ {a['median']:.4f} g β {a['beta']:.3f} "
              f"(±{a['atlas_error']:.3f}); direct 14 stripes θ {s['median']:.4f} β "
              f"{s['beta']:.3f}; direct 27 θ {d['median']:.4f} β {d['beta']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
