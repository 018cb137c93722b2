"""Multiple-stripe overturning fragility of a block: the records of a suite scaled to a set of
intensity levels (stripes), the exact response at every record × stripe, and a lognormal
fragility fitted to the stripe counts by maximum likelihood on the binomial likelihood (the
standard method for multiple-stripe analysis, Baker 2015, Earthquake Spectra 31(1) 579–599).

Overturning is not monotonic in intensity: a block that overturns at one scale factor may
survive a larger one (islands). The fraction that overturns at a level, over a suite, is a
number to build on; "the smallest factor that overturns the block" is not, since it depends on
the spacing of the stripes. :func:`overturning_pattern` says both per record.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.stats import norm

from audit.engine.defaults import DEFAULT_STRIPE_SPAN as DEFAULT_SPAN
from audit.engine.defaults import DEFAULT_STRIPES
from audit.physics.rocking import rocking_spectrum


def stripe_levels(centre, count: int = DEFAULT_STRIPES, span=DEFAULT_SPAN) -> np.ndarray:
    """Intensity levels of the stripes: ``count`` levels geometric in ``span`` × ``centre``
    (the site's design intensity, or the suite's median), in the intensity's own unit."""
    return float(centre) * np.geomspace(span[0], span[1], count)


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
        """P(overturn | IM = im) [-] of the fit."""
        return norm.cdf(np.log(np.asarray(im, dtype=float) / self.median) / self.beta)

    def probability_band(self, im) -> tuple[np.ndarray, np.ndarray]:
        """Confidence band of :meth:`probability` at ``im``, by the delta method on
        z = (ln im − ln θ)/β."""
        z = np.log(np.asarray(im, dtype=float) / self.median) / self.beta
        # ∂z/∂ln θ = −1/β, ∂z/∂ln β = −z
        gradient = np.stack([-np.ones_like(z) / self.beta, -z])
        spread = np.sqrt(np.einsum("i...,ij,j...->...", gradient, self.covariance, gradient))
        k = norm.ppf(0.5 + self.confidence / 2.0)
        return norm.cdf(z - k * spread), norm.cdf(z + k * spread)


def _negative_log_likelihood(params, log_levels, trials, successes):
    log_median, log_beta = params
    p = norm.cdf((log_levels - log_median) / np.exp(log_beta))
    p = np.clip(p, 1e-300, 1.0 - 1e-16)
    return -np.sum(successes * np.log(p) + (trials - successes) * np.log1p(-p))


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
    log_levels = np.log(np.asarray(levels, dtype=float))
    trials = np.asarray(trials, dtype=float)
    successes = np.asarray(successes, dtype=float)
    if successes.sum() == 0 or successes.sum() == trials.sum():
        raise ValueError("fragility: the block overturns at no stripe or at every one")
    start = log_levels[np.argmin(np.abs(successes / trials - 0.5))]  # the stripe nearest 50 %
    args = (log_levels, trials, successes)
    best = minimize(_negative_log_likelihood, [start, np.log(0.4)], args=args,
                    method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    information = _hessian(lambda q: _negative_log_likelihood(q, *args), best.x)
    # counts that a step fits best (β → 0, e.g. one stripe with overturning) leave the
    # likelihood flat or curved the wrong way there: no band, rather than a negative variance
    if np.all(np.linalg.eigvalsh(information) > 0.0):
        covariance = np.linalg.inv(information)
    else:
        covariance = np.full((2, 2), np.nan)
    log_median, log_beta = best.x
    k = norm.ppf(0.5 + confidence / 2.0)
    se_median, se_beta = np.sqrt(np.diag(covariance))
    with np.errstate(over="ignore"):  # a band wider than floats hold is unbounded: inf
        return LognormalFit(float(np.exp(log_median)), float(np.exp(log_beta)),
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


@dataclass(frozen=True)
class OverturningPattern:
    """Per record, where along ascending stripes the block first overturns, and whether it
    survives again above (an island of survival). Both depend on the stripe spacing.

    Attributes
    ----------
    first_stripe : numpy.ndarray of int
        Index of the first stripe that overturns the block; −1 where none does.
    islands : numpy.ndarray of bool
        The block survives at some stripe above its first overturning one.
    """

    first_stripe: np.ndarray
    islands: np.ndarray


def overturning_pattern(overturned) -> OverturningPattern:
    """The pattern of each row of ``overturned`` (records × ascending stripes, bool)."""
    overturned = np.asarray(overturned, dtype=bool)
    any_over = overturned.any(axis=1)
    first = np.where(any_over, np.argmax(overturned, axis=1), -1)
    after = np.arange(overturned.shape[1])[None, :] > first[:, None]
    islands = any_over & np.any(after & ~overturned, axis=1)
    return OverturningPattern(first, islands)


def stripe_outcomes(motion, factors, size_s, alpha_rad, g: float, free_motion_s: float,
                    jobs: int = 1, r=None) -> tuple[np.ndarray, np.ndarray]:
    """Exact overturning and peak rotation of blocks under ``motion`` scaled by each factor.

    Parameters
    ----------
    motion : records.GroundMotion
    factors : array
        Scale factors of the stripes [-], ascending.
    size_s : array
        Block sizes 2π/p [s].
    alpha_rad : array
        Slendernesses [rad].
    g, free_motion_s, jobs :
        Gravity [m/s²], free motion after the record [s], solver threads.
    r : float or audit.physics.block.Restitution, optional
        The impact model; Eq. 4.8 when not given.

    Returns
    -------
    overturned, theta_peak_rad : numpy.ndarray
        Shaped (stripe, α, size).
    """
    spectra = [rocking_spectrum(motion.scaled(float(f)), size_s, alpha_rad, r=r, g=g,
                                free_motion_s=free_motion_s, jobs=jobs, reactions=False)
               for f in factors]
    return (np.stack([s.overturned for s in spectra]),
            np.stack([s.theta_peak for s in spectra]))


__all__ = ["stripe_levels", "fit_lognormal", "LognormalFit", "overturning_pattern",
           "OverturningPattern", "stripe_outcomes", "DEFAULT_STRIPES", "DEFAULT_SPAN"]
