"""The contract of a component provision: a code's static force on an object standing on a floor.

The building codes design a component on a floor (cabinet, rack, vitrine, equipment) for a static
horizontal force F = (F/W)·W that grows with the floor's height. A component provision is a small
class, in the manner of OpenQuake hazardlib's GSIMs, that *declares* what it requires
(:attr:`ComponentProvision.requires`, names from :data:`REQUIREMENTS`) and implements only its
code's force coefficient (:meth:`ComponentProvision.force_over_weight`) and the share of the
weight its load combination lets resist overturning (:meth:`ComponentProvision.restoring_factor`).
The base class turns these into the static overturning check of the unanchored object
(:meth:`ComponentProvision.check`): the overturning moment F·h_cm about an edge of the base
against the restoring moment k·W·b, i.e. per unit weight

    F/W ≤ k·b/h  (b, h: half width and half height of the block, centre of mass at mid-height),

with the force per unit weight the anchorage would have to resist where the object fails: the
shear F/W, times Ω0p where the code asks for it (:meth:`ComponentProvision.anchorage_overstrength`),
and the tension of a line of anchors along the far edge of the base, lever arm the full width 2b,
from the moment the weight does not resist: T/W = (F/W·h − k·b)/(2b).

Each provision declares its settable parameters (:mod:`procedures.parameters`), checked when
it is constructed.

The site reaches every code in its own terms through :class:`ComponentSite`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from audit.errors import InputError
from audit.physics.building.floor import Floor
from procedures.parameters import Parameter, check_parameters

#: What a component provision may require, and what each name holds.
REQUIREMENTS = {
    "s_ds_g": "S_DS, the design short-period spectral acceleration of the site [g]",
    "ag_s_g": "a_g·S, the design peak ground acceleration times the soil factor [g]",
    "c0_g": "C(0), the site's elastic spectrum at T = 0 [g]",
    "z_over_h": "the floor's relative height z/H [-]",
    "building_period_s": "T1, the first-mode period of the building [s]",
    "object_period_s": "T_a, the object's own period [s] (0 for a rigid block)",
}

#: FEMA 356 Eq. 1-8 at T = 0: its spectrum starts at 0.4·S_XS (as ASCE 7's does at 0.4·S_DS).
FEMA356_PGA_OVER_SXS = 0.4


@dataclass(frozen=True)
class ComponentSite:
    """The design site in the inputs the component provisions take.

    The tool's sites are FEMA 356's (S_XS, S_X1 in g, BSE-1) and NTC 2018's (a_g, F0, T_C*,
    soil, topography). They map to the codes' inputs as follows (:meth:`from_design_site`):

    * S_DS (ASCE 7) = S_XS: both are the design short-period plateau of a 5 %-damped spectrum at
      two thirds of the MCE; with only an NTC site, its plateau a_g·S·F0.
    * a_g·S (EN 1998-1) = the NTC site's a_g·S_S·S_T where one is given (NTC 2018 §3.2.3.2
      mirrors EN 1998-1 §3.2.2.2), else the FEMA site's peak ground acceleration 0.4·S_XS.
    * C(0) (NZS 1170.5) = the FEMA site's peak ground acceleration 0.4·S_XS, else the NTC site's
      a_g·S.

    The NTC site's a_g, F0, T_C* are those of the limit state assessed (SLV: the design
    earthquake, as EN 1998-1's a_g is).

    Attributes
    ----------
    s_ds_g, ag_s_g, c0_g : float
        See :data:`REQUIREMENTS` [g].
    source : str
        Which of the tool's sites they come from, in words.
    read : dict
        For each of ``s_ds_g``, ``ag_s_g``, ``c0_g``: what it was read from, in words.
    """

    s_ds_g: float
    ag_s_g: float
    c0_g: float
    source: str
    read: dict

    @classmethod
    def from_design_site(cls, site=None, ntc_site=None) -> ComponentSite:
        """The codes' inputs of a FEMA 356 site ``(S_XS, S_X1)`` [g] and/or an NTC 2018 site
        ``(a_g, F0, T_C*, soil, topography)``; InputError naming ``site`` where neither is given."""
        from audit.physics.ntc2018_spectrum import NTC2018Spectrum
        ntc = NTC2018Spectrum(*ntc_site) if ntc_site is not None else None
        ntc_pga_g = ntc.ag_g * ntc.soil_factor if ntc is not None else math.nan
        ntc_words = (f"a_g·S = {ntc.ag_g:g} × {ntc.soil_factor:.4g} = {ntc_pga_g:.4g} g of the "
                     f"NTC 2018 site (S = S_S·S_T, soil {ntc.soil}, topography "
                     f"{ntc.topography})" if ntc is not None else "")
        if site is not None:
            s_xs = float(site[0])
            pga_g = FEMA356_PGA_OVER_SXS * s_xs
            fema_pga = f"0.4·S_XS = {pga_g:.4g} g of the FEMA 356 site"
            return cls(s_xs, ntc_pga_g if ntc is not None else pga_g, pga_g,
                       f"S_XS = {s_xs:g} g" + (" and the NTC 2018 site" if ntc else ""),
                       {"s_ds_g": f"S_DS = S_XS = {s_xs:g} g of the FEMA 356 site",
                        "ag_s_g": ntc_words or f"a_g·S = {fema_pga} (no NTC 2018 site)",
                        "c0_g": f"C(0) = {fema_pga}"})
        if ntc is not None:
            return cls(ntc_pga_g * ntc.f0, ntc_pga_g, ntc_pga_g, "the NTC 2018 site",
                       {"s_ds_g": f"S_DS = F0·a_g·S = {ntc.f0:g} × {ntc_pga_g:.4g} g, the "
                                  "plateau of the NTC 2018 site",
                        "ag_s_g": ntc_words, "c0_g": f"C(0) = {ntc_words}"})
        raise InputError("site: the component provisions need a design site (S_XS, S_X1) or an "
                         "NTC 2018 site", "site", "ntc_site")


@dataclass(frozen=True)
class ComponentCheck:
    """The static overturning check of one block by one component provision.

    Attributes
    ----------
    force_over_weight : float
        F/W, the code's horizontal design force per unit weight [g] (the demand).
    capacity_over_weight : float
        k·b/h, the largest F/W the restoring moment of the weight resists [g].
    factors : dict
        The named factors the code used (e.g. ``{"H_f": 2.84}``).
    basis : str
        How the verdict follows, in one sentence.
    restoring : float
        k, the share of the weight that resists overturning [-].
    width_m, height_m : float
        Full base width 2b and full height 2h of the block [m].
    overstrength : float or None
        Ω0p where the code amplifies the anchorage force of non-ductile anchors, else None.
    """

    force_over_weight: float
    capacity_over_weight: float
    factors: dict
    basis: str
    restoring: float = 1.0
    width_m: float = 2.0
    height_m: float = 2.0
    overstrength: float | None = None

    @property
    def passes(self) -> bool:
        return self.force_over_weight <= self.capacity_over_weight

    @property
    def anchorage_force_over_weight(self) -> float | None:
        """F/W the anchorage is designed for where the unanchored object fails, else None."""
        return None if self.passes else self.force_over_weight

    @property
    def anchorage(self) -> dict | None:
        """Where the unanchored object fails, the anchorage's forces per unit weight [g]:
        ``shear`` F/W and ``tension`` (F/W·h − k·b)/(2b) of a line of anchors along the far
        edge, each also times Ω0p (``shear_omega``, ``tension_omega``) where the code asks for
        it; else None."""
        if self.passes:
            return None
        b, h, force = self.width_m / 2.0, self.height_m / 2.0, self.force_over_weight
        forces = {"shear": force, "tension": (force * h - self.restoring * b) / (2.0 * b)}
        if self.overstrength is not None:
            forces.update(shear_omega=self.overstrength * forces["shear"],
                          tension_omega=(self.overstrength * force * h - self.restoring * b)
                          / (2.0 * b), omega_0p=self.overstrength)
        return forces


class ComponentProvision:
    """Base class of the component provisions: a code's static force on an object on a floor.

    A subclass declares ``name`` (its registry key), ``title``, ``reference`` and ``requires``
    (names from :data:`REQUIREMENTS`), holds its code's settings as dataclass fields with
    documented defaults for an unanchored rigid cabinet, and implements
    :meth:`force_over_weight` and :meth:`restoring_factor`.
    """

    name: ClassVar[str] = ""
    title: ClassVar[str] = ""
    reference: ClassVar[str] = ""
    requires: ClassVar[tuple[str, ...]] = ()
    #: The settable parameters (:class:`~procedures.parameters.Parameter`), checked when an
    #: instance is constructed.
    parameters: ClassVar[tuple[Parameter, ...]] = ()

    def __post_init__(self):
        check_parameters(self)

    def anchorage_overstrength(self) -> float | None:
        """Ω0p where the code amplifies the anchorage force of non-ductile anchors, else None."""
        return None

    def force_over_weight(self, site: ComponentSite, floor: Floor) -> tuple[float, dict]:
        """(F/W [g], the named factors used) of this code for an object on ``floor``."""
        raise NotImplementedError

    def restoring_factor(self, site: ComponentSite) -> float:
        """k, the share of the weight that resists overturning in this code's load combination
        [-]."""
        raise NotImplementedError

    def unmet_requirements(self, floor: Floor) -> str | None:
        """Why the code cannot be applied on ``floor`` (in words), or None."""
        return None

    def check(self, width_m: float, height_m: float, site: ComponentSite,
              floor: Floor) -> ComponentCheck:
        """The static overturning check of the unanchored block of full base width and full
        height ``width_m``, ``height_m`` [m] (b, h their halves) at ``site`` on ``floor``:
        F/W ≤ k·b/h."""
        force, factors = self.force_over_weight(site, floor)
        restoring = self.restoring_factor(site)
        capacity = restoring * (width_m / 2.0) / (height_m / 2.0)
        return ComponentCheck(force, capacity, factors,
                              f"F/W ≤ {restoring:.3g}·b/h: the overturning moment of the code's "
                              f"force about a base edge against the weight's restoring moment "
                              f"({self.reference})", restoring, width_m, height_m,
                              self.anchorage_overstrength())


__all__ = ["REQUIREMENTS", "ComponentSite", "ComponentCheck", "ComponentProvision"]
