"""The lognormal overturning fragility fitted to multiple-stripe counts by maximum likelihood on
the binomial likelihood (Baker 2015, Earthquake Spectra 31(1) 579–599): one set of counts with
its likelihood band (:func:`fit_lognormal`), or many at once by Fisher scoring
(:func:`lognormal_fits`, for a bootstrap or a grid of blocks).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import ndtr, ndtri

#: √(2π), the normal density's constant as scipy.stats.norm has it.
_SQRT_2PI = math.sqrt(2.0 * math.pi)


@dataclass(frozen=True)
class LognormalFit:
    """A lognormal fragility P(overturn | IM = x) = Φ(ln(x/median)/β) fitted to stripe counts.

    Attributes
    ----------
    median : float
        θ, the intensity with P = 0.5 (unit of the intensity measure).
    beta : float
        Logarithmic standard deviation β [-].
    median_band, beta_band : (float, float)
        Confidence bounds at :attr:`confidence` (from the observed information); NaN where
        the information is not positive definite (counts that fix β only as → 0).
    covariance : numpy.ndarray
        Covariance of (ln θ, ln β), 2 × 2.
    confidence : float
        Two-sided confidence level of the bands [-].
    """

    median: float
    beta: float
    median_band: tuple
    beta_band: tuple
    covariance: np.ndarray
    confidence: float

    def probability(self, im) -> np.ndarray:
        """P(overturn | IM = im) [-] of the fit.

        Parameters
        ----------
        im : float or array_like of float
            Intensity, in the unit of the stripes (e.g. [g]).
        """
        return ndtr(np.log(np.asarray(im, dtype=float) / self.median) / self.beta)

    def probability_band(self, im) -> tuple[np.ndarray, np.ndarray]:
        """Confidence band of :meth:`probability` at ``im``, by the delta method on
        z = (ln im − ln θ)/β.

        Parameters
        ----------
        im : float or array_like of float
            Intensity, in the unit of the stripes (e.g. [g]).

        Returns
        -------
        low, high : numpy.ndarray
            The band's ends [-] at :attr:`confidence`, shaped as ``im``.
        """
        z = np.log(np.asarray(im, dtype=float) / self.median) / self.beta
        # ∂z/∂ln θ = −1/β, ∂z/∂ln β = −z
        gradient = np.stack([-np.ones_like(z) / self.beta, -z])
        spread = np.sqrt(np.einsum("i...,ij,j...->...", gradient, self.covariance, gradient))
        k = ndtri(0.5 + self.confidence / 2.0)
        return ndtr(z - k * spread), ndtr(z + k * spread)


def _negative_log_likelihood(params, log_levels, trials, successes):
    log_median, log_beta = params
    # Φ as ``norm.cdf`` computes it (scipy.special.ndtr) without its argument checks, which
    # cost more than the likelihood itself on a few stripes
    p = ndtr((log_levels - log_median) / np.exp(log_beta))
    p = np.clip(p, 1e-300, 1.0 - 1e-16)
    return -np.sum(successes * np.log(p) + (trials - successes) * np.log1p(-p))


def _most_likely(levels, trials, successes):
    """The likelihood's arguments and its maximum over (ln θ, ln β) (scipy's result)."""
    log_levels = np.log(np.asarray(levels, dtype=float))
    trials = np.asarray(trials, dtype=float)
    successes = np.asarray(successes, dtype=float)
    if successes.sum() == 0 or successes.sum() == trials.sum():
        raise ValueError("fragility: the block overturns at no stripe or at every one")
    start = log_levels[np.argmin(np.abs(successes / trials - 0.5))]  # the stripe nearest 50 %
    args = (log_levels, trials, successes)
    return args, minimize(_negative_log_likelihood, [start, np.log(0.4)], args=args,
                          method="Nelder-Mead",
                          options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})


@dataclass(frozen=True)
class LognormalEstimate:
    """The maximum-likelihood θ (unit of the intensity measure) and β [-] alone, without the
    bands of :class:`LognormalFit`."""

    median: float
    beta: float


def lognormal_estimate(levels, trials, successes) -> LognormalEstimate:
    """:func:`fit_lognormal`'s θ and β, the same numbers, without the bands (whose Hessian
    costs a tenth of the fit); raises as it does.

    Parameters
    ----------
    levels : array_like of float
        Intensity of each stripe (> 0).
    trials, successes : array_like of int
        Records at each stripe, and how many of them overturn the block.
    """
    _, best = _most_likely(levels, trials, successes)
    return _estimate(best.x)


def _estimate(log_params) -> LognormalEstimate:
    log_median, log_beta = log_params
    return LognormalEstimate(float(np.exp(log_median)), float(np.exp(log_beta)))


def fit_lognormal(levels, trials, successes, confidence: float = 0.90) -> LognormalFit:
    """Maximum-likelihood lognormal fragility of binomial stripe counts.

    Maximises Σ [k ln Φ(z) + (n − k) ln(1 − Φ(z))], z = ln(x/θ)/β, over (ln θ, ln β); the bands
    come from the inverse of the observed information (the log-likelihood's Hessian).

    Parameters
    ----------
    levels : array
        Intensity of each stripe (> 0).
    trials, successes : array of int
        Records at each stripe, and how many of them overturn the block.
    confidence : float
        Two-sided confidence level of the bands [-].

    Returns
    -------
    LognormalFit

    Raises
    ------
    ValueError
        When no stripe overturns the block, or every one does: the counts fix no median.
    """
    args, best = _most_likely(levels, trials, successes)
    information = _hessian(lambda q: _negative_log_likelihood(q, *args), best.x)
    # counts that a step fits best (β → 0, e.g. one stripe with overturning) leave the
    # likelihood flat or curved the wrong way there: no band, rather than a negative variance
    if np.all(np.linalg.eigvalsh(information) > 0.0):
        covariance = np.linalg.inv(information)
    else:
        covariance = np.full((2, 2), np.nan)
    log_median, log_beta = best.x
    k = ndtri(0.5 + confidence / 2.0)
    se_median, se_beta = np.sqrt(np.diag(covariance))
    estimate = _estimate(best.x)
    with np.errstate(over="ignore"):  # a band wider than floats hold is unbounded: inf
        return LognormalFit(estimate.median, estimate.beta,
                            (float(np.exp(log_median - k * se_median)),
                             float(np.exp(log_median + k * se_median))),
                            (float(np.exp(log_beta - k * se_beta)),
                             float(np.exp(log_beta + k * se_beta))),
                            covariance, confidence)


def _hessian(function, x, step: float = 1e-4) -> np.ndarray:
    """Central-difference Hessian of a scalar function of two variables."""
    hessian = np.empty((2, 2))
    for i in range(2):
        for j in range(2):
            ei, ej = np.eye(2)[i] * step, np.eye(2)[j] * step
            hessian[i, j] = (function(x + ei + ej) - function(x + ei - ej)
                             - function(x - ei + ej) + function(x - ei - ej)) / (4 * step ** 2)
    return hessian


def lognormal_fits(levels, trials: int, counts) -> tuple[np.ndarray, np.ndarray]:
    """The maximum-likelihood lognormal of many sets of stripe counts at once (each row of
    ``counts``, ``trials`` records at every stripe), as :func:`fit_lognormal` fits one.

    Parameters
    ----------
    levels : array_like of float
        Intensity of each stripe (> 0).
    trials : int
        Records at every stripe.
    counts : array_like of int
        Overturning records at each stripe, one row per set (shaped (set, stripe)).

    Returns
    -------
    medians, betas : numpy.ndarray
        θ (unit of ``levels``) and β [-] per row; θ = +inf where a row counts no overturning,
        0 where every record overturns at every stripe (the likelihood's limits: P = 0, resp.
        1, at every level), β NaN there; β = :data:`STEP_BETA` where a step fits the counts best.
    """
    counts = np.atleast_2d(np.asarray(counts, dtype=float))
    total = counts.sum(axis=1)
    none, every = total == 0, total == trials * counts.shape[1]
    fitted = ~(none | every)
    medians = np.where(none, np.inf, 0.0)
    betas = np.full(len(counts), np.nan)
    if fitted.any():
        rows = counts[fitted]
        # equal rows fit alike, and a bootstrap draws many: each distinct row is fitted once,
        # from the start every row's pooled shares give (the scoring of a row depends on its
        # start and its own counts only)
        distinct, inverse = np.unique(rows, axis=0, return_inverse=True)
        fits = _probit_fits(np.log(levels), trials, distinct,
                            rows.sum(axis=0) / (trials * len(rows)))
        medians[fitted], betas[fitted] = (values[inverse.ravel()]
                                          for values in _steps_where_unsettled(
                                              levels, trials, distinct, *fits))
    return medians, betas


def _steps_where_unsettled(levels, trials: int, counts, medians, betas):
    """The fits of ``counts`` with a step (or the slow fit) where the scoring gave no finite
    θ and positive β (the likelihood's supremum at β → 0)."""
    levels = np.asarray(levels, dtype=float)
    for k in np.flatnonzero(~(np.isfinite(medians) & (betas > 0))):
        step = _step_fit(levels, trials, counts[k])
        if step is None:  # a row the scoring did not settle: the slow fit of its own
            _, best = _most_likely(levels, np.full(counts.shape[1], trials), counts[k])
            step = np.exp(best.x)
        medians[k], betas[k] = step
    return medians, betas


#: β of a fit to counts that a step fits best [-]: the likelihood's supremum is at β → 0.
STEP_BETA = 1e-6


def _step_fit(levels, trials: int, counts):
    """(θ, β) of counts that no stripe below a level and every one above it overturn, with at
    most one stripe of both between: the supremum of the likelihood as β → 0, a step there
    (at the geometric middle of the gap, or through the mixed stripe's share); None for other
    counts."""
    mixed = np.flatnonzero((counts > 0) & (counts < trials))
    if mixed.size > 1:
        return None
    cut = mixed[0] if mixed.size else int(np.argmax(counts == trials))
    if not (np.all(counts[:cut] == 0) and np.all(counts[cut + mixed.size:] == trials)):
        return None
    if mixed.size:  # Φ(ln(x/θ)/β) equals the stripe's share at its level
        return levels[cut] * math.exp(-STEP_BETA * ndtri(counts[cut] / trials)), STEP_BETA
    return math.sqrt(levels[cut - 1] * levels[cut]), STEP_BETA


#: Fisher-scoring steps of :func:`_probit_fits` at most (it settles in a few from its start).
SCORING_STEPS = 60


def _probit_fits(log_levels, trials: int, counts, share):
    """Maximum-likelihood (θ, β) of many sets of stripe counts at once.

    P = Φ(a + b ln x) is a probit regression on ln x, θ = exp(−a/b), β = 1/b: Fisher scoring
    (score Σ (k − nΦ) φ/(Φ(1 − Φ)) (1, ln x), information Σ n φ²/(Φ(1 − Φ)) (1, ln x)⊗(1, ln x))
    for every row of ``counts`` together, from the probit line of the pooled shares ``share``
    (per stripe). The same maximum as :func:`fit_lognormal`'s, reached in milliseconds for
    hundreds of resamples.
    """
    x = np.asarray(log_levels, dtype=float)[None, :]
    # start: the probit line through the pooled shares, Φ⁻¹(share) = a + b ln x by least squares
    share = np.clip(share, 0.02, 0.98)
    slope, intercept = np.polyfit(x[0], ndtri(share), 1)
    if not slope > 0:  # shares that do not rise: a median at the middle stripe, β = 0.4
        slope, intercept = 2.5, -2.5 * float(np.median(x))
    a, b = np.full(len(counts), intercept), np.full(len(counts), slope)
    for _ in range(SCORING_STEPS):
        with np.errstate(all="ignore"):  # a separated row diverges: refitted by the caller
            a, b, settled = _scoring_step(a, b, x, trials, counts)
        if settled:
            break
    with np.errstate(all="ignore"):
        return np.exp(-a / b), 1.0 / b


def _scoring_step(a, b, x, trials, counts):
    """One Fisher-scoring step of :func:`_probit_fits`, and whether every row has settled."""
    eta = a[:, None] + b[:, None] * x
    # Φ and φ with the arithmetic of ``norm.cdf`` and ``norm.pdf``, without their checks
    mu = np.clip(ndtr(eta), 1e-12, 1.0 - 1e-12)
    phi = np.exp(-eta ** 2 / 2.0) / _SQRT_2PI
    weight = trials * phi ** 2 / (mu * (1.0 - mu))
    residual = (counts - trials * mu) * phi / (mu * (1.0 - mu))
    u0, u1 = residual.sum(axis=1), (residual * x).sum(axis=1)
    i00, i01, i11 = weight.sum(axis=1), (weight * x).sum(axis=1), (weight * x * x).sum(axis=1)
    det = i00 * i11 - i01 ** 2
    step_a, step_b = (i11 * u0 - i01 * u1) / det, (i00 * u1 - i01 * u0) / det
    return a + step_a, b + step_b, bool(np.all(np.abs(step_a) + np.abs(step_b) < 1e-10))


__all__ = ["fit_lognormal", "LognormalFit", "lognormal_estimate", "LognormalEstimate",
           "lognormal_fits", "STEP_BETA"]
