"""The design-level audit: :func:`margins` and its :class:`MarginsResult`."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from audit.engine.design_site import SITE_FIELDS, DesignSite
from audit.engine.margins_settings import MARGINS_FIELDS, MarginsSettings
from audit.engine.runtime import RUNTIME_FIELDS, Runtime


class MarginsResult:
    """A design-level audit's tables: ``.stripes``, ``.fragility``, ``.capacity``,
    ``.required_alpha``, ``.scan``, ``.acceptance`` (FEMA P695's test of the blocks each
    guideline sizes, with a design site), and at a site ``.risk``, ``.risk_alpha`` (DataFrames,
    the columns of the CSV files of the same names), ``.summary``, ``.write(folder)`` (the
    files and ``margins.html``) and ``.report(path)``."""

    def __init__(self, margins):
        self.margins = margins
        self.stripes, self.fragility = margins.stripes, margins.fragility
        self.capacity, self.summary = margins.capacity, margins.summary
        self.required_alpha, self.scan = margins.required_alpha, margins.scan
        self.risk, self.risk_alpha = margins.risk, margins.risk_alpha
        self.acceptance = margins.acceptance

    def files(self) -> dict[str, bytes]:
        """Every file of the audit, the page drawn from the CSV files as saved."""
        from audit.engine.margins import margins_files
        from reports.margins_page import MARGINS_HTML, render_margins_page
        return with_page(margins_files(self.margins), MARGINS_HTML, render_margins_page)

    def write(self, out_dir) -> Path:
        """Write the files and ``margins.html`` into ``out_dir`` (atomically, together)."""
        from audit.files import write_files_atomically
        write_files_atomically(Path(out_dir), self.files())
        return Path(out_dir)

    def report(self, path) -> Path:
        """Write ``margins.html`` alone to ``path``."""
        from audit.files import write_file_atomically
        from reports.margins_page import MARGINS_HTML
        write_file_atomically(Path(path), self.files()[MARGINS_HTML])
        return Path(path)

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


def with_page(files: dict, page_name: str, render) -> dict:
    """``files`` and the page ``render(folder)`` draws from them as saved (in a scratch folder),
    so that a page is always the picture of exactly the files beside it."""
    import tempfile

    from audit.files import write_files_atomically
    with tempfile.TemporaryDirectory() as saved:
        write_files_atomically(saved, files)
        return {**files, page_name: render(saved).encode()}


def margins(procedures="all", records=None, *, force: bool = False,
            **options) -> MarginsResult:
    """The design-level audit: exact multiple-stripe fragility of every block, and where each
    procedure draws its line against it (see :mod:`audit.engine.margins`).

    Every argument is checked before anything is read or computed; a bad one raises
    :class:`~audit.errors.InputError` naming it.

    Parameters
    ----------
    procedures, records :
        As for :func:`audit.run`.
    force : bool
        Start even when the estimated work is beyond the limits (:mod:`audit.engine.guards`).
    **options :
        What is computed, the fields of
        :class:`~audit.engine.margins_settings.MarginsSettings`: ``im`` (``pga`` [g], ``pgv``
        [m/s] or ``sa:T``), ``stripes`` (intensity levels, increasing; default 24 levels,
        0.2–5 × the design intensity or the suite's median), ``alpha_deg``, ``sizes_s``
        (default 0.5 … 8 s in steps of 0.25 s), ``blocks`` (``"WIDTHxHEIGHT"`` [m] or
        :class:`Block`), ``restitution``, ``free_motion_s``, ``required`` (also the required
        slenderness of each size), ``g``, ``site_level`` (``"mce"``, the default, or
        ``"design"``: the CMR is over the MCE intensity, 1.5 × design values), ``hazard`` (a
        hazard curve or its file: the risk at the site; its IMT sets ``im``),
        ``site_location`` (lon, lat [degrees] in a file of several sites), ``risk_target``
        (probability of overturning in 50 years);
        the design site: ``site`` (S_XS, S_X1 [g], replacing the records' own: the design
        intensity of the CMR), ``scale_to_site``, ``anchor_period_s``, ``ntc_site`` (see
        :func:`audit.run`);
        how: ``jobs``, ``scheduler``, ``partial_dir``, ``resume``, ``progress``.
    """
    from audit.api.inputs import procedures_of, split, suite_of
    from audit.engine import guards
    from audit.engine.costs import margins_cost
    from audit.engine.margins_audit import design_level_audit
    from audit.engine.progress import Progress
    values, site, how = split(options, MARGINS_FIELDS,
                              tuple(f for f in SITE_FIELDS if f != "site_override"),
                              RUNTIME_FIELDS)
    settings = MarginsSettings.parse(**values)
    # one design site: the audit is of that site
    site = DesignSite.parse(**site, site_override=site.get("site") is not None)
    bar = how.get("progress") is True
    runtime = Runtime.parse(**{**how, "progress": None if how.get("progress") in (True, False)
                               else how.get("progress")})
    chosen = procedures_of(procedures)
    suite = site.apply(suite_of(records))
    guards.check(margins_cost(chosen, suite, settings, runtime), force)
    if bar:
        runtime = replace(runtime, progress=Progress(len(suite), "record"))
    try:
        run = design_level_audit(chosen, suite, settings, runtime)
    finally:
        if bar:
            runtime.progress.done()
    return MarginsResult(run)


__all__ = ["margins", "MarginsResult", "with_page"]
