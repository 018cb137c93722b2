"""What ``audit check`` computes (:mod:`audit.engine.check`), checked once."""

from __future__ import annotations

from dataclasses import dataclass

from audit import G
from audit.engine import fields as check
from audit.engine.check_limits import BOTH, LIMIT_STATES
from audit.engine.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_RESTITUTION,
                                   DEFAULT_RISK_TARGET)
from audit.engine.intensity import IntensityMeasure
from audit.errors import InputError
from audit.physics.block import Restitution

#: The fields :meth:`CheckSettings.parse` takes, and their defaults.
CHECK_DEFAULTS = {"im": DEFAULT_IM, "restitution": DEFAULT_RESTITUTION,
                  "free_motion_s": DEFAULT_FREE_MOTION_S, "g": G, "seed": None,
                  "hazard": None, "site_location": None, "risk_target": DEFAULT_RISK_TARGET,
                  "limit_state": BOTH}
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
    limit_state : str
        The limit state the site's S_XS, S_X1 are for, of a guideline that names its own
        (NTC 2018): ``SLV``, ``SLC`` or ``both`` (each reported).

    Build it with :meth:`parse`, which checks every field once.
    """

    im: IntensityMeasure
    restitution: Restitution
    free_motion_s: float
    g: float
    seed: int | None = None
    hazard: object = None
    risk_target: float = DEFAULT_RISK_TARGET
    limit_state: str = BOTH

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
        limit_state : str
            ``SLV``, ``SLC`` or ``both`` (any case).
        """
        check.unknown("the check", values, CHECK_FIELDS)
        value = {**CHECK_DEFAULTS, **values}
        im = value["im"]
        if value["site_location"] is not None and value["hazard"] is None:
            raise InputError("site_location: a site of the hazard file; no hazard given",
                             "site_location")
        hazard = value["hazard"]
        if hazard is not None:  # read and checked before any work
            from audit.engine.risk import site_hazard
            hazard, im = site_hazard(hazard, value["site_location"], value["risk_target"],
                                     im if "im" in values else None)
        im = im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im)
        if im.kind == "pgv":
            raise InputError("im: a design spectrum gives no PGV; choose pga or sa:T", "im")
        seed = value["seed"]
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int)
                                 or seed < 0):
            raise InputError(f"seed: expected a whole number ≥ 0, got {seed!r}", "seed")
        limit_state = value["limit_state"]
        choices = (*LIMIT_STATES, BOTH)
        if not isinstance(limit_state, str) or limit_state.upper() not in (
                c.upper() for c in choices):
            raise InputError(f"limit_state: expected {', '.join(choices)}, got {limit_state!r}",
                             "limit_state")
        limit_state = limit_state.upper() if limit_state.upper() in LIMIT_STATES else BOTH
        return cls(
            im=im,
            restitution=(value["restitution"] if isinstance(value["restitution"], Restitution)
                         else Restitution.parse(value["restitution"], "restitution")),
            free_motion_s=check.number("free_motion_s", value["free_motion_s"],
                                       "a duration ≥ 0 s", 0),
            g=check.number("g", value["g"], "a positive acceleration in m/s²", 0, low_open=True),
            seed=seed, hazard=hazard, risk_target=float(value["risk_target"]),
            limit_state=limit_state)


__all__ = ["CheckSettings", "CHECK_DEFAULTS", "CHECK_FIELDS"]
