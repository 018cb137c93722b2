"""ASCE/SEI 7-22 §13.3.1: the horizontal seismic design force on a nonstructural component.

Clause followed, known second-hand: the standard's text could not be read here; the equations are
as a public calculator (fendysetiawan/FpCalcApp, ``fpcalc.py``) and third-party notes give them,
and they agree with each other:

* F_p/W_p = 0.4·S_DS·I_p·(H_f/R_μ)·(C_AR/R_po)                                    (Eq. 13.3-1)
  within 0.3·S_DS·I_p and 1.6·S_DS·I_p                                         (Eqs. 13.3-2, -3)
* H_f = 1 + a1·(z/h) + a2·(z/h)^10, a1 = 1/T_a ≤ 2.5, a2 = 1 − (0.4/T_a)² ≥ 0         (Eq. 13.3-4)
  and H_f = 1 + 2.5·(z/h) where T_a is not known                                    (Eq. 13.3-5)
* R_μ = √(1.1·R/(I_e·Ω0)) ≥ 1.3                                                      (Eq. 13.3-6)
  — where the supporting structure's system is not known (Ω0 "unknown"), the bound 1.3, as the
  calculator takes it (an assumption: the standard's own words for that case were not read)
* the anchorage of a component in concrete or masonry whose anchors are not ductile is designed
  for Ω0p·F_p (§13.4.2, as a public note of an anchorage engineering firm gives it), Ω0p of
  Tables 13.5-1 and 13.6-1

Table 13.5-1's row 8a, "Cabinets: permanent floor-supported storage cabinets more than 6 ft
tall, including contents", gives C_AR = 1.0 (supported at or below grade and above it), R_po =
1.5 and Ω0p = 2.0, as the calculator's component table (``data/arch.json``) holds it: the
defaults below.

T_a in H_f is the *supporting building's* approximate fundamental period (§12.8.2.1, the
calculator computes it as C_t·h_n^x, Eq. 12.8-7), not the component's (the component's own
dynamics enter through C_AR only): by default the building's modal T1 of the floor settings
stands for it (parameter ``T_a``: a period in s, ``T1``, or ``unknown`` for Eq. 13.3-5). On the
roof of a T1 = 1 s building H_f = 1 + 1 + 0.84 = 2.84.

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
from procedures.parameters import Parameter

#: T_a's words: the building's modal T1 of the floor settings, or not known (Eq. 13.3-5).
MODAL_T1 = "T1"
UNKNOWN = "unknown"


@dataclass(frozen=True)
class ASCE722(ComponentProvision):
    """ASCE 7-22 §13.3 for an unanchored rigid cabinet, with its settings (see
    :attr:`parameters` for each one's key, range and the clause of its default).

    Attributes
    ----------
    importance : float
        I_p, the component importance factor [-].
    resonance : float
        C_AR, the component resonance ductility factor [-].
    strength : float
        R_po, the component strength factor [-].
    building_r, building_importance : float
        R and I_e of the supporting building [-].
    building_omega0 : float or None
        Ω0 of the supporting building [-]; None where its system is not known (R_μ = 1.3).
    approximate_period : float or str
        T_a of H_f: a period [s], ``"T1"`` (the building's modal T1) or ``"unknown"``.
    vertical_coefficient : float
        E_v/(S_DS·D) in 0.9D + 1.0E [-]: 0.2 (§12.4.2.2); 0 leaves E_v out.
    anchor_overstrength : float
        Ω0p, the anchorage's overstrength factor [-] (§13.4.2).
    """

    importance: float = 1.0
    resonance: float = 1.0
    strength: float = 1.5
    building_r: float = 8.0
    building_omega0: float | None = 3.0
    building_importance: float = 1.0
    approximate_period: float | str = MODAL_T1
    vertical_coefficient: float = 0.2
    anchor_overstrength: float = 2.0

    name = "asce7_22"
    title = "ASCE 7-22 §13.3"
    reference = "ASCE/SEI 7-22 §13.3.1, Eqs. 13.3-1 to 13.3-6; 0.9D + 1.0E (§2.3.6); §13.4.2"
    requires = ("s_ds_g", "z_over_h", "building_period_s")
    parameters = (
        Parameter("I_p", "importance", "-", "component importance factor",
                  "§13.1.3: 1.0 unless the component is needed for life safety (1.5)", True,
                  1.0, 1.5),
        Parameter("C_AR", "resonance", "-", "component resonance ductility factor",
                  "Table 13.5-1 row 8a (storage cabinets > 6 ft): 1.0", True, 1.0, 2.8),
        Parameter("R_po", "strength", "-", "component strength factor",
                  "Table 13.5-1 row 8a (storage cabinets > 6 ft): 1.5", True, 1.0, 2.5),
        Parameter("R", "building_r", "-", "response modification coefficient of the building",
                  "Table 12.2-1, a special steel moment frame (8): the default building model",
                  False, 1.0, 8.0),
        Parameter("Omega_0", "building_omega0", "-", "overstrength factor of the building",
                  "Table 12.2-1, a special steel moment frame (3)", False, 1.0, 3.0,
                  words=((UNKNOWN, None, "the supporting structure is not known: R_μ = 1.3"),)),
        Parameter("I_e", "building_importance", "-", "importance factor of the building",
                  "Table 1.5-2, risk category I or II (1.0)", False, 1.0, 1.5),
        Parameter("T_a", "approximate_period", "s",
                  "the building's approximate period in H_f (§12.8.2.1)",
                  "the building's modal T1 of the floor settings stands for C_t·h_n^x", False,
                  0.0, 10.0, low_open=True,
                  words=((MODAL_T1, MODAL_T1, "the building's modal T1"),
                         (UNKNOWN, UNKNOWN, "not known: H_f = 1 + 2.5·z/h, Eq. 13.3-5"))),
        Parameter("E_v", "vertical_coefficient", "-",
                  "vertical effect E_v/(S_DS·D) taken off the dead load",
                  "§12.4.2.2 and §13.3.1.2: E_v = 0.2·S_DS·D", True, 0.0, 0.2),
        Parameter("Omega_0p", "anchor_overstrength", "-",
                  "overstrength of the anchorage in concrete or masonry (non-ductile anchors)",
                  "§13.4.2 with Table 13.5-1 row 8a (storage cabinets > 6 ft): 2.0", True,
                  1.0, 3.0),
    )

    def period_in_height_factor(self, building_period_s: float | None) -> float | None:
        """T_a of H_f [s], or None where it is not known (Eq. 13.3-5)."""
        if self.approximate_period == UNKNOWN:
            return None
        if self.approximate_period == MODAL_T1:
            return building_period_s
        return self.approximate_period

    def height_factor(self, z_over_h: float, period_s: float | None) -> float:
        """H_f [-]: Eq. 13.3-4 with T_a = ``period_s`` [s], Eq. 13.3-5 without it."""
        if period_s is None:
            return 1.0 + 2.5 * z_over_h
        a1 = min(1.0 / period_s, 2.5)
        a2 = max(1.0 - (0.4 / period_s) ** 2, 0.0)
        return 1.0 + a1 * z_over_h + a2 * z_over_h ** 10

    def ductility_reduction(self) -> float:
        """R_μ = √(1.1·R/(I_e·Ω0)) ≥ 1.3 [-] (Eq. 13.3-6); 1.3 where Ω0 is not known."""
        if self.building_omega0 is None:
            return 1.3
        return max(math.sqrt(1.1 * self.building_r
                             / (self.building_importance * self.building_omega0)), 1.3)

    def force_over_weight(self, site: ComponentSite, floor: Floor):
        """F_p/W_p [g] (Eqs. 13.3-1 to 13.3-3) and its factors."""
        period_s = self.period_in_height_factor(None if floor.on_ground
                                                else floor.building.period_s)
        h_f = self.height_factor(floor.z_over_h, period_s)
        r_mu = self.ductility_reduction()
        base = site.s_ds_g * self.importance
        force = 0.4 * base * (h_f / r_mu) * (self.resonance / self.strength)
        return (min(max(force, 0.3 * base), 1.6 * base),
                {"H_f": h_f, "R_mu": r_mu, "C_AR": self.resonance, "R_po": self.strength,
                 "I_p": self.importance})

    def restoring_factor(self, site: ComponentSite) -> float:
        """0.9 − 0.2·S_DS [-]: the dead load of 0.9D + 1.0E less the vertical E_v."""
        return 0.9 - self.vertical_coefficient * site.s_ds_g

    def anchorage_overstrength(self) -> float:
        """Ω0p [-]: §13.4.2 amplifies the anchorage force of non-ductile anchors in concrete."""
        return self.anchor_overstrength
