"""The audit: exact rocking spectra against guideline estimates, block by block (SPEC §5–8).

For every record of a suite the exact rocking spectra are computed once and shared by all the
procedures of the run; each procedure then estimates every block of the grid, and each block
gets one verdict:

``no-uplift``        PGA ≤ g tan α: neither rocks.
``both-overturn``    both say the block overturns.
``false-overturn``   the procedure predicts overturning; the block survives.
``missed-overturn``  the block overturns; the procedure says it survives.
``conservative``     approx θ ≥ exact θ.
``unconservative``   approx θ < exact θ.
``not-converged``    the procedure's iteration found no fixed point.
``record-missing``   the procedure could estimate (it needs no record), but there is no file
                     to compute the exact response from.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from audit import G, __version__
from audit.physics.block import coefficient_of_restitution
from audit.physics.oscillator import response_spectra
from audit.engine.grid import DEFAULT_ALPHA_DEG, DEFAULT_SIZES, size_grid
from audit.engine.progress import Progress
from audit.physics.block import RigidBlock
from audit.physics.rocking import (DEFAULT_FREE_MOTION_S, DEFAULT_REST_TOLERANCE,
                           DEFAULT_STEPS_PER_RADIAN, rocking_spectrum, simulate)
from procedures.base import (INITIAL_ROTATION_RATIO, MAX_ITERATIONS, NO_UPLIFT,
                             NOT_CONVERGED, OVERTURN, TOLERANCE_RATIO)

VERDICTS = ("no-uplift", "both-overturn", "false-overturn", "missed-overturn", "conservative",
            "unconservative", "not-converged", "record-missing")
#: Damping ratios of the response spectra of Figures 5.x.
FIGURE_5_DAMPING = (0.05, 0.10, 0.15)
#: Periods on which procedures read record spectra (interpolated in between) [s].
SPECTRUM_PERIODS_S = np.concatenate(([0.0], np.geomspace(0.01, 100.0, 800)))
#: Periods of the stored procedure spectra (Figures 8.x, 9.x): up to 20 s [s].
PROCEDURE_SPECTRUM_PERIODS_S = SPECTRUM_PERIODS_S[SPECTRUM_PERIODS_S <= 20.0]
#: Samples kept per stored time history.
HISTORY_POINTS = 3000



class RecordContext:
    """What the procedures may ask of one record, computed once and cached.

    Parameters
    ----------
    entry : records.RecordEntry
    free_motion_s : float
        Free motion after the record [s], the same window as the exact solver's.
    """

    def __init__(self, entry, free_motion_s: float):
        self.entry = entry
        self.free_motion_s = free_motion_s
        self._spectra = {}

    def true_spectra(self, damping: float):
        """True response spectra of the record at damping β on :data:`SPECTRUM_PERIODS_S`."""
        key = round(float(damping), 12)
        if key not in self._spectra:
            self._spectra[key] = response_spectra(self.entry.motion, SPECTRUM_PERIODS_S, [key],
                                                  self.free_motion_s)
        return self._spectra[key]

    def true_displacement(self, damping: float):
        """Sd(T) [m] at damping β, linear in T between the tabulated periods."""
        spectra = self.true_spectra(damping)
        return lambda period_s: spectra.displacement_at(period_s, 0)


def classify(exact_theta, exact_overturned, exact_uplifted, approx_theta, outcome):
    """Verdict of each block (see the module docstring); arrays in, array of str out."""
    exact_missing = np.isnan(exact_theta)
    approx_over = outcome == OVERTURN
    exact_over = exact_overturned.astype(bool)
    with np.errstate(invalid="ignore"):
        conservative = approx_theta >= exact_theta
    return np.select(
        [exact_missing, (outcome == NO_UPLIFT) & ~exact_uplifted.astype(bool),
         outcome == NOT_CONVERGED, approx_over & exact_over, approx_over, exact_over,
         conservative],
        ["record-missing", "no-uplift", "not-converged", "both-overturn", "false-overturn",
         "missed-overturn", "conservative"],
        default="unconservative").astype(object)


@dataclass
class AuditRun:
    """Everything an audit produced; the report is rendered from this alone.

    Attributes
    ----------
    results : pandas.DataFrame
        One row per procedure × record × α × size (the columns of ``results.csv``).
    spectra : pandas.DataFrame
        Record response spectra (kind ``response``, Figures 5.x and 8.x).
    histories : pandas.DataFrame
        Time histories of the representative blocks.
    rocking : pandas.DataFrame
        Exact rocking spectra of every record with a file, whatever the procedures.
    summary : dict
        Settings, records, unauditable records, per-record statistics (``summary.json``).
    """

    results: pd.DataFrame
    spectra: pd.DataFrame
    histories: pd.DataFrame
    rocking: pd.DataFrame
    summary: dict = field(default_factory=dict)


def _record_summary(entry) -> dict:
    motion, facts = entry.motion, entry.facts
    item = {"id": entry.id, "name": entry.name, "component": entry.component,
            "missing": entry.missing, "missing_reason": entry.missing_reason, "site": entry.site}
    if facts is not None:
        item["table_5_1"] = {"pga_g": facts.pga_g, "pgv_ms": facts.pgv_ms,
                             "pulse_period_s": facts.pulse_period_s}
    if motion is not None:
        item.update(source=motion.source, sha256=motion.sha256, dt=motion.dt,
                    duration_s=motion.duration, pga_g=motion.pga_g, pgv_ms=motion.pgv,
                    npts=int(motion.acceleration.size))
    return item


def _statistics(frame: pd.DataFrame) -> list[dict]:
    """Counts and approx/exact ratios per procedure, record and α."""
    stats = []
    for (procedure, record, alpha), group in frame.groupby(["procedure", "record", "alpha_deg"],
                                                          sort=False):
        counts = group["verdict"].value_counts()
        ratio = group["ratio"].replace([np.inf, -np.inf], np.nan).dropna()
        stats.append({
            "procedure": procedure, "record": record, "alpha_deg": float(alpha),
            "blocks": int(len(group)),
            "counts": {v: int(counts.get(v, 0)) for v in VERDICTS},
            "median_ratio": float(ratio.median()) if len(ratio) else None,
            "min_ratio": float(ratio.min()) if len(ratio) else None,
            "max_ratio": float(ratio.max()) if len(ratio) else None,
        })
    return stats


def _representative_sizes(spectrum, alpha_index: int, count: int = 3) -> list[float]:
    """Sizes of blocks that rock and survive, spread over the range (for Figures 8.2, 8.5, …)."""
    rocking = (spectrum.uplifted[alpha_index] & ~spectrum.overturned[alpha_index]
               & (spectrum.theta_ratio[alpha_index] > 0.05))
    sizes = spectrum.size_s[rocking]
    if sizes.size == 0:
        return []
    picks = np.unique(np.quantile(np.arange(sizes.size), np.linspace(0.15, 0.85, count))
                      .round().astype(int))
    return [float(sizes[i]) for i in picks]


def _history_rows(response, record_id, alpha_deg, size_s):
    stride = max(1, response.time.size // HISTORY_POINTS)
    return pd.DataFrame({
        "record": record_id, "alpha_deg": alpha_deg, "size_s": size_s,
        "t": response.time[::stride], "theta_ratio": response.theta[::stride] / response.block.alpha,
        "omega": response.omega[::stride],
    })


def run_audit(procedures, suite, alpha_deg=DEFAULT_ALPHA_DEG, sizes=None, jobs: int = 1,
              free_motion_s: float = DEFAULT_FREE_MOTION_S, progress: Progress | None = None,
              g: float = G) -> AuditRun:
    """Audit ``procedures`` on every record of ``suite`` over the (α, 2π/p) grid.

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
    alpha_deg : sequence of float
        Slendernesses [degrees].
    sizes : array, optional
        Block sizes 2π/p [s]; default 0.5 … 8.0 step 0.05.
    jobs : int
        Threads for the exact solver.
    free_motion_s : float
        Free motion after each record, for the exact solver and the record spectra [s].

    Returns
    -------
    AuditRun
    """
    sizes = size_grid(*DEFAULT_SIZES) if sizes is None else np.asarray(sizes, dtype=float)
    alpha_deg = np.asarray(alpha_deg, dtype=float)
    alpha_rad = np.radians(alpha_deg)
    p = 2.0 * np.pi / sizes
    progress = progress or Progress(len(suite), "records", enabled=False)
    frames, spectra_frames, history_frames, rocking_frames = [], [], [], []
    unauditable, histories_meta = [], []
    for entry in suite:
        progress.step(entry.id)
        motion = entry.motion
        context = RecordContext(entry, free_motion_s) if motion is not None else None
        exact = None
        if motion is not None:
            exact = rocking_spectrum(motion, sizes, alpha_rad, g=g, free_motion_s=free_motion_s,
                                     jobs=jobs)
            rocking_frames.append(exact.to_frame().assign(record=entry.id)[ROCKING_COLUMNS])
            for damping in FIGURE_5_DAMPING:
                spectra_frames.append(_spectra_rows(entry.id, "", context.true_spectra(damping)))
        for procedure in procedures:
            reason = procedure.unmet_requirements(entry)
            if reason is not None:
                unauditable.append({"procedure": procedure.name, "record": entry.id,
                                    "reason": reason})
                continue
            if exact is None:
                unauditable.append({"procedure": procedure.name, "record": entry.id,
                                    "reason": f"no record file ({entry.missing_reason}): "
                                              "estimate shown, no exact comparison"})
            for i, alpha in enumerate(alpha_rad):
                r = float(coefficient_of_restitution(alpha))
                estimate = procedure.estimate(entry, p, alpha, r, context, g)
                # the spectrum this procedure read, whatever its source (Figures 8.x, 9.x)
                sd = procedure.displacement_spectrum(entry, estimate.damping,
                                                     context)(PROCEDURE_SPECTRUM_PERIODS_S)
                spectra_frames.append(pd.DataFrame({
                    "record": entry.id, "procedure": procedure.name, "alpha_deg": alpha_deg[i],
                    "damping": estimate.damping, "period_s": PROCEDURE_SPECTRUM_PERIODS_S,
                    "sd": sd, "sv": np.nan, "sa": np.nan}))
                frames.append(_result_rows(entry.id, procedure.name, alpha_deg[i], sizes, p,
                                           estimate, exact, i))
        if exact is not None:
            alpha_index = int(np.argmin(np.abs(alpha_deg - 15.0)))
            for size in _representative_sizes(exact, alpha_index):
                block = RigidBlock.from_size(size, alpha_rad[alpha_index], g=g)
                response = simulate(block, motion, free_motion_s)
                history_frames.append(_history_rows(response, entry.id,
                                                    alpha_deg[alpha_index], size))
                histories_meta.append({
                    "record": entry.id, "alpha_deg": float(alpha_deg[alpha_index]),
                    "size_s": size, "cycle_starts": response.cycle_starts.tolist(),
                    "cycle_durations": response.cycle_durations.tolist(),
                    "first_impact": float(response.impact_times[0]) if response.n_impacts else None,
                    "last_impact": float(response.impact_times[-1]) if response.n_impacts else None,
                    "peak_rotation_ratio": response.peak_rotation_ratio,
                    "excitation_end": response.excitation_end})
    progress.done()
    results = _concat(frames, RESULT_COLUMNS)
    summary = {
        "version": __version__,
        "procedures": [{"name": proc.name, "title": proc.title, "reference": proc.reference,
                        "damping_law": proc.damping_law, "spectrum_source": proc.spectrum_source,
                        "figure_series": proc.figure_series} for proc in procedures],
        "records_source": suite.description,
        "pulse_idealised": suite.is_pulse_idealised,
        "records": [_record_summary(entry) for entry in suite],
        "unauditable": unauditable,
        "grid": {"alpha_deg": alpha_deg.tolist(), "size_s": sizes.tolist()},
        "settings": {
            "g": g, "free_motion_s": free_motion_s,
            "steps_per_radian": DEFAULT_STEPS_PER_RADIAN, "rest_tolerance": DEFAULT_REST_TOLERANCE,
            "initial_rotation_ratio": INITIAL_ROTATION_RATIO, "tolerance_ratio": TOLERANCE_RATIO,
            "max_iterations": MAX_ITERATIONS,
            "figure_5_damping": list(FIGURE_5_DAMPING),
        },
        "statistics": _statistics(results),
        "histories": histories_meta,
    }
    return AuditRun(results, _concat(spectra_frames, SPECTRA_COLUMNS),
                    _concat(history_frames, HISTORY_COLUMNS),
                    _concat(rocking_frames, ROCKING_COLUMNS), summary)


def _concat(frames, columns) -> pd.DataFrame:
    """The frames one after the other, or an empty frame with the columns when there are none."""
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=columns)


def _spectra_rows(record_id, procedure_name, spectra):
    return spectra.to_frame().assign(record=record_id, procedure=procedure_name,
                                     alpha_deg=np.nan)[SPECTRA_COLUMNS]


SPECTRA_COLUMNS = ["record", "procedure", "alpha_deg", "damping", "period_s", "sd", "sv", "sa"]
HISTORY_COLUMNS = ["record", "alpha_deg", "size_s", "t", "theta_ratio", "omega"]
ROCKING_COLUMNS = ["record", "alpha_deg", "size_s", "p", "theta_peak", "theta_ratio",
                   "overturned", "omega_peak", "theta_after", "uplifted"]
RESULT_COLUMNS = ["record", "procedure", "alpha_deg", "size_s", "p", "exact_theta",
                  "exact_overturned", "approx_theta", "approx_overturned", "approx_period",
                  "iterations", "verdict", "ratio", "exact_omega", "exact_uplifted",
                  "approx_outcome", "approx_detail", "beta"]


def _result_rows(record_id, procedure_name, alpha_deg, sizes, p, estimate, exact, i):
    if exact is None:
        nan = np.full(sizes.shape, np.nan)
        exact_theta, exact_over, exact_omega, exact_up = nan, nan, nan, nan
    else:
        exact_theta = exact.theta_peak[i]
        exact_over = exact.overturned[i]
        exact_omega = exact.omega_peak[i]
        exact_up = exact.uplifted[i]
    verdict = classify(exact_theta, np.nan_to_num(exact_over).astype(bool),
                       np.nan_to_num(exact_up).astype(bool), estimate.theta, estimate.outcome)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.isin(verdict, ["conservative", "unconservative"]),
                         estimate.theta / exact_theta, np.nan)
    return pd.DataFrame({
        "record": record_id, "procedure": procedure_name, "alpha_deg": alpha_deg,
        "size_s": sizes, "p": p, "exact_theta": exact_theta,
        "exact_overturned": exact_over, "approx_theta": estimate.theta,
        "approx_overturned": estimate.outcome == OVERTURN, "approx_period": estimate.period_s,
        "iterations": estimate.iterations, "verdict": verdict, "ratio": ratio,
        "exact_omega": exact_omega, "exact_uplifted": exact_up,
        "approx_outcome": estimate.outcome, "approx_detail": estimate.detail,
        "beta": estimate.damping,
    })[RESULT_COLUMNS]


__all__ = ["run_audit", "AuditRun", "classify", "RecordContext", "VERDICTS", "size_grid"]
