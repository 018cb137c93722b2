"""The verdict vocabulary, defined once, and the rules that decide every verdict of an audit.

Each verdict has a name (as written to the CSV files), a meaning (as the report and
``columns.json`` explain it), a colour (the same in every figure) and a side: ``unsafe`` (the
guideline errs against safety), ``uneconomic`` (it errs on the safe side), ``agrees`` or
``neutral``. The engine decides verdicts here; the columns guide, the report and its palette
read this module and define none of their own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from procedures.base import (EXACT_OVERTURNING, EXACT_ROTATION, EXACT_UPLIFT, NO_UPLIFT,
                             NOT_CONVERGED, OVERTURN)

UNSAFE, UNECONOMIC, AGREES, NEUTRAL = "unsafe", "uneconomic", "agrees", "neutral"


@dataclass(frozen=True)
class Verdict:
    """One verdict class: ``name``, ``meaning`` in words, ``colour`` (hex) and ``side``."""

    name: str
    meaning: str
    colour: str
    side: str


#: Verdicts of a procedure's rotation against the exact response (``results.csv``), in the
#: order of the report's legends. Unsafe errors in reds, over-safe ones in orange and blue.
ROTATION_VERDICTS = (
    Verdict("no-uplift", "PGA ≤ g tan α: neither the block nor the procedure rocks", "#eeeeee",
            AGREES),
    Verdict("both-overturn", "both the exact response and the procedure overturn", "#4d4d4d",
            AGREES),
    Verdict("false-overturn", "the procedure predicts overturning; the block survives "
            "(uneconomic)", "#fdbf6f", UNECONOMIC),
    Verdict("missed-overturn", "the block overturns; the procedure says it survives (unsafe)",
            "#b2182b", UNSAFE),
    Verdict("agrees", "both survive and approx/exact lies within the agreement band", "#b2df8a",
            AGREES),
    Verdict("conservative", "the procedure's rotation exceeds the exact one beyond the band "
            "(uneconomic)", "#a6cee3", UNECONOMIC),
    Verdict("unconservative", "the procedure's rotation is below the exact one beyond the band "
            "(unsafe)", "#fb9a99", UNSAFE),
    Verdict("not-converged", "the procedure's iteration settles in a cycle or does not settle: "
            "no estimate, counted neither safe nor unsafe", "#cab2d6", NEUTRAL),
)
#: Verdicts of a limit-state check against the exact response (``checks.csv``).
CHECK_VERDICTS = (
    Verdict("agrees-safe", "the procedure passes and the exact response does not exceed the "
            "limit state", "#b2df8a", AGREES),
    Verdict("agrees-unsafe", "the procedure fails and the exact response exceeds it", "#4d4d4d",
            AGREES),
    Verdict("missed", "the procedure passes but the exact response exceeds the limit state "
            "(unsafe)", "#b2182b", UNSAFE),
    Verdict("false-alarm", "the procedure fails but the exact response does not exceed it "
            "(uneconomic)", "#fdbf6f", UNECONOMIC),
)
#: Statuses of a claim of the reference report against the tool's value (``claims.csv``).
CLAIM_STATUSES = (
    Verdict("agrees", "within the claim's tolerance", "#b2df8a", AGREES),
    Verdict("close", "outside it but within the wider 'close' tolerance, or the procedure "
            "iterated on another branch than the report's", "#fdbf6f", NEUTRAL),
    Verdict("differs", "outside both tolerances", "#b2182b", UNSAFE),
    Verdict("cannot-check", "a record the claim needs is absent from the run or has no file",
            "#cccccc", NEUTRAL),
)


def names(vocabulary) -> tuple[str, ...]:
    """The names of a vocabulary, in order.

    Parameters
    ----------
    vocabulary : iterable of Verdict
        The verdicts.
    """
    return tuple(v.name for v in vocabulary)


def on_side(vocabulary, side: str) -> tuple[str, ...]:
    """The names of a vocabulary's verdicts on ``side`` (``unsafe``, ``uneconomic``, …).

    Parameters
    ----------
    vocabulary : iterable of Verdict
        The verdicts.
    side : str
        The side.
    """
    return tuple(v.name for v in vocabulary if v.side == side)


def meanings(vocabulary) -> dict[str, str]:
    """``{name: meaning}`` of a vocabulary.

    Parameters
    ----------
    vocabulary : iterable of Verdict
        The verdicts.
    """
    return {v.name: v.meaning for v in vocabulary}


def colours(vocabulary) -> dict[str, str]:
    """``{name: colour}`` of a vocabulary.

    Parameters
    ----------
    vocabulary : iterable of Verdict
        The verdicts.
    """
    return {v.name: v.colour for v in vocabulary}


VERDICTS = names(ROTATION_VERDICTS)
#: Verdicts where the guideline errs on the unsafe side.
UNSAFE_VERDICTS = on_side(ROTATION_VERDICTS, UNSAFE)
#: Verdicts where the guideline errs on the safe side.
UNECONOMIC_VERDICTS = on_side(ROTATION_VERDICTS, UNECONOMIC)
#: Check verdicts where the guideline passes a block the exact response fails.
UNSAFE_CHECK_VERDICTS = on_side(CHECK_VERDICTS, UNSAFE)
#: Check verdicts where the guideline fails a block the exact response passes.
UNECONOMIC_CHECK_VERDICTS = on_side(CHECK_VERDICTS, UNECONOMIC)


#: A rotation below this share of α is no rocking. Where the PGA barely exceeds g tan α the
#: exact peak is ~1e-14 rad, and a guideline's 0.05 rad over it is no ratio of 1e12 but "the
#: guideline rocks, the block does not": the verdicts compare each rotation taken as at least
#: ``ROCKING_FLOOR`` α, and ``results.csv`` gives no ratio where the exact block does not rock.
ROCKING_FLOOR = 1e-3


def rotation_ratio(approx_theta, exact_theta, alpha_rad):
    """approx/exact of each block [-], each rotation [rad] floored at :data:`ROCKING_FLOOR` ×
    ``alpha_rad``; NaN where either rotation is NaN.

    Parameters
    ----------
    approx_theta, exact_theta : array_like of float
        Peak rotation by the procedure and by the exact solver [rad].
    alpha_rad : array_like of float
        Each block's slenderness α [rad].
    """
    floor = ROCKING_FLOOR * np.asarray(alpha_rad, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.maximum(approx_theta, floor) / np.maximum(exact_theta, floor)


def reported_ratio(verdict, approx_theta, exact_theta, alpha_rad):
    """The ``ratio`` of ``results.csv`` [-]: :func:`rotation_ratio` where both survive (agrees,
    conservative, unconservative) and the exact block rocks (θ ≥ :data:`ROCKING_FLOOR` α);
    NaN elsewhere.

    Parameters
    ----------
    verdict : array_like of str
        Each block's verdict.
    approx_theta, exact_theta : array_like of float
        Peak rotation by the procedure and by the exact solver [rad].
    alpha_rad : array_like of float
        Each block's slenderness α [rad].
    """
    rocks = np.asarray(exact_theta) >= ROCKING_FLOOR * np.asarray(alpha_rad, dtype=float)
    both_survive = np.isin(verdict, ["agrees", "conservative", "unconservative"])
    return np.where(both_survive & rocks, rotation_ratio(approx_theta, exact_theta, alpha_rad),
                    np.nan)


def classify(exact_theta, exact_overturned, exact_uplifted, approx_theta, outcome,
             alpha_rad, agree_band: float):
    """Rotation verdict of each block (:data:`ROTATION_VERDICTS`); arrays in, array of str out.

    Parameters
    ----------
    exact_theta : array
        Exact peak rotation [rad].
    exact_overturned, exact_uplifted : array of bool
    approx_theta : array
        The procedure's rotation [rad] (NaN where it predicts overturning or does not settle).
    outcome : array of str
        The procedure's outcome (``converged``, ``overturn``, ``no-uplift``, ``not-converged``).
    alpha_rad : float or array
        Slenderness α [rad], for the floor of :func:`rotation_ratio`.
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    """
    approx_over = outcome == OVERTURN
    exact_over = np.asarray(exact_overturned, dtype=bool)
    ratio = rotation_ratio(approx_theta, exact_theta, alpha_rad)
    return np.select(
        [(outcome == NO_UPLIFT) & ~np.asarray(exact_uplifted, dtype=bool),
         outcome == NOT_CONVERGED, approx_over & exact_over, approx_over, exact_over,
         np.abs(ratio - 1.0) <= agree_band, ratio > 1.0],
        ["no-uplift", "not-converged", "both-overturn", "false-overturn", "missed-overturn",
         "agrees", "conservative"],
        default="unconservative").astype(object)


def exact_exceeded(check, theta_peak, overturned, uplifted) -> np.ndarray:
    """Whether the exact response exceeds a check's limit state, per block.

    Parameters
    ----------
    check : procedures.base.Check
    theta_peak : array
        Exact max |θ| [rad] of the same blocks.
    overturned, uplifted : array of bool
        Exact overturning and uplift of the same blocks.

    Returns
    -------
    numpy.ndarray of bool
        ``uplifted`` for an uplift check; θ_peak ≥ θ_limit or overturned for a rotation check;
        ``overturned`` for an overturning check.
        Blocks with no exact response (NaN) are the caller's to mask.
    """
    if check.exact_event == EXACT_UPLIFT:
        return np.asarray(uplifted, dtype=bool)
    if check.exact_event == EXACT_OVERTURNING:
        return np.asarray(overturned, dtype=bool)
    if check.exact_event == EXACT_ROTATION:
        with np.errstate(invalid="ignore"):
            return (np.asarray(theta_peak) >= check.theta_limit_rad) | np.asarray(overturned,
                                                                                   dtype=bool)
    raise ValueError(f"check {check.limit_state}: unknown exact event {check.exact_event!r}")


def check_verdicts(passes, exceeded) -> np.ndarray:
    """Check verdict of each block (:data:`CHECK_VERDICTS`): the procedure's pass/fail against
    the exact event.

    Parameters
    ----------
    passes : array of bool
        The procedure passes the block.
    exceeded : array of bool
        The exact response exceeds the limit state (:func:`exact_exceeded`).
    """
    passes = np.asarray(passes, dtype=bool)
    exceeded = np.asarray(exceeded, dtype=bool)
    return np.where(passes, np.where(exceeded, "missed", "agrees-safe"),
                    np.where(exceeded, "agrees-unsafe", "false-alarm")).astype(object)
