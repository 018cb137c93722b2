"""The design site of an audit, checked once: FEMA 356's site for the records, the FEMA P695
scaling to its spectrum, NTC 2018's site (:mod:`audit.engine.shared.sites` does the work), and the
floor the objects stand on (:mod:`audit.engine.shared.floors`: the ground motions, scaled, are filtered
through the building last)."""

from __future__ import annotations

from dataclasses import dataclass

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import (BOTH, DEFAULT_ANCHOR_PERIOD_S, DEFAULT_SITE_LEVEL,
                                          LIMIT_STATES, SITE_LEVELS)
from audit.errors import InputError
from audit.physics.building.floor import Floor

#: Largest S_XS or S_X1 accepted [g]. The largest mapped MCE_R short-period values of the US
#: maps are about 3 g (S_S near faults, where F_a ≤ 1.2) and the 1 s values lower, so no code
#: design spectrum reaches S_XS ≈ 4 g; a site above 5 g is per cent of g (150 for 1.5 g) or
#: m/s² (14.7 for 1.5 g). Refused, not warned: no real site looks alike. A per-cent site
#: under 5 % g would read as 1–5 g, a real if extreme site, and cannot be told apart.
MAX_SITE_G = 5.0
#: The fields of a :class:`Site` each command reads beyond S_XS, S_X1 and the NTC site; another
#: set away from its default is refused naming it.
SITE_READS = {"check": ("limit_state",), "run": ("override", "scale_records", "anchor_period_s"),
              "margins": ("level", "scale_records", "anchor_period_s")}
#: Each such field's default.
_SITE_OPTIONS = {"limit_state": BOTH, "level": DEFAULT_SITE_LEVEL, "override": False,
                 "scale_records": False, "anchor_period_s": None}


@dataclass(frozen=True)
class Site:
    """The design site: FEMA 356 / ASCE 41 S_XS, S_X1, NTC 2018's site, and how the records meet
    them.

    :meth:`parse` checks every field once and takes the shorthand ``(S_XS, S_X1)`` or the text
    ``"S_XS,S_X1"`` (the one place ``--site`` is read).

    Attributes
    ----------
    sxs_g, sx1_g : float or None
        FEMA 356 design spectral accelerations at short periods and at 1 s [g]; None with an
        NTC 2018 site only.
    ntc : (float, float, float, str, str) or None
        NTC 2018 site a_g [g], F0 [-], T_C* [s], soil category A–E, topography T1–T4.
    limit_state : str
        ``check``: the limit state the values are for, of a guideline that names its own (NTC
        2018): ``SLV``, ``SLC`` or ``both`` (each reported).
    level : {"mce", "design"}
        ``margins``: the hazard level of the values (the CMR is over the MCE intensity, 1.5 ×
        design values).
    override : bool
        ``run``: also replace the sites records carry (Table 3.1); ``check`` and ``margins``
        give every record this site.
    scale_records : bool
        ``run``, ``margins``: scale the suite so that its median 5 %-damped Sa at
        ``anchor_period_s`` equals the design spectrum (each record first by its P695
        normalisation factor).
    anchor_period_s : float or None
        Anchor period of that scaling [s] (1 s when not given).
    """

    sxs_g: float | None
    sx1_g: float | None
    ntc: tuple | None = None
    limit_state: str = BOTH
    level: str = DEFAULT_SITE_LEVEL
    override: bool = False
    scale_records: bool = False
    anchor_period_s: float | None = None

    @classmethod
    def parse(cls, value, command: str | None = None, argument: str = "site") -> Site | None:
        """The site of ``value``, every field checked once (InputError naming
        ``argument.field``; S_XS, S_X1 named ``argument``).

        Parameters
        ----------
        value : Site, (float, float), str or None
            A Site, its shorthand ``(S_XS, S_X1)`` [g] or ``"S_XS,S_X1"``; None: no site.
        command : {"check", "run", "margins"}, optional
            The command reading it: a field it does not read (:data:`SITE_READS`), set away
            from its default, is refused naming it. None: every field read.
        argument : str
            The argument the site was given as, for the messages.
        """
        if value is None:
            return None
        if isinstance(value, str):  # "S_XS,S_X1", as typed on the command line
            pair = _numbers_of(value)
            if pair is None or len(pair) != 2:
                raise InputError(f"{argument}: expected two numbers S_XS,S_X1 in g, got "
                                 f"{value!r}", argument)
            value = cls(*pair)
        elif not isinstance(value, Site):
            value = cls(*check.pair(argument, value, "S_XS, S_X1 in g (positive)", 0,
                                    low_open=True))
        if command is not None:
            for field, default in _SITE_OPTIONS.items():
                if field not in SITE_READS[command] and getattr(value, field) != default:
                    readers = [name for name, fields in SITE_READS.items() if field in fields]
                    raise InputError(f"{argument}.{field}: {' and '.join(readers)} only",
                                     f"{argument}.{field}")
        values = (value.sxs_g, value.sx1_g)
        site = None
        if values != (None, None):
            site = check.pair(argument, values, "S_XS, S_X1 in g (positive)", 0, low_open=True)
            if max(site) > MAX_SITE_G:
                raise InputError(f"{argument}: S_XS, S_X1 = {site[0]:g}, {site[1]:g} g is beyond "
                                 f"any design spectrum (at most ~4 g; limit {MAX_SITE_G:g} g): in "
                                 f"g, not per cent of g ({site[0] / 100:g}, {site[1] / 100:g}) or "
                                 "m/s²", argument)
        ntc = value.ntc
        if ntc is not None:
            name = f"{argument}.ntc"
            if isinstance(ntc, str) or not hasattr(ntc, "__len__") or len(ntc) != 5:
                raise InputError(f"{name}: expected a_g, F0, T_C*, soil, topography, got "
                                 f"{ntc!r}", name)
            ntc = (*check.numbers(name, ntc[:3], "numbers a_g, F0, T_C*"),
                   str(ntc[3]).strip().upper(), str(ntc[4]).strip().upper())
        limit_state = limit_state_of(value.limit_state, f"{argument}.limit_state")
        level = level_of(value.level, f"{argument}.level")
        scale = check.flag(f"{argument}.scale_records", value.scale_records)
        override = check.flag(f"{argument}.override", value.override)
        anchor = value.anchor_period_s
        if anchor is not None:
            anchor = check.number(f"{argument}.anchor_period_s", anchor,
                                  "a positive period in s", 0, low_open=True)
            if not scale:
                raise InputError(f"{argument}.anchor_period_s: needs {argument}.scale_records",
                                 f"{argument}.anchor_period_s", f"{argument}.scale_records")
        if site is None and (override or scale):
            raise InputError(f"{argument}.override and {argument}.scale_records need {argument} "
                             "(S_XS, S_X1)", f"{argument}.override", f"{argument}.scale_records",
                             argument)
        if site is None and ntc is None:  # neither site: refused as the values missing
            check.pair(argument, values, "S_XS, S_X1 in g (positive)", 0, low_open=True)
        return cls(*(site or (None, None)), ntc, limit_state, level, override, scale, anchor)

    @property
    def values_g(self) -> tuple[float, float] | None:
        """(S_XS, S_X1) [g], or None with an NTC 2018 site only."""
        return None if self.sxs_g is None else (self.sxs_g, self.sx1_g)


def limit_state_of(value, name: str) -> str:
    """``SLV``, ``SLC`` or ``both`` of ``value`` (any case); InputError naming ``name``.

    Parameters
    ----------
    value : str
        What was given.
    name : str
        The argument or field it was given as (``site.limit_state``), for the message.
    """
    choices = (*LIMIT_STATES, BOTH)
    if not isinstance(value, str) or value.upper() not in (c.upper() for c in choices):
        raise InputError(f"{name}: expected {', '.join(choices)}, got {value!r}", name)
    return value.upper() if value.upper() in LIMIT_STATES else BOTH


def level_of(value, name: str) -> str:
    """The hazard level ``mce`` or ``design`` of ``value`` (:data:`SITE_LEVELS`); InputError
    naming ``name``.

    Parameters
    ----------
    value : str
        What was given.
    name : str
        The argument or field it was given as (``site.level``), for the message.
    """
    if not isinstance(value, str) or value not in SITE_LEVELS:
        raise InputError(f"{name}: expected {' or '.join(SITE_LEVELS)}, got {value!r}", name)
    return value


@dataclass(frozen=True)
class DesignSite:
    """Where the audited blocks stand: the design site (or none) and the floor.

    Attributes
    ----------
    site : Site or None
        The design site; None: the records' own.
    floor : Floor
        Where the objects stand; the ground by default.
    """

    site: Site | None = None
    floor: Floor = Floor()

    @classmethod
    def parse(cls, site=None, floor=None, command: str | None = None) -> DesignSite:
        """The design site of ``site`` (:meth:`Site.parse`, read as ``command`` reads it) and
        ``floor`` (:meth:`Floor.parse`), each checked once.

        Parameters
        ----------
        site : Site, (float, float), str or None
        floor : Floor, 0 or None
        command : {"check", "run", "margins"}, optional
        """
        return cls(Site.parse(site, command), Floor.parse(floor))

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
        site = self.site
        if site is not None and site.sxs_g is not None:
            suite = with_design_site(suite, site.sxs_g, site.sx1_g, override=site.override)
            if site.scale_records:
                suite = scale_to_site(suite, site.sxs_g, site.sx1_g, DEFAULT_ANCHOR_PERIOD_S
                                      if site.anchor_period_s is None else site.anchor_period_s)
        # after the FEMA site, whose records' sites it replaces (override, or records without
        # one): applied first, the NTC site was wiped from them and NTC read the records
        if site is not None and site.ntc is not None:
            try:
                suite = with_ntc_site(suite, *site.ntc)
            except InputError as exc:  # the spectrum names its parameter
                raise InputError(f"site.ntc: {exc}", "site.ntc") from None
        return on_floor(suite, self.floor)


def _numbers_of(text: str) -> list[float] | None:
    """The comma-separated numbers of ``text`` (empty items skipped), or None."""
    try:
        return [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        return None


__all__ = ["Site", "DesignSite", "SITE_READS", "MAX_SITE_G", "limit_state_of", "level_of"]
