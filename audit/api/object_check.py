"""``audit.check``: the Python API of ``audit check`` (one or many objects at one site).

    import audit
    result = audit.check(["0.6x1.8"], site=(1.5, 0.9))
    result.table              # one row per object × procedure (a DataFrame)
    print(result.summary_text())   # the paragraph and table the command line prints
    result.report("check.html")

Objects are ``"WIDTHxHEIGHT"`` strings [m], :class:`audit.api.Block` instances, or
``(name, width_m, height_m)`` tuples. Bad input raises :class:`audit.errors.InputError` naming the
argument.
"""

from __future__ import annotations

import html
from dataclasses import replace

import pandas as pd

from audit import G
from audit.api.result_shape import Files, with_page
from audit.engine.shared import fields as check_field
from audit.engine.check.objects import object_by_slenderness, parse_block_text, read_objects
from audit.engine.shared.defaults import (DEFAULT_CHECK_RECORDS, DEFAULT_FREE_MOTION_S, DEFAULT_JOBS,
                                   DEFAULT_RESTITUTION, DEFAULT_RISK_TARGET, DEFAULT_SCHEDULER)
from audit.engine.check.limits import BOTH
from audit.errors import InputError
from audit.physics.building.floor import DEFAULT_BUILDING_DAMPING



class CheckResult(Files):
    """The answer of a check.

    Attributes
    ----------
    document : dict
        Everything of ``check.json``: the run (site, intensity measure, records) and
        ``objects``, each with its ``exact`` answer and ``procedures``.
    table : pandas.DataFrame
        One row per object × procedure (the columns of ``check.csv``).
    summary : dict
        The run of ``check.json`` without its objects: site, intensity measure, records,
        procedures.
    """

    PAGE = "check.html"

    def __init__(self, run):
        from audit.engine.check.summary import check_table
        self.run = run
        self.summary: dict = run.summary
        self.document = {**run.summary, "objects": run.objects}
        self.table: pd.DataFrame = check_table(run.objects, run.summary.get("floor"))

    @property
    def sentences(self) -> list[str]:
        """One sentence per object, for a calculation note."""
        return [obj["sentence"] for obj in self.run.objects]

    def summary_text(self) -> str:
        """The paragraph and per-object table ``audit check`` prints."""
        from audit.engine.check.words import summary_text
        return summary_text(self.document)

    def files(self) -> dict[str, bytes]:
        """``check.json``, ``check.csv`` and ``check.html`` (the page drawn from the JSON as
        saved)."""
        from audit.engine.check.summary import CHECK_HTML, check_data_files
        from reports.check_page import render_check_page
        return with_page(check_data_files(self.run), CHECK_HTML, render_check_page)

    def _repr_html_(self) -> str:
        table = self.table[["object", "procedure", "verdict", "demand", "capacity", "unit",
                            "required_width_m", "p_overturn_at_site", "p_estimator",
                            "exact_required_width_m_10pct"]]
        return ("".join(f"<p>{html.escape(s)}</p>" for s in self.sentences)
                + table.to_html(index=False, float_format=lambda v: f"{v:.3g}", na_rep="—"))

    def __repr__(self) -> str:
        site = self.document["site"]
        return (f"CheckResult({len(self.run.objects)} object(s) at S_XS = {site['sxs_g']:g} g, "
                f"S_X1 = {site['sx1_g']:g} g, {len(self.document['procedures'])} procedure(s))")


def _objects(objects, g: float) -> list:
    from audit.engine.shared.blocks import Block, within_limits
    from audit.engine.check.objects import checked_object, parse_block_text
    if isinstance(objects, (str, Block)):
        objects = [objects]
    if not isinstance(objects, (list, tuple)):
        raise InputError(f"objects: expected 'WIDTHxHEIGHT', a Block, (name, width_m, "
                         f"height_m) or a list of those, got {objects!r}", "objects")
    out = []
    for i, item in enumerate(objects):
        where = f"objects[{i}]"
        if isinstance(item, str):
            try:
                out += parse_block_text(item, where, g)
            except InputError as exc:
                raise InputError(str(exc), "objects") from None
        elif isinstance(item, Block):  # named on the command line; by its dimensions if not
            out.append(within_limits(item if item.name else replace(
                item, name=f"{item.width_m:.3g}x{item.height_m:.3g}"), where))
        elif isinstance(item, (tuple, list)) and len(item) == 3:
            name, width, height = item
            try:
                out.append(checked_object(str(name), width, height, f"{where} ({name})", g))
            except InputError as exc:
                raise InputError(str(exc), "objects") from None
        else:
            raise InputError(f"{where}: expected 'WIDTHxHEIGHT', a Block or (name, width_m, "
                             f"height_m), got {item!r}", "objects")
    if not out:
        raise InputError("objects: no object to check", "objects")
    return out


def check(objects, site, procedures="all", records=DEFAULT_CHECK_RECORDS, *,
          im: str | None = None, restitution=DEFAULT_RESTITUTION,
          free_motion_s: float = DEFAULT_FREE_MOTION_S, g: float = G, seed: int | None = None,
          hazard=None, hazard_imt: str | None = None, site_location=None,
          risk_target: float = DEFAULT_RISK_TARGET, return_period: float | None = None,
          poe: float | None = None, friction: float | None = None, ntc_site=None,
          skip_bad_records: bool = False, dt_s: float | None = None,
          units: str | None = None, jobs: int = DEFAULT_JOBS,
          scheduler=DEFAULT_SCHEDULER, progress=False, force: bool = False, floor: float = 0.0,
          building: float | None = None, building_model: str | None = None,
          building_damping: float = DEFAULT_BUILDING_DAMPING,
          limit_state: str = BOTH, params: dict | None = None,
          mass_kg: float | None = None, guideline_spectrum: str = "ground",
          method: str | None = None) -> CheckResult:
    """Check objects at one site: each guideline's verdict, the exact P(overturn) at the site's
    intensity with a bootstrap band, and the widths required (see :mod:`audit.engine.check.pipeline`);
    with a hazard curve, also the annual rate of overturning (:mod:`audit.engine.check.risk`).

    Every argument is checked before anything is read or computed (by
    :meth:`CheckSettings.parse <audit.engine.check.settings.CheckSettings.parse>`,
    :meth:`DesignSite.parse <audit.engine.shared.design_site.DesignSite.parse>` and
    :meth:`Runtime.parse <audit.engine.shared.runtime.Runtime.parse>`); a bad one raises
    :class:`~audit.errors.InputError` naming it.

    Parameters
    ----------
    objects : str, Block or sequence
        ``"WIDTHxHEIGHT"`` [m], :class:`audit.api.Block`, ``(name, width_m, height_m)``,
        or a list of those.
    site : (float, float)
        FEMA 356 / ASCE 41 S_XS, S_X1 [g] at the hazard level assessed.
    procedures : str, Procedure, type or list
        As for :func:`audit.api.run`.
    records : str, path or records.RecordSuite
        As for :func:`audit.api.run`; default the FEMA P695 far-field set. Scaled to the site.
    im : str, optional
        Intensity measure, ``pga`` [g] or ``sa:T`` (T in s) [g], read from the site's design
        spectrum; default ``sa:1.0``, or the hazard curve's IMT.
    restitution : str or float
        Impact model of the exact solver: ``housner`` (Eq. 4.8), a fixed r in (0, 1] [-] or
        ``xFACTOR`` times Eq. 4.8.
    free_motion_s : float
        Free motion after each record [s], ≥ 0.
    g : float
        Acceleration of gravity [m/s²].
    seed : int, optional
        Seed of the bootstrap over records.
    hazard : records.hazard.HazardCurve, str or pathlib.Path, optional
        The site's hazard curve or its file: the annual rate of overturning; its IMT sets
        ``im``.
    hazard_imt : str, optional
        The IMT of a hazard file of several (``"SA(1.0)"``, ``"PGA"``); without it, ``im``'s.
    site_location : (float, float) or str, optional
        Longitude, latitude [degrees] of the site in a hazard file of several sites (west and
        south negative; ``"-118,34"`` too).
    risk_target : float or str
        Probability of overturning in 50 years the risk-targeted width meets [-], in (0, 1):
        0.01 or ``"1%"``.
    return_period : float, optional
        With ``hazard``: the site's intensity for the exact answer is the hazard curve's at this
        return period [years]; ``site`` stays the design spectrum the guidelines read.
    poe : float or str, optional
        The same, as a probability of exceedance in 50 years (0.02 or ``"2%"``).
    friction : float, optional
        Friction coefficient μ of the object's base [-]: which mode governs, sliding or
        rocking; without it no sliding is assumed and the friction the records need is given.
    ntc_site : (float, float, float, str, str), optional
        NTC 2018 site a_g [g], F0 [-], T_C* [s], soil, topography
        (see :func:`audit.api.design_suite`).
    skip_bad_records : bool
        Check with the readable records of the suite; the unreadable ones are warned about
        (:class:`~audit.errors.InputWarning`) and left out.
    dt_s : float, optional
        Time step [s] of a text record file that states none (no time column, no ``dt =``
        comment).
    units : {"g", "m/s2", "cm/s2"}, optional
        Units of the accelerations of a text record file that states none.
    jobs : int
        Solver threads, or worker processes with ``scheduler="dask"``.
    scheduler : str
        ``local``, ``dask`` or ``tcp://HOST:PORT``.
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, record_id, how)``.
    force : bool
        Start even when the work is estimated beyond the limits of
        :mod:`audit.engine.shared.guards` (as for :func:`audit.api.run`); InputError otherwise.
    floor : float
        Where the objects stand: z/H in the building, 0 the ground (the default), 1 the roof.
    building : float, optional
        The building's first-mode period T1 [s]; needed above the ground.
    building_model : str, optional
        ``shear:N`` or ``continuum:α0`` (default ``continuum:10``), see
        :mod:`audit.physics.building`.
    building_damping : float
        ζ in every mode of the building [-] (default 0.05).
    limit_state : str
        The limit state the site's values are for, of a guideline that names its own (NTC
        2018): ``SLV``, ``SLC`` or ``both`` (the default: each reported). An ``ntc_site``'s
        a_g, F0, T_C* are the values of this limit state's return period; with ``both`` the
        one set is read for SLV and SLC alike.
    params : dict, optional
        Parameters of the procedures and component provisions, ``{name: {key: value}}`` with
        keys as the code writes them (``{"asce7_22": {"I_p": 1.5}}``); each plug-in declares
        its own (docs/procedures.md), and an unknown one is refused.
    mass_kg : float, optional
        The mass of each object [kg]: the anchorage forces of the component provisions it
        fails also in kN.
    guideline_spectrum : {"ground", "floor"}
        On a floor, the spectrum FEMA 356 (a guideline reading the site's design spectrum)
        reads: the ground's design spectrum ``site`` as its text is written (the default), or
        the floor's response spectrum (:mod:`audit.engine.check.spectrum_read`); its entry
        gives its verdict on the other too.
    method : {None, "atlas", "direct"}
        Where the exact side (the fragility, P at the site, the exact widths, the risk) comes
        from: ``"atlas"`` the atlas of ``records`` on the floor with this intensity measure,
        restitution, g and free motion (``audit.build_atlas``; InputError naming ``method``
        where none is built), for each object inside its grid, with its error there;
        ``"direct"`` solved; None (the default) the atlas where one is built, else solved. The
        guidelines are judged directly either way (docs/atlas.md).

    Returns
    -------
    CheckResult
    """
    from audit.api.atlas_lookup import check_atlas, checked_method
    from audit.api.inputs import parameters_of, procedures_of, record_suite, settings_fields
    from audit.engine.shared import guards
    from audit.engine.check.costs import check_cost
    from audit.engine.check.pipeline import run_check
    from audit.engine.check.settings import CHECK_FIELDS, CheckSettings
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.progress import Progress
    from audit.engine.shared.runtime import Runtime
    settings = CheckSettings.parse(**settings_fields(locals(), CHECK_FIELDS))
    chosen_objects = _objects(objects, settings.g)
    checked_method(method)
    progress = check_field.callback("progress", progress, "progress(done, total, record_id, how)")
    runtime = Runtime.parse(jobs=jobs, scheduler=scheduler,
                            progress=progress if callable(progress) else None)
    if site is None:
        raise InputError("site: required, S_XS, S_X1 [g] of the hazard level assessed", "site")
    # each record is scaled on its own to the site and the stripes (audit.engine.check.pipeline), so no
    # suite scaling first: the records as given
    site = DesignSite.parse(site=site, site_override=True, scale_to_site=False,
                            ntc_site=ntc_site, floor=floor, building=building,
                            building_model=building_model, building_damping=building_damping)
    if settings.guideline_spectrum == "floor" and site.floor.on_ground:
        raise InputError("guideline_spectrum: 'floor' reads the floor's response spectrum; the "
                         "objects stand on the ground (give floor and building)",
                         "guideline_spectrum")
    chosen, provision_params = parameters_of(params, procedures_of(procedures))
    if mass_kg is not None:
        mass_kg = check_field.number("mass_kg", mass_kg, "a positive mass in kg", 0,
                                     low_open=True)
    given = record_suite(records, dt_s=dt_s, units=units, skip_bad_records=skip_bad_records)
    atlas = check_atlas(method, given, named=records, im=settings.im.name,
                        restitution=restitution, free_motion_s=settings.free_motion_s,
                        g=settings.g, floor=floor,
                        building=building, building_model=building_model,
                        building_damping=building_damping)
    searched = len(chosen_objects) - (int(atlas[0].covers(
        [o.alpha_deg for o in chosen_objects], [o.size_s for o in chosen_objects]).sum())
        if atlas is not None else 0)
    # the work, before the records are scaled to the site (scaling keeps their samples)
    guards.check(check_cost(chosen, given, len(chosen_objects), settings, runtime, searched),
                 check_field.flag("force", force))
    suite = site.apply(given)
    bar = Progress(len(suite), "record") if progress is True else None
    try:
        run = run_check(chosen, suite, chosen_objects, settings,
                        replace(runtime, progress=bar) if bar else runtime, site.floor,
                        provision_params, mass_kg, atlas)
    finally:
        if bar is not None:
            bar.done()
    return CheckResult(run)


__all__ = ["check", "CheckResult", "object_by_slenderness", "parse_block_text", "read_objects"]
