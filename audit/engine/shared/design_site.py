"""The design site of an audit, checked once: FEMA 356's site for the records, the FEMA P695
scaling to its spectrum, NTC 2018's site (:mod:`audit.engine.shared.sites` does the work), and the
floor the objects stand on (:mod:`audit.engine.shared.floors`: the ground motions, scaled, are filtered
through the building last)."""

from __future__ import annotations

from dataclasses import dataclass

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import DEFAULT_ANCHOR_PERIOD_S
from audit.engine.shared.floors import FLOOR_DEFAULTS
from audit.errors import InputError
from audit.physics.building.floor import Floor

#: Largest S_XS or S_X1 accepted [g]. The largest mapped MCE_R short-period values of the US
#: maps are about 3 g (S_S near faults, where F_a ≤ 1.2) and the 1 s values lower, so no code
#: design spectrum reaches S_XS ≈ 4 g; a site above 5 g is per cent of g (150 for 1.5 g) or
#: m/s² (14.7 for 1.5 g). Refused, not warned: no real site looks alike. A per-cent site
#: under 5 % g would read as 1–5 g, a real if extreme site, and cannot be told apart.
MAX_SITE_G = 5.0
#: The fields :meth:`DesignSite.parse` takes, and their defaults.
SITE_DEFAULTS = {"site": None, "site_override": False, "scale_to_site": False,
                 "anchor_period_s": None, "ntc_site": None, **FLOOR_DEFAULTS}
SITE_FIELDS = tuple(SITE_DEFAULTS)


@dataclass(frozen=True)
class DesignSite:
    """Where the audited blocks stand.

    Attributes
    ----------
    site : (float, float) or None
        FEMA 356 design site S_XS, S_X1 [g] for every record without one (:meth:`parse` takes
        the text ``"S_XS,S_X1"`` too: the one place ``--site`` is read).
    site_override : bool
        Also replace the sites records carry (Table 3.1).
    scale_to_site : bool
        Scale the suite so that its median 5 %-damped Sa at ``anchor_period_s`` equals the
        design spectrum (each record first by its P695 normalisation factor).
    anchor_period_s : float or None
        Anchor period [s] (1 s when not given); only with ``scale_to_site``.
    ntc_site : (float, float, float, str, str) or None
        NTC 2018 site a_g [g], F0 [-], T_C* [s], soil category A–E, topography T1–T4.
    floor : Floor
        Where the objects stand (keywords ``floor``, ``building``, ``building_model``,
        ``building_damping``); the ground by default.
    """

    site: tuple | None = None
    site_override: bool = False
    scale_to_site: bool = False
    anchor_period_s: float | None = None
    ntc_site: tuple | None = None
    floor: Floor = Floor()

    @classmethod
    def parse(cls, **values) -> DesignSite:
        """The design site of the given fields, each checked once (InputError naming it).

        Parameters
        ----------
        **values
            Fields of :data:`SITE_FIELDS` by name (the rest take :data:`SITE_DEFAULTS`).
        """
        check.unknown("the design site", values, SITE_FIELDS)
        value = {**SITE_DEFAULTS, **values}
        site = value["site"]
        if isinstance(site, str):  # "S_XS,S_X1", as typed on the command line
            site = _numbers_of(site)
            if site is None or len(site) != 2:
                raise InputError(f"site: expected two numbers S_XS,S_X1 in g, got "
                                 f"{value['site']!r}", "site")
        if site is not None:
            site = check.pair("site", site, "S_XS, S_X1 in g (positive)", 0, low_open=True)
            if max(site) > MAX_SITE_G:
                raise InputError(f"site: S_XS, S_X1 = {site[0]:g}, {site[1]:g} g is beyond any "
                                 f"design spectrum (at most ~4 g; limit {MAX_SITE_G:g} g): in g, "
                                 f"not per cent of g ({site[0] / 100:g}, {site[1] / 100:g}) or "
                                 "m/s²", "site")
        ntc = value["ntc_site"]
        if ntc is not None:
            if isinstance(ntc, str) or not hasattr(ntc, "__len__") or len(ntc) != 5:
                raise InputError(f"ntc_site: expected a_g, F0, T_C*, soil, topography, got {ntc!r}",
                                 "ntc_site")
            ntc = (*check.numbers("ntc_site", ntc[:3], "numbers a_g, F0, T_C*"),
                   str(ntc[3]).strip().upper(), str(ntc[4]).strip().upper())
        scale = check.flag("scale_to_site", value["scale_to_site"])
        override = check.flag("site_override", value["site_override"])
        anchor = value["anchor_period_s"]
        if anchor is not None:
            anchor = check.number("anchor_period_s", anchor, "a positive period in s", 0,
                                  low_open=True)
            if not scale:
                raise InputError("anchor_period_s: needs scale_to_site", "anchor_period_s",
                                 "scale_to_site")
        if site is None and (override or scale):
            raise InputError("site_override and scale_to_site need site (S_XS, S_X1)",
                             "site_override", "scale_to_site", "site")
        floor = Floor.parse(**{name: value[name] for name in FLOOR_DEFAULTS})
        return cls(site, override, scale, anchor, ntc, floor)

    def apply(self, suite):
        """``suite`` with these sites and scaling, on this floor.

        Parameters
        ----------
        suite : records.RecordSuite
            The records.

        Returns
        -------
        records.RecordSuite
        """
        from audit.engine.shared.floors import on_floor
        from audit.engine.shared.sites import scale_to_site, with_design_site, with_ntc_site
        if self.site is not None:
            sxs_g, sx1_g = self.site
            suite = with_design_site(suite, sxs_g, sx1_g, override=self.site_override)
            if self.scale_to_site:
                suite = scale_to_site(suite, sxs_g, sx1_g, DEFAULT_ANCHOR_PERIOD_S
                                      if self.anchor_period_s is None else self.anchor_period_s)
        # after the FEMA site, whose records' sites it replaces (override, or records without
        # one): applied first, the NTC site was wiped from them and NTC read the records
        if self.ntc_site is not None:
            try:
                suite = with_ntc_site(suite, *self.ntc_site)
            except InputError as exc:  # the spectrum names its parameter
                raise InputError(f"ntc_site: {exc}", "ntc_site") from None
        return on_floor(suite, self.floor)


def _numbers_of(text: str) -> list[float] | None:
    """The comma-separated numbers of ``text`` (empty items skipped), or None."""
    try:
        return [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        return None


__all__ = ["DesignSite", "SITE_DEFAULTS", "SITE_FIELDS", "MAX_SITE_G"]
