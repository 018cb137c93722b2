"""A band on a multiple-stripe fragility from resampling whole records (the nonparametric
bootstrap of cases): the stripes' counts share their records, so a binomial band is too
narrow."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr

from audit.engine.design.lognormal_fit import lognormal_fits


#: Resamples of :func:`bootstrap_lognormal` unless asked otherwise, and its default seed.
BOOTSTRAP_RESAMPLES = 1000
BOOTSTRAP_SEED = 20011


@dataclass(frozen=True)
class BootstrapFits:
    """Lognormal fragilities fitted to resamples of a suite's records (:func:`bootstrap_lognormal`).

    Attributes
    ----------
    medians, betas : numpy.ndarray
        θ and β of each resample's fit (unit of the intensity measure, [-]); θ = +inf where
        the resample overturns the block at no stripe, 0 where at every record × stripe (the
        likelihood's limits: P = 0, resp. 1, at every level), β NaN there.
    confidence : float
        Two-sided level of :meth:`probability_band` [-].
    """

    medians: np.ndarray
    betas: np.ndarray
    confidence: float

    def probabilities(self, im) -> np.ndarray:
        """P(overturn | IM = im) of every resample's fit, shaped (resample, *im).

        Parameters
        ----------
        im : float or array_like of float
            Intensity, in the unit of the stripes (e.g. [g]).
        """
        im = np.asarray(im, dtype=float)
        medians = self.medians.reshape(-1, *([1] * im.ndim))
        betas = self.betas.reshape(medians.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.log(im / medians) / betas
        return np.where(np.isinf(medians), 0.0, np.where(medians == 0.0, 1.0, ndtr(z)))

    def probability_band(self, im) -> tuple[np.ndarray, np.ndarray]:
        """Percentile band of P(overturn | IM = im) at :attr:`confidence` over the resamples.

        Parameters
        ----------
        im : float or array_like of float
            Intensity, in the unit of the stripes (e.g. [g]).

        Returns
        -------
        low, high : numpy.ndarray
            The band's ends [-], shaped as ``im``.
        """
        tail = 50.0 * (1.0 - self.confidence)
        low, high = np.percentile(self.probabilities(im), [tail, 100.0 - tail], axis=0)
        return low, high


def bootstrap_lognormal(levels, overturned, resamples: int = BOOTSTRAP_RESAMPLES,
                        confidence: float = 0.90, seed: int = BOOTSTRAP_SEED) -> BootstrapFits:
    """The lognormal fragility refitted to records drawn with replacement from a suite.

    In a multiple-stripe analysis every record is scaled to every stripe, so the stripes'
    counts are not independent binomials: a record that overturns the block at one level tends
    to at the next. Resampling whole records (rows of ``overturned``, each with its outcomes at
    every stripe) keeps that dependence, which the binomial likelihood's band
    (:attr:`LognormalFit.median_band`) ignores (Efron & Tibshirani 1993, ch. 6, the
    nonparametric bootstrap of cases).

    Parameters
    ----------
    levels : array
        Intensity of each stripe (> 0), ascending.
    overturned : array of bool or float
        Outcomes, shaped (record, stripe) (or per-record probabilities, as an atlas
        interpolates them between its nodes: :mod:`audit.engine.atlas.answers`).
    resamples : int
        Number of resampled suites.
    confidence : float
        Two-sided level of the percentile band [-].
    seed : int
        Seed of the resampling (numpy's default generator): the same inputs give the same band.

    Returns
    -------
    BootstrapFits
    """
    overturned = np.asarray(overturned, dtype=float)  # the counts of bools are whole numbers
    records = overturned.shape[0]
    rows = np.random.default_rng(seed).integers(0, records, size=(resamples, records))
    counts = overturned[rows].sum(axis=1)  # (resample, stripe)
    medians, betas = lognormal_fits(levels, records, counts)
    return BootstrapFits(medians, betas, confidence)


__all__ = ["bootstrap_lognormal", "BootstrapFits", "BOOTSTRAP_RESAMPLES", "BOOTSTRAP_SEED"]
