"""The site's hazard as a command is given it: the curve (or its file) and how it is read,
checked once (:class:`Hazard`). The curve itself is read where the intensity measure is known
(:func:`audit.engine.design.risk.site_hazard`). Light: no scientific import."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import DEFAULT_RISK_TARGET
from audit.errors import InputError

#: The fields of a :class:`Hazard` only some commands read; another command refuses them set.
HAZARD_READS = {"return_period": ("check",), "poe": ("check",)}


@dataclass(frozen=True)
class Hazard:
    """The site's hazard curve and how it is read.

    :meth:`parse` checks every field once and takes the shorthand of a curve or its file alone.

    Attributes
    ----------
    curve : records.hazard.HazardCurve, str, pathlib.Path or None
        The curve, or its file (OpenQuake, USGS or plain CSV); None: no curve (the risk
        target alone is checked, and unused).
    imt : str or None
        The IMT of a hazard file of several (``"SA(1.0)"``, ``"PGA"``); without it, the
        command's intensity measure's.
    location : (float, float) or None
        Longitude, latitude [degrees] of the site in a hazard file of several sites (west and
        south negative; :meth:`parse` takes ``"-118,34"`` too).
    return_period : float or None
        ``check``: the site's intensity for the exact answer is the curve's at this return
        period [years], not the design spectrum's.
    poe : float, str or None
        ``check``: the same as a probability of exceedance in 50 years (0.02 or ``"2%"``).
    risk_target : float or str
        Probability of overturning in 50 years the risk-targeted size meets [-], in (0, 1):
        0.01 or ``"1%"``.
    """

    curve: object = None
    imt: str | None = None
    location: tuple | str | None = None
    return_period: float | None = None
    poe: float | str | None = None
    risk_target: float | str = DEFAULT_RISK_TARGET

    @classmethod
    def parse(cls, value, command: str | None = None, argument: str = "hazard") -> Hazard | None:
        """The hazard of ``value``, every field checked once (InputError naming
        ``argument.field``); the curve's file is read later, with the intensity measure.

        Parameters
        ----------
        value : Hazard, records.hazard.HazardCurve, str, pathlib.Path or None
            A Hazard, or its shorthand: the curve or its file alone; None: no hazard.
        command : {"check", "margins"}, optional
            The command reading it: a field it does not read (:data:`HAZARD_READS`), set, is
            refused naming it. None: every field read.
        argument : str
            The argument the hazard was given as, for the messages.
        """
        if value is None:
            return None
        if not isinstance(value, Hazard):
            if not isinstance(value, (str, Path)) and not hasattr(value, "annual_rate"):
                raise InputError(f"{argument}: expected a Hazard, a HazardCurve or its file, got "
                                 f"{value!r}", argument)
            value = cls(value)
        for field, readers in HAZARD_READS.items():
            if command is not None and command not in readers \
                    and getattr(value, field) is not None:
                raise InputError(f"{argument}.{field}: {' and '.join(readers)} only",
                                 f"{argument}.{field}")
        curve = value.curve
        if curve is not None and isinstance(curve, (str, Path)):
            curve = check.path(f"{argument}.curve", curve, "a hazard curve or its file")
        elif curve is not None and not hasattr(curve, "annual_rate"):
            raise InputError(f"{argument}.curve: expected a HazardCurve or its file, got "
                             f"{curve!r}", f"{argument}.curve")
        for field in ("location", "imt", "return_period", "poe"):
            if getattr(value, field) is not None and curve is None:
                raise InputError(f"{argument}.{field}: read on the hazard curve; no curve given",
                                 f"{argument}.{field}")
        imt = value.imt
        if imt is not None and not isinstance(imt, str):
            raise InputError(f"{argument}.imt: expected an IMT of the hazard file (PGA, "
                             f"SA(1.0)), got {imt!r}", f"{argument}.imt")
        location = (None if value.location is None
                    else check.lon_lat(f"{argument}.location", value.location))
        if value.return_period is not None and value.poe is not None:
            raise InputError(f"{argument}.return_period and {argument}.poe: give one of them "
                             "(both say the site's hazard level)", f"{argument}.return_period",
                             f"{argument}.poe")
        return_period = (None if value.return_period is None else check.number(
            f"{argument}.return_period", value.return_period, "a return period > 1 year", 1,
            low_open=True))
        poe = None if value.poe is None else check.probability(f"{argument}.poe", value.poe)
        return cls(curve, imt, location, return_period, poe,
                   check.probability(f"{argument}.risk_target", value.risk_target))


__all__ = ["Hazard", "HAZARD_READS"]
