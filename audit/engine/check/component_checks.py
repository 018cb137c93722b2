"""The component provisions' verdicts on one object at one site and floor, as check.json entries.

Each provision (:mod:`procedures.component`) gives one entry of the agreed shape of a guideline
entry (limit state ``overturning``, demand and capacity as forces per unit weight in g, the named
factors it used, the anchorage forces per unit weight where the unanchored object fails, the
full width at which it would pass), and says which spectrum value it read and every parameter it
used (:func:`procedures.parameters.parameters_used`).
"""

from __future__ import annotations

from audit import G
from audit.engine.shared import fields as check
from audit.engine.shared.design_site import Site
from audit.errors import InputError
from audit.physics.building.floor import Floor
from procedures.component import ComponentProvision, ComponentSite
from procedures.parameters import parameters_used
from procedures.registry import available_component_provisions


def component_provisions(params: dict | None = None) -> list[ComponentProvision]:
    """Every registered component provision, each with its parameters of ``params`` and its
    defaults otherwise.

    Parameters
    ----------
    params : dict, optional
        ``{name: {attribute: value}}``, as :func:`procedures.parameters.parse_params` gives them.
    """
    params = params or {}
    return [cls(**params.get(name, {}))
            for name, cls in available_component_provisions().items()]


def component_entries(width_m: float, height_m: float, *, site=None, floor: Floor = Floor(),
                      provisions=None, mass_kg: float | None = None) -> list[dict]:
    """One check.json entry per component provision for a block on ``floor``.

    Parameters
    ----------
    width_m, height_m : float
        Full width (the dimension it rocks across) and full height of the object [m]; its
        centre of mass at mid-height.
    site : audit.engine.shared.design_site.Site, (float, float) or str
        The design site: FEMA 356 S_XS, S_X1 [g] and/or its ``ntc`` NTC 2018 site (a_g [g],
        F0, T_C* [s], soil, topography), the values of the limit state assessed
        (:meth:`Site.parse <audit.engine.shared.design_site.Site.parse>`).
    floor : audit.physics.building.floor.Floor
        Where the object stands (the ground by default; checked by :meth:`Floor.parse`).
    provisions : list of ComponentProvision or None
        Instances to apply; None applies every registered one with its default settings.
    mass_kg : float or None
        The object's mass [kg]: the anchorage forces also in kN.
    """
    width_m = check.number("width_m", width_m, "a positive length in m", 0, low_open=True)
    height_m = check.number("height_m", height_m, "a positive length in m", 0, low_open=True)
    if mass_kg is not None:
        mass_kg = check.number("mass_kg", mass_kg, "a positive mass in kg", 0, low_open=True)
    if not isinstance(floor, Floor):
        raise InputError(f"floor: expected an audit.physics.building.floor.Floor "
                         f"(Floor(z_over_h, Building(period_s))), got {floor!r}", "floor")
    if site is None:
        raise InputError("site: the component provisions need a design site (S_XS, S_X1) or an "
                         "NTC 2018 site", "site")
    checked = Site.parse(site)
    try:
        codes_site = ComponentSite.from_design_site(checked.values_g, checked.ntc)
    except InputError as exc:  # the NTC spectrum names its own field
        raise InputError(f"site.ntc: {exc}", "site.ntc") from None
    if provisions is None:
        provisions = component_provisions()
    if not isinstance(provisions, (list, tuple)) or not all(
            isinstance(p, ComponentProvision) for p in provisions):
        raise InputError(f"provisions: expected a list of ComponentProvision instances, got "
                         f"{provisions!r}", "provisions")
    half_width, half_height = width_m / 2.0, height_m / 2.0
    entries = []
    for provision in provisions:
        entry = {"procedure": provision.title, "key": provision.name,
                 "limit_state": "overturning", "share_of_records_overturning": None,
                 "exact_p_exceed": None, "unit": "g",
                 "spectrum_read": "; ".join(codes_site.read[name] for name in provision.requires
                                            if name in codes_site.read),
                 "parameters": parameters_used(provision)}
        unmet = provision.unmet_requirements(floor)
        if unmet is not None:
            entries.append({**entry, "verdict": "cannot judge", "demand": None, "capacity": None,
                            "basis": unmet, "factors": {}, "anchorage_force_over_weight": None,
                            "anchorage": None, "required_width_m": None})
            continue
        result = provision.check(width_m, height_m, codes_site, floor)
        # the width at which the restoring moment just balances the code's force
        restoring = result.capacity_over_weight * half_height / half_width
        anchorage = result.anchorage
        if anchorage is not None and mass_kg is not None:
            weight_kn = mass_kg * G / 1000.0
            anchorage = {**anchorage, **{f"{name}_kN": value * weight_kn
                                         for name, value in anchorage.items()
                                         if name != "omega_0p"}}
        entries.append({**entry, "verdict": "passes" if result.passes else "fails",
                        "demand": result.force_over_weight,
                        "capacity": result.capacity_over_weight,
                        "basis": f"{result.basis}; site {codes_site.source}, {floor.describe()}",
                        "factors": result.factors,
                        "anchorage_force_over_weight": result.anchorage_force_over_weight,
                        "anchorage": anchorage,
                        "required_width_m": (2.0 * half_height * result.force_over_weight
                                             / restoring if restoring > 0 else None)})
    return entries


__all__ = ["component_entries", "component_provisions"]
