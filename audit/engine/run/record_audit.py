"""The unit of work of an audit: one record, every procedure, every block of the grid.

For one record: its response spectra (Figures 5.x), its exact rocking spectra (also at the
record scaled by 1 ± ε, for the fragile-overturning flag, and under each alternative ground-truth
model of ``--sensitivity``), one :meth:`~procedures.base.
Procedure.evaluate` call per procedure and slenderness, the verdicts of each estimate and check
(:mod:`audit.engine.shared.verdicts`), and the time histories worth drawing
(:mod:`audit.engine.run.histories`).

A procedure that can estimate without the recorded motion (FEMA 356 reads a design spectrum)
still estimates for a record whose file is missing; those estimates have no exact response to be
compared with, so they are kept apart (``estimates_only``), not given a verdict.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pandas as pd

from audit.engine.shared.ground_truth import alternatives, slides
from audit.engine.run.histories import simulate_histories
from audit.engine.shared.schemas import (
    CHECK_COLUMNS,
    HISTORY_COLUMNS,
    RESULT_COLUMNS,
    ROCKING_COLUMNS,
    SPECTRA_COLUMNS,
)
from audit.engine.run.settings import FIGURE_5_DAMPING, AuditSettings
from audit.engine.shared.verdicts import (
    check_verdicts,
    classify,
    exact_exceeded,
    reported_ratio,
)
from audit.physics.rocking import RockingOptions, rocking_spectrum
from procedures.base import OVERTURN, STORED_SPECTRUM_PERIODS_S
from procedures.context import RecordContext


@dataclass
class RecordAudit:
    """The part of an audit that one record contributes (see :func:`audit_record`).

    Attributes
    ----------
    record_id : str
    results, estimates_only, spectra, histories, rocking, checks : pandas.DataFrame
        This record's rows of the run's tables (:mod:`audit.engine.shared.schemas`).
    unauditable : list of dict
        ``procedure, record, reason`` of each procedure that could not evaluate the record.
    histories_meta : list of dict
        What each drawn time history shows (cycles, impacts, overturning).
    """

    record_id: str
    results: pd.DataFrame
    estimates_only: pd.DataFrame
    spectra: pd.DataFrame
    histories: pd.DataFrame
    rocking: pd.DataFrame
    checks: pd.DataFrame
    unauditable: list
    histories_meta: list


def concat(frames, columns) -> pd.DataFrame:
    """The frames one after the other, or an empty frame with the columns when there are none.

    Parameters
    ----------
    frames : list of pandas.DataFrame
        The frames.
    columns : sequence of str
        The columns of the empty frame.
    """
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=columns)


def rows_frame(pieces: list[dict], columns) -> pd.DataFrame:
    """The rows of ``pieces`` (each a dict column → array, all of one length) one after the
    other, as :func:`concat` of a frame per piece gives them, each column joined once.

    A record's results and checks come in tens of pieces of a few hundred rows; a frame per
    piece and their concatenation cost more than the rows (Python work that held the GIL
    while the solver waited).

    Parameters
    ----------
    pieces : list of dict
        Column name → numpy array, every array of a piece one length.
    columns : sequence of str
        The frame's columns, in order (the columns of an empty frame).
    """
    if not pieces:
        return pd.DataFrame(columns=columns)
    data = {}
    for name in columns:
        arrays = [piece[name] for piece in pieces]
        if len({array.dtype.kind for array in arrays}) == 1:
            data[name] = np.concatenate(arrays)
        else:  # mixed kinds: pandas' own promotion (bool beside float makes object)
            data[name] = pd.concat([pd.Series(array) for array in arrays], ignore_index=True)
    return pd.DataFrame(data)


def _columns(values: dict, size: int) -> dict:
    """Each value as an array of ``size`` rows, a scalar repeated as a frame's column would
    repeat it (text as objects)."""
    return {name: np.full(size, value, dtype=object if isinstance(value, str) else None)
            if np.ndim(value) == 0 else np.asarray(value) for name, value in values.items()}


def fragile_overturning(motion, settings: AuditSettings, overturned: np.ndarray):
    """Blocks whose exact overturning verdict changes when the record is scaled by 1 ± ε.

    Parameters
    ----------
    motion : records.GroundMotion
    settings : AuditSettings
        ``robustness`` is ε [-]; 0 means not checked.
    overturned : numpy.ndarray of bool
        Exact overturning under the record as given, shaped (α, size).

    Returns
    -------
    numpy.ndarray of bool, or None when not checked
    """
    if not settings.robustness:
        return None
    fragile = np.zeros(overturned.shape, dtype=bool)
    for factor in (1.0 - settings.robustness, 1.0 + settings.robustness):
        other = _exact_spectrum(motion.scaled(factor), settings, settings.ground_truth,
                                reactions=False)
        fragile |= other.overturned != overturned
    return fragile


def _exact_spectrum(motion, settings: AuditSettings, model, reactions: bool):
    """The exact rocking spectrum of the grid under one ground-truth model."""
    return rocking_spectrum(motion, np.asarray(settings.size_s), np.radians(settings.alpha_deg),
                            r=model.impact, options=RockingOptions(
                                settings.g, settings.free_motion_s, vertical=model.vertical),
                            jobs=settings.jobs, reactions=reactions)


def _exact_response(motion, settings: AuditSettings):
    """The exact rocking spectrum of the grid (with the pivot reactions), its fragile blocks,
    and its overturning and peaks under each alternative model of ``settings.sensitivity``."""
    exact = _exact_spectrum(motion, settings, settings.ground_truth, reactions=True)
    others = [_exact_spectrum(motion, settings, model, reactions=False)
              for model in alternatives(settings.ground_truth, settings.sensitivity)]
    return exact, fragile_overturning(motion, settings, exact.overturned), others


def audit_record(entry, procedures, settings: AuditSettings) -> RecordAudit:
    """Audit every procedure on one record over the (α, 2π/p) grid.

    Parameters
    ----------
    entry : records.RecordEntry
    procedures : list of procedures.Procedure
    settings : AuditSettings

    Returns
    -------
    RecordAudit
    """
    sizes = np.asarray(settings.size_s, dtype=float)
    alpha_deg = np.asarray(settings.alpha_deg, dtype=float)
    alpha_rad = np.radians(alpha_deg)
    impact = settings.ground_truth.impact
    p = 2.0 * np.pi / sizes
    motion = entry.motion
    context = RecordContext(entry, settings.free_motion_s, settings.jobs)
    spectra, unauditable = [], []
    exact_job = None
    if motion is not None:
        # the exact solver and the oscillator kernels of the figures' spectra release the GIL:
        # they run beside the procedures, whose fixed-point iterations hold it and would leave
        # the second core idle
        pool = ThreadPoolExecutor(2)
        exact_job = pool.submit(_exact_response, motion, settings)
        for damping in FIGURE_5_DAMPING:
            context.prefetch(damping, pool)
        pool.shutdown(wait=False)  # its threads end with the jobs; an interrupt waits for none
    evaluations = []  # (procedure name, α index, Evaluation)
    for procedure in procedures:
        reason = procedure.unmet_requirements(entry)
        if reason is not None:
            unauditable.append({"procedure": procedure.name, "record": entry.id, "reason": reason})
            continue
        if motion is None:
            unauditable.append({"procedure": procedure.name, "record": entry.id,
                                "reason": f"no record file ({entry.missing_reason}): "
                                          "estimate shown, no exact comparison"})
        for i, alpha in enumerate(alpha_rad):
            # the guideline sizes the same block: its r is the impact model's
            evaluation = procedure.evaluate(entry, p, alpha, float(impact.r(alpha)), context,
                                            settings.g)
            evaluations.append((procedure.name, i, evaluation))
            if evaluation.spectrum_sd_m is not None:  # the spectrum it read (Figures 8.x, 9.x)
                spectra.append(pd.DataFrame({
                    "record": entry.id, "procedure": procedure.name, "alpha_deg": alpha_deg[i],
                    "damping_pct": 100.0 * evaluation.estimate.damping,
                    "period_s": STORED_SPECTRUM_PERIODS_S, "sd_m": evaluation.spectrum_sd_m,
                    "sv_m_s": np.nan, "sa_g": np.nan}))
    if motion is not None:  # the figures' spectra lead the record's rows, as they always have
        spectra[:0] = [context.true_spectra(damping).to_frame()
                       .assign(record=entry.id, procedure="", alpha_deg=np.nan)[SPECTRA_COLUMNS]
                       for damping in FIGURE_5_DAMPING]
    exact, fragile, others = (exact_job.result() if exact_job is not None
                              else (None, None, []))
    results, estimates_only, checks = [], [], []
    for name, i, evaluation in evaluations:
        if evaluation.estimate is not None:
            rows = _result_rows(RowKeys(entry.id, name, i, alpha_deg[i], sizes, p),
                                evaluation.estimate, ExactAnswer(exact, fragile, others),
                                settings)
            (results if exact is not None else estimates_only).append(rows)
        if exact is not None:  # a check is audited only against an exact response
            checks += [_check_rows(entry.id, name, alpha_deg[i], sizes, check, exact, i,
                                   settings.g) for check in evaluation.checks]
    results = rows_frame(results, RESULT_COLUMNS)
    rocking, histories, histories_meta = [], [], []
    if exact is not None:
        rocking.append(exact.to_frame().assign(record=entry.id)[ROCKING_COLUMNS])
        histories, histories_meta = simulate_histories(entry, results, exact, alpha_deg,
                                                       settings)
    return RecordAudit(entry.id, results, rows_frame(estimates_only, RESULT_COLUMNS),
                       concat(spectra, SPECTRA_COLUMNS), concat(histories, HISTORY_COLUMNS),
                       concat(rocking, ROCKING_COLUMNS), rows_frame(checks, CHECK_COLUMNS),
                       unauditable, histories_meta)


class RowKeys(NamedTuple):
    """What names a procedure's rows of one record at one slenderness: the record, the
    procedure, α's index on the grid and α [degrees], the blocks' sizes 2π/p [s] and p
    [rad/s]."""

    record_id: str
    procedure_name: str
    i: int
    alpha_deg: float
    sizes: np.ndarray
    p: np.ndarray


class ExactAnswer(NamedTuple):
    """The exact response of one record over the grid (None without a record file), its
    fragility flags (None with robustness off) and the responses of the alternative models."""

    response: object
    fragile: object
    others: list


def _result_rows(keys: RowKeys, estimate, truth: ExactAnswer, settings: AuditSettings):
    """One row per block of a procedure's estimate, beside the exact response it is judged
    against (``results.csv``), as columns (:func:`rows_frame` joins them)."""
    record_id, procedure_name, i, alpha_deg, sizes, p = keys
    exact, fragile, others = truth
    nan = np.full(sizes.shape, np.nan)
    band, alpha_rad = settings.agree_band, np.radians(alpha_deg)
    if exact is None:
        exact_theta, exact_over, exact_omega, exact_up, verdict = nan, nan, nan, nan, ""
        exact_fragile = friction = jumps = sliding = sensitive = nan
    else:
        exact_theta = exact.theta_peak[i]
        exact_over = exact.overturned[i]
        exact_omega = exact.omega_peak[i]
        exact_up = exact.uplifted[i]
        exact_fragile = nan if fragile is None else fragile[i]
        friction, jumps = exact.required_friction[i], exact.jumps[i]
        sliding = slides(friction, settings.friction)
        verdict = classify(exact_theta, exact_over, exact_up, estimate.theta, estimate.outcome,
                           alpha_rad, band)
        sensitive = nan
        if others:  # the verdict class under each alternative model of the ground truth
            sensitive = np.zeros(sizes.shape, dtype=bool)
            for other in others:
                sensitive |= classify(other.theta_peak[i], other.overturned[i],
                                      other.uplifted[i], estimate.theta, estimate.outcome,
                                      alpha_rad, band) != verdict
    ratio = reported_ratio(verdict, estimate.theta, exact_theta, alpha_rad)
    return _columns({
        "record": record_id, "procedure": procedure_name, "alpha_deg": alpha_deg,
        "size_s": sizes, "p_rad_s": p, "exact_theta_rad": exact_theta,
        "exact_overturned": exact_over, "exact_uplifted": exact_up,
        "exact_fragile": exact_fragile, "exact_omega_rad_s": exact_omega,
        "exact_required_friction": friction, "exact_jumps": jumps, "exact_slides": sliding,
        "exact_model_sensitive": sensitive,
        "approx_theta_rad": estimate.theta, "approx_overturned": estimate.outcome == OVERTURN,
        "approx_period_s": estimate.period_s, "approx_outcome": estimate.outcome,
        "approx_fixed_points": estimate.fixed_points, "approx_cycle": estimate.cycle,
        "approx_detail": estimate.detail, "iterations": estimate.iterations,
        "beta_pct": 100.0 * estimate.damping, "verdict": verdict, "ratio": ratio,
    }, sizes.size)


def _check_rows(record_id, procedure_name, alpha_deg, sizes, check, exact, i, g):
    """One row per block of a limit-state check, with the exact event it is audited against, as
    columns (:func:`rows_frame` joins them)."""
    exceeded = exact_exceeded(check, exact.theta_peak[i], exact.overturned[i], exact.uplifted[i])
    return _columns({
        "record": record_id, "procedure": procedure_name, "alpha_deg": alpha_deg,
        "size_s": sizes, "limit_state": check.limit_state, "exact_event": check.exact_event,
        "procedure_passes": np.asarray(check.passes, dtype=bool), "exact_exceeded": exceeded,
        "verdict": check_verdicts(check.passes, exceeded), "demand_m": check.demand_m,
        "capacity_m": check.capacity_m, "demand_g": check.demand_m_s2 / g,
        "capacity_g": check.capacity_m_s2 / g, "demand_m_s": check.demand_m_s,
        "capacity_m_s": check.capacity_m_s, "demand_theta_rad": check.demand_theta_rad,
        "theta_limit_rad": check.theta_limit_rad, "period_s": check.period_s,
    }, sizes.size)


__all__ = ["audit_record", "RecordAudit", "fragile_overturning", "concat"]
