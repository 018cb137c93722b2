"""The component provisions' verdicts on one object at one site and floor, as check.json entries.

Each provision (:mod:`procedures.component`) gives one entry of the agreed shape of a guideline
entry (limit state ``overturning``, demand and capacity as forces per unit weight in g, the named
factors it used, the anchorage force per unit weight where the unanchored object fails, and the
full width at which it would pass).
"""

from __future__ import annotations

from audit.errors import InputError
from audit.physics.building.floor import Floor
from procedures.component import ComponentSite
from procedures.registry import available_component_provisions


def component_entries(width_m: float, height_m: float, *, site=None, ntc_site=None,
                      floor: Floor = Floor(), provisions=None) -> list[dict]:
    """One check.json entry per component provision for a block on ``floor``.

    Parameters
    ----------
    width_m, height_m : float
        Full width (the dimension it rocks across) and full height of the object [m]; its
        centre of mass at mid-height.
    site : (float, float) or None
        FEMA 356 design site S_XS, S_X1 [g].
    ntc_site : tuple or None
        NTC 2018 site (a_g [g], F0, T_C* [s], soil, topography).
    floor : audit.physics.building.floor.Floor
        Where the object stands (the ground by default).
    provisions : list of ComponentProvision or None
        Instances to apply; None applies every registered one with its default settings.
    """
    for name, value in (("width_m", width_m), ("height_m", height_m)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
            raise InputError(f"{name}: expected a positive length in m, got {value!r}", name)
    codes_site = ComponentSite.from_design_site(site, ntc_site)
    if provisions is None:
        provisions = [cls() for cls in available_component_provisions().values()]
    half_width, half_height = width_m / 2.0, height_m / 2.0
    entries = []
    for provision in provisions:
        entry = {"procedure": provision.title, "key": provision.name,
                 "limit_state": "overturning", "share_of_records_overturning": None,
                 "exact_p_exceed": None, "unit": "g"}
        unmet = provision.unmet_requirements(floor)
        if unmet is not None:
            entries.append({**entry, "verdict": "cannot judge", "demand": None, "capacity": None,
                            "basis": unmet, "factors": {}, "anchorage_force_over_weight": None,
                            "required_width_m": None})
            continue
        result = provision.check(half_width, half_height, codes_site, floor)
        # the width at which the restoring moment just balances the code's force
        restoring = result.capacity_over_weight * half_height / half_width
        entries.append({**entry, "verdict": "passes" if result.passes else "fails",
                        "demand": result.force_over_weight,
                        "capacity": result.capacity_over_weight,
                        "basis": f"{result.basis}; site {codes_site.source}, {floor.describe()}",
                        "factors": result.factors,
                        "anchorage_force_over_weight": result.anchorage_force_over_weight,
                        "required_width_m": (2.0 * half_height * result.force_over_weight
                                             / restoring if restoring > 0 else None)})
    return entries


__all__ = ["component_entries"]
