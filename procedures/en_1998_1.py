"""EN 1998-1:2004 §4.3.5.2: the seismic force on a non-structural element of a building.

Clause followed, known second-hand: the standard's text could not be read here; the formula and
its variables are as a software vendor's note (ProtaStructure, "Seismic forces on non-structural
members", quoting §4.3.5.2(2)–(3), Eq. 4.25) and third-party notes give them:

* F_a = S_a·W_a·γ_a/q_a                                                               (Eq. 4.24)
* S_a = α·S·[3·(1 + z/H)/(1 + (1 − T_a/T_1)²) − 0.5] ≥ α·S                             (Eq. 4.25)

α = a_g/g, S the soil factor, T_a the element's own period (0 for a rigid block), T_1 the
building's, z/H the element's relative height. A rigid element (T_a = 0) on the roof (z/H = 1):
S_a/(α·S) = 3·2/2 − 0.5 = 2.5; on the ground, 1.

The element's T_a may be set (parameter ``T_a``), to ``T1`` too: resonance, where the bracket
peaks (5.5 on the roof against 2.5 for a rigid element); a rocking block's period lengthens with
its rotation, so a rigid T_a = 0 is the block before it rocks.

An unanchored element is checked for overturning in the seismic design situation of EN 1990
§6.4.3.4 (permanent actions at their characteristic value, γ = 1.0): F_a·h_cm ≤ W_a·b.

Verified against a worked example computed by hand in ``tests/procedures/test_component_provisions.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

from audit.physics.building.floor import Floor
from procedures.component import ComponentProvision, ComponentSite
from procedures.parameters import Parameter

#: T_a's word: the element's period equal to the building's T1 (the bracket's peak).
RESONANT = "T1"


@dataclass(frozen=True)
class EN19981(ComponentProvision):
    """EN 1998-1 §4.3.5.2 for an unanchored rigid cabinet, with its settings (see
    :attr:`parameters` for each one's key, range and the clause of its default).

    Attributes
    ----------
    importance : float
        γ_a, the element's importance factor [-].
    behaviour : float
        q_a, the element's behaviour factor [-].
    object_period_s : float or str
        T_a, the element's fundamental period [s], or ``"T1"`` (the building's).
    """

    importance: float = 1.0
    behaviour: float = 2.0
    object_period_s: float | str = 0.0

    name = "en1998_1"
    title = "EN 1998-1 §4.3.5"
    reference = "EN 1998-1:2004 §4.3.5.2, Eqs. 4.24 and 4.25; EN 1990 §6.4.3.4"
    requires = ("ag_s_g", "z_over_h", "building_period_s", "object_period_s")
    parameters = (
        Parameter("q_a", "behaviour", "-", "behaviour factor of the element",
                  "Table 4.4, the row naming cabinets (anchorage elements for permanent "
                  "cabinets and book stacks supported by the floor): 2.0; an element that "
                  "dissipates nothing takes 1.0, which doubles F/W", True, 1.0, 2.0),
        Parameter("gamma_a", "importance", "-", "importance factor of the element",
                  "§4.3.5.3: 1.0 (≥ 1.5 where its failure endangers life or it serves "
                  "essential equipment)", True, 1.0, 3.0),
        Parameter("T_a", "object_period_s", "s", "fundamental period of the element",
                  "a rigid block before it rocks (0)", False, 0.0, 10.0,
                  words=((RESONANT, RESONANT, "the building's T1: resonance"),)),
    )

    def element_period_s(self, building_period_s: float | None) -> float:
        """T_a [s]: the set period, or the building's T1 for ``"T1"``."""
        return building_period_s if self.object_period_s == RESONANT else self.object_period_s

    def unmet_requirements(self, floor: Floor) -> str | None:
        if floor.on_ground and (self.object_period_s == RESONANT
                                                or self.object_period_s > 0.0):
            return "an element with a period T_a > 0 needs the building's T1"
        return None

    def amplification(self, z_over_h: float, building_period_s: float | None) -> float:
        """S_a/(α·S) = 3(1 + z/H)/(1 + (1 − T_a/T_1)²) − 0.5 ≥ 1 [-] (Eq. 4.25)."""
        period_s = self.element_period_s(building_period_s)
        ratio = 0.0 if period_s == 0.0 else period_s / building_period_s
        return max(3.0 * (1.0 + z_over_h) / (1.0 + (1.0 - ratio) ** 2) - 0.5, 1.0)

    def force_over_weight(self, site: ComponentSite, floor: Floor):
        """F_a/W_a [g] (Eq. 4.24) and S_a/(α·S)."""
        amplification = self.amplification(floor.z_over_h, None if floor.on_ground
                                           else floor.building.period_s)
        return (site.ag_s_g * amplification * self.importance / self.behaviour,
                {"S_a_over_alpha_S": amplification, "gamma_a": self.importance,
                 "q_a": self.behaviour})

    def restoring_factor(self, site: ComponentSite) -> float:
        return 1.0
