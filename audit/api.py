"""The Python API: the engine the command line runs, for notebooks and scripts.

    import audit, records
    block = audit.Block.from_dimensions(width_m=0.8, height_m=2.4)
    response = audit.rock(block, records.load("pulses").get("pacoima_dam_1971"))
    result = audit.run("all", records="p695-far-field", site=(1.5, 0.9), scale_to_site=True)
    result.bottom_line                       # a DataFrame; result.write("out") for the files

Angles are given in degrees and accelerations in g at this edge, as on the command line;
everything inside is SI. Bad input raises :class:`audit.errors.InputError` with the message the
command line prints.
"""

from __future__ import annotations

import functools
import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from audit import G
from audit.engine.defaults import (DEFAULT_AGREE_BAND, DEFAULT_ALPHA_DEG, DEFAULT_FREE_MOTION_S,
                                   DEFAULT_JOBS, DEFAULT_ROBUSTNESS, DEFAULT_SCHEDULER)
from audit.engine.audit_run import AuditRun
from audit.engine.suite_run import compute_suite, write_suite
from audit.errors import InputError
from audit.physics.block import RigidBlock
from audit.physics.rocking import RockingResponse as _Response
from audit.physics.rocking import simulate
from procedures.base import Procedure


@dataclass(frozen=True)
class Block:
    """A free-standing rectangular block, by its slenderness and size.

    Parameters
    ----------
    alpha_deg : float
        Slenderness α = atan(b/h) [degrees], 0 < α < 45.
    size_s : float
        Size 2π/p [s], p = √(3g/(4R)) the frequency parameter (Eq. 4.2), R the half-diagonal.
    r : float, optional
        Coefficient of restitution (ratio of kinetic energies after/before an impact) [-];
        Eq. 4.8 of Makris & Konstantinidis (2001), r = (1 − 1.5 sin²α)², when not given.
    g : float
        Acceleration of gravity [m/s²].
    """

    alpha_deg: float
    size_s: float
    r: float | None = None
    g: float = G

    def __post_init__(self):
        self.rigid  # validates α, the size, r and g with the solver's own messages

    @classmethod
    def from_dimensions(cls, width_m: float, height_m: float, r: float | None = None,
                        g: float = G) -> Block:
        """The block of full width 2b and full height 2h [m]: α = atan(b/h), R = √(b² + h²)."""
        rigid = RigidBlock.from_dimensions(width_m / 2.0, height_m / 2.0, r, g)
        return cls(math.degrees(rigid.alpha), rigid.size_s, r, g)

    @property
    def rigid(self) -> RigidBlock:
        """The solver's block (p [rad/s], α [rad], r, g)."""
        return RigidBlock.from_size(self.size_s, math.radians(self.alpha_deg), self.r, self.g)

    @property
    def p_rad_s(self) -> float:
        """Frequency parameter p = 2π/size [rad/s]."""
        return 2.0 * math.pi / self.size_s

    @property
    def radius_m(self) -> float:
        """Half-diagonal R = 3g/(4p²) [m]."""
        return self.rigid.radius

    @property
    def width_m(self) -> float:
        """Full width 2b = 2R sin α [m]."""
        return 2.0 * self.rigid.half_width

    @property
    def height_m(self) -> float:
        """Full height 2h = 2R cos α [m]."""
        return 2.0 * self.rigid.half_height

    @property
    def restitution(self) -> float:
        """The coefficient of restitution r the solver uses [-]."""
        return self.rigid.r


class RockingResponse:
    """The exact response of one block to one ground motion (:func:`rock`).

    Attributes
    ----------
    block : Block
    motion : records.GroundMotion
    overturned : bool
    peak : float
        max |θ| [rad] (α when the block overturns).
    peak_ratio : float
        max |θ| / α [-].
    overturn_time_s : float or None
    impacts : int
    """

    def __init__(self, block: Block, motion, response: _Response):
        self.block, self.motion, self.solution = block, motion, response
        self.overturned = bool(response.overturned)
        self.peak = float(response.peak_rotation)
        self.peak_ratio = float(response.peak_rotation_ratio)
        self.overturn_time_s = float(response.overturn_time) if response.overturned else None
        self.impacts = int(response.n_impacts)

    @property
    def history(self) -> pd.DataFrame:
        """The response at every solver output point: ``time_s, theta_rad, theta_dot_rad_s,
        ground_acc_g``; an impact appears twice at its time (θ' before, then after)."""
        time, theta, omega = self.solution.history()
        return pd.DataFrame({"time_s": time, "theta_rad": theta, "theta_dot_rad_s": omega,
                             "ground_acc_g": self.motion.acceleration_at(time) / G})

    def plot(self):
        """θ/α and θ' against time, rocking cycles shaded: a matplotlib Figure."""
        from reports.figures import draw_time_histories, new_figure
        response = self.solution
        fig = new_figure(10.0, 5.0)
        draw_time_histories(fig, [{
            "time": response.time, "theta_ratio": response.theta / response.block.alpha,
            "omega": response.omega,
            "title": (f"{getattr(self.motion, 'id', 'motion')}: 2π/p = {self.block.size_s:.3g} s, "
                      f"α = {self.block.alpha_deg:g}°"),
            "rocking_span": ((response.impact_times[0], response.impact_times[-1])
                             if response.n_impacts else None),
            "cycle_starts": response.cycle_starts, "cycle_durations": response.cycle_durations,
            "excitation_end": response.excitation_end}])
        return fig

    def __repr__(self) -> str:
        what = (f"overturns at t = {self.overturn_time_s:.3f} s" if self.overturned
                else f"peak θ/α = {self.peak_ratio:.4f}")
        return (f"RockingResponse(α = {self.block.alpha_deg:g}°, 2π/p = {self.block.size_s:g} s: "
                f"{what}, {self.impacts} impact{'' if self.impacts == 1 else 's'})")


def rock(block: Block, motion, free_motion_s: float = DEFAULT_FREE_MOTION_S) -> RockingResponse:
    """Exact rocking response of ``block`` to ``motion`` (Eq. 4.3, impacts by Eq. 4.8).

    Parameters
    ----------
    block : Block
    motion : records.GroundMotion or records.RecordEntry
        Ground acceleration [m/s²] (a suite's record, e.g. ``records.load(...).get(id)``).
    free_motion_s : float
        Free motion simulated after the excitation ends [s].
    """
    motion = getattr(motion, "motion", motion)
    if motion is None:
        raise InputError("rock: the record has no file to read")
    return RockingResponse(block, motion, simulate(block.rigid, motion, free_motion_s))


def _procedures(procedures) -> list[Procedure]:
    """Procedure instances from ``"all"``, a name, an instance, a class or a list of those."""
    from procedures import get_procedures
    if isinstance(procedures, (str, Procedure)) or isinstance(procedures, type):
        procedures = [procedures]
    out = []
    for item in procedures:
        if isinstance(item, str):
            out += get_procedures(item)
        elif isinstance(item, Procedure):
            out.append(item)
        elif isinstance(item, type) and issubclass(item, Procedure):
            out.append(item())
        else:
            raise InputError(f"procedures: expected a name, 'all' or a Procedure, got {item!r}")
    return out


def design_suite(suite, site=None, site_override: bool = False, scale_to_site: bool = False,
                 anchor_period_s: float | None = None, ntc_site=None):
    """``suite`` with design sites and the FEMA P695 scaling to a design spectrum.

    Parameters
    ----------
    suite : records.RecordSuite
    site : (float, float), optional
        FEMA 356 design site S_XS, S_X1 [g] for every record without one.
    site_override : bool
        Also replace the sites records carry (Table 3.1).
    scale_to_site : bool
        Scale the suite so that its median 5 %-damped Sa at ``anchor_period_s`` equals the
        design spectrum (each record first by its P695 normalisation factor).
    anchor_period_s : float, optional
        Anchor period [s] (1 s when not given).
    ntc_site : (float, float, float, str, str), optional
        NTC 2018 site a_g [g], F0 [-], T_C* [s], soil category A–E, topography T1–T4.
    """
    from audit.engine.sites import scale_to_site as scaled, with_design_site, with_ntc_site
    if ntc_site is not None:
        ag_g, f0, tc_star_s, soil, topography = ntc_site
        try:
            suite = with_ntc_site(suite, ag_g, f0, tc_star_s, str(soil).strip().upper(),
                                  str(topography).strip().upper())
        except InputError as exc:  # the spectrum names the field; the user typed the option
            raise InputError(f"--ntc-site: {exc}") from None
    if anchor_period_s is not None and not scale_to_site:
        raise InputError("--anchor-period: needs --scale-to-site")
    if site is None:
        if site_override or scale_to_site:
            raise InputError("--site-override and --scale-to-site need --site SXS,SX1")
        return suite
    sxs_g, sx1_g = site
    if not (sxs_g > 0 and sx1_g > 0):
        raise InputError(f"--site: S_XS and S_X1 must be positive accelerations in g, "
                         f"got {sxs_g:g},{sx1_g:g}")
    suite = with_design_site(suite, sxs_g, sx1_g, override=site_override)
    if scale_to_site:
        suite = scaled(suite, sxs_g, sx1_g, 1.0 if anchor_period_s is None else anchor_period_s)
    return suite


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
    """

    def __init__(self, folder, scratch=None):
        self.folder = Path(folder)
        self._scratch = scratch  # a TemporaryDirectory, removed with the result

    @functools.cached_property
    def summary(self) -> dict:
        """Everything of ``summary.json``, as saved."""
        from audit.engine.results import read_summary
        return read_summary(self.folder)

    @functools.cached_property
    def run(self) -> AuditRun:
        """Everything the audit produced (also ``.spectra``, ``.rocking``, ``.histories``),
        read from its files."""
        from audit.engine.results import load_run
        return load_run(self.folder)

    results = property(lambda self: self.run.results,
                       doc="One row per procedure × record × α × size (``results.csv``).")
    suite = property(lambda self: self.run.suite,
                     doc="Verdict statistics over the records per procedure × α × size.")
    checks = property(lambda self: self.run.checks,
                      doc="Limit-state checks against the exact response (``checks.csv``).")
    claims = property(lambda self: self.run.claims,
                      doc="The reference report's claims, checked (``claims.csv``).")

    @property
    def bottom_line(self) -> pd.DataFrame:
        """Per procedure: blocks compared, the % unsafe and uneconomic, the median approx/exact,
        and the worst block."""
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

    def write(self, out_dir) -> Path:
        """Write the result files and ``report.html`` into ``out_dir`` (atomically, together)."""
        import shutil

        from audit.engine.results import COLUMNS_JSON, DATA_FILES, REPORT_HTML
        from audit.files import staged_folder
        with staged_folder(out_dir) as staging:
            for name in (*DATA_FILES, COLUMNS_JSON):
                shutil.copyfile(self.folder / name, staging / name)
            self.report(staging / REPORT_HTML)
        return Path(out_dir)

    def report(self, path) -> Path:
        """Write only the self-contained HTML report to ``path``, drawn from the files as saved
        (the rows of the records it shows, read in bounded memory)."""
        from audit.engine.results import load_run
        from audit.files import write_file_atomically
        from reports import render_report
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


def run(procedures="all", records=None, alpha_deg=DEFAULT_ALPHA_DEG, sizes_s=None, site=None,
        site_override: bool = False, scale_to_site: bool = False, anchor_period_s=None,
        ntc_site=None, jobs: int = DEFAULT_JOBS, free_motion_s: float = DEFAULT_FREE_MOTION_S,
        agree_band: float = DEFAULT_AGREE_BAND, robustness: float = DEFAULT_ROBUSTNESS,
        scheduler: str = DEFAULT_SCHEDULER, detail=(), progress: bool = False,
        partial_dir=None, resume: bool = False, restitution="housner", vertical: bool = False,
        friction: float | None = None, sensitivity=(), out_dir=None) -> AuditResult:
    """Audit guideline procedures on a suite of records over a grid of blocks.

    Parameters
    ----------
    procedures : str, Procedure, type or list
        ``"all"``, a registered name (``"fema356"``), a Procedure instance or subclass (a
        plug-in written in the notebook), or a list of those.
    records : str, path or records.RecordSuite, optional
        A built-in suite name, a manifest / record file / folder, or a suite from
        :func:`records.load`; default: ``$ROCKING_AUDIT_RECORDS``, else the shipped seed records.
    alpha_deg : sequence of float
        Slendernesses [degrees].
    sizes_s : array, optional
        Block sizes 2π/p [s]; default 0.5 … 8.0 s in steps of 0.05 s.
    site, site_override, scale_to_site, anchor_period_s, ntc_site :
        Design sites and scaling, see :func:`design_suite`.
    jobs : int
        Threads of the exact solver (worker processes with ``scheduler="dask"``).
    free_motion_s : float
        Free motion after each record [s].
    agree_band : float
        Half-width of the agreement band on approx/exact [-].
    robustness : float
        ε of the fragile-overturning flag [-] (0 turns it off).
    scheduler : str
        ``local``, ``dask`` or ``tcp://HOST:PORT``.
    detail : sequence of str
        Records whose detail the report shows.
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, record_id, how)``.
    partial_dir, resume :
        Keep each record's part in ``partial_dir`` as it completes; reuse them with ``resume``.
    restitution : str
        The impact model: ``housner`` (Eq. 4.8), a fixed r, or ``xFACTOR`` times Eq. 4.8.
    vertical : bool
        Include the records' vertical components in the exact response, where they have one.
    friction : float, optional
        Friction coefficient μ of the base [-]: flags blocks that would slide.
    sensitivity : sequence of str
        Alternative models (``"restitution=x0.9,x0.8"``, ``"vertical"``): flags verdicts that
        change under one of them.
    out_dir : str or Path, optional
        Write the result files and ``report.html`` there (atomically, together), record by
        record: memory does not grow with the suite beyond a small term per record until the
        tables are read (``.results``, ``.run``). Default: the data files in a scratch folder
        kept with the result (``.write(out_dir)`` saves them later).

    Returns
    -------
    AuditResult
    """
    from records import RecordSuite, load_records
    from audit.engine.progress import Progress
    from audit.engine.results import REPORT_HTML
    from audit.files import staged_folder
    suite = records if isinstance(records, RecordSuite) else load_records(records)
    suite = design_suite(suite, site, site_override, scale_to_site, anchor_period_s, ntc_site)
    chosen = _procedures(procedures)
    bar = Progress(len(suite), "record") if progress is True else None
    try:
        computed = compute_suite(chosen, suite, alpha_deg, sizes_s, jobs=jobs,
                                 free_motion_s=free_motion_s, progress=bar or progress or None,
                                 agree_band=agree_band, robustness=robustness,
                                 scheduler=scheduler, partial_dir=partial_dir, resume=resume,
                                 detail=list(detail), restitution=restitution,
                                 vertical=vertical, friction=friction,
                                 sensitivity=[sensitivity] if isinstance(sensitivity, str)
                                 else sensitivity)
    finally:
        if bar is not None:
            bar.done()
    stage = progress if isinstance(progress, Progress) else bar
    if out_dir is None:
        scratch = tempfile.TemporaryDirectory(prefix="rocking-audit-")
        write_suite(computed, scratch.name, stage)
        return AuditResult(scratch.name, scratch)
    # the summary is read back when asked: the report is drawn without a second copy in memory
    with staged_folder(out_dir) as staging:  # files appear only when all are written
        write_suite(computed, staging, stage)
        del computed, suite  # the motions go too, unless the caller holds them
        if stage is not None:
            stage.stage(f"writing the report to {out_dir}")
        AuditResult(staging).report(staging / REPORT_HTML)
    return AuditResult(out_dir)


class MarginsResult:
    """A design-level audit's tables: ``.stripes``, ``.fragility``, ``.capacity``,
    ``.required_alpha``, ``.scan`` (DataFrames, the columns of the CSV files of the same
    names), ``.summary``, ``.write(folder)`` (the files and ``margins.html``) and
    ``.report(path)``."""

    def __init__(self, margins):
        self.margins = margins
        self.stripes, self.fragility = margins.stripes, margins.fragility
        self.capacity, self.summary = margins.capacity, margins.summary
        self.required_alpha, self.scan = margins.required_alpha, margins.scan

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


def margins(procedures="all", records=None, im: str = "sa:1.0", stripes=None,
            alpha_deg=DEFAULT_ALPHA_DEG, sizes_s=None, blocks=(), site=None,
            scale_to_site: bool = False, anchor_period_s=None, ntc_site=None,
            restitution="housner", jobs: int = DEFAULT_JOBS,
            free_motion_s: float = DEFAULT_FREE_MOTION_S, scheduler: str = DEFAULT_SCHEDULER,
            progress=False, partial_dir=None, resume: bool = False,
            required: bool = True) -> MarginsResult:
    """The design-level audit: exact multiple-stripe fragility of every block, and where each
    procedure draws its line against it (see :mod:`audit.engine.margins`).

    Parameters
    ----------
    procedures, records :
        As for :func:`run`.
    im : str
        ``pga`` [g], ``pgv`` [m/s] or ``sa:T`` (true 5 %-damped Sa at T [s], in g).
    stripes : sequence of float, optional
        Intensity levels (unit of ``im``); default 24 levels, 0.2–5 × the design intensity
        (or the suite's median).
    alpha_deg : sequence of float
        Slendernesses of the grid [degrees].
    sizes_s : array, optional
        Block sizes 2π/p of the grid [s]; default 0.5 … 8 s in steps of 0.25 s.
    blocks : sequence of str or Block
        Blocks by their dimensions beside the grid: ``"WIDTHxHEIGHT"`` [m] or
        :meth:`Block.from_dimensions`.
    site, scale_to_site, anchor_period_s, ntc_site :
        The FEMA 356 design site (S_XS, S_X1 [g]) of every record, the FEMA P695 scaling and
        the NTC 2018 site, see :func:`design_suite`.
    restitution : str
        The impact model: ``housner`` (Eq. 4.8), a fixed r, or ``xFACTOR`` times Eq. 4.8.
    jobs, free_motion_s :
        Solver threads (worker processes with ``scheduler="dask"``); free motion after each
        record [s].
    scheduler, partial_dir, resume :
        Where records are computed; keep each record's stripes in ``partial_dir`` as they
        complete and reuse them with ``resume``.
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, record_id, how)``.
    required : bool
        Also search the required slenderness of each size (``required_alpha``).
    """
    import numpy as np

    from audit.engine.blocks import NamedBlock, parse_blocks
    from audit.engine.margins import IntensityMeasure, amplitude_scans, run_margins
    from audit.engine.progress import Progress
    from audit.engine.required_alpha import required_alpha
    from audit.engine.scheduler import open_scheduler
    from audit.physics.block import Restitution
    from records import RecordSuite, load_records
    suite = records if isinstance(records, RecordSuite) else load_records(records)
    suite = design_suite(suite, site, site is not None, scale_to_site, anchor_period_s, ntc_site)
    sizes_s = np.arange(0.5, 8.001, 0.25) if sizes_s is None else np.asarray(sizes_s, float)
    named = [NamedBlock(b.width_m, b.height_m, b.g) if isinstance(b, Block) else b
             for b in blocks if not isinstance(b, str)]
    named += parse_blocks([b for b in blocks if isinstance(b, str)])
    impact = restitution if isinstance(restitution, Restitution) else Restitution.parse(restitution)
    chosen = _procedures(procedures)
    intensity = IntensityMeasure.parse(im)
    bar = Progress(len(suite), "record") if progress is True else None
    report = bar or progress or None
    try:
        with open_scheduler(scheduler, jobs) as executor:
            if bar:
                bar.stage(f"exact fragility on {len(suite)} records × "
                          f"{len(stripes) if stripes is not None else 'the default'} stripes "
                          f"of {intensity.name}")
            run = run_margins(chosen, suite, intensity, stripes, alpha_deg, sizes_s, named,
                              impact, free_motion_s=free_motion_s, jobs=jobs, progress=report,
                              scheduler=executor, partial_dir=partial_dir, resume=resume)
            if required:
                if bar:
                    bar.stage("required slenderness of each size: α from 2° to 40°, 2° apart, "
                              "the exact curves bisected")
                run.required_alpha = required_alpha(chosen, suite, sizes_s,
                                                    restitution=impact, free_motion_s=free_motion_s,
                                                    jobs=jobs, scheduler=executor, progress=report)
    finally:
        if bar is not None:
            bar.done()
    run.scan = amplitude_scans(run, suite, impact, free_motion_s=free_motion_s, jobs=jobs)
    return MarginsResult(run)


class ValidationResult:
    """A campaign's validation: ``.fits`` (specimen → fitted block), ``.fits_table``,
    ``.scores``, ``.tests``, ``.predictions`` (DataFrames, the CSV files of the same names),
    ``.solves``, ``.methods_statement``, ``.write(folder)`` (the files and
    ``validation.html``)."""

    def __init__(self, validation):
        self.validation = validation
        self.fits, self.scores = validation.fits, validation.scores
        self.tests, self.predictions = validation.tests, validation.predictions
        self.fits_table, self.solves = validation.fits_table(), validation.solves

    @property
    def methods_statement(self) -> str:
        """What a report's Methods says of this validation and its limits."""
        from audit.engine.validation_run import methods_statement
        return methods_statement(self.fits_table, self.scores)

    def files(self) -> dict[str, bytes]:
        """Every file, ``validation.html`` drawn from the CSV files as saved."""
        from reports.validation_page import VALIDATION_HTML, render_validation_page
        title = "Shake-table validation of the exact rocking model"
        return with_page(self.validation.files(), VALIDATION_HTML,
                         lambda saved: render_validation_page(saved, title, self.solves))

    def write(self, out_dir) -> Path:
        """Write the files and ``validation.html`` into ``out_dir`` (atomically, together)."""
        from audit.files import write_files_atomically
        write_files_atomically(Path(out_dir), self.files())
        return Path(out_dir)


def validate(folder, geometry=None, folds: int = 5, jobs: int = DEFAULT_JOBS,
             free_motion_s: float = DEFAULT_FREE_MOTION_S, progress=False,
             settings=None) -> ValidationResult:
    """Fit each specimen's equivalent rigid block to a shake-table campaign and score it by
    cross-validation by ground motion against intensity baselines (docs/validation.md).

    Parameters
    ----------
    folder : str or Path
        The campaign folder (``tests.csv`` and the motion files it names).
    geometry : str or Path, optional
        CSV of geometric estimates (``specimen, alpha_deg, p_rad_s, note``); default the
        folder's ``specimens.csv`` if there is one.
    folds, jobs, free_motion_s :
        Cross-validation folds; solver threads; free motion after each test [s].
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, test_id)``.
    settings : audit.engine.validation_grid.ValidationSettings, optional
        Every setting (grid, band-pass, lapse); overrides ``folds``, ``jobs``, ``free_motion_s``.
    """
    from audit.engine.progress import Progress
    from audit.engine.validation_grid import ValidationSettings
    from audit.engine.validation_run import run_validation
    from records.campaign import campaign_geometry, read_campaign
    campaign = read_campaign(folder)
    given = campaign_geometry(campaign, geometry)
    settings = settings or ValidationSettings(folds=folds, jobs=jobs, free_motion_s=free_motion_s)
    bar = Progress(len(campaign.motions), "test") if progress is True else None
    try:
        if bar:
            bar.stage(f"exact outcomes of {settings.solves_per_test} blocks under each of "
                      f"{len(campaign.motions)} table motions")
        result = run_validation(campaign, settings, given, bar or progress or None)
    finally:
        if bar is not None:
            bar.done()
    return ValidationResult(result)


__all__ = ["Block", "RockingResponse", "rock", "run", "AuditResult", "design_suite", "margins",
           "MarginsResult", "validate", "ValidationResult"]
