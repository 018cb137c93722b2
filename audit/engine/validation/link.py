"""The link between the exact solver's outcomes and a real specimen's: a lognormal equivalent
slenderness (docs/validation.md).

A real rock is not one rigid block: its seating, the contact patch it rocks on and its 3-D
wobble change from test to test. The model gives each test its own equivalent slenderness,
lognormal with median α̂ and dispersion σ, and fixed p and restitution factor f:

    P(overturn | test i) = ε + (1 − 2ε) · E[O_i(α)],   ln α ~ N(ln α̂, σ²)

where O_i(α) is the exact solver's outcome (1 overturned) of block (α, p, f) under the test's
table motion, and ε the lapse. O_i is solved on the α nodes of a grid and read linearly in ln α
between them (outside the nodes: the end node's outcome), which makes the expectation a
weighted sum of the node outcomes with closed-form weights (:func:`slenderness_weights`), exact
for that piecewise-linear O_i and smooth in (α̂, σ). Overturning is not monotonic in α, and the
sum keeps every band of slendernesses that overturns.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ndtr


def slenderness_weights(log_alpha_nodes, log_median, sigma) -> np.ndarray:
    """Weights w_k with E[O(α)] = Σ_k w_k O(α_k) for O linear in ln α between the nodes.

    Parameters
    ----------
    log_alpha_nodes : array
        ln α_k of the nodes, increasing.
    log_median, sigma : float or array of float
        ln α̂ and the dispersion σ of ln α (arrays of one shape: one weight column each).

    Returns
    -------
    numpy.ndarray
        One weight per node (a column per (ln α̂, σ) given as arrays); they sum to 1.

    Notes
    -----
    On a segment [u_k, u_{k+1}] with z = (u − μ)/σ, ∫ φ = Φ(z_{k+1}) − Φ(z_k) = I0 and
    ∫ u φ = μ I0 − σ (φ(z_{k+1}) − φ(z_k)) = I1; node k's hat function (u_{k+1} − u)/Δ takes
    (u_{k+1} I0 − I1)/Δ, node k+1's (u − u_k)/Δ takes (I1 − u_k I0)/Δ. The tails below the
    first and above the last node go to those nodes.
    """
    scalar = np.ndim(log_median) == 0 and np.ndim(sigma) == 0
    mu = np.atleast_1d(np.asarray(log_median, dtype=float))[None, :]
    sigma = np.atleast_1d(np.asarray(sigma, dtype=float))[None, :]
    u = np.asarray(log_alpha_nodes, dtype=float)[:, None]
    z = (u - mu) / sigma
    cdf = ndtr(z)
    pdf = np.exp(-0.5 * z * z) / math.sqrt(2.0 * math.pi)
    i0 = np.diff(cdf, axis=0)
    i1 = mu * i0 - sigma * np.diff(pdf, axis=0)
    width = np.diff(u, axis=0)
    w = np.zeros(z.shape)
    w[:-1] += (u[1:] * i0 - i1) / width
    w[1:] += (i1 - u[:-1] * i0) / width
    w[0] += cdf[0]
    w[-1] += 1.0 - cdf[-1]
    return w[:, 0] if scalar else w


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



__all__ = ["slenderness_weights", "overturning_probability"]
