"""The objects of one height as one fragility family: P(overturn | im, w) = Φ((ln im − ln m(w))/β)
with ln m(w) = a + c·ln w, c ≥ 0 (the median a power of the width, β shared), fitted by maximum
likelihood on every (width, stripe) the check solved for that height, with the same records.

P(w) at the site is then monotone in width by construction (a record-by-record count at each
width is not: the exact 10 % and 50 % widths sit on its jumps), and a target width is read in
closed form, ln w = (ln im_site − a − β Φ⁻¹(t))/c. Each has a band from a bootstrap over
records (whole records resampled, with their outcomes at every width and stripe).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import log_ndtr
from scipy.stats import norm

#: Resamples of the bootstrap over records, and its band.
RESAMPLES = 200
CONFIDENCE = 0.90
SEED = 20260


@dataclass(frozen=True)
class WidthFamily:
    """ln m(w) = intercept + slope·ln w [ln of the IM's unit, w in m], common β."""

    intercept: float
    slope: float
    beta: float

    def probability(self, im, width_m):
        """P(overturn) at intensity ``im`` of the member ``width_m`` wide.

        Parameters
        ----------
        im : float or array_like of float
            Intensity [g].
        width_m : float or array_like of float
            Full base width [m].
        """
        median = self.intercept + self.slope * np.log(width_m)
        return norm.cdf((np.log(im) - median) / self.beta)

    def width_for(self, target: float, im: float) -> float:
        """The width whose P(overturn) at ``im`` is ``target`` [m].

        Parameters
        ----------
        target : float
            P(overturn) [-].
        im : float
            Intensity [g].
        """
        return math.exp((math.log(im) - self.intercept - self.beta * norm.ppf(target))
                        / self.slope)


def fit_width_family(widths_m, levels, overturned, start=None) -> WidthFamily:
    """Maximum-likelihood :class:`WidthFamily` of outcomes shaped (record, stripe, width).

    Parameters
    ----------
    widths_m : array
        The widths solved [m].
    levels : array
        The stripes [unit of the IM].
    overturned : numpy.ndarray of bool
        Exact outcomes, (record, stripe, width).
    start : sequence of three float, optional
        Starting point (intercept, ln slope, ln β) of the minimisation; the mean ln stripe less
        the mean ln width, 0 and ln 0.4 when not given.
    """
    widths = np.log(np.asarray(widths_m, dtype=float))
    ln_levels = np.log(np.asarray(levels, dtype=float))
    counts = overturned.sum(axis=0)  # (stripe, width)
    records = overturned.shape[0]

    def negative_log_likelihood(x):
        intercept, log_slope, log_beta = x
        z = (ln_levels[:, None] - intercept - math.exp(log_slope) * widths[None, :]) \
            / math.exp(log_beta)
        return -float(np.sum(counts * log_ndtr(z) + (records - counts) * log_ndtr(-z)))

    if start is None:
        start = (float(np.mean(ln_levels) - np.mean(widths)), 0.0, math.log(0.4))
    best = minimize(negative_log_likelihood, start, method="Nelder-Mead",
                    options={"xatol": 1e-7, "fatol": 1e-9, "maxiter": 4000})
    intercept, log_slope, log_beta = best.x
    return WidthFamily(float(intercept), math.exp(log_slope), math.exp(log_beta))


@dataclass(frozen=True)
class WidthAnswer:
    """The family's width curve at the site and its target widths with bootstrap bands."""

    family: WidthFamily
    curve: list
    widths: dict
    bands: dict


def width_answer(widths_m, levels, overturned, site_im: float, targets, height_m: float,
                 resamples: int = RESAMPLES, seed: int = SEED) -> WidthAnswer:
    """The family fitted on ``overturned`` (record, stripe, width); its P at the site on 40
    widths from 3 % to 95 % of the height; the width of each target with its band (the
    central ``CONFIDENCE`` of the widths the resampled families give).

    Parameters
    ----------
    widths_m : array_like of float
        Full base width of each block solved [m].
    levels : array_like of float
        The stripes [g].
    overturned : numpy.ndarray of bool
        Outcomes shaped (record, stripe, width).
    site_im : float
        The site's intensity [g].
    targets : sequence of float
        Target P(overturn) at the site [-].
    height_m : float
        The object's full height [m].
    resamples : int
        Bootstrap resamples over records.
    seed : int
        Seed of the resampling.
    """
    family = fit_width_family(widths_m, levels, overturned)
    grid = height_m * np.geomspace(0.03, 0.95, 40)
    curve = [[float(w), float(p)] for w, p in zip(grid, family.probability(site_im, grid))]
    rng = np.random.default_rng(seed)
    start = (family.intercept, math.log(family.slope), math.log(family.beta))
    resampled = []
    for _ in range(resamples):
        rows = rng.integers(0, overturned.shape[0], overturned.shape[0])
        fit = fit_width_family(widths_m, levels, overturned[rows], start)
        resampled.append([fit.width_for(t, site_im) for t in targets])
    resampled = np.array(resampled)
    tail = 100 * (1 - CONFIDENCE) / 2
    widths, bands = {}, {}
    for k, target in enumerate(targets):
        widths[target] = family.width_for(target, site_im)
        bands[target] = [float(np.percentile(resampled[:, k], tail)),
                         float(np.percentile(resampled[:, k], 100 - tail))]
    return WidthAnswer(family, curve, widths, bands)


def quoted(width_m: float, band) -> str:
    """A width to the precision its band supports: rounded to the power of ten below the band's
    half-width (at least 1 mm), with the band, e.g. ``0.56 m [0.51–0.63]``.

    Parameters
    ----------
    width_m : float
        The width [m].
    band : sequence of two float
        Its band (low, high) [m].
    """
    half = max((band[1] - band[0]) / 2.0, 1e-3)
    decimals = max(0, -math.floor(math.log10(half)))
    return f"{width_m:.{decimals}f} m [{band[0]:.{decimals}f}–{band[1]:.{decimals}f}]"


__all__ = ["WidthFamily", "fit_width_family", "width_answer", "WidthAnswer", "quoted",
           "RESAMPLES", "CONFIDENCE"]
