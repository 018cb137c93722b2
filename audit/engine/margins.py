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
from audit.engine.fragility import fit_lognormal, overturning_pattern, stripe_levels, \
    stripe_outcomes
from audit.errors import InputError
from audit.physics.block import coefficient_of_restitution
from audit.physics.design_spectra import FEMA356Spectrum
from audit.physics.oscillator import response_spectra
from audit.physics.rocking import rocking_spectrum
from procedures.base import EXACT_OVERTURNING, OVERTURN
from procedures.context import RecordContext
from records.sites import scaled_site

PGA, PGV, SA = "pga", "pgv", "sa"
#: Damping of the spectral acceleration of ``sa:T`` [-].
IM_DAMPING = 0.05


@dataclass(frozen=True)
class IntensityMeasure:
    """An intensity measure: ``pga`` [g], ``pgv`` [m/s] or ``sa:T`` (true 5 %-damped spectral
    acceleration max|ü + üg| at period T, [g])."""

    kind: str
    period_s: float | None = None

    @classmethod
    def parse(cls, text: str) -> IntensityMeasure:
        """``pga``, ``pgv`` or ``sa:T``; InputError naming ``--im`` otherwise."""
        text = text.strip().lower()
        if text in (PGA, PGV):
            return cls(text)
        if text.startswith(f"{SA}:"):
            try:
                period = float(text[3:])
            except ValueError:
                period = math.nan
            if math.isfinite(period) and period > 0:
                return cls(SA, period)
        raise InputError(f"--im: expected pga, pgv or sa:T with T a period in s, got '{text}'")

    @property
    def name(self) -> str:
        return f"{SA}:{self.period_s:g}" if self.kind == SA else self.kind

    @property
    def unit(self) -> str:
        return "m/s" if self.kind == PGV else "g"

    def of_record(self, motion, free_motion_s: float) -> float:
        """The intensity of a record (in :attr:`unit`)."""
        if self.kind == PGA:
            return motion.pga_g
        if self.kind == PGV:
            return motion.pgv
        spectra = response_spectra(motion, np.array([self.period_s]), [IM_DAMPING],
                                   free_motion_s)
        return float(spectra.sa[0, 0]) / G

    def of_design_site(self, site: dict) -> float | None:
        """The intensity of a FEMA 356 design site (S_XS, S_X1 [g]), or None: PGA = 0.4 S_XS,
        Sa(T) of the design spectrum at 5 %; PGV has no design value."""
        if not site or self.kind == PGV:
            return None
        spectrum = FEMA356Spectrum(site["sxs_g"], site["sx1_g"])
        return float(spectrum.acceleration(0.0 if self.kind == PGA else self.period_s, 0.05))


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
    ``capacity.csv`` and ``summary``)."""

    stripes: pd.DataFrame
    fragility: pd.DataFrame
    capacity: pd.DataFrame
    summary: dict = field(default_factory=dict)
    #: ``required_alpha.csv`` (:func:`required_alpha`), None when not computed.
    required_alpha: pd.DataFrame | None = None


def run_margins(procedures, suite, im: IntensityMeasure, levels=None, alpha_deg=(10.0, 15.0, 20.0),
                size_s=None, g: float = G, free_motion_s: float = 10.0, jobs: int = 1,
                progress=None) -> MarginsRun:
    """Multiple-stripe exact fragility of every block and each procedure's line against it.

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
        Its ``design_site`` (``--site``) gives the design intensity.
    im : IntensityMeasure
    levels : array, optional
        Stripes [unit of ``im``]; default :func:`~audit.engine.fragility.stripe_levels` around
        the design intensity, else the suite's median intensity.
    alpha_deg : sequence of float
        Slendernesses [degrees].
    size_s : array
        Block sizes 2π/p [s].
    g, free_motion_s, jobs :
        Gravity [m/s²], free motion after each record [s], solver threads.
    progress : callable, optional
        ``progress(done, total, record_id, how)`` after each record.
    """
    entries = [entry for entry in suite if entry.motion is not None]
    if not entries:
        raise InputError(f"--records: no record of {suite.description} has a file")
    size_s = np.asarray(size_s, dtype=float)
    alpha_rad = np.radians(np.asarray(alpha_deg, dtype=float))
    p = 2.0 * np.pi / size_s
    intensities = np.array([im.of_record(e.motion, free_motion_s) for e in entries])
    design = im.of_design_site(suite.design_site)
    levels = np.sort(np.asarray(levels if levels is not None else stripe_levels(
        design if design else float(np.median(intensities))), dtype=float))
    shape = (len(entries), levels.size, alpha_rad.size, size_s.size)
    exact_over, exact_theta = np.zeros(shape, dtype=bool), np.zeros(shape)
    predicted = {proc.name: np.zeros(shape, dtype=bool) for proc in procedures}
    # records each procedure could evaluate (its fractions are over these alone)
    evaluated = {proc.name: np.zeros(len(entries), dtype=bool) for proc in procedures}
    for k, entry in enumerate(entries):
        factors = levels / intensities[k]
        exact_over[k], exact_theta[k] = stripe_outcomes(entry.motion, factors, size_s, alpha_rad,
                                                        g, free_motion_s, jobs)
        base = RecordContext(entry, free_motion_s, jobs)
        for j, factor in enumerate(factors):
            # the record to the level; its design spectrum to the level too, where the site's
            # design intensity is known
            site_factor = levels[j] / design if design else 1.0
            scaled = replace(entry, motion=entry.motion.scaled(float(factor)),
                             site=scaled_site(entry.site, float(site_factor)))
            context = base.scaled(scaled, float(factor))
            for proc in procedures:
                if proc.unmet_requirements(scaled) is not None:
                    continue
                evaluated[proc.name][k] = True
                for i, alpha in enumerate(alpha_rad):
                    evaluation = proc.evaluate(scaled, p, alpha,
                                               float(coefficient_of_restitution(alpha)), context, g)
                    predicted[proc.name][k, j, i] = predicts_overturning(evaluation)
        if progress:
            progress(k + 1, len(entries), entry.id, "stripes computed")
    stripes = _stripe_rows(entries, levels, intensities, alpha_deg, size_s, im, exact_over,
                           exact_theta, predicted)
    fragility, fits = _fragility_rows(levels, alpha_deg, size_s, im, exact_over, design)
    capacity = _capacity_rows(procedures, levels, alpha_deg, size_s, exact_over, predicted,
                              evaluated, fits)
    summary = {"im": im.name, "im_unit": im.unit, "levels": levels.tolist(),
               "design_im": design, "records": [e.id for e in entries],
               "records_source": suite.description, "design_site": suite.design_site,
               "scaling": suite.scaling,
               "procedures": [{"name": proc.name, "title": proc.title} for proc in procedures],
               "grid": {"alpha_deg": [float(a) for a in alpha_deg], "size_s": size_s.tolist()}}
    return MarginsRun(stripes, fragility, capacity, summary)


def _stripe_rows(entries, levels, intensities, alpha_deg, size_s, im, exact_over, exact_theta,
                 predicted) -> pd.DataFrame:
    n_records, n_levels, n_alpha, n_size = exact_over.shape
    index = np.indices(exact_over.shape).reshape(4, -1)
    record, level, alpha, size = index
    frame = pd.DataFrame({
        "record": np.array([e.id for e in entries])[record],
        "alpha_deg": np.asarray(alpha_deg, dtype=float)[alpha], "size_s": size_s[size],
        "im": im.name, "im_level": levels[level],
        "scale_factor": levels[level] / intensities[record],
        "exact_overturned": exact_over.reshape(-1), "exact_theta_rad": exact_theta.reshape(-1)})
    for name, over in predicted.items():
        frame[f"{name}_overturns"] = over.reshape(-1)
    return frame


def _fragility_rows(levels, alpha_deg, size_s, im, exact_over, design):
    rows, fits = [], {}
    n_records = exact_over.shape[0]
    for i, alpha in enumerate(alpha_deg):
        for s, size in enumerate(size_s):
            counts = exact_over[:, :, i, s].sum(axis=0)
            pattern = overturning_pattern(exact_over[:, :, i, s])
            try:
                fit = fit_lognormal(levels, np.full(levels.size, n_records), counts)
            except ValueError:
                fit = None
            fits[(i, s)] = fit
            nan = math.nan
            rows.append({
                "alpha_deg": float(alpha), "size_s": float(size), "im": im.name,
                "records": n_records, "stripes": levels.size,
                "median": fit.median if fit else nan, "beta": fit.beta if fit else nan,
                "median_low": fit.median_band[0] if fit else nan,
                "median_high": fit.median_band[1] if fit else nan,
                "beta_low": fit.beta_band[0] if fit else nan,
                "beta_high": fit.beta_band[1] if fit else nan,
                "cmr": fit.median / design if fit and design else nan,
                "records_with_islands": int(pattern.islands.sum()),
                "island_share": float(pattern.islands.mean())})
    return pd.DataFrame(rows), fits


def _capacity_rows(procedures, levels, alpha_deg, size_s, exact_over, predicted, evaluated,
                   fits):
    rows = []
    exact_fraction = exact_over.mean(axis=0)  # (stripe, α, size)
    for proc in procedures:
        mine = evaluated[proc.name]
        # over the records it could evaluate; NaN (no line) where it could evaluate none
        fraction = (predicted[proc.name][mine].mean(axis=0) if mine.any()
                    else np.full(exact_fraction.shape, np.nan))
        for i, alpha in enumerate(alpha_deg):
            for s, size in enumerate(size_s):
                line = _half_crossing(levels, fraction[:, i, s])
                fit = fits[(i, s)]
                nearest = int(np.argmin(np.abs(np.log(levels / line)))) if math.isfinite(line) \
                    else None
                rows.append({
                    "procedure": proc.name, "alpha_deg": float(alpha), "size_s": float(size),
                    "guideline_im": line,
                    "ratio_to_exact_median": line / fit.median if fit and math.isfinite(line)
                    else math.nan,
                    "achieved_p_fit": float(fit.probability(line)) if fit and math.isfinite(line)
                    else math.nan,
                    "achieved_p_stripe": float(exact_fraction[nearest, i, s])
                    if nearest is not None else math.nan})
    return pd.DataFrame(rows)


#: Slendernesses searched for the required slenderness [degrees], 2° apart.
REQUIRED_ALPHA_GRID_DEG = np.arange(2.0, 40.01, 2.0)
#: Exact shares of records overturning a block that the required-slenderness curves target.
REQUIRED_ALPHA_TARGETS = (0.10, 0.50)


def _smallest_alpha_staying_below(alpha_deg, share, limit) -> float:
    """The smallest α above which ``share`` stays ≤ ``limit`` on the search: after the last
    α where it exceeds the limit, interpolated linearly between that grid point and the next;
    the first α of the grid if it never exceeds, NaN if it still does at the last."""
    over = np.flatnonzero(share > limit)
    if over.size == 0:
        return float(alpha_deg[0])
    j = over[-1]
    if j == alpha_deg.size - 1:
        return math.nan
    t = (share[j] - limit) / (share[j] - share[j + 1])
    return float(alpha_deg[j] + t * (alpha_deg[j + 1] - alpha_deg[j]))


def required_alpha(procedures, suite, size_s, alpha_grid_deg=REQUIRED_ALPHA_GRID_DEG,
                   targets=REQUIRED_ALPHA_TARGETS, g: float = G, free_motion_s: float = 10.0,
                   jobs: int = 1) -> pd.DataFrame:
    """For each size, the smallest slenderness each procedure accepts for the suite as given
    (the site-scaled records), against the smallest α for which the exact share of those
    records that overturn the block stays ≤ each target.

    A procedure accepts a block when it predicts overturning for at most half the records (a
    site-based one: not at all), over the records it can evaluate. Shares are not monotonic in
    α either, so each curve is "the smallest α above which the share stays ≤ the target on the
    search": α on a 2° grid, the last crossing interpolated linearly.

    Returns
    -------
    pandas.DataFrame
        ``procedure, size_s, required_alpha_deg``; the exact curves are named ``exact@0.10`` and
        ``exact@0.50``.
    """
    entries = [entry for entry in suite if entry.motion is not None]
    size_s = np.asarray(size_s, dtype=float)
    alpha_grid_deg = np.asarray(alpha_grid_deg, dtype=float)
    alpha_rad = np.radians(alpha_grid_deg)
    p = 2.0 * np.pi / size_s
    exact = np.zeros((alpha_rad.size, size_s.size))
    predicted = {proc.name: np.zeros((alpha_rad.size, size_s.size)) for proc in procedures}
    evaluated = dict.fromkeys(predicted, 0)
    for entry in entries:
        exact += rocking_spectrum(entry.motion, size_s, alpha_rad, g=g,
                                  free_motion_s=free_motion_s, jobs=jobs).overturned
        context = RecordContext(entry, free_motion_s, jobs)
        for proc in procedures:
            if proc.unmet_requirements(entry) is not None:
                continue
            evaluated[proc.name] += 1
            for i, alpha in enumerate(alpha_rad):
                predicted[proc.name][i] += predicts_overturning(proc.evaluate(
                    entry, p, alpha, float(coefficient_of_restitution(alpha)), context, g))
    rows = []
    curves = [(f"exact@{target:.2f}", exact / len(entries), target) for target in targets]
    # a procedure that could evaluate no record draws no curve
    curves += [(name, counts / evaluated[name], 0.5) for name, counts in predicted.items()
               if evaluated[name]]
    for name, share, limit in curves:
        for s, size in enumerate(size_s):
            rows.append({"procedure": name, "size_s": float(size),
                         "required_alpha_deg": _smallest_alpha_staying_below(
                             alpha_grid_deg, share[:, s], limit)})
    return pd.DataFrame(rows)


def margins_files(run: MarginsRun) -> dict[str, bytes]:
    """The files of a design-level audit, as bytes (columns in ``columns.json``)."""
    from audit.engine.results import json_ready
    from audit.engine.schemas import column_guide
    guide = {name: columns for name, columns in column_guide().items()
             if name in ("stripes.csv", "fragility.csv", "capacity.csv", "required_alpha.csv")}
    files = {"stripes.csv": run.stripes.to_csv(index=False, float_format="%.8g").encode(),
             "fragility.csv": run.fragility.to_csv(index=False, float_format="%.6g").encode(),
             "capacity.csv": run.capacity.to_csv(index=False, float_format="%.6g").encode()}
    if run.required_alpha is not None:
        files["required_alpha.csv"] = run.required_alpha.to_csv(index=False,
                                                                float_format="%.4g").encode()
    return {**files,
            "summary.json": json.dumps(json_ready(run.summary), indent=1,
                                       ensure_ascii=False).encode(),
            "columns.json": json.dumps(guide, indent=1, ensure_ascii=False).encode()}


__all__ = ["IntensityMeasure", "run_margins", "MarginsRun", "predicts_overturning",
           "margins_files", "required_alpha"]
