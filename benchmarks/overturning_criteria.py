"""The overturning criteria audited: the figures of the closing note of the Housner 1963 /
Makris & Roussos 2000 plug-ins, and the Zhang & Makris figure redone with the exact solver.

    python benchmarks/overturning_criteria.py [--records pulses,p695-near-field-pulse]
        [--housner-suite p695-far-field] [--figure docs/pulse-criteria.png]

1. Minimum overturning amplitude a_p0/(g tan α) of one-sine and one-cosine pulses against ω_p/p,
   for α = 10°, 15°, 20° (h = 1 m): the exact solver (scan up from 1 in 0.1 % steps, then
   bisection) against the published lines, the exact-linear conditions and Housner's eq. 12.
   Prints the worst overestimate of capacity of the published lines and draws the figure.
2. Confusion matrices (agrees-safe / agrees-unsafe / missed / false-alarm) of each criterion and
   variant against exact overturning, on each suite, over the default grid of blocks.
3. Housner's claim: the exact P(overturn) of a block over a suite whose records are each scaled
   so that their S_v equals S_v,cr — median over blocks and its 16–84 % spread.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

# appended, not inserted: a PYTHONPATH (compare.py's baseline tree) comes first, then this tree
sys.path.append(str(Path(__file__).resolve().parents[1]))

from audit import G  # noqa: E402
from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_SIZES  # noqa: E402
from audit.engine.shared.grid import size_grid  # noqa: E402
from audit.engine.shared.verdicts import CHECK_VERDICTS, check_verdicts, exact_exceeded, names  # noqa: E402
from audit.physics.block import RigidBlock  # noqa: E402
from audit.physics.overturning_criteria import (ONE_COSINE, ONE_SINE,  # noqa: E402
                                                exact_minimum_amplitude,
                                                housner_half_sine_amplitude,
                                                linear_minimum_amplitude)
from audit.physics.rocking import rocking_spectrum, simulate  # noqa: E402
from procedures.context import RecordContext  # noqa: E402
from procedures.housner_1963 import Housner1963  # noqa: E402
from procedures.makris_roussos_2000 import (EXACT_LINEAR, HOUSNER, PUBLISHED,  # noqa: E402
                                            MakrisRoussos2000, minimum_amplitude_ratio)
from records import load_records  # noqa: E402

RATIOS = np.arange(0.25, 3.01, 0.25)
#: Multiples of S_v,cr the records are scaled to, to find where P(overturn) reaches 0.5.
MULTIPLES = (1.0, 2.0, 3.0, 4.0, 6.0)


def minimum_amplitudes(figure: str | None) -> None:
    print("1. minimum overturning amplitude a_p0/(g tan α), h = 1 m")
    worst = (0.0, None)
    curves = {}
    for alpha_deg in (10.0, 15.0, 20.0):
        block = RigidBlock.from_dimensions(math.tan(math.radians(alpha_deg)), 1.0, g=G)
        for shape in (ONE_SINE, ONE_COSINE):
            exact = np.array([exact_minimum_amplitude(block, shape, 2 * math.pi / (r * block.p),
                                                      beyond=1.0)[0] for r in RATIOS])
            # the published line in g tan α units (it is written in αg)
            line = linear_minimum_amplitude(RATIOS, shape) * block.alpha / math.tan(block.alpha)
            over = line / exact - 1.0
            k = int(np.argmax(over))
            if over[k] > worst[0]:
                worst = (over[k], (alpha_deg, shape, RATIOS[k]))
            curves[(alpha_deg, shape)] = (exact, line)
            print(f"  α = {alpha_deg:g}°, {shape}: exact "
                  + " ".join(f"{v:.3f}" for v in exact) + f"; published overestimates by up to "
                  f"{100 * over.max():.1f} % (ω_p/p = {RATIOS[k]:g}), underestimates by up to "
                  f"{-100 * min(over.min(), 0):.1f} %")
    alpha_deg, shape, ratio = worst[1]
    print(f"  worst overestimate of capacity by the published lines: {100 * worst[0]:.1f} % "
          f"({shape}, α = {alpha_deg:g}°, ω_p/p = {ratio:g})")
    if figure:
        from matplotlib.figure import Figure
        fig = Figure(figsize=(11, 4.2))
        for column, shape in enumerate((ONE_SINE, ONE_COSINE)):
            ax = fig.add_subplot(1, 2, column + 1)
            for alpha_deg, colour in zip((10.0, 15.0, 20.0), ("#1f77b4", "#d62728", "#2ca02c")):
                exact, line = curves[(alpha_deg, shape)]
                ax.plot(RATIOS, exact, "o-", color=colour, ms=3,
                        label=f"exact solver, α = {alpha_deg:g}°")
                ax.plot(RATIOS, line, "--", color=colour, lw=1,
                        label=f"1 + β ω_p/p (published), α = {alpha_deg:g}°")
            ax.plot(RATIOS, minimum_amplitude_ratio(RATIOS, shape, EXACT_LINEAR), ":", color="k",
                    label="exact linearised, no impact")
            ax.plot(RATIOS, housner_half_sine_amplitude(RATIOS), "-.", color="grey", lw=1,
                    label="Housner eq. 12")
            ax.set(xlabel="ω_p/p [-]", ylabel="minimum overturning a_p/(g tan α) [-]",
                   title=f"{shape} pulse", ylim=(0.9, 3.0))
            ax.grid(alpha=0.3)
            if column == 1:
                ax.legend(fontsize=7, loc="upper left")
        fig.tight_layout()
        fig.savefig(figure, dpi=110)
        print(f"  figure written to {figure}")


def confusion(sources: list[str]) -> None:
    print("2. confusion matrices against exact overturning, default grid")
    sizes = size_grid(*DEFAULT_SIZES)
    alphas = np.radians(DEFAULT_ALPHA_DEG)
    p = 2 * np.pi / sizes
    variants = {"housner1963 eq. 17": Housner1963(), "housner1963 eq. 17a": Housner1963(slender=True),
                **{f"makrisroussos2000 {v}": MakrisRoussos2000(variant=v)
                   for v in (PUBLISHED, EXACT_LINEAR, HOUSNER)}}
    for source in sources:
        suite = load_records(source)
        totals = {name: dict.fromkeys(names(CHECK_VERDICTS), 0) for name in variants}
        skipped = dict.fromkeys(variants, 0)
        for entry in suite:
            if entry.motion is None:
                continue
            exact = rocking_spectrum(entry.motion, sizes, alphas, jobs=2)
            context = RecordContext(entry, 10.0)
            for name, procedure in variants.items():
                if procedure.unmet_requirements(entry):
                    skipped[name] += 1
                    continue
                for i, alpha in enumerate(alphas):
                    check, = procedure.checks(entry, p, alpha, 0.9, context, G)
                    exceeded = exact_exceeded(check, exact.theta_peak[i], exact.overturned[i],
                                              exact.uplifted[i])
                    for verdict in check_verdicts(check.passes, exceeded):
                        totals[name][verdict] += 1
        print(f"  {source} ({len(suite)} records):")
        for name, counts in totals.items():
            total = sum(counts.values())
            shares = ", ".join(f"{v} {n} ({100 * n / total:.1f} %)" if total else f"{v} 0"
                               for v, n in counts.items())
            print(f"    {name}: {shares}; records without a pulse: {skipped[name]}")


def housner_claim(source: str) -> None:
    print(f"3. exact P(overturn) at S_v = S_v,cr (records scaled), {source}")
    suite = [entry for entry in load_records(source) if entry.motion is not None]
    procedure = Housner1963()
    peaks = []
    for entry in suite:
        spectra = RecordContext(entry, 10.0).true_spectra(procedure.damping)
        peaks.append(spectra.sv[0][spectra.period_s <= procedure.max_period_s].max())
    for multiple in MULTIPLES:
        shares = []
        for alpha_deg in DEFAULT_ALPHA_DEG:
            for size_s in np.arange(0.5, 8.01, 0.5):
                block = RigidBlock.from_size(size_s, math.radians(alpha_deg), g=G)
                critical = multiple * G * block.alpha / block.p
                over = [simulate(block, entry.motion.scaled(critical / peak)).overturned
                        for entry, peak in zip(suite, peaks)]
                shares.append(np.mean(over))
        shares = np.array(shares)
        p16, p50, p84 = np.percentile(shares, [16, 50, 84])
        print(f"  S_v = {multiple:g} × S_v,cr: {len(shares)} blocks (α 10/15/20°, 2π/p 0.5–8 s) × "
              f"{len(suite)} records: median P(overturn) {p50:.2f}, 16–84 % of blocks "
              f"{p16:.2f}–{p84:.2f}, range {shares.min():.2f}–{shares.max():.2f} "
              "(Housner: ≈ 0.5 at 1 ×)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", default="pulses,p695-near-field-pulse")
    parser.add_argument("--housner-suite", default="p695-far-field")
    parser.add_argument("--figure", default=None, help="PNG of the minimum amplitudes")
    parser.add_argument("--housner-only", action="store_true", help="only part 3")
    args = parser.parse_args()
    start = time.perf_counter()
    if not args.housner_only:
        minimum_amplitudes(args.figure)
        confusion(args.records.split(","))
    housner_claim(args.housner_suite)
    print(f"({time.perf_counter() - start:.0f} s)")


if __name__ == "__main__":
    main()
