"""The design-level audit: :func:`margins` and its :class:`MarginsResult`."""

from __future__ import annotations

import time
from dataclasses import replace

from audit.api.result_shape import Files, with_page
from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_SITE_LEVEL


class MarginsResult(Files):
    """A design-level audit's tables: ``.stripes``, ``.fragility`` (also ``.table``),
    ``.capacity``, ``.required_alpha``, ``.scan``, ``.acceptance`` (FEMA P695's test of the
    blocks each guideline sizes, with a design site), and at a site ``.risk``, ``.risk_alpha``
    (DataFrames, the columns of the CSV files of the same names); ``.summary`` (everything of
    ``summary.json``), ``.summary_text()``, ``.write(folder)`` (the files and ``margins.html``)
    and ``.report(path)``.

    Attributes
    ----------
    seconds : float
        How long the audit took [s] (the first line of :meth:`summary_text`).
    """

    PAGE = "margins.html"

    def __init__(self, margins, seconds: float = 0.0):
        self.margins, self.seconds = margins, seconds
        self.stripes, self.fragility = margins.stripes, margins.fragility
        self.capacity, self.summary = margins.capacity, margins.summary
        self.required_alpha, self.scan = margins.required_alpha, margins.scan
        self.risk, self.risk_alpha = margins.risk, margins.risk_alpha
        self.acceptance = margins.acceptance

    @property
    def table(self):
        """One row per block: its exact fragility and collapse margin (``fragility.csv``)."""
        return self.fragility

    def summary_text(self) -> str:
        """The lines ``audit margins`` prints."""
        from audit.engine.design.words import margins_summary_text
        return margins_summary_text(self.margins, self.seconds)

    def files(self) -> dict[str, bytes]:
        """Every file of the audit, the page drawn from the CSV files as saved."""
        from audit.engine.design.margins import margins_files
        from reports.margins_page import MARGINS_HTML, render_margins_page
        return with_page(margins_files(self.margins), MARGINS_HTML, render_margins_page)

    def __repr__(self) -> str:
        blocks = len(self.fragility)
        design = self.summary.get("design_im")
        cmr = self.fragility["cmr"].median() if blocks else float("nan")
        return (f"MarginsResult({', '.join(p['name'] for p in self.summary['procedures'])} on "
                f"{self.summary['records_source']}: {blocks} blocks × "
                f"{len(self.summary['levels'])} stripes of {self.summary['im']}"
                + (f", median CMR {cmr:.3g}" if design else "") + ")")

    def _repr_html_(self) -> str:
        lines = self.capacity.groupby("procedure", sort=False)[
            ["ratio_to_exact_median", "achieved_p_fit"]].median()
        return (f"<p><b>Design-level audit</b>, {self.summary['im']}: median CMR "
                f"{self.fragility['cmr'].median():.3g}.</p>"
                + lines.to_html(float_format=lambda v: f"{v:.3g}", na_rep="—"))


def margins(procedures="all", records=None, *, im: str | None = None, stripes=None,
            alpha_deg=DEFAULT_ALPHA_DEG, size_s=None, blocks=(), solver=None,
            required: bool = True, hazard=None, site=None, floor=None, runtime=None,
            params: dict | None = None, method: str | None = None) -> MarginsResult:
    """The design-level audit: exact multiple-stripe fragility of every block, and where each
    procedure draws its line against it (see :mod:`audit.engine.design.margins`).

    Every argument is checked before anything is read or computed (by
    :meth:`MarginsSettings.parse <audit.engine.design.settings.MarginsSettings.parse>` and
    each group's ``parse``: :class:`~audit.engine.shared.solver.Solver`,
    :class:`~audit.engine.shared.hazard.Hazard`, :class:`~audit.engine.shared.design_site.Site`,
    :class:`~audit.physics.building.floor.Floor`, :class:`~audit.engine.shared.runtime.Runtime`,
    :class:`~audit.engine.shared.record_request.Records`); a bad one raises :class:`~audit.errors.InputError`
    naming it.

    Parameters
    ----------
    procedures, records :
        As for :func:`audit.run`.
    im : str, optional
        Intensity measure: ``pga`` [g], ``pgv`` [m/s] or ``sa:T`` (T in s) [g]; default
        ``sa:1.0``, or the hazard curve's IMT.
    stripes : float or sequence of float, optional
        Intensity levels, increasing [unit of ``im``]; default the fixed lattice, 27 levels
        2^(k/4), k = −16 … 10 (0.0625–5.66 in the IM's unit,
        :func:`audit.engine.shared.lattice.stripe_lattice`).
    alpha_deg : float or sequence of float
        Slendernesses [degrees], 0 < α < 45 (may be empty when ``blocks`` are given).
    size_s : float or sequence of float, optional
        Block sizes 2π/p [s]; default 0.5 … 8 s in steps of 0.25 s.
    blocks : sequence of str or Block
        Blocks by their dimensions, ``"WIDTHxHEIGHT"`` [m] or :class:`Block`, beside the grid.
    solver : Solver, optional
        The exact solver: ``Solver(restitution="housner", free_motion_s=..., g=9.81)``, as for
        :func:`audit.check`.
    required : bool
        Also search the required slenderness of each size.
    hazard : Hazard, records.hazard.HazardCurve, str or pathlib.Path, optional
        The site's hazard curve or its file: the risk at the site; its IMT sets ``im``.
        ``Hazard(curve, imt=..., location=(lon, lat), risk_target=0.01)``: the IMT of a file
        of several, the site in a file of several sites [degrees], the probability of
        overturning in 50 years [-] the risk-targeted slenderness meets.
    site : Site, (float, float) or str, optional
        FEMA 356 S_XS, S_X1 [g], replacing the records' own: the design intensity of the CMR.
        ``Site(sxs_g, sx1_g, level="mce", scale_records=..., anchor_period_s=..., ntc=...)``:
        the hazard level of the values (``mce``, or ``design``: the CMR is over 1.5 × them),
        and the scaling and NTC 2018 site as for :func:`audit.run`.
    floor : Floor, optional
        Where the blocks stand, as for :func:`audit.run`; the stripes stay in the ground's
        intensity measure.
    runtime : Runtime, optional
        How, as for :func:`audit.run`.
    params : dict, optional
        The procedures' parameters, as for :func:`audit.run`.
    method : {None, "atlas", "direct"}
        Where the blocks' exact fragilities come from: ``atlas``, the atlas of these records,
        IM, floor, restitution, g and free motion (``python -m audit atlas build``), at its 14
        stripes (the lattice's levels √2 apart), each block's error stated (InputError naming
        ``method`` where none answers: none built, a block outside its grid, other
        ``stripes`` asked); ``direct``, solved at the stripes; None, the atlas where one
        answers, else direct. The guidelines, the required slenderness and the acceptance stay
        direct (:mod:`audit.engine.atlas.fragility_read`).

    Returns
    -------
    MarginsResult
    """
    from audit.api.atlas_lookup import atlas_reading
    from audit.api.inputs import parameters_of, procedures_of, record_suite
    from audit.engine.atlas.fragility_read import checked_method
    from audit.engine.shared import guards
    from audit.engine.design.costs import margins_cost
    from audit.engine.design.pipeline import run_margins
    from audit.engine.design.settings import MarginsSettings
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.progress import Progress
    from audit.engine.shared.blocks import BlockList
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.solver import Solver
    where = DesignSite.parse(site, floor, "margins")
    if where.site is not None:  # one design site: the audit is of that site
        where = replace(where, site=replace(where.site, override=where.site.sxs_g is not None))
    settings = MarginsSettings.parse(
        im=im, stripes=stripes, alpha_deg=alpha_deg, size_s=size_s, blocks=blocks,
        solver=solver, required=required, hazard=hazard,
        site_level=DEFAULT_SITE_LEVEL if where.site is None else where.site.level)
    runtime = Runtime.parse(runtime)
    checked_method(method)
    bar = runtime.progress is True  # drawn here: the engine takes a callable
    if bar:
        runtime = replace(runtime, progress=None)
    chosen, _ = parameters_of(params, procedures_of(procedures), provisions=False)
    read = record_suite(records)
    suite = where.apply(read)
    guards.check(margins_cost(chosen, suite, settings, runtime), runtime.force,
                 force_field="runtime.force")
    grid = BlockList.of(settings.alpha_deg, settings.size_s, settings.blocks)
    atlas = atlas_reading(method, read, (grid.alpha_deg, grid.size_s), im=settings.im,
                          solver=Solver(settings.restitution, settings.free_motion_s,
                                        settings.g),
                          floor=where.floor, stripes=settings.stripes,
                          named=getattr(records, "source", records)) if len(grid) else None
    if bar:
        runtime = replace(runtime, progress=Progress(len(suite), "record"))
    start = time.perf_counter()
    try:
        run = run_margins(chosen, suite, settings, runtime, atlas)
    finally:
        if bar:
            runtime.progress.done()
    return MarginsResult(run, time.perf_counter() - start)


__all__ = ["margins", "MarginsResult"]
