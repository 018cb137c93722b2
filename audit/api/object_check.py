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

from dataclasses import replace
from typing import TYPE_CHECKING

from audit.api.result_shape import Files, with_page
from audit.engine.check.objects import object_by_slenderness, parse_block_text, read_objects
from audit.engine.shared.defaults import DEFAULT_CHECK_RECORDS
from audit.errors import InputError

if TYPE_CHECKING:  # pandas is loaded by the check, not by the front door
    import pandas as pd



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
        import html
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
          im: str | None = None, seed: int | None = None, hazard=None,
          friction: float | None = None, params: dict | None = None,
          mass_kg: float | None = None, guideline_spectrum: str = "ground", floor=None,
          solver=None, runtime=None, method: str | None = None) -> CheckResult:
    """Check objects at one site: each guideline's verdict, the exact P(overturn) at the site's
    intensity with a bootstrap band, and the widths required (see :mod:`audit.engine.check.pipeline`);
    with a hazard curve, also the annual rate of overturning (:mod:`audit.engine.check.risk`).

    Every argument is checked before anything is read or computed (by
    :meth:`CheckSettings.parse <audit.engine.check.settings.CheckSettings.parse>` and each
    group's ``parse``: :class:`~audit.engine.shared.design_site.Site`,
    :class:`~audit.physics.building.floor.Floor`, :class:`~audit.engine.shared.hazard.Hazard`,
    :class:`~audit.engine.shared.solver.Solver`, :class:`~audit.engine.shared.runtime.Runtime`,
    :class:`~audit.engine.shared.record_request.Records`); a bad one raises :class:`~audit.errors.InputError`
    naming it (``site``, ``floor.building.period_s``).

    Parameters
    ----------
    objects : str, Block or sequence
        ``"WIDTHxHEIGHT"`` [m], :class:`audit.api.Block`, ``(name, width_m, height_m)``,
        or a list of those.
    site : Site, (float, float) or str
        The design site: FEMA 356 / ASCE 41 S_XS, S_X1 [g] at the hazard level assessed
        (``(1.5, 0.9)`` or ``"1.5,0.9"`` for those alone); ``Site(..., ntc=(a_g, F0, T_C*,
        soil, topography))`` an NTC 2018 site, read by NTC 2018 and EN 1998-1, its values
        those of ``limit_state``'s return period (``SLV``, ``SLC`` or ``both``, the default:
        each reported; with ``both`` the one set is read for SLV and SLC alike).
    procedures : str, Procedure, type or list
        As for :func:`audit.api.run`.
    records : str, path, records.RecordSuite or Records
        As for :func:`audit.api.run`; default the FEMA P695 far-field set. Scaled to the site.
    im : str, optional
        Intensity measure, ``pga`` [g] or ``sa:T`` (T in s) [g], read from the site's design
        spectrum; default ``sa:1.0``, or the hazard curve's IMT.
    seed : int, optional
        Seed of the bootstrap over records.
    hazard : Hazard, records.hazard.HazardCurve, str or pathlib.Path, optional
        The site's hazard curve or its file: the annual rate of overturning; its IMT sets
        ``im``. ``Hazard(curve, imt=..., location=(lon, lat), return_period=..., poe=...,
        risk_target=0.01)``: the IMT of a file of several, the site in a file of several
        sites [degrees], the site's intensity for the exact answer at a return period [years]
        or a probability of exceedance in 50 years (``site`` stays the design spectrum the
        guidelines read), and the P of overturning in 50 years the risk-targeted width meets.
    friction : float, optional
        Friction coefficient μ of the object's base [-]: which mode governs, sliding or
        rocking; without it no sliding is assumed and the friction the records need is given.
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
    floor : Floor, optional
        Where the objects stand: ``Floor(z_over_h, Building(period_s, model="continuum:10",
        damping=0.05))`` (z/H 1 the roof, T1 [s]; :mod:`audit.physics.building`); None or 0
        the ground (the default).
    solver : Solver, optional
        The exact solver: ``Solver(restitution="housner", free_motion_s=..., g=9.81)``
        (``housner``, Eq. 4.8, a fixed r in (0, 1] or ``xFACTOR`` times Eq. 4.8; free motion
        after each record [s]; gravity [m/s²]).
    runtime : Runtime, optional
        How: ``Runtime(jobs, scheduler, progress, force)`` (solver threads, or worker
        processes with ``scheduler="dask"``; ``local``, ``dask`` or ``tcp://HOST:PORT``; a
        progress bar on standard error, or ``progress(done, total, record_id, how)``; start
        even when the work is estimated beyond the limits of :mod:`audit.engine.shared.guards`).
    method : {None, "atlas", "direct"}
        Where the exact side (the fragility, P at the site, the exact widths, the risk) comes
        from: ``"atlas"`` the atlas of ``records`` on the floor with this intensity measure,
        restitution, g and free motion (``audit.api.build_atlas``;
        :class:`~audit.errors.NoAtlas` naming ``method`` where none is built), for each object inside its grid, with its error there;
        ``"direct"`` solved; None (the default) the atlas where one is built, else solved. P
        at the other standard IM is read from that IM's atlas where one is built (unless
        ``"direct"``), else solved. The guidelines are judged directly either way
        (docs/atlas.md).

    Returns
    -------
    CheckResult
    """
    from audit.api.atlas_lookup import check_atlas, stored_atlas
    from audit.engine.check.atlas_side import CheckAtlases
    from audit.engine.check.other_im import other_im
    from audit.api.inputs import parameters_of, procedures_of, record_suite
    from audit.engine.atlas.fragility_read import checked_method
    from audit.engine.shared import guards
    from audit.engine.check.costs import check_cost
    from audit.engine.check.pipeline import run_check
    from audit.engine.check.settings import CheckSettings
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.progress import Progress
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.solver import Solver
    # each record is scaled on its own to the site and the stripes (audit.engine.check.pipeline),
    # so no suite scaling first: the records as given, every one given the site
    where = DesignSite.parse(site, floor, "check")
    if where.site is None or where.site.sxs_g is None:
        raise InputError("site: required, S_XS, S_X1 [g] of the hazard level assessed", "site")
    where = replace(where, site=replace(where.site, override=True))
    settings = CheckSettings.parse(im=im, solver=solver, seed=seed, hazard=hazard,
                                   friction=friction, limit_state=where.site.limit_state,
                                   guideline_spectrum=guideline_spectrum, mass_kg=mass_kg)
    checked_method(method)
    chosen_objects = _objects(objects, settings.g)
    runtime = Runtime.parse(runtime)
    if settings.guideline_spectrum == "floor" and where.floor.on_ground:
        raise InputError("guideline_spectrum: 'floor' reads the floor's response spectrum; the "
                         "objects stand on the ground (give floor and building)",
                         "guideline_spectrum")
    chosen, provision_params = parameters_of(params, procedures_of(procedures))
    given = record_suite(records)
    exact_solver = Solver(settings.restitution, settings.free_motion_s, settings.g)
    atlas = check_atlas(method, given, named=getattr(records, "source", records),
                        im=settings.im.name, solver=exact_solver, floor=where.floor)
    # P at the other standard IM from its own atlas where one is built (else solved, whatever
    # the method: the method names the check's own IM's)
    other = (stored_atlas(given, im=other_im(settings.im).name, solver=exact_solver,
                          floor=where.floor) if method != "direct" else None)
    # the objects the atlas answers have no exact width search to solve
    searched = len(chosen_objects) - (int(atlas[0].covers(
        [o.alpha_deg for o in chosen_objects], [o.size_s for o in chosen_objects]).sum())
        if atlas is not None else 0)
    bar = runtime.progress is True  # drawn here: the engine takes a callable
    if bar:
        runtime = replace(runtime, progress=None)
    # the work, before the records are scaled to the site (scaling keeps their samples)
    guards.check(check_cost(chosen, given, len(chosen_objects), settings, runtime, searched),
                 runtime.force, force_field="runtime.force")
    suite = where.apply(given)
    if bar:
        runtime = replace(runtime, progress=Progress(len(suite), "record"))
    try:
        run = run_check(chosen, suite, chosen_objects, settings, runtime, where.floor,
                        provision_params, CheckAtlases(atlas, other))
    finally:
        if bar:
            runtime.progress.done()
    return CheckResult(run)


__all__ = ["check", "CheckResult", "object_by_slenderness", "parse_block_text", "read_objects"]
