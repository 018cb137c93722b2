"""What ``audit check`` computes (:mod:`audit.engine.check`), checked once."""

from __future__ import annotations

from dataclasses import dataclass

from audit import G
from audit.engine import fields as check
from audit.engine.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_RESTITUTION,
                                   DEFAULT_RISK_TARGET)
from audit.engine.intensity import IntensityMeasure
from audit.errors import InputError
from audit.physics.block import Restitution

#: The fields :meth:`CheckSettings.parse` takes, and their defaults (``im``: None, the hazard
#: curve's IMT, else ``DEFAULT_IM``).
CHECK_DEFAULTS = {"im": None, "restitution": DEFAULT_RESTITUTION,
                  "free_motion_s": DEFAULT_FREE_MOTION_S, "g": G, "seed": None,
                  "hazard": None, "site_location": None, "risk_target": DEFAULT_RISK_TARGET}
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

    Build it with :meth:`parse`, which checks every field once.
    """

    im: IntensityMeasure
    restitution: Restitution
    free_motion_s: float
    g: float
    seed: int | None = None
    hazard: object = None
    risk_target: float = DEFAULT_RISK_TARGET

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
        risk_target : float
            In (0, 1).
        """
        check.unknown("the check", values, CHECK_FIELDS)
        value = {**CHECK_DEFAULTS, **values}
        im = value["im"]
        risk_target = check.number("risk_target", value["risk_target"],
                                   "a probability in 50 years in (0, 1)", 0, 1, low_open=True,
                                   high_open=True)
        if value["site_location"] is not None and value["hazard"] is None:
            raise InputError("site_location: a site of the hazard file; no hazard given",
                             "site_location")
        hazard = value["hazard"]
        if not isinstance(im, (str, IntensityMeasure, type(None))):
            IntensityMeasure.parse(im)  # refused, naming im
        if hazard is not None:  # read and checked before any work
            from audit.engine.risk import site_hazard
            hazard, im = site_hazard(hazard, value["site_location"], risk_target, im)
        im = DEFAULT_IM if im is None else im
        im = im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im)
        if im.kind == "pgv":
            raise InputError("im: a design spectrum gives no PGV; choose pga or sa:T", "im")
        seed = value["seed"]
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int)
                                 or seed < 0):
            raise InputError(f"seed: expected a whole number ≥ 0, got {seed!r}", "seed")
        return cls(
            im=im,
            restitution=(value["restitution"] if isinstance(value["restitution"], Restitution)
                         else Restitution.parse(value["restitution"], "restitution")),
            free_motion_s=check.number("free_motion_s", value["free_motion_s"],
                                       "a duration ≥ 0 s", 0),
            g=check.number("g", value["g"], "a positive acceleration in m/s²", 0, low_open=True),
            seed=seed, hazard=hazard, risk_target=risk_target)


__all__ = ["CheckSettings", "CHECK_DEFAULTS", "CHECK_FIELDS"]
