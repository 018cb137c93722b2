"""Audit of a probabilistic procedure against exact outcomes: stripes, fit, calibration, scores.

The exact fragility is found by multiple stripes: every record is scaled to each of a set of
intensity levels, the exact solver says whether the block overturns, and the lognormal whose
binomial likelihood of those counts is greatest is fitted (Baker 2015, "Efficient analytical
fragility function fitting using dynamic structural analysis", Earthquake Spectra 31(1),).
Stripes, not incremental scaling to a first overturning: a rocking block that overturns at one
scale may survive a larger one, so "the" collapse intensity of a record is not well defined.

The procedure's probabilities at the same scaled intensities are then scored against the exact
outcomes: calibration (mean predicted probability against observed frequency, in bins of the
prediction), Brier score (Brier 1950) and the Bernoulli log-likelihood.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import log_ndtr

from audit.physics.rocking import rocking_spectrum

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
    prediction called impossible happened (no clipping: that is the finding)."""
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
    """Bin the outcomes by predicted probability (see :class:`Calibration`)."""
    predicted = np.asarray(predicted, dtype=float).ravel()
    observed = np.asarray(observed, dtype=float).ravel()
    edges = np.asarray(edges, dtype=float)
    index = np.clip(np.searchsorted(edges, predicted, side="right") - 1, 0, edges.size - 2)
    count = np.bincount(index, minlength=edges.size - 1)
    with np.errstate(invalid="ignore"):
        mean = np.bincount(index, predicted, minlength=edges.size - 1) / count
        frequency = np.bincount(index, observed, minlength=edges.size - 1) / count
    return Calibration(edges[:-1], edges[1:], count, mean, frequency)


def overturn_stripes(motions, size_s: float, alpha_rad: float, pgv_levels_m_s,
                     r: float | None = None, g: float | None = None) -> np.ndarray:
    """Whether the exact response overturns with each record scaled to each PGV level.

    Parameters
    ----------
    motions : sequence of records.GroundMotion
        The records, each scaled by level / its PGV.
    size_s, alpha_rad : float
        The block: size 2π/p [s] and slenderness α [rad].
    pgv_levels_m_s : array
        PGV of the stripes [m/s].
    r, g : float, optional
        Coefficient of restitution (Eq. 4.8 of Makris & Konstantinidis 2001 when not given) and
        gravity [m/s²].

    Returns
    -------
    numpy.ndarray of bool, shaped (len(motions), len(pgv_levels_m_s))
    """
    levels = np.asarray(pgv_levels_m_s, dtype=float)
    overturned = np.zeros((len(motions), levels.size), dtype=bool)
    for i, motion in enumerate(motions):
        for j, level in enumerate(levels):
            spectrum = rocking_spectrum(motion.scaled(level / motion.pgv), [size_s], [alpha_rad],
                                        r=r, g=g)
            overturned[i, j] = spectrum.overturned[0, 0]
    return overturned


def fit_lognormal_fragility(levels, n_events, n_trials) -> tuple[float, float]:
    """Median θ and β of the lognormal fragility of greatest binomial likelihood of the counts
    (Baker 2015): Σ_j [z_j ln Φ(x_j) + (n_j − z_j) ln Φ(−x_j)], x_j = ln(IM_j/θ)/β.

    Parameters
    ----------
    levels : array
        Intensity of each stripe (any positive unit; θ comes back in it).
    n_events, n_trials : array of int
        Events observed and records run at each stripe.

    Returns
    -------
    median, beta : float
        NaN, NaN when no stripe has an event or every stripe has only events (no fit exists).
    """
    log_levels = np.log(np.asarray(levels, dtype=float))
    events = np.asarray(n_events, dtype=float)
    misses = np.asarray(n_trials, dtype=float) - events
    if events.sum() == 0 or misses.sum() == 0:
        return float("nan"), float("nan")

    def negative_log_likelihood(parameters):
        x = (log_levels - parameters[0]) / np.exp(parameters[1])
        return -np.sum(events * log_ndtr(x) + misses * log_ndtr(-x))

    weights = events / events.sum()  # start from the mean log-level of the events
    start = np.array([np.sum(weights * log_levels), np.log(0.4)])
    result = minimize(negative_log_likelihood, start, method="Nelder-Mead",
                      options={"xatol": 1e-8, "fatol": 1e-10, "maxiter": 4000})
    return float(np.exp(result.x[0])), float(np.exp(result.x[1]))
