"""The audit of guideline procedures over a grid of blocks: :func:`run` and its
:class:`AuditResult`."""

from __future__ import annotations

import functools
import warnings
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import DEFAULT_AGREE_BAND, DEFAULT_ALPHA_DEG, DEFAULT_ROBUSTNESS
from audit.errors import InputWarning

if TYPE_CHECKING:  # pandas and the engine are loaded by what uses them, not by the front door
    import pandas as pd

    from audit.engine.run.audit_run import AuditRun
    from audit.engine.run.settings import AuditSettings
    from audit.engine.shared.design_site import Site
    from audit.physics.building.floor import Floor

#: The run's self-contained HTML report, beside its files.
REPORT_HTML = "report.html"


def typed(table: pd.DataFrame, file_name: str) -> pd.DataFrame:
    """``table`` of ``file_name`` with its columns typed by the schema (the column guide):
    numbers as floats (NaN where empty), flags as booleans (NA where empty), text as text."""
    import pandas as pd

    from audit.engine.shared.schemas import GUIDE
    table = table.copy()
    for column, (unit, _) in GUIDE[file_name].items():
        if column not in table:
            continue
        values = table[column]
        if unit == "bool":
            table[column] = values.map({True: True, False: False, "True": True,
                                        "False": False}).astype("boolean")
        elif unit != "text":
            table[column] = pd.to_numeric(values.replace("", None), errors="coerce")
    return table


class AuditResult:
    """An audit's files in a folder, its tables as DataFrames (read on first use), its bottom
    line, and its report.

    Attributes
    ----------
    folder : Path
        Where the data files are (a scratch folder kept with the result unless ``run`` was
        given one).
    summary : dict
        Everything of ``summary.json`` (read on first use).
    table : pandas.DataFrame
        One row per procedure × record × α × size (``results.csv``), as :attr:`results`.
    """

    def __init__(self, folder, scratch=None):
        self.folder = Path(folder)
        self._scratch = scratch  # a TemporaryDirectory, removed with the result

    @functools.cached_property
    def summary(self) -> dict:
        """Everything of ``summary.json``, as saved."""
        from audit.engine.run.results import read_summary
        return read_summary(self.folder)

    @functools.cached_property
    def run(self) -> AuditRun:
        """Everything the audit produced (also ``.spectra``, ``.rocking``, ``.histories``),
        read from its files."""
        from audit.engine.run.results import load_run
        return load_run(self.folder)

    results = property(lambda self: typed(self.run.results, "results.csv"),
                       doc="One row per procedure × record × α × size (``results.csv``).")
    table = property(lambda self: self.results,
                     doc="The audit's table: :attr:`results` (``results.csv``).")
    suite = property(lambda self: typed(self.run.suite, "suite.csv"),
                     doc="Verdict statistics over the records per procedure × α × size.")
    checks = property(lambda self: typed(self.run.checks, "checks.csv"),
                      doc="Limit-state checks against the exact response (``checks.csv``).")
    claims = property(lambda self: typed(self.run.claims, "claims.csv"),
                      doc="The reference report's claims, checked (``claims.csv``).")

    @property
    def bottom_line(self) -> pd.DataFrame:
        """Per procedure: blocks compared, the % unsafe and uneconomic, the median approx/exact,
        and the worst block."""
        import pandas as pd
        titles = {p["name"]: p["title"] for p in self.summary["procedures"]}
        rows = []
        for line in self.summary["bottom_line"]:
            worst = line["worst"] or {}
            rows.append({"procedure": line["name"], "title": titles[line["name"]],
                         "records": line["records"], "blocks": line["blocks"],
                         "unsafe_pct": line["unsafe_pct"],
                         "uneconomic_pct": line["uneconomic_pct"],
                         "agrees_pct": line["pct"]["agrees"],
                         "not_converged_pct": line["pct"]["not-converged"],
                         "median_ratio": line["median_ratio"],
                         "worst_record": worst.get("record"),
                         "worst_alpha_deg": worst.get("alpha_deg"),
                         "worst_size_s": worst.get("size_s"),
                         "worst_verdict": worst.get("verdict")})
        return pd.DataFrame(rows)

    def summary_text(self) -> str:
        """The lines ``audit run`` prints: what was audited where, what could not be, and the
        count of each verdict."""
        from audit.engine.run.words import audit_summary_text
        return audit_summary_text(self.summary)

    def write(self, out_dir) -> Path:
        """Write the result files and ``report.html`` into ``out_dir`` (atomically, together)."""
        import shutil

        from audit.engine.run.results import COLUMNS_JSON, DATA_FILES
        from audit.files import staged_folder
        out_dir = check.path("out_dir", out_dir, "a folder")
        with staged_folder(out_dir) as staging:
            for name in (*DATA_FILES, COLUMNS_JSON):
                shutil.copyfile(self.folder / name, staging / name)
            self.report(staging / REPORT_HTML)
        return Path(out_dir)

    def report(self, path) -> Path:
        """Write only the self-contained HTML report to ``path``, drawn from the files as saved
        (the rows of the records it shows, read in bounded memory)."""
        from audit.engine.run.results import load_run
        from audit.files import write_file_atomically
        from reports import render_report
        path = check.path("path", path, "a file name")
        html = render_report(load_run(self.folder, shown=True))
        write_file_atomically(Path(path), html.encode("utf-8"))
        return Path(path)

    def _repr_html_(self) -> str:
        table = self.bottom_line[["title", "records", "blocks", "unsafe_pct",
                                  "uneconomic_pct", "agrees_pct", "median_ratio"]]
        return (f"<p><b>Rocking audit</b> on {self.summary['records_source']}: "
                f"{self.blocks} block comparisons.</p>"
                + table.to_html(index=False, float_format=lambda v: f"{v:.3g}", na_rep="—"))

    def __repr__(self) -> str:
        return (f"AuditResult({', '.join(p['name'] for p in self.summary['procedures'])} on "
                f"{self.summary['records_source']}: {self.blocks} block comparisons)")

    @property
    def blocks(self) -> int:
        """Blocks compared with the exact response, every procedure."""
        return sum(line["blocks"] for line in self.summary["bottom_line"])


def run(procedures="all", records=None, *, alpha_deg=DEFAULT_ALPHA_DEG, size_s=None,
        solver=None, agree_band: float = DEFAULT_AGREE_BAND,
        robustness: float = DEFAULT_ROBUSTNESS, friction: float | None = None, sensitivity=(),
        site=None, floor=None, detail=(), out_dir=None, runtime=None,
        params: dict | None = None) -> AuditResult:
    """Audit guideline procedures on a suite of records over a grid of blocks.

    Every argument is checked before anything is read or computed (by
    :meth:`AuditSettings.parse <audit.engine.run.settings.AuditSettings.parse>` and each
    group's ``parse``: :class:`~audit.engine.shared.solver.Solver`,
    :class:`~audit.engine.shared.design_site.Site`, :class:`~audit.physics.building.floor.Floor`,
    :class:`~audit.engine.shared.runtime.Runtime`, :class:`~audit.engine.shared.record_request.Records`); a bad one
    raises :class:`~audit.errors.InputError` naming it (``size_s``, ``site.anchor_period_s``).

    Parameters
    ----------
    procedures : str, Procedure, type or list
        ``"all"``, a registered name (``"fema356"``), a Procedure instance or subclass (a
        plug-in written in the notebook), or a list of those.
    records : str, path, records.RecordSuite or Records, optional
        A built-in suite name, a manifest / record file / folder, or a suite from
        :func:`records.load`; default: ``$ROCKING_AUDIT_RECORDS``, else the shipped seed
        records. ``Records(source, dt_s=..., units=..., skip_bad_records=...)`` says how a
        text record file that states neither is read (time step [s]; ``g``, ``m/s2`` or
        ``cm/s2``), and audits the readable records of the suite, the unreadable ones warned
        about (:class:`~audit.errors.InputWarning`) and left out.
    alpha_deg : float or sequence of float
        Slendernesses α [degrees], 0 < α < 45.
    size_s : float or sequence of float, optional
        Block sizes 2π/p [s]; default 0.5 … 8.0 s in steps of 0.05 s.
    solver : Solver, optional
        The exact solver: ``Solver(restitution="housner", free_motion_s=..., g=9.81,
        vertical=False)``: the impact model (``housner``, Eq. 4.8, a fixed r in (0, 1] [-] or
        ``xFACTOR`` times Eq. 4.8), the free motion after each record for the exact solver
        and the record spectra [s], gravity [m/s²], and the records' vertical components in
        the exact response.
    agree_band : float
        Half-width of the agreement band on approx/exact [-], in [0, 1).
    robustness : float
        ε of the fragility flag: exact spectra also at the record × (1 ± ε) [-]; 0 = off.
    friction : float, optional
        Friction coefficient μ of the base [-]: blocks that would slide are flagged.
    sensitivity : str or sequence of str
        Alternative ground-truth models (``"restitution=x0.9,x0.8"``, ``"vertical"``).
    site : Site, (float, float) or str, optional
        FEMA 356 design site S_XS, S_X1 [g] for every record without one (``(1.5, 0.9)`` or
        ``"1.5,0.9"``); ``Site(sxs_g, sx1_g, ntc=..., override=..., scale_records=...,
        anchor_period_s=...)``: an NTC 2018 site a_g [g], F0 [-], T_C* [s], soil category A–E,
        topography T1–T4 (``Site(None, None, ntc=...)`` alone); also replace the sites records
        carry (Table 3.1); scale the suite to the design spectrum at the anchor period [s]
        (1 s when not given) the FEMA P695 way.
    floor : Floor, optional
        Where the blocks stand: ``Floor(z_over_h, Building(period_s, model="continuum:10",
        damping=0.05))``, z/H in the building (1 the roof), its first-mode period T1 [s], its
        model (``shear:N`` or ``continuum:α0``) and damping ζ [-]; None or 0 the ground (the
        default). The site scales the ground motion, the blocks rock on the floor's
        (:mod:`audit.engine.shared.floors`).
    detail : str or sequence of str
        Records whose detail the report shows.
    out_dir : str or Path, optional
        Write the result files and ``report.html`` there (atomically, together), record by
        record: memory does not grow with the suite beyond a small term per record until the
        tables are read (``.results``, ``.run``). Default: the data files in a scratch folder
        kept with the result (``.write(out_dir)`` saves them later).
    runtime : Runtime, optional
        How: ``Runtime(jobs, scheduler, progress, force, partial_dir, resume)``: threads of
        the exact solver, or worker processes with ``scheduler="dask"``; ``local``, ``dask``
        or ``tcp://HOST:PORT``; a progress bar on standard error (True), or
        ``progress(done, total, record_id, how)``; start even when the estimated work is
        beyond the limits (:mod:`audit.engine.shared.guards`); the folder for the per-record
        results as they complete, and reuse of the matching ones already there.
    params : dict, optional
        The procedures' parameters, ``{name: {key: value}}`` (``{"ntc2018": {"q": 1.5}}``),
        each declared by its procedure (docs/procedures.md); an unknown one is refused.

    Returns
    -------
    AuditResult
    """
    from audit.api.inputs import parameters_of, procedures_of, record_suite
    from audit.engine.shared import guards
    from audit.engine.run.costs import audit_cost
    from audit.engine.shared.progress import Progress
    from audit.engine.run.pipeline import run_audit, compiles_first
    from audit.engine.run.settings import AuditSettings
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.runtime import Runtime
    from audit.files import staged_folder
    settings = AuditSettings.parse(alpha_deg=alpha_deg, size_s=size_s, solver=solver,
                                   agree_band=agree_band, robustness=robustness,
                                   friction=friction, sensitivity=sensitivity)
    where = DesignSite.parse(site, floor, "run")
    detail = check.words("detail", detail)
    runtime = Runtime.parse(runtime)
    bar = runtime.progress is True  # drawn here: the engine takes a callable
    if bar:
        runtime = replace(runtime, progress=None)
    if out_dir is not None:
        out_dir = check.path("out_dir", out_dir, "a folder")
    chosen, _ = parameters_of(params, procedures_of(procedures), provisions=False)
    suite = where.apply(record_suite(records))
    _warn_without_vertical(suite, settings)
    guards.check(audit_cost(chosen, suite, settings, runtime), runtime.force,
                 force_field="runtime.force")
    stage = Progress(len(suite), "record") if bar else runtime.progress
    if bar:
        runtime = replace(runtime, progress=stage)
        stage.stage(f"auditing {', '.join(p.name for p in chosen)} on {len(suite)} records")
        if compiles_first():
            stage.stage("compiling the rocking solver and the oscillator kernels for this "
                        "machine (only the first run after installing or updating: about 40 s)")
    stage = stage if hasattr(stage, "stage") else None
    if out_dir is None:
        import tempfile
        scratch = tempfile.TemporaryDirectory(prefix="rocking-audit-")
        run_audit(chosen, suite, settings, runtime, scratch.name, detail, progress=stage)
        return AuditResult(scratch.name, scratch)
    # the summary is read back when asked: the report is drawn without a second copy in memory
    with staged_folder(out_dir) as staging:  # files appear only when all are written
        run_audit(chosen, suite, settings, runtime, staging, detail, progress=stage)
        del suite  # the motions go too, unless the caller holds them
        if stage is not None:
            stage.stage(f"writing the report to {out_dir}")
        AuditResult(staging).report(staging / REPORT_HTML)
    return AuditResult(out_dir)


def load_result(folder) -> AuditResult:
    """The audit whose files are in ``folder`` (the output of :func:`run`, or of ``python -m
    audit run``), read on first use.

    Parameters
    ----------
    folder : str or Path
        The folder of an audit's files.

    Returns
    -------
    AuditResult
    """
    from audit.engine.run.results import checked_summary
    result = AuditResult(check.path("folder", folder, "the folder of an audit's files"))
    result.summary = checked_summary(result.folder)  # a folder without an audit is refused
    return result


def design_suite(suite, *, site: Site | None = None, floor: Floor | None = None):
    """``suite`` at the design site, on the floor (:meth:`DesignSite.apply
    <audit.engine.shared.design_site.DesignSite.apply>`).

    Parameters
    ----------
    suite : records.RecordSuite
    site : Site, (float, float) or str, optional
        As for :func:`run`: S_XS, S_X1 [g], and ``Site(…, ntc=…, override=…,
        scale_records=…, anchor_period_s=…)``: NTC 2018 a_g [g], F0, T_C* [s], soil,
        topography; the site over the records' own; the records scaled to it (FEMA P695) at
        the anchor period [s].
    floor : Floor, optional
        Where the blocks stand (``Floor(z_over_h, Building(period_s, model, damping))``,
        default the ground); the site scales the ground motion, the blocks rock on the
        floor's (:mod:`audit.engine.shared.floors`).
    """
    from audit.engine.shared.design_site import DesignSite
    return DesignSite.parse(site, floor, "run").apply(suite)


def _warn_without_vertical(suite, settings: AuditSettings) -> None:
    if settings.vertical or "vertical" in settings.sensitivity:
        if not any(e.motion is not None and e.motion.vertical is not None for e in suite):
            warnings.warn(f"vertical: none of the {len(suite)} records has a vertical "
                          "component; the exact response stays horizontal", InputWarning,
                          stacklevel=3)


__all__ = ["run", "AuditResult", "typed", "design_suite", "load_result", "REPORT_HTML"]
