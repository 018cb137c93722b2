"""Maximum-likelihood fit of a specimen's equivalent rigid block to observed outcomes.

The link. A real rock is not one rigid block: its seating, the contact patch it rocks on and
its 3-D wobble change from test to test. The model therefore gives each test its own equivalent
slenderness, lognormal with median α̂ and dispersion σ, and fixed p and restitution factor f:

    P(overturn | test i) = ε + (1 − 2ε) · E[O_i(α)],   ln α ~ N(ln α̂, σ²)

where O_i(α) is the exact solver's outcome (1 overturned) of block (α, p, f) under the test's
table motion, and ε the lapse of :class:`~audit.engine.validation.grid.ValidationSettings`. O_i
is solved on the α nodes of the grid and read linearly in ln α between them (outside the nodes:
the end node's outcome), which makes the expectation a weighted sum of the node outcomes with
closed-form weights (:func:`slenderness_weights`), exact for that piecewise-linear O_i and
smooth in (α̂, σ). Overturning is not monotonic in α, and the sum keeps every band of
slendernesses that overturns. A probit on a peak-rotation margin θ/α was not used: the margin
saturates at 1 on overturning, so it cannot rank the motions that overturn the block.

(α̂, σ) are fitted by maximum likelihood at every (p, f) of the grid, and (p, f) chosen by the
profile likelihood; its 95 % interval is the set of grid values within χ²₁(0.95)/2 = 1.92 of
the best log-likelihood, and the standard errors of ln α̂ and ln σ come from the observed
information (numerical Hessian) at the optimum; their intervals stop at the bounds of the search
(an interval that reaches one says the outcomes do not pin that parameter down).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import ndtr

#: Half the χ²(1) 95 % quantile: a profile log-likelihood this far below the best is excluded.
PROFILE_DROP_95 = 1.92
#: Bounds of the fitted dispersion σ of ln α [-].
SIGMA_BOUNDS = (0.01, 2.0)


def slenderness_weights(log_alpha_nodes, log_median: float, sigma: float) -> np.ndarray:
    """Weights w_k with E[O(α)] = Σ_k w_k O(α_k) for O linear in ln α between the nodes.

    Parameters
    ----------
    log_alpha_nodes : array
        ln α_k of the nodes, increasing.
    log_median, sigma : float
        ln α̂ and the dispersion σ of ln α.

    Returns
    -------
    numpy.ndarray
        One weight per node; they sum to 1.

    Notes
    -----
    On a segment [u_k, u_{k+1}] with z = (u − μ)/σ, ∫ φ = Φ(z_{k+1}) − Φ(z_k) = I0 and
    ∫ u φ = μ I0 − σ (φ(z_{k+1}) − φ(z_k)) = I1; node k's hat function (u_{k+1} − u)/Δ takes
    (u_{k+1} I0 − I1)/Δ, node k+1's (u − u_k)/Δ takes (I1 − u_k I0)/Δ. The tails below the
    first and above the last node go to those nodes.
    """
    u = np.asarray(log_alpha_nodes, dtype=float)
    z = (u - log_median) / sigma
    cdf = ndtr(z)
    pdf = np.exp(-0.5 * z * z) / math.sqrt(2.0 * math.pi)
    i0 = np.diff(cdf)
    i1 = log_median * i0 - sigma * np.diff(pdf)
    width = np.diff(u)
    w = np.zeros(u.size)
    w[:-1] += (u[1:] * i0 - i1) / width
    w[1:] += (i1 - u[:-1] * i0) / width
    w[0] += cdf[0]
    w[-1] += 1.0 - cdf[-1]
    return w


def overturning_probability(node_outcomes, log_alpha_nodes, log_median, sigma, lapse):
    """P(overturn) per test from its node outcomes (test × α node), with the lapse.

    Parameters
    ----------
    node_outcomes : numpy.ndarray
        Exact outcomes (0 or 1) of each test at each α node, shaped (test, node).
    log_alpha_nodes : array_like of float
        ln α_k of the nodes (α [rad]), increasing.
    log_median : float
        ln α̂ (α [rad]).
    sigma : float
        Dispersion σ of ln α [-].
    lapse : float
        The lapse ε [-].
    """
    weights = slenderness_weights(log_alpha_nodes, log_median, sigma)
    return lapse + (1.0 - 2.0 * lapse) * np.clip(node_outcomes @ weights, 0.0, 1.0)


def _log_likelihood(outcomes, probability) -> float:
    return float(np.sum(np.where(outcomes > 0.5, np.log(probability), np.log1p(-probability))))


@dataclass(frozen=True)
class BlockFit:
    """A specimen's fitted equivalent block.

    Attributes
    ----------
    alpha_deg : float
        Median equivalent slenderness α̂ [degrees].
    alpha_deg_95 : tuple
        Its 95 % interval (from the standard error of ln α̂) [degrees].
    sigma : float
        Dispersion of ln α from test to test [-].
    sigma_95 : tuple
    p_rad_s : float
        Frequency parameter [rad/s] (a grid value).
    p_rad_s_95 : tuple
        Smallest and largest grid p of the 95 % profile-likelihood set [rad/s].
    restitution_factor : float
        Multiple of Eq. 4.8's r (a grid value) [-].
    restitution_factor_95 : tuple
    log_likelihood : float
    n_tests : int
        Outcomes fitted.
    profile : numpy.ndarray
        Best log-likelihood at each (f, p) of the grid.
    """

    alpha_deg: float
    alpha_deg_95: tuple
    sigma: float
    sigma_95: tuple
    p_rad_s: float
    p_rad_s_95: tuple
    restitution_factor: float
    restitution_factor_95: tuple
    log_likelihood: float
    n_tests: int
    profile: np.ndarray

    def probability(self, overturned: np.ndarray, settings) -> np.ndarray:
        """P(overturn) of each test from a grid's exact outcomes (test, f, p, α).

        Parameters
        ----------
        overturned : numpy.ndarray of bool
            The grid's exact outcomes, shaped (test, restitution factor, p, α).
        settings : ValidationSettings
            The grid (``restitution_factors``, ``p_rad_s`` [rad/s], ``alpha_deg`` [degrees])
            and the lapse.
        """
        j = list(settings.restitution_factors).index(self.restitution_factor)
        k = list(settings.p_rad_s).index(self.p_rad_s)
        return overturning_probability(overturned[:, j, k, :].astype(float),
                                       np.log(np.radians(settings.alpha_deg)),
                                       math.log(math.radians(self.alpha_deg)), self.sigma,
                                       settings.lapse)


def _fit_slice(nodes, outcomes, log_nodes, lapse):
    """Best (ln α̂, ln σ) and log-likelihood for one (f, p): a coarse scan, then L-BFGS-B."""
    def negative(x):
        return -_log_likelihood(outcomes, overturning_probability(
            nodes, log_nodes, x[0], math.exp(x[1]), lapse))
    starts = [(mu, math.log(s)) for mu in log_nodes for s in (0.1, 0.4)]
    start = min(starts, key=negative)
    bounds = [(log_nodes[0], log_nodes[-1]), tuple(np.log(SIGMA_BOUNDS))]
    best = minimize(negative, start, method="L-BFGS-B", bounds=bounds)
    return best.x, -float(best.fun), negative


def _hessian(function, x, step=1e-3):
    n = len(x)
    h = np.zeros((n, n))
    for a in range(n):
        for b in range(n):
            ea, eb = np.eye(n)[a] * step, np.eye(n)[b] * step
            h[a, b] = (function(x + ea + eb) - function(x + ea - eb) - function(x - ea + eb)
                       + function(x - ea - eb)) / (4 * step * step)
    return h


def fit_block(overturned: np.ndarray, outcomes: np.ndarray, settings) -> BlockFit:
    """Maximum-likelihood equivalent block of one specimen.

    Parameters
    ----------
    overturned : numpy.ndarray of bool
        Exact outcomes of the grid for the tests fitted, shaped (test, f, p, α).
    outcomes : numpy.ndarray
        Observed outcomes of the same tests (1 overturned, 0 stood).
    settings : ValidationSettings
    """
    log_nodes = np.log(np.radians(np.asarray(settings.alpha_deg, dtype=float)))
    factors, ps = settings.restitution_factors, settings.p_rad_s
    profile = np.empty((len(factors), len(ps)))
    best = None
    for j in range(len(factors)):
        for k in range(len(ps)):
            x, value, negative = _fit_slice(overturned[:, j, k, :].astype(float), outcomes,
                                            log_nodes, settings.lapse)
            profile[j, k] = value
            if best is None or value > best[0]:
                best = (value, j, k, x, negative)
    value, j, k, x, negative = best
    covariance = np.linalg.pinv(_hessian(negative, x))
    se = np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    inside = profile >= value - PROFILE_DROP_95
    kept_f = [factors[i] for i in np.flatnonzero(inside.any(axis=1))]
    kept_p = [ps[i] for i in np.flatnonzero(inside.any(axis=0))]
    # an interval reaching a bound of the search (grid ends, SIGMA_BOUNDS) is not pinned down
    bounds = ((log_nodes[0], log_nodes[-1]), np.log(SIGMA_BOUNDS))
    low, high = (np.clip(x + side * 1.96 * se, *np.transpose(bounds)) for side in (-1, 1))
    return BlockFit(
        alpha_deg=math.degrees(math.exp(x[0])),
        alpha_deg_95=(math.degrees(math.exp(low[0])), math.degrees(math.exp(high[0]))),
        sigma=math.exp(x[1]), sigma_95=(math.exp(low[1]), math.exp(high[1])),
        p_rad_s=ps[k], p_rad_s_95=(min(kept_p), max(kept_p)),
        restitution_factor=factors[j], restitution_factor_95=(min(kept_f), max(kept_f)),
        log_likelihood=value, n_tests=int(outcomes.size), profile=profile)


__all__ = ["BlockFit", "fit_block", "slenderness_weights", "overturning_probability",
           "PROFILE_DROP_95"]
