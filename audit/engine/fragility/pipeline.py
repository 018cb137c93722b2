"""The audit of a probabilistic procedure on a record suite: one table per file it writes.

For every component with a block (b = depth/2, h = height/2), the exact outcomes of the records
scaled to each PGV stripe (:func:`audit.engine.design.fragility.stripe_outcomes`), the lognormal fitted
to them, and the procedure's probability at each scaled intensity scored against the outcomes.
Components without dimensions (FEMA P-58's PGA rows) have no block and are not audited.

Read from an atlas of the records in PGV (``atlas``, :mod:`audit.engine.atlas.fragility_read`),
the exact side is at the atlas's 14 stripes instead (0.0625–5.66 m/s, √2 apart), each record's
outcome interpolated between the grid's nodes: a per-record probability, 0 or 1 at a node. The
scores are then their expectations over those outcomes (the log-likelihood and the calibration
are linear in an outcome; the Brier score gains Σ w(1 − w)/n, zero for whole outcomes), and
each component says its source and the atlas's error along its curve.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from audit import G
from audit.engine.fragility.calibration import brier_score, calibration, log_likelihood
from audit.engine.fragility.settings import FragilitySettings
from audit.engine.design.fragility import stripe_outcomes
from audit.engine.design.lognormal_fit import fit_lognormal
from audit.errors import InputError
from audit.engine.shared.blocks import Block
from procedures.probabilistic import LognormalFragility

#: The files of the audit, written together into the output folder.
COMPONENTS_CSV = "fragility-components.csv"
STRIPES_CSV = "fragility-stripes.csv"
OUTCOMES_CSV = "fragility-outcomes.csv"
CALIBRATION_CSV = "fragility-calibration.csv"


def run_fragility(procedure, record_ids, motions,
                  settings: FragilitySettings = FragilitySettings(), atlas=None) -> dict:
    """The tables of the audit of ``procedure`` (a :class:`procedures.probabilistic.ProbabilisticProcedure`)
    on the records: file name → :class:`pandas.DataFrame`.

    Parameters
    ----------
    procedure : procedures.probabilistic.ProbabilisticProcedure
        The procedure and its components.
    record_ids : sequence of str
        The records' ids.
    motions : sequence of records.GroundMotion
        Their motions, in the same order.
    settings : FragilitySettings
        The PGV stripes and the free motion.
    atlas : audit.engine.atlas.fragility_read.AtlasReading, optional
        The atlas of these records in PGV on their floor: the exact outcomes are read from it,
        at its stripes (see the module); None, the direct solve at ``settings``' stripes.
    """
    levels = np.asarray(settings.levels_m_s if atlas is None else atlas.levels, dtype=float)
    zero = [record_id for record_id, motion in zip(record_ids, motions) if not motion.pgv > 0]
    if zero:
        raise InputError(f"records: {zero[0]} has zero intensity (PGV = 0: an all-zero record), "
                         "so no PGV stripe can be reached by scaling it; leave it out"
                         + (f" ({len(zero) - 1} other record(s) too)" if len(zero) > 1 else ""),
                         "records")
    components, stripes, outcomes, bins = [], [], [], []
    for component in procedure.components:
        if not (component.has_block and component.intensity_measure == "PGV"):
            continue
        block = Block.of_dimensions(component.depth_m, component.height_m)
        if atlas is None:
            overturned = np.array([stripe_outcomes(motion, levels / motion.pgv, [block.size_s],
                                                   [block.rigid.alpha], G,
                                                   settings.free_motion_s)[0][:, 0, 0]
                                   for motion in motions])
            source = {"exact_source": "direct", "atlas_key": "", "atlas_error": math.nan}
        else:  # (record, stripe) per-record probabilities
            overturned = atlas.outcomes([block.alpha_deg], [block.size_s])[:, :, 0]
            source = {"exact_source": "atlas", "atlas_key": atlas.key,
                      "atlas_error": float(atlas.errors([block.alpha_deg], [block.size_s])[0])}
        counts = overturned.sum(axis=0)
        try:
            fit = fit_lognormal(levels, np.full(levels.size, len(motions)), counts)
            median, beta = fit.median, fit.beta
        except ValueError:  # no stripe or every stripe overturns it: no fit exists
            median, beta = math.nan, math.nan
        predicted = np.broadcast_to(component.fragility.probability(levels), overturned.shape)
        exact_predicted = (np.broadcast_to(LognormalFragility(median, beta).probability(levels),
                                           overturned.shape)
                           if math.isfinite(median) else np.full(overturned.shape, np.nan))
        components.append({
            "component": component.id, "description": component.description,
            "width_m": block.width_m, "height_m": block.height_m,
            "alpha_deg": block.alpha_deg, "p_rad_s": block.p_rad_s,
            "procedure_median_m_s": component.fragility.median,
            "procedure_beta": component.fragility.beta,
            "exact_median_m_s": median, "exact_beta": beta,
            "median_ratio": component.fragility.median / median,
            "conservative_at_median": component.fragility.median <= median,
            "brier": _brier(predicted, overturned),
            "log_likelihood": log_likelihood(predicted, overturned),
            "exact_fit_brier": _brier(exact_predicted, overturned),
            "exact_fit_log_likelihood": log_likelihood(exact_predicted, overturned),
            "outcomes": overturned.size, **source})
        for level, count, probability in zip(levels, counts, predicted[0]):
            stripes.append({"component": component.id, "pgv_m_s": level,
                            "records": len(motions),
                            "overturned": int(count) if atlas is None else float(count),
                            "procedure_probability": probability})
        for record, row in zip(record_ids, overturned):
            for level, outcome, probability in zip(levels, row, predicted[0]):
                outcomes.append({"component": component.id, "record": record, "pgv_m_s": level,
                                 "exact_overturned": bool(outcome) if atlas is None
                                 else float(outcome),
                                 "procedure_probability": probability})
        table = calibration(predicted, overturned)
        for values in zip(table.lower, table.upper, table.count, table.mean_predicted,
                          table.observed_frequency):
            bins.append(dict(zip(("component", "predicted_lower", "predicted_upper", "outcomes",
                                  "mean_predicted", "observed_frequency"),
                                 (component.id, *values))))
    return {COMPONENTS_CSV: pd.DataFrame(components), STRIPES_CSV: pd.DataFrame(stripes),
            OUTCOMES_CSV: pd.DataFrame(outcomes), CALIBRATION_CSV: pd.DataFrame(bins)}


def _brier(predicted, overturned) -> float:
    """The Brier score against outcomes that may be per-record probabilities w (an atlas's,
    between its nodes): its expectation, mean (p − w)² + mean w(1 − w); the plain score for
    whole outcomes (the second term is not added, so the direct score is unchanged)."""
    if overturned.dtype == bool:
        return brier_score(predicted, overturned)
    return brier_score(predicted, overturned) + float(np.mean(overturned * (1.0 - overturned)))
