"""ASCE/SEI 7-22 §13.3.1: the horizontal seismic design force on a nonstructural component.

Clause followed, known second-hand: the standard's text could not be read here; the equations are
as a public calculator (fendysetiawan/FpCalcApp, ``fpcalc.py``) and third-party notes give them,
and they agree with each other:

* F_p/W_p = 0.4·S_DS·I_p·(H_f/R_μ)·(C_AR/R_po)                                    (Eq. 13.3-1)
  within 0.3·S_DS·I_p and 1.6·S_DS·I_p                                         (Eqs. 13.3-2, -3)
* H_f = 1 + a1·(z/h) + a2·(z/h)^10, a1 = 1/T_a ≤ 2.5, a2 = 1 − (0.4/T_a)² ≥ 0         (Eq. 13.3-4)
  and H_f = 1 + 2.5·(z/h) where T_a is not known                                    (Eq. 13.3-5)
* R_μ = √(1.1·R/(I_e·Ω0)) ≥ 1.3                                                      (Eq. 13.3-6)

T_a in H_f is the *supporting building's* approximate fundamental period (§12.8.2.1, the
calculator computes it as C_t·h_n^x, Eq. 12.8-7), not the component's (the component's own
dynamics enter through C_AR only): here the building's T1 of the floor settings stands for it. On the roof of a T1 = 1 s building H_f = 1 + 1 + 0.84 = 2.84.

An unanchored object is checked for overturning with the strength combination 0.9D + 1.0E of
§2.3.6, E = E_h − E_v with the concurrent vertical force E_v = 0.2·S_DS·D (§12.4.2.2, and
±0.2·S_DS·W_p for components, §13.3.1.2, also second-hand): F_p·h_cm ≤ (0.9 − 0.2·S_DS)·W·b.
``vertical_coefficient = 0`` drops E_v (the F_p·h_cm ≤ 0.9·W·b often quoted).

Verified against a worked example computed by hand in ``tests/procedures/test_component_provisions.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from audit.physics.building.floor import Floor
from procedures.component import ComponentProvision, ComponentSite


@dataclass(frozen=True)
class ASCE722(ComponentProvision):
    """ASCE 7-22 §13.3 for an unanchored rigid cabinet, with its settings.

    Attributes
    ----------
    importance : float
        I_p, the component importance factor [-] (§13.1.3: 1.0 unless life-safety, 1.5).
    resonance : float
        C_AR, the component resonance ductility factor [-]: 1.0, a rigid component (no
        resonance with the floor), as Tables 13.5-1 and 13.6-1 give rigid items.
    strength : float
        R_po, the component strength factor [-]: 1.5, the lowest value of the tables, taken for
        a cabinet with no anchorage ductility (second-hand; choose the table's row).
    building_r, building_omega0, building_importance : float
        R, Ω0 and I_e of the supporting building [-]: a special steel moment frame (R = 8,
        Ω0 = 3, Table 12.2-1) with I_e = 1, matching the default moment-frame building model.
    period_known : bool
        Use the building's T1 in H_f (Eq. 13.3-4); False takes Eq. 13.3-5.
    vertical_coefficient : float
        E_v/(S_DS·D) in 0.9D + 1.0E [-]: 0.2 (§12.4.2.2); 0 leaves E_v out.
    """

    importance: float = 1.0
    resonance: float = 1.0
    strength: float = 1.5
    building_r: float = 8.0
    building_omega0: float = 3.0
    building_importance: float = 1.0
    period_known: bool = True
    vertical_coefficient: float = 0.2

    name = "asce7_22"
    title = "ASCE 7-22 §13.3"
    reference = "ASCE/SEI 7-22 §13.3.1, Eqs. 13.3-1 to 13.3-6; 0.9D + 1.0E (§2.3.6)"
    requires = ("s_ds_g", "z_over_h", "building_period_s")

    def height_factor(self, z_over_h: float, building_period_s: float | None) -> float:
        """H_f [-]: Eq. 13.3-4 with T_a = T1 of the building [s], Eq. 13.3-5 without it."""
        if building_period_s is None or not self.period_known:
            return 1.0 + 2.5 * z_over_h
        a1 = min(1.0 / building_period_s, 2.5)
        a2 = max(1.0 - (0.4 / building_period_s) ** 2, 0.0)
        return 1.0 + a1 * z_over_h + a2 * z_over_h ** 10

    def ductility_reduction(self) -> float:
        """R_μ = √(1.1·R/(I_e·Ω0)) ≥ 1.3 [-] (Eq. 13.3-6)."""
        return max(math.sqrt(1.1 * self.building_r
                             / (self.building_importance * self.building_omega0)), 1.3)

    def force_over_weight(self, site: ComponentSite, floor: Floor):
        """F_p/W_p [g] (Eqs. 13.3-1 to 13.3-3) and its factors."""
        h_f = self.height_factor(floor.z_over_h, floor.building_period_s)
        r_mu = self.ductility_reduction()
        base = site.s_ds_g * self.importance
        force = 0.4 * base * (h_f / r_mu) * (self.resonance / self.strength)
        return (min(max(force, 0.3 * base), 1.6 * base),
                {"H_f": h_f, "R_mu": r_mu, "C_AR": self.resonance, "R_po": self.strength,
                 "I_p": self.importance})

    def restoring_factor(self, site: ComponentSite) -> float:
        """0.9 − 0.2·S_DS [-]: the dead load of 0.9D + 1.0E less the vertical E_v."""
        return 0.9 - self.vertical_coefficient * site.s_ds_g
