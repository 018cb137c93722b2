"""What ``audit check`` computes (:mod:`audit.engine.check.pipeline`), checked once."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

from audit import G
from audit.engine.shared import fields as check
from audit.engine.check.spectrum_read import GROUND, GUIDELINE_SPECTRA
from audit.engine.check.limits import BOTH, LIMIT_STATES
from audit.engine.shared.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_RESTITUTION,
                                   DEFAULT_RISK_TARGET)
from audit.engine.shared.intensity import IntensityMeasure
from audit.errors import InputError
from audit.physics.block import Restitution

#: The fields :meth:`CheckSettings.parse` takes, and their defaults (``im``: None, the hazard
#: curve's IMT, else ``DEFAULT_IM``).
CHECK_DEFAULTS = {"im": None, "restitution": DEFAULT_RESTITUTION,
                  "free_motion_s": DEFAULT_FREE_MOTION_S, "g": G, "seed": None,
                  "hazard": None, "site_location": None, "risk_target": DEFAULT_RISK_TARGET,
                  "hazard_imt": None, "return_period": None, "poe": None, "friction": None,
                  "limit_state": BOTH, "guideline_spectrum": GROUND}
CHECK_FIELDS = tuple(CHECK_DEFAULTS)


@dataclass(frozen=True)
class CheckSettings:
    """What a check computes, for any objects at any site.

    Attributes
    ----------
    im : IntensityMeasure
        PGA or S_a(T): the site's intensity is read from its design spectrum.
    restitution : Restitution
    free_motion_s, g : float
        Free motion after each record [s]; gravity [m/s²].
    seed : int or None
        Seed of the bootstrap over records (its default when None).
    hazard : records.hazard.HazardCurve or None
        The site's hazard curve: each object's annual rate of overturning, the risk of the
        object as each guideline would size it, and the exact width for ``risk_target``.
    risk_target : float
        Probability of overturning in 50 years [-].
    site_return_period_years : float or None
        With a hazard curve: the return period whose intensity on the curve is the site's for
        the exact answer (:mod:`audit.engine.check.site`); None: the design spectrum's.
    friction : float or None
        Friction coefficient μ of the object's base [-]: which mode governs, sliding or rocking
        (:mod:`audit.engine.check.sliding`); None: no sliding assumed.
    limit_state : str
        The limit state the site's S_XS, S_X1 are for, of a guideline that names its own
        (NTC 2018): ``SLV``, ``SLC`` or ``both`` (each reported).
    guideline_spectrum : str
        On a floor, the spectrum a guideline reading the site's design spectrum (FEMA 356)
        reads: ``ground`` (as written) or ``floor``
        (:mod:`audit.engine.check.spectrum_read`).

    Build it with :meth:`parse`, which checks every field once.
    """

    im: IntensityMeasure
    restitution: Restitution
    free_motion_s: float
    g: float
    seed: int | None = None
    hazard: object = None
    risk_target: float = DEFAULT_RISK_TARGET
    site_return_period_years: float | None = None
    friction: float | None = None
    limit_state: str = BOTH
    guideline_spectrum: str = GROUND

    @classmethod
    def parse(cls, **values) -> CheckSettings:
        """The settings of the given fields, each checked once (InputError naming the field).

        Parameters
        ----------
        im : str or IntensityMeasure
            ``pga`` or ``sa:T`` (a design spectrum gives no PGV).
        restitution : str, float or Restitution
        free_motion_s, g : float
        seed : int, optional
        hazard : records.hazard.HazardCurve, str or pathlib.Path, optional
            A hazard curve or its file (OpenQuake, USGS or plain CSV); its IMT sets ``im``
            when ``im`` is not given, and must be ``im`` when it is.
        site_location : (float, float), optional
            Longitude, latitude [degrees] of the site in a hazard file of several sites.
        risk_target : float or str
            In (0, 1): 0.02 or '2%'.
        hazard_imt : str, optional
            The IMT of a hazard file of several (``PGA``, ``SA(1.0)``); without it, ``im``'s.
        return_period : float, optional
            Years: the site's intensity for the exact answer is the hazard curve's at this
            return period (log–log interpolation), not the design spectrum's.
        poe : float or str, optional
            The same as a probability of exceedance in 50 years (0.02 or '2%').
        friction : float, optional
            Friction coefficient μ > 0 of the object's base.
        limit_state : str
            ``SLV``, ``SLC`` or ``both`` (any case).
        guideline_spectrum : str
            ``ground`` or ``floor``.
        """
        check.unknown("the check", values, CHECK_FIELDS)
        value = {**CHECK_DEFAULTS, **values}
        im = value["im"]
        if value["site_location"] is not None and value["hazard"] is None:
            raise InputError("site_location: a site of the hazard file; no hazard given",
                             "site_location")
        for field in ("hazard_imt", "return_period", "poe"):
            if value[field] is not None and value["hazard"] is None:
                raise InputError(f"{field}: read on the hazard curve; no hazard given", field)
        risk_target = check.probability("risk_target", value["risk_target"])
        hazard = value["hazard"]
        if not isinstance(im, (str, IntensityMeasure, type(None))):
            IntensityMeasure.parse(im)  # refused, naming im
        location = (None if value["site_location"] is None
                    else check.lon_lat("site_location", value["site_location"]))
        if hazard is not None:  # read and checked before any work
            from audit.engine.design.risk import site_hazard
            hazard, im = site_hazard(hazard, location, risk_target, im, value["hazard_imt"])
        im = DEFAULT_IM if im is None else im
        friction = value["friction"]
        if friction is not None:
            friction = check.number("friction", friction, "a positive friction coefficient μ",
                                    0, low_open=True)
        im = im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im)
        if im.kind == "pgv":
            raise InputError("im: a design spectrum gives no PGV; choose pga or sa:T", "im")
        seed = value["seed"]
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)
                                 or seed < 0):
            raise InputError(f"seed: expected a whole number ≥ 0, got {seed!r}", "seed")
        limit_state = value["limit_state"]
        choices = (*LIMIT_STATES, BOTH)
        if not isinstance(limit_state, str) or limit_state.upper() not in (
                c.upper() for c in choices):
            raise InputError(f"limit_state: expected {', '.join(choices)}, got {limit_state!r}",
                             "limit_state")
        limit_state = limit_state.upper() if limit_state.upper() in LIMIT_STATES else BOTH
        spectrum = value["guideline_spectrum"]
        if spectrum not in GUIDELINE_SPECTRA:
            raise InputError(f"guideline_spectrum: expected {' or '.join(GUIDELINE_SPECTRA)}, "
                             f"got {spectrum!r}", "guideline_spectrum")
        return_period_years = site_return_period(value["return_period"], value["poe"])
        if return_period_years is not None:  # on the curve, or refused naming what was given
            hazard.im_at_rate(1.0 / return_period_years,
                              "return_period" if value["poe"] is None else "poe")
        return cls(
            im=im,
            restitution=(value["restitution"] if isinstance(value["restitution"], Restitution)
                         else Restitution.parse(value["restitution"], "restitution")),
            free_motion_s=check.number("free_motion_s", value["free_motion_s"],
                                       "a duration ≥ 0 s", 0),
            g=check.number("g", value["g"], "a positive acceleration in m/s²", 0, low_open=True),
            seed=seed, hazard=hazard, risk_target=risk_target,
            site_return_period_years=return_period_years,
            friction=friction, limit_state=limit_state, guideline_spectrum=spectrum)


def site_return_period(return_period, poe) -> float | None:
    """The return period [years] of ``return_period`` or ``poe`` (in 50 years, Poisson:
    T = −50 / ln(1 − P)), at most one of them given; None when neither is.

    Parameters
    ----------
    return_period : float or None
        Return period of the site's hazard level [years].
    poe : float or str or None
        Its probability of exceedance in 50 years (``0.1`` or ``"10%"``) [-].
    """
    if return_period is not None and poe is not None:
        raise InputError("return_period and poe: give one of them (both say the site's "
                         "hazard level)", "return_period", "poe")
    if poe is not None:
        from audit.engine.design.risk import YEARS
        return -YEARS / math.log1p(-check.probability("poe", poe))
    if return_period is not None:
        return check.number("return_period", return_period, "a return period > 1 year", 1,
                            low_open=True)
    return None


__all__ = ["CheckSettings", "CHECK_DEFAULTS", "CHECK_FIELDS"]
