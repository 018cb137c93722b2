"""The design-level audit: how likely is a block to overturn, and where each guideline draws
its line, the FEMA P695 way.

For every block of the grid, the suite's records are scaled to a set of intensity levels
(stripes, :mod:`audit.engine.fragility`); the exact response at every record × stripe gives the
fraction that overturns at each level, and a lognormal fragility fitted to those counts. Each
procedure is evaluated at the same stripes, on the same scaled records (and on its site's design
spectrum scaled to the same level, for one that reads a design spectrum): the fraction of
records for which it predicts overturning is its fragility (a step, for a procedure that reads
only the site). Per procedure and block:

* the guideline's overturning intensity: where the fraction it predicts first reaches one half
  (interpolated in ln IM between stripes; a step's level for a site-based procedure);
* its ratio to the exact fragility's median;
* the achieved probability of overturning there, from the exact fit and from the nearest
  stripe's count;
* the FEMA P695 collapse margin ratio CMR = exact median / the site's MCE intensity (the
  site's values are taken as MCE-level, or as design-level and × 1.5: :data:`SITE_LEVELS`); a
  median beyond the stripes is an extrapolation and its CMR a bound.

A procedure predicts overturning for a block when its estimate is ``overturn`` or one of its
checks of limit state ``overturning`` fails.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from audit.engine.blocks import BlockList
from audit.engine.csv_text import csv_bytes
from audit.engine.fragility import overturning_pattern, stripe_levels, stripe_outcomes
from audit.engine.fragility_bootstrap import bootstrap_lognormal
from audit.engine.lognormal_fit import fit_lognormal
from audit.engine.intensity import IntensityMeasure
from audit.engine.defaults import SITE_LEVELS
from audit.engine.margins_settings import MarginsSettings
from audit.engine.partial import PartialStore
from audit.engine.runtime import Runtime
from audit.engine.scheduler import computed_parts
from audit.errors import InputError
from audit.physics.block import Restitution
from audit.physics.rocking import rocking_blocks
from procedures.context import RecordContext
from procedures.overturning import overturning_predictions, predicts_overturning
from records.sites import scaled_site

def half_crossing(levels, fraction) -> float:
    """Where ``fraction`` first reaches 0.5 along ascending ``levels``, ln-interpolated; NaN if
    never."""
    above = np.flatnonzero(fraction >= 0.5)
    if above.size == 0:
        return math.nan
    j = above[0]
    if j == 0 or fraction[j] == fraction[j - 1]:
        return float(levels[j])
    t = (0.5 - fraction[j - 1]) / (fraction[j] - fraction[j - 1])
    return float(np.exp(np.log(levels[j - 1]) + t * np.log(levels[j] / levels[j - 1])))


@dataclass
class MarginsRun:
    """Everything the design-level audit produced (``stripes.csv``, ``fragility.csv``,
    ``capacity.csv``, ``scan.csv`` and ``summary``)."""

    stripes: pd.DataFrame
    fragility: pd.DataFrame
    capacity: pd.DataFrame
    summary: dict = field(default_factory=dict)
    #: ``required_alpha.csv`` (:func:`~audit.engine.required_alpha.required_alpha`), None when
    #: not computed.
    required_alpha: pd.DataFrame | None = None
    #: ``scan.csv`` (:func:`amplitude_scans`), None when not computed.
    scan: pd.DataFrame | None = None
    #: ``risk.csv``, ``risk_alpha.csv`` and ``hazard.csv`` at a site
    #: (:func:`~audit.engine.margins_risk.margins_risk`), None without a hazard curve.
    risk: pd.DataFrame | None = None
    risk_alpha: pd.DataFrame | None = None
    hazard: pd.DataFrame | None = None
    #: ``acceptance.csv`` (:func:`~audit.engine.p695_acceptance.p695_acceptance`), None
    #: without the required slenderness or a design site.
    acceptance: pd.DataFrame | None = None


@dataclass(frozen=True)
class StripeSettings:
    """What every record's stripes depend on (and the key of a resumable part).

    Attributes
    ----------
    im : IntensityMeasure
    levels : tuple of float
        Stripes, ascending [unit of ``im``].
    design_im : float or None
        The site's design intensity [unit of ``im``]: design spectra are scaled by
        level / design_im.
    blocks : audit.engine.blocks.BlockList
    restitution : audit.physics.block.Restitution
    g, free_motion_s : float
        Gravity [m/s²], free motion after each record [s].
    jobs : int
        Solver threads of a task.
    """

    im: IntensityMeasure
    levels: tuple
    design_im: float | None
    blocks: BlockList
    restitution: Restitution
    g: float
    free_motion_s: float
    jobs: int

    def as_dict(self) -> dict:
        return {"kind": "margins stripes", "im": self.im.name, "levels": list(self.levels),
                "design_im": self.design_im, "alpha_deg": self.blocks.alpha_deg.tolist(),
                "size_s": self.blocks.size_s.tolist(), "block_m": self.blocks.label.tolist(),
                "restitution": str(self.restitution), "g": self.g,
                "free_motion_s": self.free_motion_s}


@dataclass
class RecordStripes:
    """One record's part of the design-level audit: arrays shaped (stripe, block).

    Attributes
    ----------
    record_id : str
    intensity : float
        The record's intensity as given [unit of the intensity measure].
    exact_overturned, exact_theta_rad : numpy.ndarray
    predicted : dict
        Per procedure name, whether it predicts overturning (False where it cannot evaluate).
    evaluated : dict
        Per procedure name, whether it could evaluate the record.
    """

    record_id: str
    intensity: float
    exact_overturned: np.ndarray
    exact_theta_rad: np.ndarray
    predicted: dict
    evaluated: dict


def _at_level(entry, base: RecordContext, level: float, intensity: float,
              settings: StripeSettings):
    """The record scaled to ``level`` and its context; its design spectrum scaled to the level
    too, where the site's design intensity is known."""
    factor = level / intensity
    site_factor = level / settings.design_im if settings.design_im else 1.0
    scaled = replace(entry, motion=entry.motion.scaled(factor),
                     site=scaled_site(entry.site, site_factor))
    return scaled, base.scaled(scaled, factor)


#: Relative width in level to which the step of a site-based procedure is located.
STEP_TOLERANCE = 1e-7


def step_level(procedure, entry, settings: StripeSettings, block: int, low: float,
               high: float) -> float:
    """The level at which a procedure that reads only the site's design spectrum turns from
    not predicting overturning (at ``low``) to predicting it (at ``high``) for one block:
    its answer is a step in intensity, located by bisection in ln(level) to
    :data:`STEP_TOLERANCE`, not at a point between the stripes."""
    blocks = settings.blocks
    p = np.array([2.0 * math.pi / blocks.size_s[block]])
    alpha = math.radians(float(blocks.alpha_deg[block]))
    r = float(settings.restitution.r(alpha))
    intensity = settings.im.of_record(entry.motion, settings.free_motion_s)
    base = RecordContext(entry, settings.free_motion_s, settings.jobs)
    while high / low > 1.0 + STEP_TOLERANCE:
        middle = math.sqrt(low * high)
        scaled, context = _at_level(entry, base, middle, intensity, settings)
        evaluation = procedure.evaluate(scaled, p, alpha, r, context, settings.g)
        if predicts_overturning(evaluation)[0]:
            high = middle
        else:
            low = middle
    return math.sqrt(low * high)


#: Answers of procedures that read only the site (:meth:`~procedures.base.Procedure.reads_record`
#: false): one answer for every record of a suite, so each process computes it once.
_SITE_ANSWERS: dict = {}


def procedure_predictions(proc, cases, p, groups, g) -> np.ndarray:
    """:func:`~procedures.overturning.overturning_predictions`, kept across records for a
    procedure that reads only the (scaled) sites."""
    if any(proc.reads_record(entry) for entry, _ in cases):
        return overturning_predictions(proc, cases, p, groups, g)
    # ``proc`` is kept with its answer, so its id is not reused while the answer is
    key = (id(proc), tuple(tuple(sorted(entry.site.items())) for entry, _ in cases),
           p.tobytes(), tuple((alpha, index.tobytes(), r) for alpha, index, r in groups), g)
    if key not in _SITE_ANSWERS:
        if len(_SITE_ANSWERS) >= 16:
            _SITE_ANSWERS.clear()
        _SITE_ANSWERS[key] = (proc, overturning_predictions(proc, cases, p, groups, g))
    return _SITE_ANSWERS[key][1].copy()


def record_stripes(entry, procedures, settings: StripeSettings,
                   context: RecordContext | None = None) -> RecordStripes:
    """The exact response and every procedure's prediction for one record scaled to each stripe
    (the unit of work of the design-level audit); ``context``, the record's spectra, when a
    caller reads them again after."""
    blocks, levels = settings.blocks, np.asarray(settings.levels, dtype=float)
    intensity = settings.im.of_record(entry.motion, settings.free_motion_s)
    factors = levels / intensity
    shape = (levels.size, len(blocks))
    exact_over, exact_theta = np.zeros(shape, dtype=bool), np.zeros(shape)
    groups = blocks.groups()
    for alpha, index in groups:
        over, theta = stripe_outcomes(entry.motion, factors, blocks.size_s[index], [alpha],
                                      settings.g, settings.free_motion_s, settings.jobs,
                                      r=settings.restitution)
        exact_over[:, index], exact_theta[:, index] = over[:, 0], theta[:, 0]
    p = 2.0 * np.pi / blocks.size_s
    base = context or RecordContext(entry, settings.free_motion_s, settings.jobs)
    cases = [_at_level(entry, base, float(level), intensity, settings) for level in levels]
    alpha_groups = [(alpha, index, float(settings.restitution.r(alpha)))
                    for alpha, index in groups]
    predicted, evaluated = {}, {}
    for proc in procedures:
        predicted[proc.name] = np.zeros(shape, dtype=bool)
        mine = [j for j, (scaled, _) in enumerate(cases)
                if proc.unmet_requirements(scaled) is None]
        evaluated[proc.name] = bool(mine)
        if mine:
            predicted[proc.name][mine] = procedure_predictions(
                proc, [cases[j] for j in mine], p, alpha_groups, settings.g)
    return RecordStripes(entry.id, intensity, exact_over, exact_theta, predicted, evaluated)


def run_margins(procedures, suite, settings: MarginsSettings, runtime: Runtime) -> MarginsRun:
    """Multiple-stripe exact fragility of every block and each procedure's line against it.

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
        Its ``design_site`` gives the design intensity.
    settings : MarginsSettings
        The intensity measure, the stripes (default
        :func:`~audit.engine.fragility.stripe_levels` around the design intensity, else the
        suite's median intensity), the grid and the named blocks, the impact model, gravity
        and the free motion.
    runtime : Runtime
        Solver threads (worker processes of ``scheduler="dask"``), where records are computed,
        the folder of parts kept as they complete and whether to reuse them, progress.
    """
    im, levels, alpha_deg = settings.im, settings.stripes, settings.alpha_deg
    size_s, named_blocks, g = settings.size_s, settings.blocks, settings.g
    restitution, free_motion_s, jobs = settings.restitution, settings.free_motion_s, runtime.jobs
    partial_dir, resume, site_level = runtime.partial_dir, runtime.resume, settings.site_level
    entries = [entry for entry in suite if entry.motion is not None]
    if not entries:
        raise InputError(f"records: no record of {suite.description} has a file", "records")
    intensities = {entry.id: im.of_record(entry.motion, free_motion_s) for entry in entries}
    zero = [record_id for record_id, intensity in intensities.items() if not intensity > 0]
    if zero:
        raise InputError(f"records: {zero[0]} has zero intensity ({im.name} = 0: an all-zero "
                         f"record), so no stripe can be reached by scaling it; leave it out"
                         + (f" ({len(zero) - 1} other record(s) too)" if len(zero) > 1 else ""),
                         "records")
    design = im.of_design_site(suite.design_site)
    if levels is None:
        centre = design if design else float(np.median(list(intensities.values())))
        levels = stripe_levels(centre)
    blocks = BlockList.of(alpha_deg, size_s if size_s is not None else (), named_blocks)
    if not len(blocks):
        raise InputError("sizes_s, alpha_deg, blocks: no block to audit", "sizes_s",
                         "alpha_deg", "blocks")
    settings = StripeSettings(im, tuple(np.sort(np.asarray(levels, dtype=float)).tolist()),
                              design, blocks, restitution, float(g), float(free_motion_s),
                              int(jobs))
    store = PartialStore(partial_dir, procedures, settings, resume) if partial_dir else None
    parts, resumed, where = computed_parts(record_stripes, entries, procedures, settings,
                                           runtime.scheduler, store, resume, runtime.progress)
    levels = np.asarray(settings.levels)
    intensities = np.array([part.intensity for part in parts])
    exact_over = np.stack([part.exact_overturned for part in parts])  # (record, stripe, block)
    exact_theta = np.stack([part.exact_theta_rad for part in parts])
    predicted = {proc.name: np.stack([part.predicted[proc.name] for part in parts])
                 for proc in procedures}
    evaluated = {proc.name: np.array([part.evaluated[proc.name] for part in parts])
                 for proc in procedures}
    site_factors = np.array([site_factor(suite, e.id) for e in entries])
    stripes = _stripe_rows(entries, levels, intensities, site_factors, blocks, im, exact_over,
                           exact_theta, predicted)
    mce = design * SITE_LEVELS[site_level] if design else None
    fragility, fits, boots = _fragility_rows(levels, blocks, im, exact_over, mce)
    steps = _step_levels(procedures, entries, settings, predicted, evaluated)
    capacity = _capacity_rows(procedures, levels, blocks, exact_over, predicted, evaluated, fits,
                              boots, steps)
    summary = {"im": im.name, "im_unit": im.unit, "levels": levels.tolist(),
               "design_im": design, "site_level": site_level, "mce_im": mce,
               "records": [e.id for e in entries],
               "records_source": suite.description, "design_site": suite.design_site,
               "scaling": suite.scaling, "restitution": str(settings.restitution),
               "scheduler": where, "resumed": resumed,
               "procedures": [{"name": proc.name, "title": proc.title,
                               "reads": _reading(proc, entries)} for proc in procedures],
               "grid": {"alpha_deg": [float(a) for a in alpha_deg],
                        "size_s": np.asarray(size_s if size_s is not None else (),
                                             dtype=float).tolist()},
               "blocks": [{"block_m": b.label, "width_m": b.width_m, "height_m": b.height_m,
                           "alpha_deg": b.alpha_deg, "size_s": b.size_s}
                          for b in named_blocks]}
    return MarginsRun(stripes, fragility, capacity, summary)


#: How a procedure meets the stripes, by whether it reads the records (the report says it).
READINGS = {True: "each record scaled to the level: a fragility, the share of records for "
                  "which it predicts overturning",
            False: "the site's design spectrum scaled to the level: a step, one answer for "
                   "every record"}


def _reading(procedure, entries) -> str:
    """Which reading of the stripes a procedure gets, over the records it can evaluate."""
    readings = {procedure.reads_record(e) for e in entries
                if procedure.unmet_requirements(e) is None}
    if not readings:
        return "none: it can evaluate no record of the suite"
    return "; ".join(READINGS[reading] for reading in sorted(readings, reverse=True))


def _block_columns(blocks: BlockList, index) -> dict:
    return {"alpha_deg": blocks.alpha_deg[index], "size_s": blocks.size_s[index],
            "block_m": blocks.label[index]}


def site_factor(suite, record_id: str) -> float:
    """The factor by which the suite's scaling to a site (FEMA P695) scaled a record, 1 where
    it was not scaled."""
    scaled = (suite.scaling or {}).get("records", {}).get(record_id)
    return float(scaled["scale_factor"]) if scaled else 1.0


def _stripe_rows(entries, levels, intensities, site_factors, blocks, im, exact_over,
                 exact_theta, predicted) -> pd.DataFrame:
    record, level, block = np.indices(exact_over.shape).reshape(3, -1)
    frame = pd.DataFrame({
        "record": np.array([e.id for e in entries])[record], **_block_columns(blocks, block),
        "im": im.name, "im_level": levels[level],
        "scale_factor": levels[level] / intensities[record] * site_factors[record],
        "site_factor": site_factors[record],
        "exact_overturned": exact_over.reshape(-1), "exact_theta_rad": exact_theta.reshape(-1)})
    for name, over in predicted.items():
        frame[f"{name}_overturns"] = over.reshape(-1)
    return frame


def _cmr(fit, levels, mce) -> tuple[float, str]:
    """The collapse margin ratio and how far it is known: a median beyond the stripes is an
    extrapolation of the fit, so the CMR is only bounded by the outermost stripe there."""
    if fit is None or not mce:
        return math.nan, ""
    if fit.median > levels[-1]:
        return levels[-1] / mce, "at least"
    if fit.median < levels[0]:
        return levels[0] / mce, "at most"
    return fit.median / mce, ""


def _percentile_band(values, confidence: float = 0.90) -> tuple[float, float]:
    """The two-sided percentile band of resampled values that may be ±inf (a resample with no
    overturning has θ = inf): read at the order statistics, without interpolating."""
    tail = 50.0 * (1.0 - confidence)
    return (float(np.percentile(values, tail, method="lower")),
            float(np.percentile(values, 100.0 - tail, method="higher")))


def _fragility_rows(levels, blocks, im, exact_over, mce):
    """``fragility.csv`` and, per block, its lognormal fit and its bootstrap over records
    (records are reused across the stripes, so the binomial band is too narrow)."""
    rows, fits, boots = [], [], []
    n_records = exact_over.shape[0]
    nan = math.nan
    for b in range(len(blocks)):
        counts = exact_over[:, :, b].sum(axis=0)
        pattern = overturning_pattern(exact_over[:, :, b])
        try:
            fit = fit_lognormal(levels, np.full(levels.size, n_records), counts)
        except ValueError:
            fit = None
        boot = bootstrap_lognormal(levels, exact_over[:, :, b]) if fit else None
        fits.append(fit)
        boots.append(boot)
        cmr, bound = _cmr(fit, levels, mce)
        median_band = _percentile_band(boot.medians) if boot else (nan, nan)
        beta_band = _percentile_band(boot.betas[np.isfinite(boot.betas)]) \
            if boot and np.isfinite(boot.betas).any() else (nan, nan)
        rows.append({
            **_block_columns(blocks, b), "im": im.name, "records": n_records,
            "stripes": levels.size, "median": fit.median if fit else nan,
            "beta": fit.beta if fit else nan,
            "median_low": fit.median_band[0] if fit else nan,
            "median_high": fit.median_band[1] if fit else nan,
            "beta_low": fit.beta_band[0] if fit else nan,
            "beta_high": fit.beta_band[1] if fit else nan,
            "median_boot_low": median_band[0], "median_boot_high": median_band[1],
            "beta_boot_low": beta_band[0], "beta_boot_high": beta_band[1],
            "median_extrapolated": fit is not None and not levels[0] <= fit.median <= levels[-1],
            "cmr": cmr, "cmr_bound": bound,
            "cmr_boot_low": median_band[0] / mce if mce else nan,
            "cmr_boot_high": median_band[1] / mce if mce else nan,
            "records_with_islands": int(pattern.islands.sum()),
            "island_share": float(pattern.islands.mean())})
    return pd.DataFrame(rows), fits, boots


def _step_levels(procedures, entries, settings: StripeSettings, predicted, evaluated) -> dict:
    """Per (procedure name, block), the exact step of a procedure that reads only the site's
    design spectrum, where it turns to predicting overturning between two stripes."""
    levels = np.asarray(settings.levels)
    steps = {}
    for proc in procedures:
        mine = [e for e, used in zip(entries, evaluated[proc.name]) if used]
        if not mine or any(proc.reads_record(e) for e in mine):
            continue
        answer = predicted[proc.name][np.asarray(evaluated[proc.name])][0]  # (stripe, block)
        for b in range(answer.shape[1]):
            switch = np.flatnonzero(answer[1:, b] & ~answer[:-1, b])
            if switch.size:
                j = int(switch[0])
                steps[proc.name, b] = step_level(proc, mine[0], settings, b, levels[j],
                                                 levels[j + 1])
    return steps


def _capacity_rows(procedures, levels, blocks, exact_over, predicted, evaluated, fits, boots,
                   steps):
    rows = []
    exact_fraction = exact_over.mean(axis=0)  # (stripe, block)
    for proc in procedures:
        mine = evaluated[proc.name]
        # over the records it could evaluate; NaN (no line) where it could evaluate none
        fraction = (predicted[proc.name][mine].mean(axis=0) if mine.any()
                    else np.full(exact_fraction.shape, np.nan))
        for b in range(len(blocks)):
            line = steps.get((proc.name, b), half_crossing(levels, fraction[:, b]))
            fit = fits[b]
            known = fit is not None and math.isfinite(line)
            nearest = int(np.argmin(np.abs(np.log(levels / line)))) if math.isfinite(line) \
                else None
            band = boots[b].probability_band(line) if known else (math.nan, math.nan)
            rows.append({
                "procedure": proc.name, **_block_columns(blocks, b), "guideline_im": line,
                "ratio_to_exact_median": line / fit.median if known else math.nan,
                "achieved_p_fit": float(fit.probability(line)) if known else math.nan,
                "achieved_p_boot_low": float(band[0]), "achieved_p_boot_high": float(band[1]),
                "achieved_p_stripe": float(exact_fraction[nearest, b])
                if nearest is not None else math.nan})
    return pd.DataFrame(rows)


#: Blocks drawn with a fine amplitude scan: the named blocks, else the grid's most islanded.
SCAN_BLOCKS = 3
#: Step of the fine amplitude scan, as a ratio of scale factors (0.2 %).
SCAN_STEP = 1.002


def amplitude_scans(run: MarginsRun, suite, settings: MarginsSettings,
                    runtime: Runtime) -> pd.DataFrame:
    """A fine amplitude scan of chosen blocks: why the first overturning intensity is not a
    number to build on.

    The blocks are the named ones (``--block``), else the :data:`SCAN_BLOCKS` grid blocks with
    the most records showing islands; for each, the record whose stripes show islands (else
    the one overturning it at the lowest stripe) is scaled in steps of :data:`SCAN_STEP` from
    the stripe below its first overturning stripe to two stripes above it.

    Returns
    -------
    pandas.DataFrame
        ``record, alpha_deg, size_s, block_m, scale_factor, im_level, exact_overturned,
        exact_theta_rad`` (the columns of ``scan.csv``).
    """
    restitution, g, free_motion_s = settings.restitution, settings.g, settings.free_motion_s
    jobs = runtime.jobs
    fragility, stripes = run.fragility, run.stripes
    named = fragility[fragility["block_m"] != ""]
    chosen = named if len(named) else fragility.sort_values(
        ["records_with_islands", "island_share"], ascending=False, kind="stable").head(SCAN_BLOCKS)
    motions = {entry.id: entry.motion for entry in suite if entry.motion is not None}
    levels = np.asarray(run.summary["levels"])
    frames = []
    for block in chosen.itertuples():
        rows = stripes[(stripes["alpha_deg"] == block.alpha_deg)
                       & (stripes["size_s"] == block.size_s)
                       & (stripes["block_m"] == block.block_m)]
        over = rows.pivot(index="record", columns="im_level", values="exact_overturned")
        if not over.to_numpy().any():
            continue
        pattern = overturning_pattern(over.to_numpy(dtype=bool))
        first = np.where(pattern.first_stripe < 0, levels.size, pattern.first_stripe)
        k = int(np.argmax(pattern.islands)) if pattern.islands.any() else int(np.argmin(first))
        record = over.index[k]
        first_row = rows.loc[rows["record"] == record].iloc[0]
        # per unit of intensity, on the motion as audited (scaled to the site, where it was)
        factor_per_im = float(first_row["scale_factor"] / first_row["site_factor"]
                              / first_row["im_level"])
        low = levels[max(first[k] - 1, 0)]
        high = levels[min(first[k] + 2, levels.size - 1)]
        im_levels = low * SCAN_STEP ** np.arange(int(np.log(high / low) / np.log(SCAN_STEP)) + 1)
        peaks = [rocking_blocks(motions[record].scaled(float(level * factor_per_im)),
                                [block.size_s], [math.radians(block.alpha_deg)], r=restitution,
                                g=g, free_motion_s=free_motion_s, jobs=jobs)
                 for level in im_levels]
        frames.append(pd.DataFrame({
            "record": record, "alpha_deg": block.alpha_deg, "size_s": block.size_s,
            "block_m": block.block_m,
            "scale_factor": im_levels * factor_per_im * float(first_row["site_factor"]),
            "im_level": im_levels,
            "exact_overturned": np.concatenate([one.overturned for one in peaks]),
            "exact_theta_rad": np.concatenate([one.theta_peak for one in peaks])}))
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=SCAN_COLUMNS)


SCAN_COLUMNS = ["record", "alpha_deg", "size_s", "block_m", "scale_factor", "im_level",
                "exact_overturned", "exact_theta_rad"]


def margins_files(run: MarginsRun) -> dict[str, bytes]:
    """The files of a design-level audit, as bytes (columns in ``columns.json``)."""
    from audit.engine.results import json_ready
    from audit.engine.schemas import column_guide
    files = {"stripes.csv": csv_bytes(run.stripes, "%.8g"),
             "fragility.csv": csv_bytes(run.fragility, "%.6g"),
             "capacity.csv": csv_bytes(run.capacity, "%.6g")}
    if run.required_alpha is not None:
        files["required_alpha.csv"] = csv_bytes(run.required_alpha, "%.4g")
    if run.scan is not None:
        files["scan.csv"] = csv_bytes(run.scan, "%.8g")
    if run.acceptance is not None:
        files["acceptance.csv"] = csv_bytes(run.acceptance, "%.6g")
    guides = column_guide()
    if run.risk is not None:
        from audit.engine.risk_schema import RISK_GUIDE
        files.update({"risk.csv": csv_bytes(run.risk, "%.6g"),
                      "risk_alpha.csv": csv_bytes(run.risk_alpha, "%.6g"),
                      "hazard.csv": csv_bytes(run.hazard, "%.8g")})
        guides.update({name: {column: {"unit": unit, "meaning": meaning}
                              for column, (unit, meaning) in columns.items()}
                       for name, columns in RISK_GUIDE.items()})
    guide = {name: columns for name, columns in guides.items() if name in files}
    return {**files,
            "summary.json": json.dumps(json_ready(run.summary), indent=1,
                                       ensure_ascii=False).encode(),
            "columns.json": json.dumps(guide, indent=1, ensure_ascii=False).encode()}


__all__ = ["IntensityMeasure", "run_margins", "MarginsRun", "StripeSettings", "RecordStripes",
           "record_stripes", "procedure_predictions", "half_crossing", "amplitude_scans",
           "margins_files", "SCAN_COLUMNS"]
