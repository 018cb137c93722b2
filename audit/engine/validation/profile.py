"""The likelihood of a specimen's outcomes over a lattice of every parameter, and what is read
from it: profile-likelihood intervals, the α–p ridge, and predictions averaged over the
parameters the outcomes allow.

The lattice holds the log-likelihood at every (restitution factor f, frequency parameter p) of
the solved grid × a line of medians α̂ (log-spaced at half the α nodes' step, each (f, p)
searched within its own α nodes) × a set of dispersions σ. A parameter's profile is the
lattice maximised over the others (not a slice at their best values: p and α trade off, and a
slice hides the trade-off); its 95 % set is where the profile is within χ²₁(0.95)/2 = 1.92 of
the best log-likelihood, widened by one lattice step. A set that reaches an end of the search
range says the outcomes do not identify the parameter there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit.engine.validation.link import slenderness_weights

#: Half the χ²(1) 95 % quantile: a profile log-likelihood this far below the best is excluded.
PROFILE_DROP_95 = 1.92
#: Dispersions σ of ln α on the lattice [-] (ratio 1.42; the point estimate is refined
#: continuously between them).
SIGMA_NODES = tuple(np.geomspace(0.01, 2.0, 16))
#: Lattice points further below the best than this carry no weight in the predictions
#: (e^−12 ≈ 6e−6 of the best point's).
_WEIGHT_DROP = 12.0
#: Bins of P(overturn) in which the predictive band is read.
_BINS = 400
#: The most medians α̂ searched.
_MEDIANS = 600


@dataclass(frozen=True)
class Lattice:
    """Log-likelihood over (f, p, median α̂, σ).

    Attributes
    ----------
    log_likelihood : numpy.ndarray
        Shaped (f, p, median, σ); −inf where a median lies outside that (f, p)'s α nodes.
    blocks : BlockGrid
        The grid solved (each (f, p) its α nodes).
    log_medians : numpy.ndarray
        ln α̂ of the median line (α̂ [rad]), common to every (f, p).
    sigma : numpy.ndarray
        σ of ln α [-].
    """

    log_likelihood: np.ndarray
    blocks: object
    log_medians: np.ndarray
    sigma: np.ndarray

    def log_nodes(self, j: int, k: int) -> np.ndarray:
        """ln α [rad] of the α nodes of (f_j, p_k).

        Parameters
        ----------
        j, k : int
            Indices of the restitution factor and of p.
        """
        return np.log(np.radians(self.blocks.alpha_deg[j, k]))

    def columns(self, j: int, k: int, keep=None):
        """Node weights of (f_j, p_k) for some (median, σ) columns, shaped (node, column).

        Parameters
        ----------
        j, k : int
            Indices of the restitution factor and of p.
        keep : array of int, optional
            Flat indices into (median, σ) of the columns; all by default.
        """
        medians, sigma = np.meshgrid(self.log_medians, self.sigma, indexing="ij")
        medians, sigma = medians.ravel(), sigma.ravel()
        if keep is not None:
            medians, sigma = medians[keep], sigma[keep]
        return slenderness_weights(self.log_nodes(j, k), medians, sigma)


def median_line(blocks) -> np.ndarray:
    """ln α̂ [rad] of the medians searched: log-spaced over every node, at half the median
    node step of the grid (the α nodes and the midpoints between them on a shared grid).

    Parameters
    ----------
    blocks : BlockGrid
        The grid solved (α nodes [degrees] of each (f, p)).
    """
    u = np.log(np.radians(blocks.alpha_deg))
    step = 0.5 * float(np.median(np.diff(u, axis=-1)))
    count = min(int(math.ceil((u.max() - u.min()) / step)) + 1, _MEDIANS)
    return np.linspace(u.min(), u.max(), count)


def lattice(overturned, outcomes, blocks, lapse: float) -> Lattice:
    """Log-likelihood of ``outcomes`` at every lattice point.

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
    medians, sigma = median_line(blocks), np.asarray(SIGMA_NODES)
    y = np.asarray(outcomes, dtype=float)
    n_f, n_p = overturned.shape[1:3]
    out = np.full((n_f, n_p, medians.size, sigma.size), -np.inf)
    surface = Lattice(out, blocks, medians, sigma)
    tolerance = 1e-9
    for j in range(n_f):
        for k in range(n_p):
            u = surface.log_nodes(j, k)
            inside = np.flatnonzero((medians >= u[0] - tolerance) & (medians <= u[-1] + tolerance))
            keep = (inside[:, None] * sigma.size + np.arange(sigma.size)).ravel()
            p = lapse + (1 - 2 * lapse) * np.clip(
                overturned[:, j, k, :].astype(float) @ surface.columns(j, k, keep), 0, 1)
            out[j, k, inside] = (y @ np.log(p) + (1 - y) @ np.log1p(-p)).reshape(inside.size,
                                                                               sigma.size)
    return surface


@dataclass(frozen=True)
class Interval:
    """A parameter's 95 % profile-likelihood set, as its hull.

    Attributes
    ----------
    low, high : float
        Ends of the set, in the parameter's unit.
    identified : bool
        False where the set reaches an end of the search range: the outcomes do not bound the
        parameter on that side within it.
    """

    low: float
    high: float
    identified: bool


def profile_interval(values, profile, best: float, search=None) -> Interval:
    """The 95 % set of a parameter from its profile log-likelihood on ``values`` (increasing),
    as its hull widened to the lattice values next to it: a true value between two lattice
    points is represented by neither (the outcomes between α nodes are interpolated, and p and
    f are solved only on theirs), so it costs likelihood at both; the lattice's step is the
    set's resolution.

    Parameters
    ----------
    values : array_like of float
        The parameter's lattice values, increasing.
    profile : array_like of float
        The log-likelihood maximised over the other parameters at each value.
    best : float
        The best log-likelihood (≥ every profile value).
    search : tuple of float, optional
        The range searched, if wider than ``values``' (a fine grid's): the set identifies the
        parameter unless it reaches an end of ``values`` that is an end of this range.
    """
    inside = np.flatnonzero(np.asarray(profile) >= best - PROFILE_DROP_95)
    if inside.size == 0:  # only the continuous refinement reached the best: its lattice point
        inside = np.array([int(np.argmax(profile))])
    values = np.asarray(values, dtype=float)
    first, last = inside[0], inside[-1]
    low, high = (values[0], values[-1]) if search is None else search
    at_end = (first == 0 and values[0] <= low * (1 + 1e-6)) or \
        (last == values.size - 1 and values[-1] >= high * (1 - 1e-6))
    return Interval(float(values[max(first - 1, 0)]),
                    float(values[min(last + 1, values.size - 1)]), not at_end)


def ridge(surface: Lattice, best: float) -> dict:
    """The α–p trade-off: at each p, the best median α̂ and the 95 % region's α̂ range.

    Parameters
    ----------
    surface : Lattice
    best : float
        The best log-likelihood.

    Returns
    -------
    dict
        ``p_rad_s``, ``alpha_deg`` (best α̂ at each p [degrees]), ``alpha_deg_low``,
        ``alpha_deg_high`` (NaN where the region does not reach that p), ``log_likelihood``
        (the profile in p), ``inside_95`` (bool).
    """
    by_p_median = surface.log_likelihood.max(axis=(0, 3))  # (p, median)
    alpha = np.degrees(np.exp(surface.log_medians))
    inside = by_p_median >= best - PROFILE_DROP_95
    low = np.array([alpha[row].min() if row.any() else math.nan for row in inside])
    high = np.array([alpha[row].max() if row.any() else math.nan for row in inside])
    return {"p_rad_s": np.asarray(surface.blocks.p_rad_s, dtype=float),
            "alpha_deg": alpha[np.argmax(by_p_median, axis=1)], "alpha_deg_low": low,
            "alpha_deg_high": high, "log_likelihood": by_p_median.max(axis=1),
            "inside_95": inside.any(axis=1)}


@dataclass(frozen=True)
class Prediction:
    """P(overturn) of tests, averaged over the parameters the outcomes allow.

    Attributes
    ----------
    p_overturn : numpy.ndarray
        The likelihood-weighted mean of P over the lattice [-].
    low, high : numpy.ndarray
        The 2.5 % and 97.5 % quantiles of P under the same weights [-] (resolution 1/400).
    """

    p_overturn: np.ndarray
    low: np.ndarray
    high: np.ndarray


def predictive(surface: Lattice, overturned, lapse: float) -> Prediction:
    """Each test's P(overturn), weighted over the lattice by the likelihood (a flat prior on the
    lattice: uniform in ln α̂, ln σ, ln p and f), with its 95 % band.

    Parameters
    ----------
    surface : Lattice
        The fit's lattice.
    overturned : numpy.ndarray of bool
        Exact outcomes of the tests predicted, on the grid the lattice was computed on, shaped
        (test, f, p, α node).
    lapse : float
        The lapse ε [-].
    """
    values = surface.log_likelihood
    n = overturned.shape[0]
    mean = np.zeros(n)
    histogram = np.zeros(n * _BINS)
    total = 0.0
    top = values.max()
    for j, k in zip(*np.nonzero((values >= top - _WEIGHT_DROP).any(axis=(2, 3)))):
        flat = values[j, k].ravel()
        keep = np.flatnonzero(flat >= top - _WEIGHT_DROP)
        w = np.exp(flat[keep] - top)
        p = lapse + (1 - 2 * lapse) * np.clip(
            overturned[:, j, k, :].astype(float) @ surface.columns(j, k, keep), 0, 1)
        mean += p @ w
        total += w.sum()
        bins = np.minimum((p * _BINS).astype(int), _BINS - 1) + _BINS * np.arange(n)[:, None]
        histogram += np.bincount(bins.ravel(), np.broadcast_to(w, p.shape).ravel(),
                                 minlength=n * _BINS)
    cumulative = np.cumsum(histogram.reshape(n, _BINS), axis=1) / total
    low = (np.argmax(cumulative >= 0.025, axis=1)) / _BINS
    high = (np.argmax(cumulative >= 0.975, axis=1) + 1) / _BINS
    return Prediction(mean / total, np.maximum(low, lapse), np.minimum(high, 1 - lapse))


__all__ = ["Lattice", "Interval", "Prediction", "lattice", "profile_interval", "ridge",
           "predictive", "median_line", "PROFILE_DROP_95", "SIGMA_NODES"]
