"""The evaluators of the reproduction checklist (:mod:`audit.engine.claims`): each computes one
kind of quantity a claim of the reference report names, from the physics (one block, one record)
wherever it can, so a claim stays checkable on a partial grid; only statements about regions of
the grid read the run's tables. ``claims.toml`` names the evaluator and its parameters. Past 300
lines on purpose: one short function per kind of claim, registered in :data:`EVALUATORS`, which
``claims.toml`` must be able to name in one place.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np
import pandas as pd

from audit import G
from audit.errors import InputError
from audit.physics.block import RigidBlock, coefficient_of_restitution, radius_from_p
from audit.physics.damping import (damping_fema356, damping_free_rocking, damping_priestley,
                                   housner_peak_ratio, housner_period)
from audit.physics.response_spectra import response_spectra
from audit.physics.rocking import simulate
from procedures.base import CONVERGED, NO_UPLIFT, OVERTURN
from records import GroundMotion, one_pulse

#: The claims these evaluators serve, beside this module (named in their errors).
CLAIMS_FILE = "claims.toml"
#: Duration of the one-cosine pulses of Figures 4.1, 4.2 and 7.2 [s] and the free motion after.
PULSE_PERIOD_S = 2.0
PULSE_FREE_MOTION_S = 8.0
#: "Within ±25 %" of the exact rotation, for the report's "good" / "poor" statements.
GOOD_RATIO = 1.25
#: "Grossly overestimates": the estimate is at least twice the exact rotation.
GROSS_RATIO = 2.0
#: Two sizes closer than this are the same grid block [s].
SIZE_MATCH_S = 1e-6


class CannotCheck(Exception):
    """The run lacks what a claim needs; the message says what."""


@dataclass(frozen=True)
class Value:
    """An evaluator's answer: the number (or yes/no), a note, or the branches of a cycle."""

    value: float | bool | None
    note: str = ""
    #: Values of the branches of a cycle the procedure settled in instead of a fixed point.
    branches: tuple = ()


def _block(alpha_deg: float, size_s: float | None = None, p_rad_s: float | None = None,
           g: float = G) -> RigidBlock:
    p = p_rad_s if p_rad_s is not None else 2.0 * math.pi / size_s
    return RigidBlock(p, math.radians(alpha_deg), g=g)


# ------------------------------------------------------------------------------ evaluators

def closed_form(ctx, quantity: str, **params) -> Value:
    """A value of the report's closed forms (Eqs. 4.8, 7.9, 7.10, 9.1, R = 3g/(4p²))."""
    alpha = np.radians(params.get("alpha_deg", 0.0))
    r = coefficient_of_restitution(alpha)
    if quantity == "restitution":
        return Value(float(r))
    if quantity in ("half_height_m", "half_width_m"):
        block = _block(params["alpha_deg"], p_rad_s=params["p_rad_s"], g=ctx.g)
        return Value(block.half_height if quantity == "half_height_m" else block.half_width)
    if quantity == "radius_m":
        return Value(float(radius_from_p(2.0 * math.pi / params["size_s"], ctx.g)))
    if quantity == "tan":
        return Value(float(np.tan(alpha)))
    if quantity == "radians":
        return Value(float(alpha))
    if quantity == "damping_priestley_pct":
        return Value(100.0 * float(damping_priestley(r)))
    if quantity == "damping_fema_pct":
        return Value(100.0 * float(damping_fema356(r)))
    if quantity == "fema_to_priestley_damping":
        return Value(float(np.mean(damping_fema356(r) / damping_priestley(r))))
    if quantity == "eq79_max_deviation":
        x0, n, rr = np.meshgrid(params["theta0_ratio"], params["n_impacts"], r, indexing="ij")
        return Value(float(np.max(np.abs(damping_free_rocking(x0, n, rr)
                                         / damping_priestley(rr) - 1.0))))
    raise InputError(f"{CLAIMS_FILE}: closed_form: unknown quantity '{quantity}'")


@cache
def _pulse_response(p_rad_s: float, alpha_deg: float, amplitude_g: float):
    motion = one_pulse("cosine", amplitude_g, PULSE_PERIOD_S)
    return simulate(_block(alpha_deg, p_rad_s=p_rad_s), motion, PULSE_FREE_MOTION_S)


def pulse_block(ctx, quantity: str, p_rad_s: float, alpha_deg: float,
                amplitude_g: float) -> Value:
    """One block under the 2-s one-cosine pulse of Figures 4.1/4.2 (Eq. 4.9), 8 s after it.

    Quantities: ``overturned``; ``impacts_after_pulse``; ``free_peak_ratio`` (largest |θ|/α at a
    turning point after the pulse); ``first_free_cycle_s`` (first full cycle, two impacts,
    after the pulse [s]); ``fraction_cycles_shortening`` (share of successive free cycles no
    longer than the one before).
    """
    response = _pulse_response(p_rad_s, alpha_deg, amplitude_g)
    end = response.excitation_end
    if quantity == "overturned":
        return Value(response.overturned)
    if response.overturned:
        return Value(None, f"the block overturns at t = {response.overturn_time:.2f} s")
    impacts = response.impact_times[response.impact_times > end]
    if quantity == "impacts_after_pulse":
        return Value(int(impacts.size))
    if quantity == "free_peak_ratio":
        peak = response.peak_rotation_free_vibration
        return Value(peak / response.block.alpha if math.isfinite(peak) else None)
    cycles = impacts[2::2] - impacts[:-2:2]
    if quantity == "first_free_cycle_s":
        return Value(float(cycles[0]) if cycles.size else None)
    if quantity == "fraction_cycles_shortening":
        if cycles.size < 2:
            return Value(None, "fewer than two free cycles")
        return Value(float(np.mean(cycles[1:] <= cycles[:-1] * (1.0 + 1e-9))))
    raise InputError(f"{CLAIMS_FILE}: pulse_block: unknown quantity '{quantity}'")


def oscillator_pulse(ctx, period_s: float, damping_pct: float, amplitude_g: float) -> Value:
    """Peak |u| [m] of the linear oscillator (Eq. 3.2) under the pulse of Figure 7.2."""
    motion = one_pulse("cosine", amplitude_g, PULSE_PERIOD_S)
    spectra = response_spectra(motion, [period_s], [damping_pct / 100.0], PULSE_FREE_MOTION_S)
    return Value(float(spectra.sd[0, 0]))


def free_rocking(ctx, alpha_deg: float, size_s: float, theta0_ratio: float,
                 n_impacts: int) -> Value:
    """Simulated θn/α of free rocking from θ0 at rest, over Housner's Eq. 7.5, minus 1."""
    block = _block(alpha_deg, size_s=size_s, g=ctx.g)
    # enough time for n impacts: each half-cycle is shorter than a quarter of T(θ0) × 2
    duration = (n_impacts + 2) * float(housner_period(theta0_ratio, block.p))
    still = GroundMotion("free rocking", np.zeros(2), dt=1e-3)
    response = simulate(block, still, duration, initial_rotation=theta0_ratio * block.alpha)
    if response.n_impacts < n_impacts + 1:
        return Value(None, f"only {response.n_impacts} impacts")
    after = response.turning_times > response.impact_times[n_impacts - 1]
    simulated = abs(response.turning_rotations[after][0]) / block.alpha
    return Value(float(simulated / housner_peak_ratio(theta0_ratio, n_impacts, block.r) - 1.0))


def record_peak(ctx, quantity: str, record: str) -> Value:
    """PGA [g] or PGV [m/s] of a record's file (the processing of ``SOURCES.md``)."""
    entry = ctx.entry(record)
    if entry is not None:
        return Value(entry.motion.pga_g if quantity == "pga_g" else entry.motion.pgv)
    item = ctx.records[record]
    return Value(item["pga_g"] if quantity == "pga_g" else item["pgv_m_s"])


def _grid_row(frame: pd.DataFrame, size_s: float, what: str, **equal) -> pd.Series:
    """The row of a run table at one block, or CannotCheck when the grid lacks it."""
    mask = np.abs(frame["size_s"].to_numpy(dtype=float) - size_s) <= SIZE_MATCH_S
    for column, value in equal.items():
        mask &= (frame[column] == value).to_numpy()
    if not mask.any():
        raise CannotCheck(f"{what} at 2π/p = {size_s:g} s is not on this run's grid "
                          f"(and no record file was given to simulate it)")
    return frame[mask].iloc[0]


def exact_block(ctx, quantity: str, record: str, alpha_deg: float, size_s: float) -> Value:
    """Exact response of one block to a record: ``theta_rad``, ``overturned`` or
    ``max_cycle_s`` (longest full rocking cycle, every second impact [s])."""
    entry = ctx.entry(record)
    if entry is None:
        if quantity == "max_cycle_s":
            raise CannotCheck("cycle durations need the record file (pass the suite)")
        row = _grid_row(ctx.run.rocking, size_s, "the exact response", record=record,
                        alpha_deg=alpha_deg)
        return Value(bool(row["overturned"]) if quantity == "overturned"
                     else float(row["theta_peak_rad"]))
    response = simulate(_block(alpha_deg, size_s=size_s, g=ctx.g), entry.motion, ctx.free_motion_s)
    if quantity == "overturned":
        return Value(response.overturned)
    if response.overturned:
        return Value(None, f"the block overturns at t = {response.overturn_time:.2f} s")
    if quantity == "theta_rad":
        return Value(response.peak_rotation)
    if quantity == "max_cycle_s":
        durations = response.cycle_durations
        return Value(float(durations.max()) if durations.size else None)
    raise InputError(f"{CLAIMS_FILE}: exact_block: unknown quantity '{quantity}'")


def procedure_block(ctx, quantity: str, procedure: str, record: str, alpha_deg: float,
                    size_s: float) -> Value:
    """A procedure's estimate for one block: ``theta_rad`` or ``period_s`` (T(θ), Eq. 8.1).

    Where the iteration settles on a cycle instead of a fixed point, the answer is the cycle's
    branches: the claim is graded on the branch nearest the report's number, and at best
    ``close``, since the report reads that branch as converged.
    """
    entry = ctx.entry(record)
    alpha = math.radians(alpha_deg)
    p = 2.0 * math.pi / size_s
    if entry is None:
        row = _grid_row(pd.concat([ctx.run.results, ctx.run.estimates_only]), size_s,
                        f"the {procedure} estimate", procedure=procedure, record=record,
                        alpha_deg=alpha_deg)
        outcome, theta = row["approx_outcome"], row["approx_theta_rad"]
        detail, cycle = row["approx_detail"], row["approx_cycle"]
    else:
        # the verdict's evaluation: the iteration reads the spectrum only where it goes
        estimate = ctx.procedure(procedure).evaluate_for_verdict(
            entry, np.array([p]), alpha, float(coefficient_of_restitution(alpha)),
            ctx.record_context(entry).on_demand(), ctx.g).estimate
        outcome, theta = estimate.outcome[0], estimate.theta[0]
        detail, cycle = estimate.detail[0], estimate.cycle[0]
    if outcome == OVERTURN:
        return Value(None, "the procedure predicts overturning")
    if outcome in (CONVERGED, NO_UPLIFT):
        return Value(float(theta if quantity == "theta_rad" else housner_period(theta / alpha, p)))
    if not isinstance(cycle, str) or not cycle:
        return Value(None, detail)
    ratios = np.array([float(x) for x in cycle.split(";")])
    branches = ratios * alpha if quantity == "theta_rad" else housner_period(ratios, p)
    return Value(None, f"not converged: a cycle θ/α = {cycle.replace(';', ' ↔ ')}; the value is "
                       "its branch nearest the report's", tuple(float(b) for b in branches))


def ratio(ctx, numerator: dict, denominator: dict, percent_change: bool = False) -> Value:
    """numerator/denominator of two other evaluations, or 100·(ratio − 1) [%]."""
    top, bottom = evaluate_method(ctx, numerator), evaluate_method(ctx, denominator)
    note = "; ".join(v.note for v in (top, bottom) if v.note)
    if top.value is None or bottom.value is None or bottom.value == 0:
        return Value(None, note)
    value = top.value / bottom.value
    return Value(100.0 * (value - 1.0) if percent_change else value, note)


def _window(frame: pd.DataFrame, size_min: float, size_max: float) -> pd.DataFrame:
    sizes = frame["size_s"].astype(float)
    return frame[(sizes >= size_min - SIZE_MATCH_S) & (sizes <= size_max + SIZE_MATCH_S)]


def _exact_curve(ctx, record: str, alpha_deg: list[float], size_min: float,
                 size_max: float) -> pd.DataFrame:
    rocking = ctx.run.rocking
    if rocking.empty:
        raise CannotCheck("this run has no exact rocking spectra")
    rows = _window(rocking[(rocking["record"] == record)
                           & rocking["alpha_deg"].isin(alpha_deg)], size_min, size_max)
    if rows.empty:
        raise CannotCheck(f"no exact spectrum of {record} at α = {alpha_deg} on this run's grid "
                          f"between {size_min:g} and {size_max:g} s")
    return rows


def exact_region(ctx, quantity: str, record: str, alpha_deg: list[float], size_min: float,
                 size_max: float, threshold: float = 0.0) -> Value:
    """A statement over a region of a record's exact rocking spectra (the run's grid).

    Quantities: ``fraction_overturned``, ``fraction_survived``,
    ``fraction_theta_ratio_at_least`` (θ/α ≥ ``threshold``, overturning counts as 1),
    ``max_theta_ratio`` (of the surviving blocks; None if one overturns), and
    ``small_survives_large_overturns`` (yes/no).
    """
    rows = _exact_curve(ctx, record, alpha_deg, size_min, size_max)
    overturned = rows["overturned"].astype(bool).to_numpy()
    ratio_ = np.where(overturned, 1.0, rows["theta_ratio"].to_numpy(dtype=float))
    note = f"{len(rows)} blocks"
    if quantity == "fraction_overturned":
        return Value(float(overturned.mean()), note)
    if quantity == "fraction_survived":
        return Value(float(1.0 - overturned.mean()), note)
    if quantity == "fraction_theta_ratio_at_least":
        return Value(float(np.mean(ratio_ >= threshold)), note)
    if quantity == "max_theta_ratio":
        if overturned.any():
            return Value(None, f"{int(overturned.sum())} of {note} overturn")
        return Value(float(ratio_.max()), note)
    if quantity == "small_survives_large_overturns":
        sizes = rows["size_s"].to_numpy(dtype=float)
        survivors = sizes[~overturned]
        return Value(bool(survivors.size and np.any(sizes[overturned] > survivors.min())))
    raise InputError(f"{CLAIMS_FILE}: exact_region: unknown quantity '{quantity}'")


def exact_compare(ctx, quantity: str, record_a: str, alpha_a: float, record_b: str,
                  alpha_b: float, size_min: float, size_max: float) -> Value:
    """Two exact rotation spectra θ [rad] on the same sizes (overturning counts as θ = α).

    ``fraction_exceeds``: share of the sizes where θ_a ≥ θ_b; ``mean_ratio``: mean θ_a over
    mean θ_b in the window.
    """
    def curve(record, alpha):
        rows = _exact_curve(ctx, record, [alpha], size_min, size_max)
        theta = np.where(rows["overturned"].astype(bool), math.radians(alpha),
                         rows["theta_peak_rad"].astype(float))
        return pd.Series(theta, index=rows["size_s"].astype(float).round(6).to_numpy())

    a, b = curve(record_a, alpha_a), curve(record_b, alpha_b)
    a, b = a.align(b, join="inner")
    if quantity == "fraction_exceeds":
        return Value(float(np.mean(a.to_numpy() >= b.to_numpy())), f"{a.size} sizes")
    if quantity == "mean_ratio":
        return Value(float(a.mean() / b.mean()) if b.mean() > 0 else None)
    raise InputError(f"{CLAIMS_FILE}: exact_compare: unknown quantity '{quantity}'")


def procedure_region(ctx, quantity: str, procedure: str, records: list[str],
                     alpha_deg: list[float], size_min: float, size_max: float) -> Value:
    """A statement over a region of a procedure's audit (the run's ``results``).

    Quantities over the blocks that rock (``exact_uplifted``) and whose estimate is a value
    or an overturning (not-converged iterations are left out and counted in the note):
    ``fraction_conservative`` (approx θ ≥ exact θ, or overturning predicted),
    ``fraction_unconservative`` (approx θ < exact θ, or a missed overturning),
    ``count_false_overturn``, ``fraction_good`` (within ±25 % or both overturn),
    ``fraction_gross_overestimate`` (of the exact survivors: overturning predicted or approx
    ≥ 2× exact). ``fraction_approx_overturned`` counts every block, with or without a file.
    """
    # records without a file still have the procedure's estimates, kept apart from the verdicts
    results = pd.concat([ctx.run.results, ctx.run.estimates_only], ignore_index=True)
    if results.empty or procedure not in set(results["procedure"]):
        raise CannotCheck(f"procedure {procedure} is not part of this run")
    rows = _window(results[(results["procedure"] == procedure) & results["record"].isin(records)
                           & results["alpha_deg"].isin(alpha_deg)], size_min, size_max)
    absent = [r for r in records if r not in set(rows["record"])]
    notes = [f"not in this run: {', '.join(absent)}"] if absent else []
    if rows.empty:
        raise CannotCheck(f"no {procedure} results for {', '.join(records)} in this run")
    approx_over = rows["approx_outcome"].to_numpy() == OVERTURN
    if quantity == "fraction_approx_overturned":
        return Value(float(approx_over.mean()), "; ".join(notes + [f"{len(rows)} blocks"]))
    ctx.require_unscaled()
    exact_theta = rows["exact_theta_rad"].to_numpy(dtype=float)
    has_file = np.isfinite(exact_theta)
    if not has_file.any():
        raise CannotCheck(f"no exact response of {', '.join(records)} in this run (no file)")
    no_file = sorted(set(rows["record"][~has_file]))
    if no_file:
        notes.append(f"no file: {', '.join(no_file)}")
    rocks = has_file & (rows["exact_uplifted"].to_numpy() == True)  # noqa: E712 (object column)
    estimated = np.isin(rows["approx_outcome"].to_numpy(), (CONVERGED, OVERTURN, "no-uplift"))
    left_out = int(np.sum(rocks & ~estimated))
    if left_out:
        notes.append(f"{left_out} not-converged blocks left out")
    keep = rocks & estimated
    exact_over = rows["exact_overturned"].to_numpy() == True  # noqa: E712
    approx_theta = np.nan_to_num(rows["approx_theta_rad"].to_numpy(dtype=float))
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = approx_theta / exact_theta
    both_survive = ~approx_over & ~exact_over
    if quantity == "count_false_overturn":
        return Value(int(np.sum(keep & approx_over & ~exact_over)), "; ".join(notes))
    if quantity == "fraction_gross_overestimate":
        keep &= ~exact_over
        hit = approx_over | (both_survive & (factor >= GROSS_RATIO))
    elif quantity == "fraction_conservative":
        hit = approx_over | (both_survive & (factor >= 1.0))
    elif quantity == "fraction_unconservative":
        hit = (exact_over & ~approx_over) | (both_survive & (factor < 1.0))
    elif quantity == "fraction_good":
        with np.errstate(divide="ignore", invalid="ignore"):
            within = np.abs(np.log(factor)) <= math.log(GOOD_RATIO)
        hit = (approx_over & exact_over) | (both_survive & within)
    else:
        raise InputError(f"{CLAIMS_FILE}: procedure_region: unknown quantity '{quantity}'")
    if not keep.any():
        return Value(None, "; ".join(notes + ["no rocking block to judge"]))
    notes.append(f"{int(keep.sum())} blocks")
    return Value(float(np.mean(hit[keep])), "; ".join(notes))


EVALUATORS = {f.__name__: f for f in (closed_form, pulse_block, oscillator_pulse, free_rocking,
                                      record_peak, exact_block, procedure_block, ratio,
                                      exact_region, exact_compare, procedure_region)}


def evaluate_method(ctx, method: dict) -> Value:
    """Run the evaluator a claim's ``method`` names, with its parameters."""
    params = {k: v for k, v in method.items() if k != "name"}
    return EVALUATORS[method["name"]](ctx, **params)
