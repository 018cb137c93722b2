"""Evaluators of the claims (:mod:`audit.engine.claims.evaluators`) that read the run: a record's
peaks and one block's exact response or procedure estimate (simulated from the record's file when
the suite is given, else read from the run's grid), and statements over regions of the grid (the
run's ``rocking`` and ``results`` tables).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from audit.engine.claims.value import CLAIMS_FILE, CannotCheck, Value
from audit.errors import InputError
from audit.engine.shared.blocks import Block
from audit.physics.block import coefficient_of_restitution
from audit.physics.damping import housner_period
from audit.physics.rocking import simulate
from procedures.base import CONVERGED, NO_UPLIFT, OVERTURN

#: "Within ±25 %" of the exact rotation, for the report's "good" / "poor" statements.
GOOD_RATIO = 1.25
#: "Grossly overestimates": the estimate is at least twice the exact rotation.
GROSS_RATIO = 2.0
#: Two sizes closer than this are the same grid block [s].
SIZE_MATCH_S = 1e-6


def record_peak(ctx, quantity: str, record: str) -> Value:
    """PGA [g] or PGV [m/s] of a record's file (the processing of ``SOURCES.md``).

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    quantity : str
        ``pga_g`` or ``pgv_m_s``.
    record : str
        The record's id.
    """
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
    ``max_cycle_s`` (longest full rocking cycle, every second impact [s]).

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    quantity : str
        ``theta_rad``, ``overturned`` or ``max_cycle_s``.
    record : str
        The record's id.
    alpha_deg : float
        Slenderness α [degrees].
    size_s : float
        Size 2π/p [s].
    """
    entry = ctx.entry(record)
    if entry is None:
        if quantity == "max_cycle_s":
            raise CannotCheck("cycle durations need the record file (pass the suite)")
        row = _grid_row(ctx.run.rocking, size_s, "the exact response", record=record,
                        alpha_deg=alpha_deg)
        return Value(bool(row["overturned"]) if quantity == "overturned"
                     else float(row["theta_peak_rad"]))
    response = simulate(Block(alpha_deg=alpha_deg, size_s=size_s, g=ctx.g).rigid, entry.motion,
                        ctx.free_motion_s)
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

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    quantity : str
        ``theta_rad`` or ``period_s``.
    procedure : str
        The procedure's registered name.
    record : str
        The record's id.
    alpha_deg : float
        Slenderness α [degrees].
    size_s : float
        Size 2π/p [s].
    """
    entry = ctx.entry(record)
    alpha = math.radians(alpha_deg)
    p = 2.0 * math.pi / size_s
    if entry is None:
        row = _grid_row(ctx.estimates, size_s, f"the {procedure} estimate",
                        procedure=procedure, record=record, alpha_deg=alpha_deg)
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

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    quantity : str
        One of the quantities above.
    record : str
        The record's id.
    alpha_deg : list of float
        Slendernesses of the region [degrees].
    size_min, size_max : float
        Sizes 2π/p bounding the region [s].
    threshold : float
        θ/α of ``fraction_theta_ratio_at_least`` [-].
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

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    quantity : str
        ``fraction_exceeds`` or ``mean_ratio``.
    record_a, record_b : str
        The two records' ids.
    alpha_a, alpha_b : float
        Their slendernesses α [degrees].
    size_min, size_max : float
        Sizes 2π/p bounding the window [s].
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

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    quantity : str
        One of the quantities above.
    procedure : str
        The procedure's registered name.
    records : list of str
        The records' ids.
    alpha_deg : list of float
        Slendernesses of the region [degrees].
    size_min, size_max : float
        Sizes 2π/p bounding the region [s].
    """
    results = ctx.estimates
    if results.empty or not (results["procedure"] == procedure).any():
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
