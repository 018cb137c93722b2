"""Whether a procedure predicts overturning, for many scaled records and slendernesses at once
(the design-level audit asks only this, at every stripe of every record).

A procedure predicts overturning of a block when its estimate is ``overturn`` or one of its
checks of the exact event ``overturning`` fails (:func:`predicts_overturning`). For a procedure
that keeps the contract's own :meth:`~procedures.base.Procedure.evaluate` and reads a tabulated
spectrum (the record's, :class:`procedures.tabulated.TabulatedDisplacement`), every case and
slenderness is iterated at once (:func:`procedures.iteration.iterate_tabulated`), and neither
the fixed points nor the stored spectrum, which only a report reads, are computed; its iterates
are those of one :meth:`~procedures.base.Procedure.evaluate` per case, bit for bit. A procedure
that takes α per block (:attr:`~procedures.base.Procedure.alpha_per_block`: closed-form checks)
is evaluated once per case for blocks of every slenderness. Any other procedure is evaluated
case by case and slenderness by slenderness.
"""

from __future__ import annotations

import numpy as np

from procedures.base import EXACT_OVERTURNING, OVERTURN, Procedure
from procedures.iteration import iterate_rotation, iterate_tabulated, uplifts
from procedures.rotation_map import map_scale
from procedures.tabulated import TabulatedDisplacement


def predicts_overturning(evaluation) -> np.ndarray:
    """Per block, whether a procedure's :class:`~procedures.base.Evaluation` predicts
    overturning."""
    over = (evaluation.estimate.outcome == OVERTURN if evaluation.estimate is not None
            else np.zeros(len(evaluation.checks[0].passes), dtype=bool))
    for check in evaluation.checks:
        if check.exact_event == EXACT_OVERTURNING:
            over = over | ~np.asarray(check.passes, dtype=bool)
    return np.asarray(over, dtype=bool)


def _checks_overturn(checks, size) -> np.ndarray:
    over = np.zeros(size, dtype=bool)
    for check in checks:
        if check.exact_event == EXACT_OVERTURNING:
            over = over | ~np.asarray(check.passes, dtype=bool)
    return over


def overturning_predictions(procedure, cases, p, groups, g: float) -> np.ndarray:
    """Whether ``procedure`` predicts overturning of each block under each case.

    Parameters
    ----------
    procedure : procedures.base.Procedure
    cases : sequence of (records.RecordEntry, procedures.context.RecordContext)
        The records (scaled) it is evaluated under, each with its context.
    p : numpy.ndarray
        Frequency parameters of all blocks [rad/s].
    groups : sequence of (float, numpy.ndarray, float)
        (α [rad], indices into ``p`` of the blocks of that slenderness, r [-]).
    g : float
        Acceleration of gravity [m/s²].

    Returns
    -------
    numpy.ndarray of bool, shaped (case, block)
    """
    out = np.zeros((len(cases), p.size), dtype=bool)
    if procedure.alpha_per_block and len(groups) > 1:
        blocks = np.concatenate([index for _, index, _ in groups])
        alpha = np.concatenate([np.full(index.size, a) for a, index, _ in groups])
        restitution = np.concatenate([np.full(index.size, r) for _, index, r in groups])
        for c, (entry, context) in enumerate(cases):
            out[c, blocks] = predicts_overturning(procedure.evaluate_for_verdict(
                entry, p[blocks], alpha, restitution, context, g))
        return out
    if type(procedure).evaluate is not Procedure.evaluate or not procedure.estimates_rotation:
        for c, (entry, context) in enumerate(cases):
            for alpha, index, r in groups:
                out[c, index] = predicts_overturning(
                    procedure.evaluate(entry, p[index], alpha, r, context, g))
        return out
    # the contract's evaluate: its checks case by case, its iterations all at once where the
    # spectra are tabulated on the same periods
    tables, cells, block_p, block_scale, rows = [], [], [], [], []
    for c, (entry, context) in enumerate(cases):
        pga = procedure.peak_ground_acceleration(entry, context)
        for alpha, index, r in groups:
            out[c, index] = _checks_overturn(
                procedure.checks(entry, p[index], alpha, r, context, g), index.size)
            if not uplifts(pga, alpha, g):
                continue
            spectrum = procedure.displacement_spectrum(entry, float(procedure.damping(r)),
                                                       context)
            if not (isinstance(spectrum, TabulatedDisplacement)
                    and (not tables or spectrum.period_s is tables[0].period_s
                         or np.array_equal(spectrum.period_s, tables[0].period_s))):
                outcome = iterate_rotation(spectrum, p[index], alpha, g)[1]
                out[c, index] |= outcome == OVERTURN
                continue
            cells.append((c, index))
            block_p.append(p[index])
            block_scale.append(map_scale(p[index], alpha, g))
            rows.append(np.full(index.size, len(tables)))
            tables.append(spectrum)
    if tables:
        outcome = iterate_tabulated(tables[0].period_s, np.stack([t.sd_m for t in tables]),
                                    np.concatenate(rows), np.concatenate(block_p),
                                    np.concatenate(block_scale))[1]
        start = 0
        for c, index in cells:
            out[c, index] |= outcome[start:start + index.size] == OVERTURN
            start += index.size
    return out


def site_predictions(procedure, cases, p, alpha_rad: float, r: float, g: float) -> np.ndarray:
    """Whether ``procedure``, one that reads only the site, predicts overturning of block k
    (frequency parameter ``p[k]``, all of slenderness α) under case k, each case with its own
    (scaled) site.

    With the contract's :meth:`~procedures.base.Procedure.evaluate` and
    :meth:`~procedures.base.Procedure.site_displacements`, every block is iterated at once,
    each on its own site's spectrum (the iterates of an evaluation of that block alone, bit for
    bit); otherwise each case is evaluated on its own.

    Parameters
    ----------
    procedure : procedures.base.Procedure
    cases : sequence of (records.RecordEntry, procedures.context.RecordContext)
    p : numpy.ndarray
        Frequency parameter of each case's block [rad/s].
    alpha_rad, r, g : float
        Slenderness [rad], coefficient of restitution [-], gravity [m/s²].

    Returns
    -------
    numpy.ndarray of bool, one per case
    """
    beta = float(procedure.damping(r)) if procedure.estimates_rotation else None
    spectra = (procedure.site_displacements([entry for entry, _ in cases], beta)
               if type(procedure).evaluate is Procedure.evaluate and beta is not None else None)
    if spectra is None:
        return np.array([predicts_overturning(procedure.evaluate(entry, p[[k]], alpha_rad, r,
                                                                 context, g))[0]
                         for k, (entry, context) in enumerate(cases)], dtype=bool)
    over = np.array([_checks_overturn(procedure.checks(entry, p[[k]], alpha_rad, r, context, g),
                                      1)[0] for k, (entry, context) in enumerate(cases)],
                    dtype=bool)
    pga = np.array([procedure.peak_ground_acceleration(entry, context) for entry, context in cases])
    uplift = np.flatnonzero(uplifts(pga, alpha_rad, g))
    if uplift.size:
        outcome = iterate_rotation(lambda index: spectra(uplift[index]), p[uplift], alpha_rad,
                                   g, blockwise=True)[1]
        over[uplift] |= outcome == OVERTURN
    return over


__all__ = ["overturning_predictions", "predicts_overturning", "site_predictions"]
