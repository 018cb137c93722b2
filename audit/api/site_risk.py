"""Risk at a site: hazard curves read from the files of the tools engineers run, and the
annual rate of overturning of a block (:mod:`audit.engine.design.risk`)."""

from __future__ import annotations

from audit.errors import InputError


def read_hazard(hazard, site=None, imt: str | None = None):
    """A :class:`records.hazard.HazardCurve` as given, or read from a file: an OpenQuake
    hazard-curve export, a USGS hazard service response (``.json``) or a plain CSV
    ``im_g,annual_rate`` with a ``# imt=...`` line (see :func:`records.hazard.read_hazard`).

    Parameters
    ----------
    hazard : HazardCurve, str or pathlib.Path
    site : (float, float), optional
        Longitude, latitude [degrees] of the site, matched within 0.001°.
    imt : str, optional
        ``PGA`` or ``SA(T)``: which curve of a USGS response.
    """
    from audit.engine.shared import fields as check
    from records.hazard import HazardCurve
    from records.hazard import read_hazard as read_file
    if site is not None:
        site = check.pair("site", site, "longitude, latitude in degrees")
    if imt is not None and not isinstance(imt, str):
        raise InputError(f"imt: expected PGA or SA(T), got {imt!r}", "imt")
    if isinstance(hazard, HazardCurve):
        return hazard
    return read_file(check.path("hazard", hazard, "a hazard curve or its file"), site, imt)


def risk(fragility, hazard, site=None, imt: str | None = None):
    """The mean annual rate of overturning of one block at a site, its probability in 50
    years, and where it comes from (see :mod:`audit.engine.design.risk`).

    Parameters
    ----------
    fragility :
        ``(median_g, beta)``; a row of :attr:`MarginsResult.fragility` (its lognormal fit, of
        its ``im``); or :class:`audit.engine.design.risk.LognormalFragility` /
        :class:`~audit.engine.design.risk.StripeFragility`.
    hazard : records.hazard.HazardCurve, str or pathlib.Path
        The curve, or its file (:func:`read_hazard`).
    site, imt :
        As for :func:`read_hazard`.

    Returns
    -------
    audit.engine.design.risk.OverturningRisk
        ``.annual_rate`` [1/yr], ``.p50``, ``.im_range_90_g``, ``.deaggregation``, ...
    """
    from audit.engine.shared import fields as check
    from audit.engine.design.risk import LognormalFragility, StripeFragility, risk_integral
    if not isinstance(fragility, (LognormalFragility, StripeFragility)):
        if hasattr(fragility, "get") and "median" in fragility:  # a fragility.csv row
            values, im = (fragility["median"], fragility.get("beta")), fragility.get("im")
        elif isinstance(fragility, (str, bytes)) or not hasattr(fragility, "__len__") \
                or len(fragility) != 2:
            raise InputError(f"fragility: expected (median_g, beta), a row of "
                             f"MarginsResult.fragility or a LognormalFragility, got "
                             f"{fragility!r}", "fragility")
        else:
            values, im = fragility, None
        median_g, beta = check.numbers("fragility", values, "a positive median in g and a "
                                       "positive dispersion β", 0, low_open=True)
        fragility = LognormalFragility(median_g, beta, im)
    return risk_integral(fragility, read_hazard(hazard, site, imt))


__all__ = ["read_hazard", "risk"]
