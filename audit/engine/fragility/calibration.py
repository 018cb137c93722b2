"""Scores of a probabilistic procedure against exact outcomes: calibration (mean predicted
probability against observed frequency, in bins of the prediction), Brier score (Brier 1950) and
the Bernoulli log-likelihood. The exact outcomes come from multiple stripes
(:mod:`audit.engine.design.fragility`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


#: PGV levels of the stripes [m/s]: 0.05 to 3.2 m/s, 1.26 apart (19 levels), around the
#: P-58 medians of unanchored contents (0.25 to 1.23 m/s) with β = 0.5 on either side.
PGV_LEVELS_M_S = np.geomspace(0.05, 3.2, 19)
#: Bins of predicted probability for the calibration table [-].
CALIBRATION_EDGES = np.linspace(0.0, 1.0, 11)


def brier_score(predicted, observed) -> float:
    """Mean of (p − o)² over the outcomes [-] (Brier 1950): 0 is perfect, 0.25 a coin toss.

    Parameters
    ----------
    predicted : array
        Predicted probabilities of the event [-].
    observed : array of bool
        Whether the event happened.
    """
    predicted = np.asarray(predicted, dtype=float)
    return float(np.mean((predicted - np.asarray(observed, dtype=float)) ** 2))


def log_likelihood(predicted, observed) -> float:
    """Σ [o ln p + (1 − o) ln(1 − p)] over the outcomes [nats]; −inf where an outcome the
    prediction called impossible happened (no clipping: that is the finding).

    Parameters
    ----------
    predicted : array_like of float
        Predicted probability of each outcome [-].
    observed : array_like of bool
        Whether it happened.
    """
    predicted = np.asarray(predicted, dtype=float)
    observed = np.asarray(observed, dtype=bool)
    with np.errstate(divide="ignore"):
        return float(np.sum(np.where(observed, np.log(predicted), np.log1p(-predicted))))


@dataclass(frozen=True)
class Calibration:
    """Predicted probability against observed frequency, in bins of the prediction.

    Attributes
    ----------
    lower, upper : numpy.ndarray
        Bin edges of predicted probability [-]; the last bin includes 1.
    count : numpy.ndarray of int
        Outcomes in each bin.
    mean_predicted, observed_frequency : numpy.ndarray
        Mean prediction and frequency of the event in each bin [-]; NaN in an empty bin.
    """

    lower: np.ndarray
    upper: np.ndarray
    count: np.ndarray
    mean_predicted: np.ndarray
    observed_frequency: np.ndarray


def calibration(predicted, observed, edges=CALIBRATION_EDGES) -> Calibration:
    """Bin the outcomes by predicted probability (see :class:`Calibration`).

    Parameters
    ----------
    predicted : array_like of float
        Predicted probability of each outcome [-].
    observed : array_like of bool
        Whether it happened.
    edges : array_like of float
        Edges of the probability bins [-], ascending from 0 to 1.
    """
    predicted = np.asarray(predicted, dtype=float).ravel()
    observed = np.asarray(observed, dtype=float).ravel()
    edges = np.asarray(edges, dtype=float)
    index = np.clip(np.searchsorted(edges, predicted, side="right") - 1, 0, edges.size - 2)
    count = np.bincount(index, minlength=edges.size - 1)
    with np.errstate(invalid="ignore"):
        mean = np.bincount(index, predicted, minlength=edges.size - 1) / count
        frequency = np.bincount(index, observed, minlength=edges.size - 1) / count
    return Calibration(edges[:-1], edges[1:], count, mean, frequency)
