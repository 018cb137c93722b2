"""Intensity-measure baselines the rocking model must beat, and the scores that compare them.

Each baseline is fitted by maximum likelihood on the same training tests as the model, with the
same lapse ε (probabilities kept in [ε, 1 − ε]):

- a threshold on one intensity (PGA or PGV): the lognormal fragility P = Φ(ln(x/x̂)/β), whose
  median x̂ is the threshold (predicted overturned where x ≥ x̂, i.e. P ≥ 0.5);
- the Purvance-style vector predictor: a logistic on ln(PGA/g) and ln(PGV/PGA).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import expit, ndtr


def _with_lapse(probability, lapse):
    return lapse + (1.0 - 2.0 * lapse) * probability


def _negative_log_likelihood(outcomes, probability):
    """Cross-entropy −Σ [y ln P + (1 − y) ln(1 − P)]: the binomial log-likelihood for 0/1
    outcomes, and the smoothing criterion for probabilities y."""
    return -float(np.sum(outcomes * np.log(probability) + (1 - outcomes) * np.log1p(-probability)))


@dataclass(frozen=True)
class ThresholdFragility:
    """P(overturn) = Φ(ln(x/threshold)/β) of one intensity x (with the lapse)."""

    threshold: float
    beta: float
    lapse: float

    @classmethod
    def fit(cls, intensity, outcomes, lapse: float) -> ThresholdFragility:
        """The maximum-likelihood threshold and β of the outcomes, for a fixed lapse (the best
        of a grid of starts, refined).

        Parameters
        ----------
        intensity : array_like of float
            Each test's intensity x (PGA [g] or PGV [m/s]), positive.
        outcomes : array_like of float
            Each test's observed outcome, 0 or 1.
        lapse : float
            The lapse ε [-]: probabilities kept in [ε, 1 − ε].
        """
        log_x = np.log(intensity)

        def negative(theta):
            return _negative_log_likelihood(
                outcomes, _with_lapse(ndtr((log_x - theta[0]) / math.exp(theta[1])), lapse))
        starts = [(m, math.log(b)) for m in np.quantile(log_x, np.linspace(0.05, 0.95, 19))
                  for b in (0.05, 0.2, 0.5, 1.0)]
        best = minimize(negative, min(starts, key=negative), method="L-BFGS-B",
                        bounds=[(log_x.min() - 1, log_x.max() + 1), (math.log(0.01), math.log(5))])
        return cls(math.exp(best.x[0]), math.exp(best.x[1]), lapse)

    def probability(self, intensity) -> np.ndarray:
        """P(overturn) [-] at each intensity, with the lapse.

        Parameters
        ----------
        intensity : array_like of float
            Intensity x, in the unit of the fit (PGA [g] or PGV [m/s]).
        """
        return _with_lapse(ndtr(np.log(np.asarray(intensity) / self.threshold) / self.beta),
                           self.lapse)


@dataclass(frozen=True)
class VectorLogistic:
    """P(overturn) = logistic(b0 + b1 ln(PGA/g) + b2 ln(PGV/PGA)) (with the lapse)."""

    coefficients: tuple
    lapse: float

    @staticmethod
    def _design(pga_g, pgv_pga_s):
        return np.column_stack((np.ones(len(pga_g)), np.log(pga_g), np.log(pgv_pga_s)))

    @classmethod
    def fit(cls, pga_g, pgv_pga_s, outcomes, lapse: float) -> VectorLogistic:
        """The maximum-likelihood coefficients of the outcomes, for a fixed lapse.

        Parameters
        ----------
        pga_g : array_like of float
            Each test's PGA [g].
        pgv_pga_s : array_like of float
            Each test's PGV/PGA [s].
        outcomes : array_like of float
            Each test's outcome, 0 or 1.
        lapse : float
            The lapse ε [-]: probabilities kept in [ε, 1 − ε].
        """
        design = cls._design(pga_g, pgv_pga_s)

        def negative(b):
            return _negative_log_likelihood(outcomes, _with_lapse(expit(design @ b), lapse))
        best = minimize(negative, np.zeros(3), method="BFGS")
        return cls(tuple(float(b) for b in best.x), lapse)

    def probability(self, pga_g, pgv_pga_s) -> np.ndarray:
        """P(overturn) [-] of each test, with the lapse.

        Parameters
        ----------
        pga_g : array_like of float
            PGA [g].
        pgv_pga_s : array_like of float
            PGV/PGA [s].
        """
        return _with_lapse(expit(self._design(pga_g, pgv_pga_s) @ np.asarray(self.coefficients)),
                           self.lapse)


@dataclass(frozen=True)
class Scores:
    """Scores of probabilities against outcomes (classification at P ≥ 0.5).

    Attributes
    ----------
    n : int
    accuracy : float
        Share classified correctly [-].
    brier : float
        Mean (P − outcome)² [-].
    log_loss : float
        Mean −ln P(observed outcome) [nats].
    true_positive, false_positive, true_negative, false_negative : int
        The confusion matrix (positive = overturned).
    """

    n: int
    accuracy: float
    brier: float
    log_loss: float
    true_positive: int
    false_positive: int
    true_negative: int
    false_negative: int


def scores(probability, outcomes) -> Scores:
    """:class:`Scores` of ``probability`` (already within (0, 1)) against 0/1 ``outcomes``.

    Parameters
    ----------
    probability : array_like of float
        Predicted P(overturn) of each test [-].
    outcomes : array_like of float
        Each test's outcome, 0 or 1.
    """
    probability = np.asarray(probability, dtype=float)
    observed = np.asarray(outcomes) > 0.5
    predicted = probability >= 0.5
    loss = -np.where(observed, np.log(probability), np.log1p(-probability))
    return Scores(int(observed.size), float(np.mean(predicted == observed)),
                  float(np.mean((probability - observed) ** 2)), float(np.mean(loss)),
                  int(np.sum(predicted & observed)), int(np.sum(predicted & ~observed)),
                  int(np.sum(~predicted & ~observed)), int(np.sum(~predicted & observed)))


__all__ = ["ThresholdFragility", "VectorLogistic", "Scores", "scores"]
