"""Maximum-likelihood fit of a specimen's equivalent rigid block to observed outcomes.

The link (:mod:`~audit.engine.validation.link`): each test's equivalent slenderness is
lognormal with median α̂ and dispersion σ; p and the restitution factor f are fixed per
specimen. The log-likelihood is computed over a lattice of all four parameters
(:mod:`~audit.engine.validation.profile`); the best lattice point is refined continuously in
(α̂, σ) by L-BFGS-B, and every interval is a profile-likelihood interval read from the lattice
(maximised over the other parameters). Resolution: α̂ to half the α node spacing, p and f to
their grid spacing, which :mod:`~audit.engine.validation.refine` makes fine around the region
the outcomes allow.

A probit on a peak-rotation margin θ/α was not used: the margin saturates at 1 on overturning,
so it cannot rank the motions that overturn the block.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from audit.engine.validation.link import overturning_probability
from audit.engine.validation.profile import (Interval, Lattice, Prediction, lattice,
                                             predictive, profile_interval, ridge)

#: Bounds of the fitted dispersion σ of ln α [-].
SIGMA_BOUNDS = (0.01, 2.0)


def _log_likelihood(outcomes, probability) -> float:
    return float(np.sum(np.where(outcomes > 0.5, np.log(probability), np.log1p(-probability))))


@dataclass(frozen=True)
class BlockFit:
    """A specimen's fitted equivalent block.

    Attributes
    ----------
    alpha_deg : float
        Median equivalent slenderness α̂ [degrees].
    alpha : Interval
        Its 95 % profile-likelihood interval [degrees]; ``identified`` False where it reaches an
        end of the searched α (the outcomes pin down only the ridge α(p)).
    sigma : float
        Dispersion of ln α from test to test [-].
    sigma_95 : Interval
    p_rad_s : float
        Frequency parameter [rad/s] (a grid value).
    p : Interval
        95 % profile set of p (grid values) [rad/s].
    restitution_factor : float
        Multiple of Eq. 4.8's r (a grid value) [-].
    restitution : Interval
    log_likelihood : float
    n_tests : int
        Outcomes fitted.
    blocks : BlockGrid
        The grid the fit read.
    lapse : float
        The lapse ε [-].
    surface : Lattice
        The log-likelihood over every parameter.
    ridge : dict
        At each p of the grid, the best α̂ and the 95 % region's α̂ range
        (:func:`~audit.engine.validation.profile.ridge`).
    """

    alpha_deg: float
    alpha: Interval
    sigma: float
    sigma_95: Interval
    p_rad_s: float
    p: Interval
    restitution_factor: float
    restitution: Interval
    log_likelihood: float
    n_tests: int
    blocks: object
    lapse: float
    surface: Lattice
    ridge: dict

    @property
    def identified(self) -> bool:
        """Whether the outcomes bound both α̂ and p inside the searched range."""
        return self.alpha.identified and self.p.identified

    def predict(self, overturned: np.ndarray) -> Prediction:
        """P(overturn) of each test averaged over the parameters, weighted by the likelihood,
        with its 95 % band (:func:`~audit.engine.validation.profile.predictive`).

        Parameters
        ----------
        overturned : numpy.ndarray of bool
            Exact outcomes on the fit's grid, shaped (test, restitution factor, p, α).
        """
        return predictive(self.surface, overturned, self.lapse)


def _refine(nodes, outcomes, log_nodes, lapse, start):
    """(ln α̂, ln σ) and log-likelihood at one (f, p), by L-BFGS-B from a lattice point."""
    def negative(x):
        return -_log_likelihood(outcomes, overturning_probability(
            nodes, log_nodes, x[0], math.exp(x[1]), lapse))
    bounds = [(log_nodes[0], log_nodes[-1]), tuple(np.log(SIGMA_BOUNDS))]
    best = minimize(negative, start, method="L-BFGS-B", bounds=bounds)
    if best.fun > negative(np.asarray(start)):  # never worse than the lattice point
        return np.asarray(start), -negative(np.asarray(start))
    return best.x, -float(best.fun)


def fit_block(overturned: np.ndarray, outcomes: np.ndarray, blocks, lapse: float) -> BlockFit:
    """Maximum-likelihood equivalent block of one specimen, with profile-likelihood intervals.

    Parameters
    ----------
    overturned : numpy.ndarray of bool
        Exact outcomes of the grid for the tests fitted, shaped (test, f, p, α node).
    outcomes : numpy.ndarray
        Observed outcomes of the same tests (1 overturned, 0 stood).
    blocks : BlockGrid
        The grid solved.
    lapse : float
        The lapse ε [-].
    """
    surface = lattice(overturned, outcomes, blocks, lapse)
    values = surface.log_likelihood
    j, k, m, s = np.unravel_index(int(np.argmax(values)), values.shape)
    x, best = _refine(overturned[:, j, k, :].astype(float), outcomes, surface.log_nodes(j, k),
                      lapse, (surface.log_medians[m], math.log(surface.sigma[s])))
    alpha_line = np.degrees(np.exp(surface.log_medians))
    return BlockFit(
        alpha_deg=math.degrees(math.exp(x[0])),
        alpha=profile_interval(alpha_line, values.max(axis=(0, 1, 3)), best,
                               blocks.search_alpha_deg),
        sigma=math.exp(x[1]),
        sigma_95=profile_interval(surface.sigma, values.max(axis=(0, 1, 2)), best),
        p_rad_s=float(blocks.p_rad_s[k]),
        p=profile_interval(blocks.p_rad_s, values.max(axis=(0, 2, 3)), best,
                           blocks.search_p_rad_s),
        restitution_factor=float(blocks.restitution_factors[j]),
        restitution=profile_interval(blocks.restitution_factors, values.max(axis=(1, 2, 3)),
                                     best),
        log_likelihood=best, n_tests=int(np.asarray(outcomes).size), blocks=blocks,
        lapse=lapse, surface=surface, ridge=ridge(surface, best))


__all__ = ["BlockFit", "fit_block", "SIGMA_BOUNDS"]
