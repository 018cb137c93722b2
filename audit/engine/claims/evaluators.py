"""The evaluators of the reproduction checklist (:mod:`audit.engine.claims.checklist`), by the name
``claims.toml`` gives them: each computes one kind of quantity a claim of the reference report
names, from the physics (:mod:`audit.engine.claims.physics_evaluators`) or from the run
(:mod:`audit.engine.claims.run_evaluators`; one block from its record wherever it can, so that a
claim stays checkable on a partial grid, and only statements about regions of the grid from the
run's tables); :func:`ratio` combines two of them.
"""

from __future__ import annotations

from audit.engine.claims.physics_evaluators import (closed_form, free_rocking, oscillator_pulse,
                                                   pulse_block)
from audit.engine.claims.run_evaluators import (exact_block, exact_compare, exact_region,
                                               procedure_block, procedure_region, record_peak)
from audit.engine.claims.value import Value


def ratio(ctx, numerator: dict, denominator: dict, percent_change: bool = False) -> Value:
    """numerator/denominator of two other evaluations, or 100·(ratio − 1) [%].

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    numerator, denominator : dict
        Two claim methods (``name`` and parameters).
    percent_change : bool
        Give 100·(ratio − 1) [%] instead of the ratio [-].
    """
    top, bottom = evaluate_method(ctx, numerator), evaluate_method(ctx, denominator)
    note = "; ".join(v.note for v in (top, bottom) if v.note)
    if top.value is None or bottom.value is None or bottom.value == 0:
        return Value(None, note)
    value = top.value / bottom.value
    return Value(100.0 * (value - 1.0) if percent_change else value, note)


EVALUATORS = {f.__name__: f for f in (closed_form, pulse_block, oscillator_pulse, free_rocking,
                                      record_peak, exact_block, procedure_block, ratio,
                                      exact_region, exact_compare, procedure_region)}


def evaluate_method(ctx, method: dict) -> Value:
    """Run the evaluator a claim's ``method`` names, with its parameters.

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    method : dict
        The claim's ``method``: the evaluator's ``name`` and its parameters.
    """
    params = {k: v for k, v in method.items() if k != "name"}
    return EVALUATORS[method["name"]](ctx, **params)
