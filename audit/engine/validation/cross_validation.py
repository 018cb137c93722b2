"""Cross-validation by ground motion: folds, and out-of-fold predictions of model and baselines.

Tests of one ground motion (the same record at other scales) share a fold, so no prediction is
scored on a record the fit has seen: a random split would let the model learn a record's
overturning scale from its neighbours and overstate the accuracy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from audit.engine.validation.baselines import ThresholdFragility, VectorLogistic
from audit.engine.validation.fit import fit_block

#: Method names, in the order of the tables.
MODEL, PGA, PGV = "rocking model", "PGA threshold", "PGV threshold"
VECTOR = "logistic (PGA, PGV/PGA)"


def folds_by_record(groups, folds: int) -> np.ndarray:
    """Fold index (0 … folds−1) of every test, whole ground motions at a time.

    Motions go largest first (ties by name) to the fold with the fewest tests so far (ties:
    the lowest index): deterministic, and the folds' sizes differ by at most one motion's.

    Parameters
    ----------
    groups : array_like of str
        Each test's ground motion.
    folds : int
        Number of folds.
    """
    groups = np.asarray(groups, dtype=str)
    names, counts = np.unique(groups, return_counts=True)
    sizes = np.zeros(folds, dtype=int)
    fold_of = {}
    for index in sorted(range(names.size), key=lambda i: (-counts[i], names[i])):
        target = int(np.argmin(sizes))
        fold_of[names[index]] = target
        sizes[target] += counts[index]
    return np.array([fold_of[g] for g in groups], dtype=int)


@dataclass(frozen=True)
class OutOfFold:
    """Out-of-fold predictions: ``probabilities`` (method name → P(overturn) of every test,
    from the fit on the other folds) and ``fits`` (the model's BlockFit of each fold)."""

    probabilities: dict
    fits: tuple


def out_of_fold(overturned, outcomes, fold, intensities, settings, blocks) -> OutOfFold:
    """Each method's probability for every test, fitted on the other folds.

    Parameters
    ----------
    overturned : numpy.ndarray of bool
        Exact grid outcomes of these tests (test, f, p, α).
    outcomes : numpy.ndarray
        Observed 0/1 outcomes.
    fold : numpy.ndarray of int
        Fold of each test.
    intensities : Intensities
        PGA and PGV of these tests.
    settings : ValidationSettings
        The folds and the lapse.
    blocks : BlockGrid
        The grid ``overturned`` was solved on.

    Returns
    -------
    OutOfFold
    """
    out = {name: np.empty(outcomes.size) for name in (MODEL, PGA, PGV, VECTOR)}
    fits = []
    pga_g, pgv, ratio = intensities.pga_g, intensities.pgv, intensities.pgv_pga_s
    for k in range(settings.folds):
        test, train = fold == k, fold != k
        if not test.any():
            continue
        y = outcomes[train]
        fit = fit_block(overturned[train], y, blocks, settings.lapse)
        fits.append(fit)
        out[MODEL][test] = fit.predict(overturned[test]).p_overturn
        out[PGA][test] = ThresholdFragility.fit(pga_g[train], y, settings.lapse).probability(
            pga_g[test])
        out[PGV][test] = ThresholdFragility.fit(pgv[train], y, settings.lapse).probability(
            pgv[test])
        out[VECTOR][test] = VectorLogistic.fit(pga_g[train], ratio[train], y,
                                               settings.lapse).probability(pga_g[test],
                                                                           ratio[test])
    return OutOfFold(out, tuple(fits))


__all__ = ["OutOfFold", "folds_by_record", "out_of_fold", "MODEL", "PGA", "PGV", "VECTOR"]
