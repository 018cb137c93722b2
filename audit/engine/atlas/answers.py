"""Answers read from an atlas: an object's stripe outcomes interpolated in (α, ln 2π/p), then
the check's own rules on them.

Per record, the outcome at a stripe (overturned: 1, not: 0) is interpolated bilinearly in α
and ln(2π/p) (ln p up to its sign) between the grid's four nodes around the object: a
per-record probability, whose sum over records is the stripe's count (fractional between
nodes, exact at a node). On them:

* the lognormal fragility and its bootstrap over records, the count at the site's intensity and
  the headline P at the site: :mod:`audit.engine.design.site_probability`, as ``check`` does.
  The site's stripe is not a lattice level: its per-record outcome is interpolated linearly in
  ln(IM) between the two lattice stripes around it, and its count rounded to a whole record for
  the exact binomial band (the one approximation beyond the grid's);
* the exact width for P(overturn) at the site ≤ 10 % (and 50 %): the lognormal's P on the
  interpolated counts (:func:`audit.engine.check.widths.probability_at_site`'s rule) in the
  check's width search (:func:`audit.engine.check.widths.required_width`).

Each P comes with the atlas's error at that point (:meth:`Atlas.local_error`): the grid's own
estimate from the curvature of P across the cell's nodes, whose adequacy docs/atlas.md measures
against direct solves of held-out objects.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.special import ndtr

from audit import G
from audit.engine.atlas.store import ATLAS_JSON, ATLAS_NPZ
from audit.engine.design.lognormal_fit import lognormal_fits
from audit.engine.design.site_probability import COUNT_CONFIDENCE, site_probability
from audit.errors import InputError
from audit.physics.block import frequency_parameter, slenderness

#: Bilinear interpolation's error at a grid spacing h grows as h²: an interpolation across two
#: cells (2h) errs about this many times one cell's (the local error's estimate divides by it).
DOUBLE_SPACING_ERROR_RATIO = 4.0
#: Standard deviations of the count's error from the records undecided within a cell that the
#: stated error allows (:meth:`Atlas.local_error`).
RECORD_SPREAD = 2.0


def size_of(width_m, height_m, g: float = G):
    """(α [degrees], 2π/p [s]) of rectangular blocks.

    Parameters
    ----------
    width_m, height_m : array_like of float
        Full base width and full height [m].
    g : float
        Gravity [m/s²].
    """
    b, h = np.asarray(width_m, dtype=float) / 2.0, np.asarray(height_m, dtype=float) / 2.0
    return (np.degrees(slenderness(b, h)),
            2.0 * np.pi / frequency_parameter(np.hypot(b, h), g))


@dataclass(frozen=True)
class AtlasPoint:
    """What the atlas says about one object at one site intensity.

    Attributes
    ----------
    alpha_deg, size_s : float
    outcomes : numpy.ndarray
        Per-record interpolated outcomes at the lattice's stripes, shaped (record, stripe) [-].
    site : audit.engine.design.site_probability.SiteProbability
        The headline P at the site, by the check's rule.
    error : float
        The atlas's error of P at this point (absolute) [-].
    """

    alpha_deg: float
    size_s: float
    outcomes: np.ndarray
    site: object
    error: float


class Atlas:
    """A complete atlas, loaded (:mod:`audit.engine.atlas.store`).

    Parameters
    ----------
    directory : pathlib.Path
        Its folder.
    """

    def __init__(self, directory):
        directory = Path(directory)
        self.provenance = json.loads((directory / ATLAS_JSON).read_text())
        with np.load(directory / ATLAS_NPZ) as data:
            shape = tuple(int(v) for v in data["shape"])
            bits = np.unpackbits(data["overturned"])[:int(np.prod(shape))]
            #: outcomes (record, stripe, α, size)
            self.overturned = bits.astype(bool).reshape(shape)
            self.levels = data["levels"]
            self.alpha_deg = data["alpha_deg"]
            self.size_s = data["size_s"]
        self.records = shape[0]
        self._ln_size = np.log(self.size_s)

    def covers(self, alpha_deg, size_s) -> np.ndarray:
        """Whether each object lies within the grid.

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The objects [degrees], [s].
        """
        alpha_deg, size_s = np.asarray(alpha_deg), np.asarray(size_s)
        return ((alpha_deg >= self.alpha_deg[0]) & (alpha_deg <= self.alpha_deg[-1])
                & (size_s >= self.size_s[0]) & (size_s <= self.size_s[-1]))

    def _cell(self, alpha_deg, size_s):
        """Lower node indices and weights (i, j, u, v) of each point's cell."""
        alpha_deg, size_s = np.atleast_1d(alpha_deg).astype(float), np.atleast_1d(size_s)
        if not np.all(self.covers(alpha_deg, size_s)):
            raise InputError(f"object: outside the atlas (α {self.alpha_deg[0]:g}–"
                             f"{self.alpha_deg[-1]:g}°, 2π/p {self.size_s[0]:g}–"
                             f"{self.size_s[-1]:g} s)", "object")
        x, y = alpha_deg, np.log(size_s)
        i = np.clip(np.searchsorted(self.alpha_deg, x, side="right") - 1, 0,
                    self.alpha_deg.size - 2)
        j = np.clip(np.searchsorted(self._ln_size, y, side="right") - 1, 0,
                    self.size_s.size - 2)
        u = (x - self.alpha_deg[i]) / (self.alpha_deg[i + 1] - self.alpha_deg[i])
        v = (y - self._ln_size[j]) / (self._ln_size[j + 1] - self._ln_size[j])
        return i, j, u, v

    def outcomes(self, alpha_deg, size_s) -> np.ndarray:
        """Per-record outcomes at the lattice's stripes, interpolated bilinearly in (α,
        ln 2π/p), shaped (point, record, stripe) [-]; at a node, the node's own (0 or 1).

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The objects [degrees], [s].
        """
        i, j, u, v = self._cell(alpha_deg, size_s)
        o = self.overturned
        corner = lambda di, dj: np.moveaxis(o[:, :, i + di, j + dj], 2, 0)  # (point, rec, stripe)
        u, v = u[:, None, None], v[:, None, None]
        return ((1 - u) * (1 - v) * corner(0, 0) + u * (1 - v) * corner(1, 0)
                + (1 - u) * v * corner(0, 1) + u * v * corner(1, 1))

    def site_outcomes(self, outcomes, site_im: float) -> np.ndarray:
        """Per-record outcomes at ``site_im``, linear in ln(IM) between the lattice's stripes
        around it, shaped (point, record) [-].

        Parameters
        ----------
        outcomes : numpy.ndarray
            (point, record, stripe), from :meth:`outcomes`.
        site_im : float
            The site's intensity [unit of the IM].
        """
        x = np.log(site_im)
        ln_levels = np.log(self.levels)
        if not ln_levels[0] <= x <= ln_levels[-1]:
            raise InputError(f"site: its intensity {site_im:g} lies outside the lattice "
                             f"({self.levels[0]:g}–{self.levels[-1]:g})", "site")
        k = min(int(np.searchsorted(ln_levels, x, side="right")) - 1, ln_levels.size - 2)
        t = (x - ln_levels[k]) / (ln_levels[k + 1] - ln_levels[k])
        return (1 - t) * outcomes[:, :, k] + t * outcomes[:, :, k + 1]

    def probability_at_site(self, alpha_deg, size_s, site_im: float) -> np.ndarray:
        """The lognormal's P(overturn) at ``site_im`` on each object's interpolated counts (the
        measure of the check's width search), shaped (point,) [-].

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The objects [degrees], [s].
        site_im : float
            The site's intensity [unit of the IM].
        """
        counts = self.outcomes(alpha_deg, size_s).sum(axis=1)
        return _lognormal_p(self.levels, self.records, counts, site_im)

    def local_error(self, alpha_deg, size_s, site_im: float) -> np.ndarray:
        """The atlas's error of P at each object (see the module), the sum of two terms:

        * the smooth part's: at each node of its cell, P there against P interpolated from the
          nodes one step either side (along α and along ln 2π/p, an interpolation across 2h),
          the largest of those differences divided by :data:`DOUBLE_SPACING_ERROR_RATIO`;
        * the records': a record whose outcome differs between the cell's nodes is, at the
          object itself, overturned or not, not the fraction w interpolated; taken as a
          Bernoulli of mean w, the count's error has the standard deviation √Σ w(1 − w), and
          P's :data:`RECORD_SPREAD` of them over n records, at the site's level (between the
          lattice's stripes around it). Zero at a node.

        Shaped (point,) [-].

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The objects [degrees], [s].
        site_im : float
            The site's intensity [unit of the IM].
        """
        i, j, _, _ = self._cell(alpha_deg, size_s)
        counts = self.overturned.sum(axis=0)  # (stripe, α, size)
        na, ns = self.alpha_deg.size, self.size_s.size
        worst = np.zeros(i.size)
        for di in (0, 1):
            for dj in (0, 1):
                a, s = i + di, j + dj
                here = _lognormal_p(self.levels, self.records, counts[:, a, s].T, site_im)
                for step_a, step_s in ((1, 0), (0, 1)):
                    lo_a, hi_a = np.clip(a - step_a, 0, na - 1), np.clip(a + step_a, 0, na - 1)
                    lo_s, hi_s = np.clip(s - step_s, 0, ns - 1), np.clip(s + step_s, 0, ns - 1)
                    mid = (counts[:, lo_a, lo_s] + counts[:, hi_a, hi_s]).T / 2.0
                    across = _lognormal_p(self.levels, self.records, mid, site_im)
                    worst = np.maximum(worst, np.abs(here - across))
        outcomes = self.outcomes(alpha_deg, size_s)
        # w(1 − w) ≥ 0; the interpolation's rounding can put w a hair above 1
        spread = np.sqrt(np.maximum(
            self.site_outcomes(outcomes * (1.0 - outcomes), site_im).sum(axis=1), 0.0))
        return worst / DOUBLE_SPACING_ERROR_RATIO + RECORD_SPREAD * spread / self.records

    def at(self, alpha_deg, size_s, site_im: float, seed: int | None = None) -> list:
        """Each object's P at the site by the check's rule (see the module), every object's
        fit, site count and error computed together; the bootstrap band one object at a time.

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The objects [degrees], [s].
        site_im : float
            The site's intensity [unit of the IM].
        seed : int, optional
            The bootstrap's seed (its default when None).

        Returns
        -------
        list of AtlasPoint
        """
        alpha_deg, size_s = np.atleast_1d(alpha_deg), np.atleast_1d(size_s)
        outcomes = self.outcomes(alpha_deg, size_s)
        model_p = _lognormal_p(self.levels, self.records, outcomes.sum(axis=1), site_im)
        counts = np.rint(self.site_outcomes(outcomes, site_im).sum(axis=1)).astype(int)
        errors = self.local_error(alpha_deg, size_s, site_im)
        total = outcomes.sum(axis=(1, 2))
        fits = (total > 0.0) & (total < outcomes[0].size)  # lognormal_fits' limits
        bands = _bootstrap_bands(self.levels, outcomes, fits, site_im, seed)
        out = []
        for k in range(alpha_deg.size):
            site = site_probability(float(model_p[k]) if fits[k] else None, bands[k],
                                    int(counts[k]), self.records)
            out.append(AtlasPoint(float(alpha_deg[k]), float(size_s[k]), outcomes[k], site,
                                  float(errors[k])))
        return out


def _bootstrap_bands(levels, outcomes, fits, site_im: float, seed) -> list:
    """Each object's bootstrap band of P at ``site_im`` (None where no lognormal fits): the
    resampling of :func:`~audit.engine.design.bootstrap.bootstrap_lognormal` (its seed and
    resamples: the same records drawn for every object, so drawn once), one object's
    resamples fitted at a time (fitting many objects' together measured slower: the scoring
    runs until its slowest row settles)."""
    from audit.engine.design.bootstrap import (BOOTSTRAP_RESAMPLES, BOOTSTRAP_SEED,
                                               BootstrapFits)
    records = outcomes.shape[1]
    rows = np.random.default_rng(BOOTSTRAP_SEED if seed is None else seed).integers(
        0, records, size=(BOOTSTRAP_RESAMPLES, records))
    bands = [None] * len(outcomes)
    for k in np.flatnonzero(fits):
        medians, betas = lognormal_fits(levels, records, outcomes[k][rows].sum(axis=1))
        band = BootstrapFits(medians, betas, COUNT_CONFIDENCE).probability_band(site_im)
        bands[k] = tuple(float(v) for v in band)
    return bands


def _lognormal_p(levels, records: int, counts, site_im: float) -> np.ndarray:
    """Φ(ln(x/θ)/β) of the lognormal fitted to each row of ``counts`` (P = 0 where no record
    overturns at any stripe, 1 where every record does at every stripe)."""
    medians, betas = lognormal_fits(levels, records, counts)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = ndtr(np.log(site_im / medians) / betas)
    return np.where(np.isinf(medians), 0.0, np.where(medians == 0.0, 1.0, p))




def atlas_required_widths(atlas: Atlas, heights_m, site_im: float, targets,
                          g: float = G) -> np.ndarray:
    """The exact width for P(overturn) at the site ≤ each target at each height, by the check's
    width search (:func:`audit.engine.check.widths.required_width`) on the atlas's P; shaped
    (height, target) [m], NaN where the P exceeds the target still at the widest, or where the
    width's α lies beyond the grid's.

    Parameters
    ----------
    atlas : Atlas
    heights_m : array_like of float
        Full heights [m].
    site_im : float
        The site's intensity [unit of the IM].
    targets : sequence of float
        P(overturn) at the site [-].
    g : float
        Gravity [m/s²] (the atlas's).
    """
    from audit.engine.check.widths import required_width
    low, high = atlas.alpha_deg[0], atlas.alpha_deg[-1]

    # the check's own scan of widths (its last crossing depends on where it looks); a width
    # whose α lies beyond the grid is measured at the grid's edge, and an answer there refused
    def measure(heights, widths):
        alpha_deg, size_s = size_of(widths, heights, g)
        return atlas.probability_at_site(np.clip(alpha_deg, low, high), size_s, site_im)

    widths = required_width(measure, heights_m, list(targets))
    alpha_deg, _ = size_of(widths, np.asarray(heights_m, dtype=float)[:, None], g)
    return np.where((alpha_deg >= low) & (alpha_deg <= high), widths, np.nan)

__all__ = ["Atlas", "AtlasPoint", "size_of", "atlas_required_widths",
           "DOUBLE_SPACING_ERROR_RATIO", "RECORD_SPREAD"]
