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
from scipy.special import log_ndtr, ndtr, ndtri

#: Resamples of the bootstrap over records, and its band.
RESAMPLES = 200
CONFIDENCE = 0.90
SEED = 20260
#: Newton's method of :func:`fit_width_families`: most iterations, and the relative size of
#: the last step at which a fit has settled (far below the widths' printed precision).
NEWTON_ITERATIONS = 100
NEWTON_TOLERANCE = 1e-10
#: Relative size of the log-likelihood's rounding (a sum of a few hundred terms).
ROUNDING = 1e-13


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
        return ndtr((np.log(im) - median) / self.beta)

    def width_for(self, target: float, im: float) -> float:
        """The width whose P(overturn) at ``im`` is ``target`` [m].

        Parameters
        ----------
        target : float
            P(overturn) [-].
        im : float
            Intensity [g].
        """
        return math.exp((math.log(im) - self.intercept - self.beta * ndtri(target))
                        / self.slope)


def fit_width_family(widths_m, levels, overturned, start=None) -> WidthFamily:
    """Maximum-likelihood :class:`WidthFamily` of outcomes shaped (record, stripe, width), by
    Nelder–Mead on (a, ln c, ln β): the slow path, for a family whose likelihood has no
    interior maximum (outcomes separated by a line in (ln im, ln w)), and the referee of
    :func:`fit_width_families` in the tests.

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
    ln_w = np.log(np.asarray(widths_m, dtype=float))
    ln_im = np.log(np.asarray(levels, dtype=float))
    if start is None:
        start = (float(np.mean(ln_im) - np.mean(ln_w)), 0.0, math.log(0.4))
    return _nelder_mead(ln_w, ln_im, overturned.sum(axis=0), overturned.shape[0], start)


def _nelder_mead(ln_w, ln_im, counts, records: int, start) -> WidthFamily:
    """:func:`fit_width_family` of counts (stripe, width) out of ``records`` (the likelihood
    reads only the counts), from ``start`` = (a, ln c, ln β)."""
    def negative_log_likelihood(x):
        intercept, log_slope, log_beta = x
        z = (ln_im[:, None] - intercept - math.exp(log_slope) * ln_w[None, :]) \
            / math.exp(log_beta)
        return -float(np.sum(counts * log_ndtr(z) + (records - counts) * log_ndtr(-z)))

    best = minimize(negative_log_likelihood, start, method="Nelder-Mead",
                    options={"xatol": 1e-7, "fatol": 1e-9, "maxiter": 4000})
    intercept, log_slope, log_beta = best.x
    return WidthFamily(float(intercept), math.exp(log_slope), math.exp(log_beta))


def _probit_log_likelihood(eta, counts, records):
    return np.sum(counts * log_ndtr(eta) + (records - counts) * log_ndtr(-eta), axis=-1)


def _mills(x):
    """φ(x)/Φ(x), without overflow in either tail."""
    return np.exp(-0.5 * x * x - 0.5 * math.log(2.0 * math.pi) - log_ndtr(x))


def fit_width_families(widths_m, levels, counts, records: int, start=None):
    """:class:`WidthFamily` of many sets of counts at once, each by maximum likelihood.

    In θ = (−a/β, 1/β, −c/β) the family is a probit model, P = Φ(θ₀ + θ₁ ln im + θ₂ ln w),
    whose log-likelihood is concave: Newton's method with step halving climbs to its one
    maximum, every set of counts (a bootstrap's resamples) in the same array operations. A set
    whose maximum is not interior with β, c > 0 (Newton does not settle within
    :data:`NEWTON_ITERATIONS`, or lands outside) is refitted by :func:`fit_width_family`.

    Parameters
    ----------
    widths_m : array
        The widths solved [m], shaped (width,).
    levels : array
        The stripes [unit of the IM], shaped (stripe,).
    counts : numpy.ndarray
        Records overturned, shaped (set, stripe, width).
    records : int
        Records behind every count.
    start : WidthFamily, optional
        Where Newton starts (a fit of nearby counts); else a = mean ln im − mean ln w, c = 1,
        β = 0.4.

    Returns
    -------
    list of WidthFamily
        One per set.
    """
    ln_w = np.log(np.asarray(widths_m, dtype=float))
    ln_im = np.log(np.asarray(levels, dtype=float))
    counts = np.asarray(counts, dtype=float)
    sets = counts.shape[0]
    x = np.stack(np.broadcast_arrays(np.ones((ln_im.size, ln_w.size)), ln_im[:, None],
                                     ln_w[None, :]), axis=-1).reshape(-1, 3)  # (cell, 3)
    k = counts.reshape(sets, -1)
    if start is None:
        start = WidthFamily(float(np.mean(ln_im) - np.mean(ln_w)), 1.0, 0.4)
    theta = np.tile([-start.intercept / start.beta, 1.0 / start.beta,
                     -start.slope / start.beta], (sets, 1))
    log_likelihood = _probit_log_likelihood(theta @ x.T, k, records)
    settled = np.zeros(sets, dtype=bool)
    for _ in range(NEWTON_ITERATIONS):
        active = np.flatnonzero(~settled)
        if not active.size:
            break
        here, kk, before = theta[active], k[active], log_likelihood[active]
        eta = here @ x.T  # (set, cell)
        up, down = _mills(eta), _mills(-eta)
        gradient = np.einsum("sc,cj->sj", kk * up - (records - kk) * down, x)
        curvature = kk * up * (eta + up) + (records - kk) * down * (down - eta)
        hessian = np.einsum("sc,ci,cj->sij", curvature, x, x)
        # the pseudo-inverse: one width alone leaves ln w collinear with the constant
        step = np.einsum("sij,sj->si", np.linalg.pinv(hessian), gradient)
        # a step this small is the last: at the maximum the likelihood's rounding, not its
        # shape, decides whether it climbs; so is a small one whose climb, the Newton
        # decrement g·H⁻¹g / 2, is below that rounding (outcomes a line separates also climb
        # ever less, but by steps that do not shrink)
        relative = np.max(np.abs(step) / (1.0 + np.abs(here)), axis=1)
        decrement = 0.5 * np.einsum("sj,sj->s", gradient, step)
        last = (relative <= NEWTON_TOLERANCE) | (
            (relative <= 1e3 * NEWTON_TOLERANCE)
            & (decrement <= ROUNDING * np.maximum(1.0, np.abs(before))))
        value = before.copy()
        climbing = ~last
        for _ in range(40):  # halve each step that does not climb
            trial = here[climbing] + step[climbing]
            value[climbing] = _probit_log_likelihood(trial @ x.T, kk[climbing], records)
            worse = climbing & ~(value >= before)
            if not worse.any():
                break
            step[worse] *= 0.5
            climbing = worse
        moved = last | (value >= before)
        theta[active[moved]] = here[moved] + step[moved]
        log_likelihood[active[moved]] = value[moved]
        settled[active[last]] = True
    beta = 1.0 / theta[:, 1]
    slope = -theta[:, 2] * beta
    fits = []
    for j in range(sets):
        if settled[j] and np.isfinite(theta[j]).all() and beta[j] > 0 and slope[j] > 0:
            fits.append(WidthFamily(float(-theta[j, 0] * beta[j]), float(slope[j]),
                                    float(beta[j])))
        else:
            fits.append(_nelder_mead(ln_w, ln_im, counts[j], records,
                                     (start.intercept, math.log(start.slope),
                                      math.log(start.beta))))
    return fits


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
    records = overturned.shape[0]
    family, = fit_width_families(widths_m, levels, overturned.sum(axis=0)[None], records)
    grid = height_m * np.geomspace(0.03, 0.95, 40)
    curve = [[float(w), float(p)] for w, p in zip(grid, family.probability(site_im, grid))]
    rng = np.random.default_rng(seed)
    rows = [rng.integers(0, records, records) for _ in range(resamples)]
    counts = np.stack([overturned[r].sum(axis=0) for r in rows])
    fits = fit_width_families(widths_m, levels, counts, records, family)
    intercept, slope, beta = (np.array([getattr(f, name) for f in fits])[:, None]
                              for name in ("intercept", "slope", "beta"))
    # WidthFamily.width_for of every resample and target at once
    resampled = np.exp((math.log(site_im) - intercept - beta * ndtri(np.asarray(targets)))
                       / slope)
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


__all__ = ["WidthFamily", "fit_width_family", "fit_width_families", "width_answer", "WidthAnswer", "quoted",
           "RESAMPLES", "CONFIDENCE"]
