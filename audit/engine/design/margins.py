"""The design-level audit: how likely is a block to overturn, and where each guideline draws
its line, the FEMA P695 way.

For every block of the grid, the suite's records are scaled to a set of intensity levels
(stripes, :mod:`audit.engine.design.fragility`); the exact response at every record × stripe gives the
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
checks of limit state ``overturning`` fails. One record's part is
:func:`~audit.engine.design.stripes.record_stripes`; the tables are built in
:mod:`audit.engine.design.tables`.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from audit.engine.shared.blocks import BlockList
from audit.engine.shared.csv_text import csv_bytes
from audit.engine.shared.json_text import json_ready
from audit.engine.shared.floors import suite_floor
from audit.engine.shared.defaults import DEFAULT_STRIPES, SITE_LEVELS
from audit.engine.shared.lattice import stripe_lattice
from audit.engine.design.settings import MarginsSettings
from audit.engine.design.guideline_lines import guideline_lines
from audit.engine.design.tables import (capacity_rows, fragility_rows, reading, site_factor,
                                         stripe_rows)
from audit.engine.shared.partial import PartialStore
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.scheduler import computed_parts
from audit.engine.design.stripes import StripeSettings, record_stripes
from audit.errors import InputError
from procedures.parameters import parameters_used


#: With ``--method atlas``: what the atlas answers, what stays direct, and what neither gives
#: (summary.json's ``exact_source``; :mod:`audit.engine.atlas.fragility_read`).
MARGINS_FROM_ATLAS = ("fragility.csv: each block's exact fit, CMR and bootstrap bands, on the "
                      "atlas's stripes", "capacity.csv: the achieved P", "stripes.csv: "
                      "exact_overturned, a per-record probability between the atlas's nodes",
                      "risk.csv, risk_alpha.csv: the risk at the site")
MARGINS_DIRECT = ("the guidelines' predictions at every stripe (stripes.csv's *_overturns, "
                  "capacity.csv's guideline_im)", "required_alpha.csv: the records at their "
                  "own site-scaled intensity, which lies between the atlas's stripes",
                  "acceptance.csv: its impact model × 0.9 and × 0.8 is another atlas")
MARGINS_NOT_ANSWERED = ("stripes.csv's exact_theta_rad (empty: the atlas keeps no rotation "
                        "between its nodes)", "fragility.csv's records_with_islands and "
                        "island_share (empty: islands are read from whole outcomes)",
                        "scan.csv (not written: it picks a record by its whole outcomes)")


@dataclass
class MarginsRun:
    """Everything the design-level audit produced (``stripes.csv``, ``fragility.csv``,
    ``capacity.csv``, ``scan.csv`` and ``summary``)."""

    stripes: pd.DataFrame
    fragility: pd.DataFrame
    capacity: pd.DataFrame
    summary: dict = field(default_factory=dict)
    #: ``required_alpha.csv`` (:func:`~audit.engine.design.required_alpha.required_alpha`), None when
    #: not computed.
    required_alpha: pd.DataFrame | None = None
    #: ``scan.csv`` (:func:`~audit.engine.design.scans.amplitude_scans`), None when not
    #: computed.
    scan: pd.DataFrame | None = None
    #: ``risk.csv``, ``risk_alpha.csv`` and ``hazard.csv`` at a site
    #: (:func:`~audit.engine.design.margins_risk.margins_risk`), None without a hazard curve.
    risk: pd.DataFrame | None = None
    risk_alpha: pd.DataFrame | None = None
    hazard: pd.DataFrame | None = None
    #: ``acceptance.csv`` (:func:`~audit.engine.design.p695_acceptance.p695_acceptance`), None
    #: without the required slenderness or a design site.
    acceptance: pd.DataFrame | None = None


@dataclass
class MarginsStripes:
    """Every record's part of the design-level audit together (:func:`margins_stripes`):
    arrays shaped (record, stripe, block).

    Attributes
    ----------
    entries : list of records.RecordEntry
        The records with a file, in the suite's order.
    settings : audit.engine.design.stripes.StripeSettings
        The stripes (ascending), the blocks, and how they were solved.
    mce_im : float or None
        The site's MCE intensity (the CMR's denominator) [unit of the intensity measure].
    intensities : numpy.ndarray
        Each record's intensity as given.
    exact_overturned, exact_theta_rad : numpy.ndarray
    predicted, evaluated : dict
        Per procedure name, as in :class:`~audit.engine.design.stripes.RecordStripes`, stacked.
    resumed : list of str
    where : str
        The records' parts reused, and where the others were computed.
    """

    entries: list
    settings: StripeSettings
    mce_im: float | None
    intensities: np.ndarray
    exact_overturned: np.ndarray
    exact_theta_rad: np.ndarray
    predicted: dict
    evaluated: dict
    resumed: list
    where: str


def margins_stripes(procedures, suite, settings: MarginsSettings, runtime: Runtime,
                    atlas=None) -> MarginsStripes:
    """Every record of ``suite`` scaled to the stripes, with the exact response of every block
    and each procedure's prediction there (the arguments of :func:`margins_tables`).

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    suite : records.RecordSuite
        The records.
    settings : MarginsSettings
        The design-level settings.
    runtime : Runtime
        How it runs.
    atlas : audit.engine.atlas.fragility_read.AtlasReading, optional
        The atlas the exact outcomes are read from, at its stripes (or those of them asked):
        per-record probabilities between its nodes, no peak rotation (NaN); the records then
        carry the procedures' predictions alone.
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
    design = im.of_design_site(suite.design_site)  # FEMA 356's: the MCE of the margins
    # what each record's design spectra are scaled from to a stripe: FEMA 356's intensity, else
    # an NTC 2018 site's own at the IM (unscaled, NTC's spectrum would be the same at every
    # stripe, and its line the lowest stripe where it fails or none)
    scaled_from = design if design is not None else im.of_ntc_site(entries[0].site)
    if levels is None:  # the fixed lattice: the fragility is the block's, not the site's
        levels = stripe_lattice() if atlas is None else atlas.levels
    blocks = BlockList.of(alpha_deg, size_s if size_s is not None else (), named_blocks)
    if not len(blocks):
        raise InputError("size_s, alpha_deg, blocks: no block to audit", "size_s",
                         "alpha_deg", "blocks")
    settings_of_stripes = StripeSettings(
        im, tuple(np.sort(np.asarray(levels, dtype=float)).tolist()), scaled_from, blocks,
        restitution, float(g), float(free_motion_s), int(jobs), exact=atlas is None)
    store = (PartialStore(partial_dir, procedures, settings_of_stripes, resume) if partial_dir
             else None)
    parts, resumed, where = computed_parts(record_stripes, entries, procedures,
                                           settings_of_stripes, runtime.scheduler, store,
                                           runtime.progress)
    if atlas is None:
        exact_over = np.stack([part.exact_overturned for part in parts])
        exact_theta = np.stack([part.exact_theta_rad for part in parts])
    else:  # the atlas's records are these, in this order (its key hashes them)
        exact_over = atlas.outcomes(blocks.alpha_deg, blocks.size_s,
                                    settings_of_stripes.levels)
        exact_theta = np.full(exact_over.shape, np.nan)
    return MarginsStripes(
        entries, settings_of_stripes,
        design * SITE_LEVELS[settings.site_level] if design else None,
        np.array([part.intensity for part in parts]), exact_over, exact_theta,
        {proc.name: np.stack([part.predicted[proc.name] for part in parts])
         for proc in procedures},
        {proc.name: np.array([part.evaluated[proc.name] for part in parts])
         for proc in procedures},
        resumed, where)


def margins_tables(procedures, suite, settings: MarginsSettings, runtime: Runtime,
                   atlas=None) -> MarginsRun:
    """Multiple-stripe exact fragility of every block and each procedure's line against it.

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
        Its ``design_site`` gives the design intensity.
    settings : MarginsSettings
        The intensity measure, the stripes (default the fixed lattice,
        :func:`~audit.engine.shared.lattice.stripe_lattice`), the grid and the named blocks, the impact model, gravity
        and the free motion.
    runtime : Runtime
        Solver threads (worker processes of ``scheduler="dask"``), where records are computed,
        the folder of parts kept as they complete and whether to reuse them, progress.
    atlas : audit.engine.atlas.fragility_read.AtlasReading, optional
        The atlas the exact fragilities are read from (:func:`margins_stripes`).
    """
    run = margins_stripes(procedures, suite, settings, runtime, atlas)
    entries, im, blocks = run.entries, settings.im, run.settings.blocks
    levels, exact_over = np.asarray(run.settings.levels), run.exact_overturned
    site_factors = np.array([site_factor(suite, e.id) for e in entries])
    stripes = stripe_rows(run, site_factors)
    fragility, fits, boots = fragility_rows(levels, blocks, im, exact_over, run.mce_im)
    if atlas is None:
        source = {"method": "direct"}
        fragility = fragility.assign(exact_source="direct", atlas_key="", atlas_error=np.nan)
    else:
        errors = atlas.errors(blocks.alpha_deg, blocks.size_s)
        source = {"method": "atlas", "atlas_key": atlas.key,
                  "atlas_error_max": float(np.max(errors)),
                  "atlas_error_median": float(np.median(errors)),
                  "text": atlas.words(errors), "stripes": (
                      f"the atlas's {levels.size} stripes (the lattice's levels with k even, "
                      f"√2 apart), not the {DEFAULT_STRIPES} of the direct audit"),
                  "from_atlas": list(MARGINS_FROM_ATLAS), "direct": list(MARGINS_DIRECT),
                  "not_answered": list(MARGINS_NOT_ANSWERED)}
        fragility = fragility.assign(exact_source="atlas", atlas_key=atlas.key,
                                     atlas_error=errors)
    lines = guideline_lines(procedures, entries, run.settings, run.predicted, run.evaluated)
    capacity = capacity_rows(procedures, run, fits, boots, lines)
    named_blocks = settings.blocks
    summary = {"im": im.name, "im_unit": im.unit, "levels": levels.tolist(),
               "design_im": im.of_design_site(suite.design_site),
               "site_level": settings.site_level,
               "mce_im": run.mce_im, "records": [e.id for e in entries],
               "records_source": suite.description, "design_site": suite.design_site,
               "scaling": suite.scaling, "floor": suite_floor(suite),
               "restitution": str(run.settings.restitution),
               "scheduler": run.where, "resumed": run.resumed, "exact_source": source,
               "procedures": [{"name": proc.name, "title": proc.title,
                               "reads": reading(proc, entries),
                               **({"parameters": parameters_used(proc)}
                                  if type(proc).parameters else {})} for proc in procedures],
               "grid": {"alpha_deg": [float(a) for a in settings.alpha_deg],
                        "size_s": np.asarray(settings.size_s if settings.size_s is not None
                                             else (), dtype=float).tolist()},
               "blocks": [{"width_m": b.width_m, "height_m": b.height_m,
                           "alpha_deg": b.alpha_deg, "size_s": b.size_s}
                          for b in named_blocks]}
    return MarginsRun(stripes, fragility, capacity, summary)


def margins_files(run: MarginsRun) -> dict[str, bytes]:
    """The files of a design-level audit, as bytes (columns in ``columns.json``).

    Parameters
    ----------
    run : MarginsRun
        The finished design-level audit.

    Returns
    -------
    dict of str to bytes
        File name → contents.
    """
    from audit.engine.shared.schemas import column_guide
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
        from audit.engine.design.risk_schema import RISK_GUIDE
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


__all__ = ["MARGINS_FROM_ATLAS", "MARGINS_DIRECT", "MARGINS_NOT_ANSWERED", "margins_tables", "margins_stripes", "MarginsRun", "MarginsStripes", "margins_files"]
