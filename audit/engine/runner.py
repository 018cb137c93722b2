"""The audit: exact rocking spectra against guideline estimates, block by block (SPEC §5–8).

The unit of work is one record (:func:`audit_record`): its response spectra, its exact rocking
spectra (also at the record scaled by 1 ± ε, for the fragility flag), and every procedure's
estimates for every block of the grid. :func:`run_audit` runs it for each record of a suite and
combines the parts. Each block gets one verdict:

``no-uplift``        PGA ≤ g tan α: neither rocks.
``both-overturn``    both say the block overturns.
``false-overturn``   the procedure predicts overturning; the block survives.
``missed-overturn``  the block overturns; the procedure says it survives.
``agrees``           both survive and |approx/exact − 1| ≤ the agreement band.
``conservative``     approx/exact > 1 + band.
``unconservative``   approx/exact < 1 − band.
``not-converged``    the procedure's iteration settles in a cycle or does not settle.

A procedure that can estimate without the recorded motion (FEMA 356 reads a design spectrum)
still estimates for a record whose file is missing; those estimates have no exact response to be
compared with, so they are kept apart (``AuditRun.estimates_only``), not given a verdict.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from audit import G, __version__
from audit.engine.grid import DEFAULT_ALPHA_DEG, DEFAULT_SIZES, size_grid
from audit.errors import InputError
from audit.physics.block import RigidBlock, coefficient_of_restitution
from audit.physics.oscillator import response_spectra
from audit.physics.rocking import (DEFAULT_FREE_MOTION_S, DEFAULT_REST_TOLERANCE,
                                   DEFAULT_STEPS_PER_RADIAN, rocking_spectrum, simulate)
from procedures.base import (CYCLE_TOLERANCE_RATIO, INITIAL_ROTATION_RATIO, MAX_CYCLE_LENGTH,
                             MAX_ITERATIONS, NO_UPLIFT, NOT_CONVERGED, OVERTURN, TOLERANCE_RATIO,
                             check_verdicts, exact_exceeded)

VERDICTS = ("no-uplift", "both-overturn", "false-overturn", "missed-overturn", "agrees",
            "conservative", "unconservative", "not-converged")
#: Verdicts where the guideline errs on the unsafe side.
UNSAFE_VERDICTS = ("missed-overturn", "unconservative")
#: Verdicts where the guideline errs on the safe side.
UNECONOMIC_VERDICTS = ("false-overturn", "conservative")
#: Default half-width of the agreement band on approx/exact [-].
DEFAULT_AGREE_BAND = 0.10
#: Default relative scaling ε of the record for the fragility flag [-] (0 turns it off).
DEFAULT_ROBUSTNESS = 0.03
#: Damping ratios of the response spectra of Figures 5.x [-].
FIGURE_5_DAMPING = (0.05, 0.10, 0.15)
#: Periods on which procedures read record spectra (interpolated in between) [s].
SPECTRUM_PERIODS_S = np.concatenate(([0.0], np.geomspace(0.01, 100.0, 800)))
#: Periods of the stored procedure spectra (Figures 8.x, 9.x): up to 20 s [s].
PROCEDURE_SPECTRUM_PERIODS_S = SPECTRUM_PERIODS_S[SPECTRUM_PERIODS_S <= 20.0]
#: Samples kept per stored time history (about 2 per pixel of the report's figures).
HISTORY_POINTS = 2000

SPECTRA_COLUMNS = ["record", "procedure", "alpha_deg", "damping_pct", "period_s", "sd_m",
                   "sv_m_s", "sa_g"]
HISTORY_COLUMNS = ["record", "alpha_deg", "size_s", "time_s", "theta_ratio", "omega_rad_s"]
ROCKING_COLUMNS = ["record", "alpha_deg", "size_s", "p_rad_s", "theta_peak_rad", "theta_ratio",
                   "overturned", "omega_peak_rad_s", "theta_after_rad", "uplifted"]
RESULT_COLUMNS = ["record", "procedure", "alpha_deg", "size_s", "p_rad_s", "exact_theta_rad",
                  "exact_overturned", "exact_uplifted", "exact_fragile", "exact_omega_rad_s",
                  "approx_theta_rad", "approx_overturned", "approx_period_s", "approx_outcome",
                  "approx_fixed_points", "approx_cycle", "approx_detail", "iterations",
                  "beta_pct", "verdict", "ratio"]
#: ``checks.csv``: limit-state checks of check-type procedures (e.g. NTC 2018), one row per
#: procedure × record × α × size × limit state.
CHECK_COLUMNS = ["record", "procedure", "alpha_deg", "size_s", "limit_state", "exact_event",
                 "procedure_passes", "exact_exceeded", "verdict", "demand_m", "capacity_m",
                 "demand_g", "capacity_g", "demand_theta_rad", "theta_limit_rad", "period_s"]
#: ``suite.csv``: verdict statistics over the records, one row per procedure × α × size.
SUITE_COLUMNS = (["procedure", "alpha_deg", "size_s", "records"]
                 + [f"frac_{v.replace('-', '_')}" for v in VERDICTS]
                 + ["frac_unsafe", "ratio_p16", "ratio_p50", "ratio_p84"])
#: ``claims.csv``: the reproduction checklist of the reference report.
CLAIM_COLUMNS = ["id", "section", "claim", "reference_value", "tool_value", "status", "note"]
#: Columns holding booleans in ``results.csv`` (``exact_fragile`` is empty when not checked).
BOOLEAN_COLUMNS = ("exact_overturned", "exact_uplifted", "exact_fragile", "approx_overturned")


@dataclass(frozen=True)
class AuditSettings:
    """What a run computes, the same for every record (and hashed for resumable runs).

    Attributes
    ----------
    alpha_deg : tuple of float
        Slendernesses [degrees].
    size_s : tuple of float
        Block sizes 2π/p [s].
    free_motion_s : float
        Free motion after each record, for the exact solver and the record spectra [s].
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    robustness : float
        ε of the fragility flag: exact spectra also at the record × (1 ± ε) [-]; 0 = off.
    g : float
        Acceleration of gravity [m/s²].
    jobs : int
        Threads of the exact solver.
    """

    alpha_deg: tuple = DEFAULT_ALPHA_DEG
    size_s: tuple = tuple(size_grid(*DEFAULT_SIZES))
    free_motion_s: float = DEFAULT_FREE_MOTION_S
    agree_band: float = DEFAULT_AGREE_BAND
    robustness: float = DEFAULT_ROBUSTNESS
    g: float = G
    jobs: int = 1

    def as_dict(self) -> dict:
        """Plain values for ``summary.json`` (angles in degrees, sizes in s)."""
        values = asdict(self)
        values.pop("jobs")
        values.update(alpha_deg=list(self.alpha_deg), size_s=list(self.size_s))
        return values


class RecordContext:
    """What the procedures may ask of one record, computed once and cached.

    Parameters
    ----------
    entry : records.RecordEntry
    free_motion_s : float
        Free motion after the record [s], the same window as the exact solver's.
    jobs : int
        Threads computing the record's spectra.
    """

    def __init__(self, entry, free_motion_s: float, jobs: int = 1):
        self.entry = entry
        self.free_motion_s = free_motion_s
        self.jobs = jobs
        self._spectra = {}

    def true_spectra(self, damping: float, displacement_only: bool = False):
        """True response spectra of the record at damping β [-] on :data:`SPECTRUM_PERIODS_S`;
        Sd alone (Sv, Sa NaN) when ``displacement_only`` and no full spectra are cached."""
        key = round(float(damping), 12)
        cached = self._spectra.get(key)
        if cached is None or (cached[1] and not displacement_only):
            self._spectra[key] = (response_spectra(
                self.entry.motion, SPECTRUM_PERIODS_S, [key], self.free_motion_s, jobs=self.jobs,
                displacement_only=displacement_only), displacement_only)
        return self._spectra[key][0]

    def true_displacement(self, damping: float):
        """Sd(T) [m] at damping β [-], linear in T between the tabulated periods."""
        spectra = self.true_spectra(damping, displacement_only=True)
        return lambda period_s: spectra.displacement_at(period_s, 0)


def classify(exact_theta, exact_overturned, exact_uplifted, approx_theta, outcome,
             agree_band: float = DEFAULT_AGREE_BAND):
    """Verdict of each block (see the module docstring); arrays in, array of str out.

    Parameters
    ----------
    exact_theta : array
        Exact peak rotation [rad].
    exact_overturned, exact_uplifted : array of bool
    approx_theta : array
        The procedure's rotation [rad] (NaN where it predicts overturning or does not settle).
    outcome : array of str
        The procedure's outcome (``converged``, ``overturn``, ``no-uplift``, ``not-converged``).
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    """
    approx_over = outcome == OVERTURN
    exact_over = np.asarray(exact_overturned, dtype=bool)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = approx_theta / exact_theta
    return np.select(
        [(outcome == NO_UPLIFT) & ~np.asarray(exact_uplifted, dtype=bool),
         outcome == NOT_CONVERGED, approx_over & exact_over, approx_over, exact_over,
         np.abs(ratio - 1.0) <= agree_band, ratio > 1.0],
        ["no-uplift", "not-converged", "both-overturn", "false-overturn", "missed-overturn",
         "agrees", "conservative"],
        default="unconservative").astype(object)


@dataclass
class AuditRun:
    """Everything an audit produced; the report is rendered from this alone.

    Attributes
    ----------
    results : pandas.DataFrame
        One row per procedure × record × α × size with an exact response (``results.csv``).
    spectra : pandas.DataFrame
        Record response spectra (procedure "") and the spectra each procedure read.
    histories : pandas.DataFrame
        Time histories of the representative blocks.
    rocking : pandas.DataFrame
        Exact rocking spectra of every record with a file, whatever the procedures.
    estimates_only : pandas.DataFrame
        Estimates for records without a file (no exact response, no verdict); the columns
        of ``results`` that an estimate has.
    summary : dict
        Settings, records, unauditable records, per-record statistics (``summary.json``).
    checks : pandas.DataFrame
        Limit-state checks (:data:`CHECK_COLUMNS`), empty when no procedure makes any.
    suite : pandas.DataFrame
        Verdict statistics across the records (:data:`SUITE_COLUMNS`).
    claims : pandas.DataFrame
        The reproduction checklist of the reference report (:data:`CLAIM_COLUMNS`).
    """

    results: pd.DataFrame
    spectra: pd.DataFrame
    histories: pd.DataFrame
    rocking: pd.DataFrame
    estimates_only: pd.DataFrame
    summary: dict = field(default_factory=dict)
    checks: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(columns=CHECK_COLUMNS))
    suite: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(columns=SUITE_COLUMNS))
    claims: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(columns=CLAIM_COLUMNS))


@dataclass
class RecordAudit:
    """The part of an audit that one record contributes (see :func:`audit_record`)."""

    record_id: str
    results: pd.DataFrame
    estimates_only: pd.DataFrame
    spectra: pd.DataFrame
    histories: pd.DataFrame
    rocking: pd.DataFrame
    checks: pd.DataFrame
    unauditable: list
    histories_meta: list


def record_summary(entry) -> dict:
    """Provenance of one record for ``summary.json``: facts, site, file, PGA/PGV recomputed."""
    motion, facts = entry.motion, entry.facts
    item = {"id": entry.id, "name": entry.name, "component": entry.component,
            "missing": entry.missing, "missing_reason": entry.missing_reason, "site": entry.site,
            "metadata": entry.metadata}
    if facts is not None:
        item["table_5_1"] = {"pga_g": facts.pga_g, "pgv_m_s": facts.pgv_ms,
                             "pulse_period_s": facts.pulse_period_s}
    if motion is not None:
        # absolute, so a moved summary.json or report still names the file
        source = Path(motion.source) if motion.source else None
        item.update(source=str(source.absolute()) if source and source.is_file()
                    else motion.source, sha256=motion.sha256, dt_s=motion.dt,
                    duration_s=motion.duration, pga_g=motion.pga_g, pgv_m_s=motion.pgv,
                    npts=int(motion.acceleration.size))
    return item


def statistics(frame: pd.DataFrame) -> list[dict]:
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
            "fragile": int(group["exact_fragile"].eq(True).sum()),
            "median_ratio": float(ratio.median()) if len(ratio) else None,
            "min_ratio": float(ratio.min()) if len(ratio) else None,
            "max_ratio": float(ratio.max()) if len(ratio) else None,
        })
    return stats


def _representative_sizes(spectrum, alpha_index: int, count: int = 2) -> list[float]:
    """Sizes of blocks that rock and survive, spread over the range (for Figures 8.2, 8.5, …)."""
    rocking = (spectrum.uplifted[alpha_index] & ~spectrum.overturned[alpha_index]
               & (spectrum.theta_ratio[alpha_index] > 0.05))
    sizes = spectrum.size_s[rocking]
    if sizes.size == 0:
        return []
    picks = np.unique(np.quantile(np.arange(sizes.size), np.linspace(0.25, 0.75, count))
                      .round().astype(int))
    return [float(sizes[i]) for i in picks]


#: The worst blocks drawn as time histories, per procedure: (verdict, column ranked, largest
#: first?, reason). Missed overturnings rank by how small the procedure's rotation is.
WORST_CLASSES = (("unconservative", "ratio", False, "largest underestimate"),
                 ("missed-overturn", "approx_theta_rad", False, "missed overturning"),
                 ("conservative", "ratio", True, "largest overestimate"))


def rank_worst(rows: pd.DataFrame, column: str, largest: bool) -> pd.DataFrame:
    """``rows`` worst first by ``column``, blocks with a robust exact verdict before fragile ones
    (a missed overturning that a 3 % change of the record undoes is a weaker case)."""
    fragile = rows["exact_fragile"].eq(True)
    return rows.assign(_fragile=fragile).sort_values(
        ["_fragile", column], ascending=[True, not largest], kind="stable").drop(
        columns="_fragile")


def compiles_first() -> bool:
    """Whether the rocking solver and the oscillator kernels the audit runs lack cached machine
    code, so that the first record waits for numba to compile them (once after installing)."""
    from audit.physics import oscillator, rocking
    from audit.physics.tiers import machine_code_cached
    return not (machine_code_cached(rocking._spectrum) and machine_code_cached(oscillator._peaks))


def history_blocks(results: pd.DataFrame, spectrum, alpha_deg, per_class: int = 1) -> list[dict]:
    """The blocks of one record worth a time history: each procedure's worst ones per class
    (:data:`WORST_CLASSES`) and representative rocking blocks at α ≈ 15°.

    Returns
    -------
    list of dict
        ``alpha_deg``, ``size_s`` and ``reason`` (why it was picked; reasons of a block picked
        several times are joined with "; "), in order of first pick.
    """
    picks = {}

    def pick(alpha, size, reason):
        key = (round(float(alpha), 9), round(float(size), 9))
        picks.setdefault(key, []).append(reason)

    for procedure, rows in results.groupby("procedure", sort=False):
        for verdict, column, largest, reason in WORST_CLASSES:
            hits = rank_worst(rows[rows["verdict"] == verdict], column, largest)
            for _, row in hits.head(per_class).iterrows():
                pick(row["alpha_deg"], row["size_s"], f"{reason}, {procedure}")
    alpha_index = int(np.argmin(np.abs(np.asarray(alpha_deg) - 15.0)))
    for size in _representative_sizes(spectrum, alpha_index):
        pick(alpha_deg[alpha_index], size, "representative")
    return [{"alpha_deg": alpha, "size_s": size, "reason": "; ".join(reasons)}
            for (alpha, size), reasons in picks.items()]


def _history_rows(response, record_id, alpha_deg, size_s):
    stride = max(1, response.time.size // HISTORY_POINTS)
    return pd.DataFrame({
        "record": record_id, "alpha_deg": alpha_deg, "size_s": size_s,
        "time_s": response.time[::stride],
        "theta_ratio": response.theta[::stride] / response.block.alpha,
        "omega_rad_s": response.omega[::stride],
    })


def fragile_overturning(motion, settings: AuditSettings, overturned: np.ndarray):
    """Blocks whose overturning verdict changes when the record is scaled by 1 ± ε.

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
        other = rocking_spectrum(motion.scaled(factor), np.asarray(settings.size_s),
                                 np.radians(settings.alpha_deg), g=settings.g,
                                 free_motion_s=settings.free_motion_s, jobs=settings.jobs)
        fragile |= other.overturned != overturned
    return fragile


def _exact_response(motion, sizes, alpha_rad, settings: AuditSettings):
    """The exact rocking spectrum of the grid and its fragile blocks (see
    :func:`fragile_overturning`)."""
    exact = rocking_spectrum(motion, sizes, alpha_rad, g=settings.g,
                             free_motion_s=settings.free_motion_s, jobs=settings.jobs)
    return exact, fragile_overturning(motion, settings, exact.overturned)


def audit_record(entry, procedures, settings: AuditSettings) -> RecordAudit:
    """Audit every procedure on one record over the (α, 2π/p) grid: the unit of work.

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
    p = 2.0 * np.pi / sizes
    g = settings.g
    motion = entry.motion
    context = (RecordContext(entry, settings.free_motion_s, settings.jobs)
               if motion is not None else None)
    results, estimates_only, spectra, histories, rocking, checks = [], [], [], [], [], []
    unauditable, histories_meta = [], []
    exact_job = None
    if motion is not None:
        # the exact solver releases the GIL: it runs beside the procedures, whose fixed-point
        # iterations hold it and would leave the second core idle
        for damping in FIGURE_5_DAMPING:
            spectra.append(context.true_spectra(damping).to_frame()
                           .assign(record=entry.id, procedure="", alpha_deg=np.nan)
                           [SPECTRA_COLUMNS])
        pool = ThreadPoolExecutor(1)
        exact_job = pool.submit(_exact_response, motion, sizes, alpha_rad, settings)
        pool.shutdown(wait=False)  # its one thread ends with the job; an interrupt waits for none
    estimates = []  # (procedure, α index, estimate, checks)
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
            r = float(coefficient_of_restitution(alpha))
            estimate = procedure.estimate(entry, p, alpha, r, context, g)
            # the spectrum this procedure read, whatever its source (Figures 8.x, 9.x)
            sd = procedure.displacement_spectrum(entry, estimate.damping,
                                                 context)(PROCEDURE_SPECTRUM_PERIODS_S)
            spectra.append(pd.DataFrame({
                "record": entry.id, "procedure": procedure.name, "alpha_deg": alpha_deg[i],
                "damping_pct": 100.0 * estimate.damping, "period_s": PROCEDURE_SPECTRUM_PERIODS_S,
                "sd_m": sd, "sv_m_s": np.nan, "sa_g": np.nan}))
            # a check is audited only against an exact response
            estimates.append((procedure.name, i, estimate, procedure.checks(
                entry, p, alpha, r, context, g) if motion is not None else []))
    exact, fragile = exact_job.result() if exact_job is not None else (None, None)
    if exact is not None:
        rocking.append(exact.to_frame().assign(record=entry.id)[ROCKING_COLUMNS])
    for name, i, estimate, procedure_checks in estimates:
        rows = _result_rows(entry.id, name, alpha_deg[i], sizes, p, estimate, exact, fragile, i,
                            settings.agree_band)
        (results if exact is not None else estimates_only).append(rows)
        checks += [_check_rows(entry.id, name, alpha_deg[i], sizes, check, exact, i, g)
                   for check in procedure_checks]
    if exact is not None:
        for pick in history_blocks(_concat(results, RESULT_COLUMNS), exact, alpha_deg):
            block = RigidBlock.from_size(pick["size_s"], np.radians(pick["alpha_deg"]), g=g)
            response = simulate(block, motion, settings.free_motion_s)
            histories.append(_history_rows(response, entry.id, pick["alpha_deg"],
                                           pick["size_s"]))
            histories_meta.append({
                "record": entry.id, **pick, "cycle_starts_s": response.cycle_starts.tolist(),
                "cycle_durations_s": response.cycle_durations.tolist(),
                "first_impact_s": float(response.impact_times[0]) if response.n_impacts else None,
                "last_impact_s": float(response.impact_times[-1]) if response.n_impacts else None,
                "peak_rotation_ratio": response.peak_rotation_ratio,
                "overturned": bool(response.overturned),
                "overturn_time_s": (float(response.overturn_time) if response.overturned
                                    else None),
                "excitation_end_s": response.excitation_end})
    return RecordAudit(entry.id, _concat(results, RESULT_COLUMNS),
                       _concat(estimates_only, RESULT_COLUMNS), _concat(spectra, SPECTRA_COLUMNS),
                       _concat(histories, HISTORY_COLUMNS), _concat(rocking, ROCKING_COLUMNS),
                       _concat(checks, CHECK_COLUMNS), unauditable, histories_meta)


def combine(parts: list[RecordAudit], procedures, suite, settings: AuditSettings) -> AuditRun:
    """One :class:`AuditRun` from the per-record parts, in the suite's order.

    Adds the suite statistics (:func:`audit.engine.suite.suite_statistics`, ``AuditRun.suite``)
    and their summary (``summary["suite"]``).
    """
    def cat(name, columns):
        return _concat([getattr(part, name) for part in parts if len(getattr(part, name))],
                       columns)

    from audit.engine.suite import suite_statistics, suite_summary
    results = cat("results", RESULT_COLUMNS)
    suite_frame = suite_statistics(results)
    summary = {
        "version": __version__,
        "procedures": [{"name": proc.name, "title": proc.title, "reference": proc.reference,
                        "damping_law": proc.damping_law, "spectrum_source": proc.spectrum_source,
                        "figure_series": proc.figure_series} for proc in procedures],
        "records_source": suite.description,
        "pulse_idealised": suite.is_pulse_idealised,
        "records": [record_summary(entry) for entry in suite],
        "rejected_records": list(getattr(suite, "rejected", ())),
        "design_site": suite.design_site,
        "scaling": suite.scaling,
        "unauditable": [item for part in parts for item in part.unauditable],
        "grid": {"alpha_deg": list(settings.alpha_deg), "size_s": list(settings.size_s)},
        "settings": {
            **settings.as_dict(),
            "steps_per_radian": DEFAULT_STEPS_PER_RADIAN, "rest_tolerance": DEFAULT_REST_TOLERANCE,
            "initial_rotation_ratio": INITIAL_ROTATION_RATIO, "tolerance_ratio": TOLERANCE_RATIO,
            "max_iterations": MAX_ITERATIONS, "max_cycle_length": MAX_CYCLE_LENGTH,
            "cycle_tolerance_ratio": CYCLE_TOLERANCE_RATIO,
            "figure_5_damping_pct": [100.0 * d for d in FIGURE_5_DAMPING],
        },
        "statistics": statistics(results),
        "suite": suite_summary(suite_frame, {proc.name: proc.title for proc in procedures}),
        "histories": [item for part in parts for item in part.histories_meta],
    }
    return AuditRun(results, cat("spectra", SPECTRA_COLUMNS), cat("histories", HISTORY_COLUMNS),
                    cat("rocking", ROCKING_COLUMNS), cat("estimates_only", RESULT_COLUMNS),
                    summary, checks=cat("checks", CHECK_COLUMNS), suite=suite_frame)


def run_audit(procedures, suite, alpha_deg=DEFAULT_ALPHA_DEG, sizes=None, jobs: int = 1,
              free_motion_s: float = DEFAULT_FREE_MOTION_S, progress=None, g: float = G,
              agree_band: float = DEFAULT_AGREE_BAND, robustness: float = DEFAULT_ROBUSTNESS,
              scheduler: str = "local", partial_dir=None, resume: bool = False,
              detail=()) -> AuditRun:
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
        ``local``: threads of the exact solver; ``dask``: worker processes of the LocalCluster.
    free_motion_s : float
        Free motion after each record, for the exact solver and the record spectra [s].
    progress : callable, optional
        ``progress(done, total, record_id, how)`` after each record (``how`` in words).
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    robustness : float
        ε of the fragility flag [-]; 0 turns it off.
    scheduler : str
        ``local``, ``dask`` or ``tcp://HOST:PORT`` (:mod:`audit.engine.scheduler`).
    partial_dir : str or Path, optional
        Folder for per-record results as they complete (:mod:`audit.engine.partial`).
    resume : bool
        Reuse the matching per-record results already in ``partial_dir``.
    detail : sequence of str
        Record ids whose per-record detail the report should show (``summary["detail"]``).

    Returns
    -------
    AuditRun
        ``summary["resumed"]`` lists the records taken from ``partial_dir``.
    """
    from audit.engine.partial import PartialStore
    from audit.engine.scheduler import open_scheduler
    sizes = size_grid(*DEFAULT_SIZES) if sizes is None else np.asarray(sizes, dtype=float)
    settings = AuditSettings(tuple(float(a) for a in alpha_deg), tuple(float(s) for s in sizes),
                             float(free_motion_s), float(agree_band), float(robustness), float(g),
                             int(jobs))
    entries = list(suite)
    known = {entry.id for entry in entries}
    unknown = [record_id for record_id in detail if record_id not in known]
    if unknown:
        raise InputError(f"--detail: unknown record(s) {', '.join(unknown)} in "
                         f"{suite.description}")
    store = PartialStore(partial_dir, procedures, settings, resume) if partial_dir else None
    progress = progress or (lambda done, total, record_id, how: None)
    parts = [store.load(entry) if store and resume else None for entry in entries]
    resumed = [entry.id for entry, part in zip(entries, parts) if part is not None]
    for count, record_id in enumerate(resumed, start=1):
        progress(count, len(entries), record_id, "reused from an interrupted run")
    todo = [i for i, part in enumerate(parts) if part is None]
    with open_scheduler(scheduler, jobs) as executor:
        for count, (k, part, seconds) in enumerate(
                executor.audit([entries[i] for i in todo], procedures, settings),
                start=len(resumed) + 1):
            parts[todo[k]] = part
            if store:
                store.save(entries[todo[k]], part)
            progress(count, len(entries), part.record_id, f"computed in {seconds:.1f} s")
    run = combine(parts, procedures, suite, settings)
    run.summary.update(scheduler=executor.description, resumed=resumed, detail=list(detail))
    return run


def _concat(frames, columns) -> pd.DataFrame:
    """The frames one after the other, or an empty frame with the columns when there are none."""
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=columns)


def _result_rows(record_id, procedure_name, alpha_deg, sizes, p, estimate, exact, fragile, i,
                 agree_band):
    nan = np.full(sizes.shape, np.nan)
    if exact is None:
        exact_theta, exact_over, exact_omega, exact_up, verdict = nan, nan, nan, nan, ""
        exact_fragile = nan
    else:
        exact_theta = exact.theta_peak[i]
        exact_over = exact.overturned[i]
        exact_omega = exact.omega_peak[i]
        exact_up = exact.uplifted[i]
        exact_fragile = nan if fragile is None else fragile[i]
        verdict = classify(exact_theta, exact_over, exact_up, estimate.theta, estimate.outcome,
                           agree_band)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.isin(verdict, ["agrees", "conservative", "unconservative"]),
                         estimate.theta / exact_theta, np.nan)
    return pd.DataFrame({
        "record": record_id, "procedure": procedure_name, "alpha_deg": alpha_deg,
        "size_s": sizes, "p_rad_s": p, "exact_theta_rad": exact_theta,
        "exact_overturned": exact_over, "exact_uplifted": exact_up,
        "exact_fragile": exact_fragile, "exact_omega_rad_s": exact_omega,
        "approx_theta_rad": estimate.theta, "approx_overturned": estimate.outcome == OVERTURN,
        "approx_period_s": estimate.period_s, "approx_outcome": estimate.outcome,
        "approx_fixed_points": estimate.fixed_points, "approx_cycle": estimate.cycle,
        "approx_detail": estimate.detail, "iterations": estimate.iterations,
        "beta_pct": 100.0 * estimate.damping, "verdict": verdict, "ratio": ratio,
    })[RESULT_COLUMNS]


def _check_rows(record_id, procedure_name, alpha_deg, sizes, check, exact, i, g):
    """One row per block of a limit-state check, with the exact event it is audited against."""
    exceeded = exact_exceeded(check, exact.theta_peak[i], exact.overturned[i], exact.uplifted[i])
    return pd.DataFrame({
        "record": record_id, "procedure": procedure_name, "alpha_deg": alpha_deg,
        "size_s": sizes, "limit_state": check.limit_state, "exact_event": check.exact_event,
        "procedure_passes": np.asarray(check.passes, dtype=bool), "exact_exceeded": exceeded,
        "verdict": check_verdicts(check.passes, exceeded), "demand_m": check.demand_m,
        "capacity_m": check.capacity_m, "demand_g": check.demand_m_s2 / g,
        "capacity_g": check.capacity_m_s2 / g, "demand_theta_rad": check.demand_theta_rad,
        "theta_limit_rad": check.theta_limit_rad, "period_s": check.period_s,
    })[CHECK_COLUMNS]


__all__ = ["run_audit", "audit_record", "combine", "AuditRun", "AuditSettings", "RecordAudit",
           "classify", "RecordContext", "VERDICTS", "UNSAFE_VERDICTS", "UNECONOMIC_VERDICTS"]
