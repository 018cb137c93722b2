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
* the FEMA P695 collapse margin ratio CMR = exact median / the site's design intensity.

A procedure predicts overturning for a block when its estimate is ``overturn`` or one of its
checks of limit state ``overturning`` fails.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from audit import G
from audit.engine.blocks import BlockList
from audit.engine.csv_text import csv_bytes
from audit.engine.intensity import IntensityMeasure
from audit.engine.margins_settings import MarginsSettings
from audit.engine.fragility import fit_lognormal, overturning_pattern, stripe_levels, \
    stripe_outcomes
from audit.engine.partial import PartialStore
from audit.engine.runtime import Runtime
from audit.engine.scheduler import computed_parts
from audit.errors import InputError
from audit.physics.block import Restitution
from audit.physics.rocking import rocking_blocks
from procedures.base import EXACT_OVERTURNING, OVERTURN
from procedures.context import RecordContext
from records.sites import scaled_site

def predicts_overturning(evaluation) -> np.ndarray:
    """Per block, whether a procedure's evaluation predicts overturning."""
    over = (evaluation.estimate.outcome == OVERTURN if evaluation.estimate is not None
            else np.zeros(len(evaluation.checks[0].passes), dtype=bool))
    for check in evaluation.checks:
        if check.exact_event == EXACT_OVERTURNING:
            over = over | ~np.asarray(check.passes, dtype=bool)
    return np.asarray(over, dtype=bool)


def _half_crossing(levels, fraction) -> float:
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


def record_stripes(entry, procedures, settings: StripeSettings) -> RecordStripes:
    """The exact response and every procedure's prediction for one record scaled to each stripe
    (the unit of work of the design-level audit)."""
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
    predicted = {proc.name: np.zeros(shape, dtype=bool) for proc in procedures}
    evaluated = dict.fromkeys(predicted, False)
    base = RecordContext(entry, settings.free_motion_s, settings.jobs)
    for j, factor in enumerate(factors):
        # the record to the level; its design spectrum to the level too, where the site's
        # design intensity is known
        site_factor = levels[j] / settings.design_im if settings.design_im else 1.0
        scaled = replace(entry, motion=entry.motion.scaled(float(factor)),
                         site=scaled_site(entry.site, float(site_factor)))
        context = base.scaled(scaled, float(factor))
        for proc in procedures:
            if proc.unmet_requirements(scaled) is not None:
                continue
            evaluated[proc.name] = True
            for alpha, index in groups:
                evaluation = proc.evaluate(scaled, p[index], alpha,
                                           float(settings.restitution.r(alpha)), context,
                                           settings.g)
                predicted[proc.name][j, index] = predicts_overturning(evaluation)
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
    partial_dir, resume = runtime.partial_dir, runtime.resume
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
                               design, blocks, restitution, float(g),
                               float(free_motion_s), int(jobs))
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
    stripes = _stripe_rows(entries, levels, intensities, blocks, im, exact_over, exact_theta,
                           predicted)
    fragility, fits = _fragility_rows(levels, blocks, im, exact_over, design)
    capacity = _capacity_rows(procedures, levels, blocks, exact_over, predicted, evaluated, fits)
    summary = {"im": im.name, "im_unit": im.unit, "levels": levels.tolist(),
               "design_im": design, "records": [e.id for e in entries],
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


def _stripe_rows(entries, levels, intensities, blocks, im, exact_over, exact_theta,
                 predicted) -> pd.DataFrame:
    record, level, block = np.indices(exact_over.shape).reshape(3, -1)
    frame = pd.DataFrame({
        "record": np.array([e.id for e in entries])[record], **_block_columns(blocks, block),
        "im": im.name, "im_level": levels[level],
        "scale_factor": levels[level] / intensities[record],
        "exact_overturned": exact_over.reshape(-1), "exact_theta_rad": exact_theta.reshape(-1)})
    for name, over in predicted.items():
        frame[f"{name}_overturns"] = over.reshape(-1)
    return frame


def _fragility_rows(levels, blocks, im, exact_over, design):
    rows, fits = [], []
    n_records = exact_over.shape[0]
    nan = math.nan
    for b in range(len(blocks)):
        counts = exact_over[:, :, b].sum(axis=0)
        pattern = overturning_pattern(exact_over[:, :, b])
        try:
            fit = fit_lognormal(levels, np.full(levels.size, n_records), counts)
        except ValueError:
            fit = None
        fits.append(fit)
        rows.append({
            **_block_columns(blocks, b), "im": im.name, "records": n_records,
            "stripes": levels.size, "median": fit.median if fit else nan,
            "beta": fit.beta if fit else nan,
            "median_low": fit.median_band[0] if fit else nan,
            "median_high": fit.median_band[1] if fit else nan,
            "beta_low": fit.beta_band[0] if fit else nan,
            "beta_high": fit.beta_band[1] if fit else nan,
            "cmr": fit.median / design if fit and design else nan,
            "records_with_islands": int(pattern.islands.sum()),
            "island_share": float(pattern.islands.mean())})
    return pd.DataFrame(rows), fits


def _capacity_rows(procedures, levels, blocks, exact_over, predicted, evaluated, fits):
    rows = []
    exact_fraction = exact_over.mean(axis=0)  # (stripe, block)
    for proc in procedures:
        mine = evaluated[proc.name]
        # over the records it could evaluate; NaN (no line) where it could evaluate none
        fraction = (predicted[proc.name][mine].mean(axis=0) if mine.any()
                    else np.full(exact_fraction.shape, np.nan))
        for b in range(len(blocks)):
            line = _half_crossing(levels, fraction[:, b])
            fit = fits[b]
            known = fit is not None and math.isfinite(line)
            nearest = int(np.argmin(np.abs(np.log(levels / line)))) if math.isfinite(line) \
                else None
            rows.append({
                "procedure": proc.name, **_block_columns(blocks, b), "guideline_im": line,
                "ratio_to_exact_median": line / fit.median if known else math.nan,
                "achieved_p_fit": float(fit.probability(line)) if known else math.nan,
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
        factor_per_im = float(rows.loc[rows["record"] == record, "scale_factor"].iloc[0]
                              / rows.loc[rows["record"] == record, "im_level"].iloc[0])
        low = levels[max(first[k] - 1, 0)]
        high = levels[min(first[k] + 2, levels.size - 1)]
        im_levels = low * SCAN_STEP ** np.arange(int(np.log(high / low) / np.log(SCAN_STEP)) + 1)
        peaks = np.array([rocking_blocks(motions[record].scaled(float(level * factor_per_im)),
                                         [block.size_s], [math.radians(block.alpha_deg)],
                                         r=restitution, g=g, free_motion_s=free_motion_s,
                                         jobs=jobs)[0] for level in im_levels])
        frames.append(pd.DataFrame({
            "record": record, "alpha_deg": block.alpha_deg, "size_s": block.size_s,
            "block_m": block.block_m, "scale_factor": im_levels * factor_per_im,
            "im_level": im_levels, "exact_overturned": peaks[:, 3] > 0,
            "exact_theta_rad": peaks[:, 0]}))
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
    guide = {name: columns for name, columns in column_guide().items() if name in files}
    return {**files,
            "summary.json": json.dumps(json_ready(run.summary), indent=1,
                                       ensure_ascii=False).encode(),
            "columns.json": json.dumps(guide, indent=1, ensure_ascii=False).encode()}


__all__ = ["IntensityMeasure", "run_margins", "MarginsRun", "StripeSettings", "RecordStripes",
           "record_stripes", "predicts_overturning", "amplitude_scans", "margins_files",
           "SCAN_COLUMNS"]
