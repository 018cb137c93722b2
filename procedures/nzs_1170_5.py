"""NZS 1170.5:2004 Section 8: the design actions on parts and components.

Clause followed, known second-hand: the standard's text could not be read here; the equations
are as a public VBA module and its notes (engineervsheep.com, "Functions for calculating the New
Zealand seismic 'Parts' coefficient", 2021) and a forum thread on the draft's §8.3 give them:

* F_ph = C_p(T_p)·C_ph·R_p·W_p ≤ 3.6·W_p                                              (Eq. 8.5(1))
* C_p(T_p) = C(0)·C_Hi·C_i(T_p)                                                        (Eq. 8.2(1))
* C_Hi = 1 + h_i/6 (h_i < 12 m), 1 + 10·h_i/h_n (h_i < 0.2·h_n), 3.0 (h_i ≥ 0.2·h_n)   (§8.3)
  — read here, as the final text is reported to say, as: below 12 m the lesser of the first
  and whichever of the other two applies; h_i, h_n in metres
* C_i(T_p) = 2.0 (T_p ≤ 0.75 s), 2·(1.75 − T_p) (0.75–1.5 s), 0.5 (T_p ≥ 1.5 s)        (§8.4)

C(0) is the site's elastic spectrum at T = 0 (§3.1.1), C_ph the part response factor (Table
8.2: 1.0 for a part of ductility μ_p = 1), R_p the part risk factor (Table 8.1). C_Hi needs the
heights in metres where the floor settings give z/H and T1: h_i = (z/H)·h_n with h_n the
parameter ``h_n`` (the building's height), by default estimated from T1 as ten 3.5 m storeys per
second (the rule T1 ≈ 0.1 s per storey, an assumption).

An unanchored part is checked for overturning, a check of stability: AS/NZS 1170.0 §4.2.1(a)
takes the stabilising permanent action at 0.9G (as a structural-software vendor's documentation
of the clause gives it, second-hand) against the destabilising E_u: F_ph·h_cm ≤ 0.9·W_p·b (the
parameter ``k``; 1.0 is the strength combination G + E_u of §4.2.2).

Verified against a worked example computed by hand in ``tests/procedures/test_component_provisions.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

from audit.physics.building.floor import Floor
from procedures.component import ComponentProvision, ComponentSite
from procedures.parameters import Parameter

#: h_n per second of T1 when the building's height is not given [m/s]: 10 storeys of 3.5 m.
HEIGHT_PER_PERIOD_M_S = 35.0
#: The cap of C_p·C_ph·R_p (Eq. 8.5(1)) [-].
CAP = 3.6


@dataclass(frozen=True)
class NZS11705(ComponentProvision):
    """NZS 1170.5 Section 8 for an unanchored rigid cabinet, with its settings (see
    :attr:`parameters` for each one's key, range and the clause of its default).

    Attributes
    ----------
    part_response : float
        C_ph [-].
    risk : float
        R_p [-].
    object_period_s : float
        T_p [s].
    building_height_m : float or None
        h_n [m]; None estimates it as 35 m per second of T1.
    stabilising : float
        k, the factor on G that resists overturning [-].
    """

    part_response: float = 1.0
    risk: float = 1.0
    object_period_s: float = 0.0
    building_height_m: float | None = None
    stabilising: float = 0.9

    name = "nzs1170_5"
    title = "NZS 1170.5 §8"
    reference = ("NZS 1170.5:2004 §8.2–8.5, Eqs. 8.2(1), 8.3, 8.5(1); stability 0.9G "
                 "(AS/NZS 1170.0 §4.2.1)")
    requires = ("c0_g", "z_over_h", "building_period_s", "object_period_s")
    parameters = (
        Parameter("h_n", "building_height_m", "m", "height of the building",
                  "estimated from T1 as 35 m per second (ten 3.5 m storeys)",
                  False, 0.0, 1000.0, low_open=True,
                  words=(("estimate", None, "35 m per second of T1"),)),
        Parameter("R_p", "risk", "-", "part risk factor",
                  "Table 8.1, parts not in the life-safety or essential categories: 1.0", True,
                  0.0, 2.0, low_open=True),
        Parameter("C_ph", "part_response", "-", "part response factor",
                  "Table 8.2, ductility μ_p = 1 (a rocking block dissipates nothing before it "
                  "overturns): 1.0", True, 0.0, 1.0, low_open=True),
        Parameter("T_p", "object_period_s", "s", "period of the part in C_i(T_p)",
                  "a rigid block before it rocks (0)", False, 0.0, 10.0),
        Parameter("k", "stabilising", "-", "factor on G resisting overturning",
                  "AS/NZS 1170.0 §4.2.1(a), stability: stabilising 0.9G", True, 0.0, 1.0,
                  low_open=True),
    )

    def height_coefficient(self, height_m: float, building_height_m: float) -> float:
        """C_Hi [-] of §8.3 at h_i = ``height_m`` in a building h_n = ``building_height_m`` [m]."""
        tall = 1.0 + 10.0 * height_m / building_height_m if height_m < 0.2 * building_height_m \
            else 3.0
        return min(1.0 + height_m / 6.0, tall) if height_m < 12.0 else tall

    def spectral_shape(self) -> float:
        """C_i(T_p) [-] of §8.4."""
        t_p = self.object_period_s
        return 2.0 if t_p <= 0.75 else (2.0 * (1.75 - t_p) if t_p < 1.5 else 0.5)

    def force_over_weight(self, site: ComponentSite, floor: Floor):
        """F_ph/W_p [g] (Eqs. 8.2(1), 8.5(1)) and its factors."""
        if floor.on_ground:
            c_hi = 1.0
        else:
            building_m = (self.building_height_m if self.building_height_m is not None
                          else HEIGHT_PER_PERIOD_M_S * floor.building.period_s)
            c_hi = self.height_coefficient(floor.z_over_h * building_m, building_m)
        c_i = self.spectral_shape()
        return (min(site.c0_g * c_hi * c_i * self.part_response * self.risk, CAP),
                {"C_Hi": c_hi, "C_i": c_i, "C_ph": self.part_response, "R_p": self.risk})

    def restoring_factor(self, site: ComponentSite) -> float:
        """k [-]: 0.9, the stabilising G of AS/NZS 1170.0 §4.2.1(a)."""
        return self.stabilising
