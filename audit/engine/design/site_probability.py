"""P(overturn) at one intensity that the records at that intensity do not contradict.

Two estimates of P at an intensity x stand side by side:

* the model's: the lognormal fragility fitted on the lattice's stripes
  (:mod:`audit.engine.shared.lattice`), Φ(ln(x/θ)/β), with the bootstrap band over records;
* the count's: k of the n records scaled to x itself overturn the block, k/n, with the exact
  (Clopper–Pearson) two-sided band, from the beta distribution's quantiles
  (Clopper & Pearson 1934, Biometrika 26(4) 404–413): B⁻¹(a/2; k, n − k + 1) and
  B⁻¹(1 − a/2; k + 1, n − k), a = 1 − confidence, 0 and 1 at k = 0 and k = n.

The headline is the model's unless the records at x reject it: the model's P lies outside the
count's exact band, i.e. the exact binomial test of k against n·P rejects the lognormal at 10 %
(one curve across the whole lattice can be pulled off at x by the stripes far from it). Then the
headline is the count with its exact band. The test is the count's band, not the model's: the
model's bootstrap band holds the uncertainty of the expected P, not the binomial noise of k
records, so a count outside it is no evidence of misfit (1 of 44 records where the lognormal says
6.9 % [2.4–11.8 %] happens with probability 0.19). Either way the headline's P lies inside the
count's exact band. Where no record (or every record) overturns the block at x, the headline is
the one-sided bound at :data:`BOUND_CONFIDENCE`: P < 1 − 0.05^(1/n) (or P > 0.05^(1/n)), never a
certain-looking 0 % or 100 %.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import betaincinv

from audit.engine.design.bootstrap import bootstrap_lognormal
from audit.engine.design.lognormal_fit import fit_lognormal

#: Two-sided level of the count's band [-] (that of the bootstrap band).
COUNT_CONFIDENCE = 0.90
#: One-sided level of the bound where no record, or every record, overturns the block [-].
BOUND_CONFIDENCE = 0.95
MODEL, COUNT = "lognormal", "count"


def clopper_pearson(overturned: int, records: int,
                    confidence: float = COUNT_CONFIDENCE) -> tuple[float, float]:
    """The exact two-sided band of a binomial share k/n (see the module).

    Parameters
    ----------
    overturned : int
        k, the records that overturn the block.
    records : int
        n, the records.
    confidence : float
        Two-sided level [-].
    """
    tail = (1.0 - confidence) / 2.0
    # the beta distribution's quantiles (what scipy.stats.beta.ppf computes, without importing
    # scipy.stats: ~0.6 s of a check's start)
    low = 0.0 if overturned == 0 else float(betaincinv(
        overturned, records - overturned + 1, tail))
    high = 1.0 if overturned == records else float(betaincinv(
        overturned + 1, records - overturned, 1.0 - tail))
    return low, high


def one_sided_bound(records: int, confidence: float = BOUND_CONFIDENCE) -> float:
    """The upper bound on P where none of ``records`` records overturns the block, 1 −
    (1 − confidence)^(1/n) (the exact binomial bound at k = 0); where every record does, P >
    1 minus it.

    Parameters
    ----------
    records : int
        n, the records.
    confidence : float
        One-sided level [-].
    """
    return 1.0 - (1.0 - confidence) ** (1.0 / records)


@dataclass(frozen=True)
class SiteProbability:
    """P(overturn) at one intensity: the model's and the count's, and which one is the headline.

    Attributes
    ----------
    p, band :
        The headline P [-] and its band (low, high) [-].
    estimator : str
        :data:`MODEL` or :data:`COUNT`.
    reason : str
        Why the headline uses it, in words.
    bound : dict or None
        ``{"side": "upper"|"lower", "value", "confidence"}`` where no record (or every record)
        overturns the block at the intensity: the headline is then "< value" (or "> value").
    model_p, model_band :
        The lognormal's P and its bootstrap band (None where no lognormal fits).
    overturned, records : int
        The count at the intensity, k of n.
    count_band : (float, float)
        Its exact Clopper–Pearson band at :data:`COUNT_CONFIDENCE`.
    """

    p: float
    band: tuple
    estimator: str
    reason: str
    bound: dict | None
    model_p: float | None
    model_band: tuple | None
    overturned: int
    records: int
    count_band: tuple

    def words(self) -> str:
        """The headline as a reader sees it: ``"< 6.6 %"``, ``"> 93 %"`` or ``"12 % [8–17 %]"``."""
        if self.bound is not None:
            sign = "<" if self.bound["side"] == "upper" else ">"
            return f"{sign} {100 * self.bound['value']:.2g} %"
        low, high = self.band
        return f"{100 * self.p:.0f} % [{100 * low:.0f}–{100 * high:.0f} %]"

    def as_dict(self) -> dict:
        """The fields of ``check.json``'s ``p_at_site``."""
        return {"p": self.p, "band": list(self.band), "estimator": self.estimator,
                "reason": self.reason, "bound": self.bound, "headline": self.words(),
                "model": {"p": self.model_p,
                          "band": list(self.model_band) if self.model_band else None},
                "count": {"overturned": self.overturned, "records": self.records,
                          "p": self.overturned / self.records, "band": list(self.count_band),
                          "band_method": f"exact two-sided {COUNT_CONFIDENCE:.0%} "
                                         "Clopper–Pearson"}}


def lattice_fragility(levels, overturned, seed: int | None = None):
    """The lognormal fragility of outcomes (record, stripe) on the lattice's stripes and its
    bootstrap over records: (fit or None where no lognormal fits, the bootstrap).

    Parameters
    ----------
    levels : numpy.ndarray
        The lattice's stripes [unit of the IM].
    overturned : numpy.ndarray of bool
        Outcomes shaped (record, stripe).
    seed : int, optional
        The bootstrap's seed (its default when None).
    """
    try:
        fit = fit_lognormal(levels, np.full(levels.size, overturned.shape[0]),
                            overturned.sum(axis=0))
    except ValueError:
        fit = None
    boot = (bootstrap_lognormal(levels, overturned) if seed is None
            else bootstrap_lognormal(levels, overturned, seed=seed))
    return fit, boot


def site_probability(model_p: float | None, model_band, overturned: int,
                     records: int) -> SiteProbability:
    """The headline P at an intensity from the model's P and band and the count there (see the
    module).

    Parameters
    ----------
    model_p : float or None
        The lognormal's P at the intensity [-]; None where no lognormal fits.
    model_band : (float, float) or None
        Its band [-] (the headline's where the lognormal is; None where only the P is wanted:
        the rule reads the count's band alone).
    overturned, records : int
        k of the n records scaled to the intensity overturn the block.
    """
    k, n = int(overturned), int(records)
    count_band = clopper_pearson(k, n)
    share = k / n
    model_band = tuple(float(v) for v in model_band) if model_band is not None else None
    common = dict(model_p=model_p, model_band=model_band, overturned=k, records=n,
                  count_band=count_band)
    if k in (0, n):
        value = one_sided_bound(n)
        side = "upper" if k == 0 else "lower"
        bound = {"side": side, "value": value if k == 0 else 1.0 - value,
                 "confidence": BOUND_CONFIDENCE}
        return SiteProbability(share, count_band, COUNT,
                               f"{'no' if k == 0 else 'every'} record of {n} overturns it at "
                               f"this intensity: the one-sided {BOUND_CONFIDENCE:.0%} bound",
                               bound, **common)
    low, high = count_band
    if model_p is None or not low <= model_p <= high:
        return SiteProbability(share, count_band, COUNT,
                               f"the lognormal's {100 * model_p:.1f} % lies outside the exact "
                               f"band of the count {k}/{n} [{100 * low:.1f}–{100 * high:.1f} %]: "
                               "the records here reject it" if model_p is not None
                               else "no lognormal fits", None, **common)
    return SiteProbability(float(model_p), model_band, MODEL,
                           f"the lognormal's {100 * model_p:.1f} % lies inside the exact band of "
                           f"the count {k}/{n} [{100 * low:.1f}–{100 * high:.1f} %]", None,
                           **common)


__all__ = ["site_probability", "lattice_fragility", "SiteProbability", "clopper_pearson", "one_sided_bound",
           "COUNT_CONFIDENCE", "BOUND_CONFIDENCE", "MODEL", "COUNT"]
