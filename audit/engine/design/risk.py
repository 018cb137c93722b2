"""The risk integral: the mean annual rate of overturning of a block at a site, from its
overturning fragility and the site's hazard curve.

.. math::

    \\lambda_{ov} = \\int_0^\\infty P(\\text{overturn} \\mid im)
                   \\left|\\frac{d\\lambda(im)}{d\\,im}\\right| d\\,im ,
    \\qquad P_{50} = 1 - e^{-50\\,\\lambda_{ov}}

(the total probability theorem with Poisson occurrence, as in Cornell et al. 2002, J. Struct.
Eng. 128(4) 526–533, and FEMA P-58). The hazard curve is interpolated log–log between its
levels (a power law λ = λᵢ (im/imᵢ)^(−kᵢ) on each interval, so |dλ/d im| = kᵢ λ/im) and the
integral is taken in ln im, :data:`POINTS_PER_INTERVAL` points an interval. The fragility is
either the fitted lognormal Φ(ln(im/θ)/β) or the counted shares of the stripes, linear in
ln im between stripes and held at the end stripes' shares beyond them.

Where the curve ends: above its last level with a positive rate, the exceedances λ(im_last)
are counted at P(overturn | im_last), the least they can contribute; at most they contribute
λ(im_last) × P at the next level, where the file says the rate is 0, else × 1
(:attr:`OverturningRisk.annual_rate_upper`). A curve that stops below the fragility's median
gives a warning with that bound. Below the first level nothing is counted (the rate of the
intensities there is unknown); :attr:`OverturningRisk.p_at_first_level` says what that omits.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.special import ndtr

from audit.errors import InputError, InputWarning

#: Integration points on each interval of the hazard curve.
POINTS_PER_INTERVAL = 200
#: Share of λ_ov whose intensity range is reported (the central 90 %: 5 % to 95 %).
RANGE_SHARE = 0.90
#: Years of the probability reported beside the annual rate.
YEARS = 50.0


@dataclass(frozen=True)
class LognormalFragility:
    """P(overturn | im) = Φ(ln(im/θ)/β): a fitted fragility.

    Attributes
    ----------
    median_g : float
        θ [g]. beta : float, β [-]. im : str or None, the fragility's intensity measure as
        ``--im`` names it (``pga``, ``sa:1``); None when not known.
    """

    median_g: float
    beta: float
    im: str | None = None

    def __post_init__(self):
        if not (math.isfinite(self.median_g) and self.median_g > 0
                and math.isfinite(self.beta) and self.beta > 0):
            raise InputError(f"fragility: median and beta must be positive numbers, got "
                             f"median {self.median_g}, beta {self.beta}")

    def probability(self, im_g) -> np.ndarray:
        """P(overturn | IM = ``im_g``) [-].

        Parameters
        ----------
        im_g : float or array_like of float
            Intensity [g].
        """
        return ndtr(np.log(np.asarray(im_g, dtype=float) / self.median_g) / self.beta)

    @property
    def half_g(self) -> float:
        """Where P reaches one half [g]."""
        return self.median_g

    def describe(self) -> str:
        return f"lognormal fit, median {self.median_g:.4g} g, β {self.beta:.3g}"


@dataclass(frozen=True)
class StripeFragility:
    """The counted fragility: the share of records overturning the block at each stripe,
    linear in ln im between stripes, held at the end stripes' shares beyond them.

    Attributes
    ----------
    levels_g : numpy.ndarray
        Stripes, ascending [g]. shares : numpy.ndarray, [-]. im : str or None, as for
        :class:`LognormalFragility`.
    """

    levels_g: np.ndarray
    shares: np.ndarray
    im: str | None = None

    def probability(self, im_g) -> np.ndarray:
        """P(overturn | IM = ``im_g``) [-], linear in ln IM between the stripes, held at the
        end stripes' shares beyond them.

        Parameters
        ----------
        im_g : float or array_like of float
            Intensity [g].
        """
        return np.interp(np.log(np.asarray(im_g, dtype=float)), np.log(self.levels_g),
                         self.shares)

    @property
    def half_g(self) -> float:
        """The first stripe where the share reaches one half [g]; inf if none does."""
        reached = np.flatnonzero(np.asarray(self.shares) >= 0.5)
        return float(self.levels_g[reached[0]]) if reached.size else math.inf

    def describe(self) -> str:
        return f"stripe shares, {len(self.levels_g)} stripes"


@dataclass(frozen=True)
class OverturningRisk:
    """The mean annual rate of overturning of one block at one site.

    Attributes
    ----------
    annual_rate : float
        λ_ov [1/yr] (the tail above the curve's last level counted at the least it adds).
    annual_rate_upper : float
        The most λ_ov can be given where the curve stops [1/yr].
    p50 : float
        Probability of overturning in 50 years, 1 − exp(−50 λ_ov) [-].
    im : str
        The hazard curve's intensity measure (``PGA``, ``SA(1.0)``).
    hazard_source, fragility : str
        What the curve and the fragility are.
    im_range_90_g : (float, float)
        Intensities between which the central 90 % of λ_ov arises (its 5 % and 95 % points
        along im) [g]; the upper one inf when it lies above the curve's last level.
    truncated : bool
        The curve stops below the fragility's median.
    p_at_first_level : float
        P(overturn) at the curve's first level: overturning by lower intensities is not counted.
    deaggregation : pandas.DataFrame
        Per interval of the hazard curve (and the tail above it): ``im_low_g, im_high_g,
        annual_rate, share``.
    density_im_g, density : numpy.ndarray
        dλ_ov/d ln im [1/yr] on the integration points (for a figure).
    """

    annual_rate: float
    annual_rate_upper: float
    p50: float
    im: str
    hazard_source: str
    fragility: str
    im_range_90_g: tuple
    truncated: bool
    p_at_first_level: float
    deaggregation: pd.DataFrame
    density_im_g: np.ndarray
    density: np.ndarray

    def probability_in(self, years: float) -> float:
        """Probability of at least one overturning in ``years`` [-] (Poisson).

        Parameters
        ----------
        years : float
            Exposure time [years].
        """
        return float(-np.expm1(-years * self.annual_rate))

    def as_dict(self) -> dict:
        """``annual_rate, p50, im, hazard_source`` (what ``check.json`` holds per object)."""
        return {"annual_rate": self.annual_rate, "p50": self.p50, "im": self.im,
                "hazard_source": self.hazard_source}


def annual_rate_for(probability: float, years: float = YEARS) -> float:
    """The annual rate [1/yr] whose probability in ``years`` is ``probability`` (Poisson).

    Parameters
    ----------
    probability : float
        Probability in ``years`` [-], in (0, 1).
    years : float
        Exposure time [years].
    """
    if not 0.0 < probability < 1.0:
        raise InputError(f"risk_target: a probability in (0, 1) is needed, got {probability}",
                         "risk_target")
    return float(-np.log1p(-probability) / years)


def hazard_im(curve):
    """The project's intensity measure (:class:`~audit.engine.shared.intensity.IntensityMeasure`) of a
    hazard curve: PGA → ``pga``, SA(T) → ``sa:T``.

    Parameters
    ----------
    curve : records.hazard.HazardCurve
        The hazard curve.
    """
    from audit.engine.shared.intensity import IntensityMeasure
    return IntensityMeasure("pga") if curve.imt == "PGA" else \
        IntensityMeasure("sa", float(curve.period_s))


def _same_im(one, other) -> bool:
    """Whether two intensity measures are one (SA periods equal to 1e-6)."""
    return one.kind == other.kind and (
        one.kind != "sa" or math.isclose(one.period_s, other.period_s, rel_tol=1e-6))


def check_same_im(curve, im: str | None, what: str = "fragility") -> None:
    """InputError when the fragility's intensity measure ``im`` (``pga``, ``sa:1``) is not
    the hazard curve's; None passes (the caller vouches for it).

    Parameters
    ----------
    curve : records.hazard.HazardCurve
        The hazard curve.
    im : str or None
        The fragility's intensity measure.
    what : str
        The argument ``im`` came from, for the message.
    """
    if im is None:
        return
    from audit.engine.shared.intensity import IntensityMeasure
    mine, theirs = IntensityMeasure.parse(im), hazard_im(curve)
    if not _same_im(mine, theirs):
        raise InputError(f"hazard: imt: the curve is of {curve.im_name} ({curve.source}) but "
                         f"the {what} is of {mine.name}; use the intensity measure "
                         f"{theirs.name} for both", "hazard", what)


def site_hazard(hazard, im=None):
    """(curve, intensity measure) of a command's ``hazard`` (an
    :class:`~audit.engine.shared.hazard.Hazard`, parsed): the curve read from its file (at
    ``hazard.location``; of the IMT ``hazard.imt``, else of ``im`` in a file of several IMTs)
    unless given, ``im`` (when the user gave one) held to the curve's IMT, which sets the
    intensity measure.

    Parameters
    ----------
    hazard : audit.engine.shared.hazard.Hazard
        Its fields checked (:meth:`Hazard.parse <audit.engine.shared.hazard.Hazard.parse>`),
        with a curve.
    im : str or IntensityMeasure, optional
        The intensity measure the user gave.

    Returns
    -------
    tuple of (records.hazard.HazardCurve, IntensityMeasure)
    """
    from audit.engine.shared.hazard_imt import im_of_imt, imt_of
    from audit.engine.shared.intensity import IntensityMeasure
    from records.hazard import HazardCurve, read_hazard
    curve, imt = hazard.curve, hazard.imt
    im_text = None if im is None else im if isinstance(im, str) else im.name
    if not isinstance(curve, HazardCurve):
        curve = read_hazard(curve, hazard.location, imt or (imt_of(im_text) if im_text else None),
                            imt_field="hazard.imt" if imt else "im")
    if imt is not None:  # a file of one IMT has no choice: it must be the one asked
        asked = IntensityMeasure.parse(im_of_imt(imt))
        if not _same_im(asked, hazard_im(curve)):
            raise InputError(f"hazard.imt: {imt}: the curve is of {curve.im_name} "
                             f"({curve.source}), not {imt}", "hazard.imt")
    if im_text is not None:
        check_same_im(curve, im_text, "im")
    return curve, hazard_im(curve)


def risk_integral(fragility, curve) -> OverturningRisk:
    """λ_ov = ∫ P(overturn | im) |dλ/d im| d im of a fragility and a hazard curve (see the
    module for the interpolation and what the curve's ends count).

    Parameters
    ----------
    fragility : LognormalFragility or StripeFragility
        Its ``im``, when given, must be the curve's (:func:`check_same_im`).
    curve : records.hazard.HazardCurve

    Returns
    -------
    OverturningRisk
    """
    check_same_im(curve, fragility.im)
    rates = np.asarray(curve.annual_rate, dtype=float)
    n = int(np.count_nonzero(rates > 0))  # the curve is non-increasing: a prefix
    levels, rates = np.asarray(curve.im_g[:n], dtype=float), rates[:n]
    ln_s, ln_rate = np.log(levels), np.log(rates)
    t = np.linspace(0.0, 1.0, POINTS_PER_INTERVAL)
    # each interval's points: ln s and ln λ linear in t; |dλ/d ln s| = k λ
    x = ln_s[:-1, None] + t[None, :] * np.diff(ln_s)[:, None]
    slope = -np.diff(ln_rate) / np.diff(ln_s)
    lam = np.exp(ln_rate[:-1, None] + t[None, :] * np.diff(ln_rate)[:, None])
    density = fragility.probability(np.exp(x)) * slope[:, None] * lam
    parts = np.trapezoid(density, x, axis=1)
    p_last = float(fragility.probability(levels[-1]))
    p_end = float(fragility.probability(curve.im_g[n])) if n < len(curve.im_g) else 1.0
    tail, tail_upper = rates[-1] * p_last, rates[-1] * p_end
    annual_rate = float(parts.sum() + tail)
    upper = float(parts.sum() + tail_upper)
    truncated = levels[-1] < fragility.half_g
    if truncated:
        warnings.warn(f"hazard: {curve.source}: the curve stops at {levels[-1]:.3g} g, below "
                      f"the fragility's median {fragility.half_g:.3g} g: λ_ov = "
                      f"{annual_rate:.3g}/yr counts the {rates[-1]:.3g}/yr exceedances above "
                      f"it at P(overturn) = {p_last:.2g}; the truncation bounds it by "
                      f"{upper:.3g}/yr", InputWarning, stacklevel=2)
    top = curve.im_g[n] if n < len(curve.im_g) else math.inf
    deaggregation = pd.DataFrame({
        "im_low_g": np.append(levels[:-1], levels[-1]),
        "im_high_g": np.append(levels[1:], top),
        "annual_rate": np.append(parts, tail)})
    deaggregation["share"] = deaggregation["annual_rate"] / annual_rate if annual_rate > 0 \
        else np.nan
    return OverturningRisk(
        annual_rate, upper, float(-np.expm1(-YEARS * annual_rate)), curve.im_name,
        curve.source, fragility.describe(), _central_range(x, density, tail, top, annual_rate),
        bool(truncated), float(fragility.probability(levels[0])), deaggregation,
        np.exp(x).reshape(-1), density.reshape(-1))


def block_fragilities(fragility_row, stripes: pd.DataFrame):
    """The fitted (None where the fit failed) and counted fragility of one block of a
    design-level audit, from its row of ``fragility.csv`` and its rows of ``stripes.csv``
    (their intensity measure checked by the caller, once).

    Parameters
    ----------
    fragility_row : pandas.Series
        The block's row of ``fragility.csv``.
    stripes : pandas.DataFrame
        The block's rows of ``stripes.csv``.

    Returns
    -------
    tuple of (LognormalFragility or None, StripeFragility)
    """
    shares = stripes.groupby("im_level")["exact_overturned"].mean()
    counted = StripeFragility(shares.index.to_numpy(dtype=float), shares.to_numpy(dtype=float))
    median, beta = float(fragility_row["median"]), float(fragility_row["beta"])
    return (LognormalFragility(median, beta) if math.isfinite(median) else None), counted


def _central_range(x, density, tail, top, total) -> tuple:
    """The intensities [g] at which the cumulative λ_ov along im reaches (1 ∓ RANGE_SHARE)/2
    of the total, interpolated in ln im; above the curve (in its tail), ``top``."""
    if not total > 0:
        return (math.nan, math.nan)
    steps = 0.5 * (density[:, 1:] + density[:, :-1]) * np.diff(x, axis=1)
    cumulative = np.concatenate([[0.0], np.cumsum(steps)])
    ln_im = np.concatenate([x[:1, 0], x[:, 1:].reshape(-1)])
    out = []
    for share in ((1 - RANGE_SHARE) / 2, (1 + RANGE_SHARE) / 2):
        goal = share * total
        out.append(float(np.exp(np.interp(goal, cumulative, ln_im))) if goal <= cumulative[-1]
                   else float(top))
    return tuple(out)


__all__ = ["risk_integral", "site_hazard", "OverturningRisk", "LognormalFragility", "StripeFragility",
           "block_fragilities",
           "annual_rate_for", "hazard_im", "check_same_im", "POINTS_PER_INTERVAL",
           "RANGE_SHARE", "YEARS"]
