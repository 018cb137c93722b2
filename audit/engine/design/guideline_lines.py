"""Where a guideline draws its line on the stripes — the intensity at which it starts predicting
overturning — one function for ``margins`` and ``check`` (:func:`guideline_lines`).

A procedure that reads the records gives each record its own answer, so its prediction over the
suite is a fraction of records; its line is where that fraction first reaches one half,
ln-interpolated between stripes (:func:`~audit.engine.design.stripes.half_crossing`). A procedure
that reads only the site's design spectrum (FEMA 356) gives one answer for every record: a step
in intensity, not a fraction, so its line is the step itself, located by bisection between the
two stripes it falls between (:func:`~audit.engine.design.stripes.locate_steps`). Interpolating a
step between stripes would put it at their geometric mean whatever the text says (for FEMA 356
the uplift step, 0.4·S_XS·λ = tan α, λ the design spectrum's scale).
"""

from __future__ import annotations

import numpy as np

from audit.engine.design.stripes import StripeSettings, half_crossing, locate_steps


def step_levels(procedures, entries, settings: StripeSettings, predicted, evaluated) -> dict:
    """Per (procedure name, block), the exact step of a procedure that reads only the site's
    design spectrum, where it turns to predicting overturning between two stripes.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    entries : sequence of records.RecordEntry
        The records.
    settings : StripeSettings
        The blocks, stripes and solver settings.
    predicted : dict
        Procedure name → predictions shaped (record, stripe, block).
    evaluated : dict
        Procedure name → whether it evaluated each record.
    """
    levels = np.asarray(settings.levels)
    steps = {}
    for proc in procedures:
        mine = [e for e, used in zip(entries, evaluated[proc.name]) if used]
        if not mine or any(proc.reads_record(e) for e in mine):
            continue
        answer = predicted[proc.name][np.asarray(evaluated[proc.name])][0]  # (stripe, block)
        brackets = {}
        for b in range(answer.shape[1]):
            switch = np.flatnonzero(answer[1:, b] & ~answer[:-1, b])
            if switch.size:
                brackets[b] = levels[int(switch[0])], levels[int(switch[0]) + 1]
        steps.update(((proc.name, b), level) for b, level
                     in locate_steps(proc, mine[0], settings, brackets).items())
    return steps


def guideline_lines(procedures, entries, settings: StripeSettings, predicted,
                    evaluated) -> dict:
    """Per procedure name, its line for every block [unit of the intensity measure]: the
    step of a procedure that reads only the site (:func:`step_levels`), else where the share of
    the records it evaluates for which it predicts overturning first reaches one half; NaN
    where it never does or evaluates no record.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    entries : sequence of records.RecordEntry
        The records.
    settings : StripeSettings
        The blocks, stripes (ascending) and solver settings.
    predicted : dict
        Procedure name → predictions shaped (record, stripe, block).
    evaluated : dict
        Procedure name → whether it evaluated each record, shaped (record,).

    Returns
    -------
    dict
        Procedure name → numpy.ndarray of one line per block.
    """
    levels, n_blocks = np.asarray(settings.levels), len(settings.blocks)
    steps = step_levels(procedures, entries, settings, predicted, evaluated)
    lines = {}
    for proc in procedures:
        mine = np.asarray(evaluated[proc.name])
        fraction = predicted[proc.name][mine].mean(axis=0) if mine.any() else None
        lines[proc.name] = np.array([
            steps.get((proc.name, b),
                      half_crossing(levels, fraction[:, b]) if fraction is not None else np.nan)
            for b in range(n_blocks)], dtype=float)
    return lines


__all__ = ["guideline_lines", "step_levels"]
