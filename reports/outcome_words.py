"""The outcome of a block in words, as hovers, tables and sentences of the report give it: the
exact response and the guideline's."""

from __future__ import annotations

import math

import numpy as np

from audit.engine.shared.verdicts import ROCKING_FLOOR


def describe_exact(row) -> str:
    """The exact response of a result row in words (θ/α or 'overturns')."""
    if row["exact_overturned"] is True:
        return "overturns" + (" (fragile)" if row["exact_fragile"] is True else "")
    if not np.isfinite(row["exact_theta_rad"]):
        return "no record file"
    theta_ratio = row["exact_theta_rad"] / math.radians(row["alpha_deg"])
    if theta_ratio < ROCKING_FLOOR:
        return f"no rocking (θ/α = {theta_ratio:.2g})"
    return f"θ/α = {theta_ratio:.4g}"


def describe_guideline(row) -> str:
    """The procedure's outcome of a result row in words."""
    outcome = row["approx_outcome"]
    if outcome == "converged":
        return (f"θ/α = {row['approx_theta_rad'] / math.radians(row['alpha_deg']):.4g}, "
                f"T(θ) = {row['approx_period_s']:.3g} s")
    if outcome == "not-converged":
        cycle = row.get("approx_cycle") or ""
        return f"no fixed point reached (cycle θ/α {cycle.replace(';', ' ↔ ')})" if cycle \
            else "no fixed point reached"
    return {"overturn": "predicts overturning", "no-uplift": "predicts no rocking"}.get(
        outcome, str(outcome))
