"""What ``audit check`` computes (:mod:`audit.engine.check.pipeline`), checked once."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

from audit.engine.shared import fields as check
from audit.engine.check.spectrum_read import GROUND, GUIDELINE_SPECTRA
from audit.engine.shared.defaults import BOTH, DEFAULT_IM, DEFAULT_RISK_TARGET
from audit.engine.shared.intensity import IntensityMeasure
from audit.errors import InputError
from audit.physics.block import Restitution


@dataclass(frozen=True)
class CheckSettings:
    """What a check computes, for any objects at any site.

    Build it with :meth:`parse`, which checks every field once.

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
    mass_kg : float or None
        Each object's mass [kg]: the anchorage forces of the component provisions it fails
        also in kN (:mod:`audit.engine.check.component_checks`).
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
    mass_kg: float | None = None

    @classmethod
    def parse(cls, *, im=None, solver=None, seed: int | None = None, hazard=None,
              friction: float | None = None, limit_state: str = BOTH,
              guideline_spectrum: str = GROUND, mass_kg: float | None = None) -> CheckSettings:
        """The settings of the given fields, each checked once (InputError naming the
        argument, or the group's field: ``solver.g``, ``hazard.poe``).

        Parameters
        ----------
        im : str or IntensityMeasure, optional
            ``pga`` or ``sa:T`` (a design spectrum gives no PGV); default the hazard curve's
            IMT, else ``DEFAULT_IM``.
        solver : audit.engine.shared.solver.Solver, optional
            The exact solver's impact model, free motion and g (:meth:`Solver.parse
            <audit.engine.shared.solver.Solver.parse>`; ``vertical`` refused).
        seed : int, optional
        hazard : audit.engine.shared.hazard.Hazard, records.hazard.HazardCurve, str or path
            The site's hazard (:meth:`Hazard.parse <audit.engine.shared.hazard.Hazard.parse>`):
            its curve's IMT sets ``im`` when ``im`` is not given, and must be ``im`` when it
            is; its ``return_period`` or ``poe`` the site's intensity for the exact answer
            (log–log interpolation on the curve), not the design spectrum's.
        friction : float, optional
            Friction coefficient μ > 0 of the object's base.
        limit_state : str
            ``SLV``, ``SLC`` or ``both`` (any case), the site's (``site.limit_state``).
        guideline_spectrum : str
            ``ground`` or ``floor``.
        mass_kg : float, optional
            Each object's mass [kg], > 0.
        """
        from audit.engine.shared.design_site import limit_state_of
        from audit.engine.shared.hazard import Hazard
        from audit.engine.shared.solver import Solver
        hazard = Hazard.parse(hazard, "check")
        risk_target = DEFAULT_RISK_TARGET if hazard is None else hazard.risk_target
        if hazard is not None and hazard.curve is None:
            hazard = None  # a risk target alone: no curve to read it on
        if not isinstance(im, (str, IntensityMeasure, type(None))):
            IntensityMeasure.parse(im)  # refused, naming im
        curve = None
        if hazard is not None:  # read and checked before any work
            from audit.engine.design.risk import site_hazard
            curve, im = site_hazard(hazard, im)
        im = DEFAULT_IM if im is None else im
        if friction is not None:
            friction = check.number("friction", friction, "a positive friction coefficient μ",
                                    0, low_open=True)
        im = im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im)
        if im.kind == "pgv":
            raise InputError("im: a design spectrum gives no PGV; choose pga or sa:T", "im")
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)
                                 or seed < 0):
            raise InputError(f"seed: expected a whole number ≥ 0, got {seed!r}", "seed")
        limit_state = limit_state_of(limit_state, "site.limit_state")
        if guideline_spectrum not in GUIDELINE_SPECTRA:
            raise InputError(f"guideline_spectrum: expected {' or '.join(GUIDELINE_SPECTRA)}, "
                             f"got {guideline_spectrum!r}", "guideline_spectrum")
        return_period_years = None if hazard is None else site_return_period(hazard)
        if return_period_years is not None:  # on the curve, or refused naming what was given
            curve.im_at_rate(1.0 / return_period_years,
                             "hazard.return_period" if hazard.poe is None else "hazard.poe")
        if mass_kg is not None:
            mass_kg = check.number("mass_kg", mass_kg, "a positive mass in kg", 0,
                                   low_open=True)
        solver = Solver.parse(solver, "check")
        return cls(im=im, restitution=solver.restitution, free_motion_s=solver.free_motion_s,
                   g=solver.g, seed=seed, hazard=curve,
                   risk_target=risk_target,
                   site_return_period_years=return_period_years, friction=friction,
                   limit_state=limit_state, guideline_spectrum=guideline_spectrum,
                   mass_kg=mass_kg)


def site_return_period(hazard) -> float | None:
    """The return period [years] of the hazard's ``return_period`` or ``poe`` (in 50 years,
    Poisson: T = −50 / ln(1 − P)), as :meth:`Hazard.parse
    <audit.engine.shared.hazard.Hazard.parse>` checked them; None when neither is given.

    Parameters
    ----------
    hazard : audit.engine.shared.hazard.Hazard
        Parsed.
    """
    if hazard.poe is not None:
        from audit.engine.design.risk import YEARS
        return -YEARS / math.log1p(-hazard.poe)
    return hazard.return_period


__all__ = ["CheckSettings", "site_return_period"]
