"""``audit.check``: the Python API of ``audit check`` (one or many objects at one site).

    import audit
    result = audit.check(["0.6x1.8"], site=(1.5, 0.9))
    result.table              # one row per object × procedure (a DataFrame)
    print(result.summary())   # the paragraph and table the command line prints
    result.report("check.html")

Objects are ``"WIDTHxHEIGHT"`` strings [m], :class:`audit.api.Block` instances, or
``(name, width_m, height_m)`` tuples. Bad input raises :class:`audit.errors.InputError` naming the
argument.
"""

from __future__ import annotations

import html
from dataclasses import replace
from pathlib import Path

import pandas as pd

from audit.engine.check_objects import object_by_slenderness, parse_block_text, read_objects
from audit.engine.defaults import DEFAULT_CHECK_RECORDS
from audit.errors import InputError



class CheckResult:
    """The answer of a check.

    Attributes
    ----------
    document : dict
        Everything of ``check.json``: the run (site, intensity measure, records) and
        ``objects``, each with its ``exact`` answer and ``procedures``.
    table : pandas.DataFrame
        One row per object × procedure (the columns of ``check.csv``).
    """

    def __init__(self, run):
        from audit.engine.check_summary import check_table
        self.run = run
        self.document = {**run.summary, "objects": run.objects}
        self.table: pd.DataFrame = check_table(run.objects)

    @property
    def sentences(self) -> list[str]:
        """One sentence per object, for a calculation note."""
        return [obj["sentence"] for obj in self.run.objects]

    def summary(self) -> str:
        """The paragraph and per-object table ``audit check`` prints."""
        from audit.engine.check_words import summary_text
        return summary_text(self.document)

    def files(self) -> dict[str, bytes]:
        """``check.json``, ``check.csv`` and ``check.html`` (the page drawn from the JSON as
        saved)."""
        from audit.api import with_page
        from audit.engine.check_summary import CHECK_HTML, check_data_files
        from reports.check_page import render_check_page
        return with_page(check_data_files(self.run), CHECK_HTML, render_check_page)

    def write(self, out_dir) -> Path:
        """Write the three files into ``out_dir`` (atomically, together)."""
        from audit.files import write_files_atomically
        write_files_atomically(Path(out_dir), self.files())
        return Path(out_dir)

    def report(self, path) -> Path:
        """Write ``check.html`` alone to ``path``."""
        from audit.engine.check_summary import CHECK_HTML
        from audit.files import write_file_atomically
        write_file_atomically(Path(path), self.files()[CHECK_HTML])
        return Path(path)

    def _repr_html_(self) -> str:
        table = self.table[["object", "procedure", "verdict", "demand", "capacity", "unit",
                            "required_width_m", "p_overturn_at_site",
                            "exact_required_width_m_10pct"]]
        return ("".join(f"<p>{html.escape(s)}</p>" for s in self.sentences)
                + table.to_html(index=False, float_format=lambda v: f"{v:.3g}", na_rep="—"))

    def __repr__(self) -> str:
        site = self.document["site"]
        return (f"CheckResult({len(self.run.objects)} object(s) at S_XS = {site['sxs_g']:g} g, "
                f"S_X1 = {site['sx1_g']:g} g, {len(self.document['procedures'])} procedure(s))")


def _objects(objects, g: float) -> list:
    from audit.api import Block
    from audit.engine.check_objects import CheckObject, checked_object, parse_block_text
    if isinstance(objects, (str, Block, CheckObject)):
        objects = [objects]
    out = []
    for i, item in enumerate(objects):
        where = f"objects[{i}]"
        if isinstance(item, CheckObject):  # checked where it was made (the command line)
            out.append(item)
        elif isinstance(item, str):
            try:
                out += parse_block_text(item, where, g)
            except InputError as exc:
                raise InputError(str(exc)) from None
        elif isinstance(item, Block):
            out.append(checked_object(f"{item.width_m:.3g}x{item.height_m:.3g}", item.width_m,
                                      item.height_m, where, g))
        elif isinstance(item, (tuple, list)) and len(item) == 3:
            name, width, height = item
            out.append(checked_object(str(name), width, height, f"{where} ({name})", g))
        else:
            raise InputError(f"{where}: expected 'WIDTHxHEIGHT', a Block or (name, width_m, "
                             f"height_m), got {item!r}")
    if not out:
        raise InputError("objects: no object to check")
    return out


def check(objects, site, procedures="all", records=DEFAULT_CHECK_RECORDS, *, ntc_site=None,
          progress=False, **options) -> CheckResult:
    """Check objects at one site: each guideline's verdict, the exact P(overturn) at the site's
    intensity with a bootstrap band, and the widths required (see :mod:`audit.engine.check`);
    with a hazard curve, also the annual rate of overturning (:mod:`audit.engine.check_risk`).

    Every argument is checked before anything is read or computed; a bad one raises
    :class:`~audit.errors.InputError` naming it.

    Parameters
    ----------
    objects : str, Block or sequence
        ``"WIDTHxHEIGHT"`` [m], :class:`audit.api.Block`, ``(name, width_m, height_m)``,
        :class:`audit.engine.check_objects.CheckObject`, or a list of those.
    site : (float, float)
        FEMA 356 / ASCE 41 S_XS, S_X1 [g] at the hazard level assessed.
    procedures, records :
        As for :func:`audit.api.run`; records default to the FEMA P695 far-field set, scaled to
        the site.
    ntc_site : (float, float, float, str, str), optional
        NTC 2018 site, see :func:`audit.api.design_suite`.
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, record_id, how)``.
    **options :
        What is computed, the fields of :class:`~audit.engine.check_settings.CheckSettings`:
        ``im`` (``pga`` or ``sa:T``, the site's intensity read from its design spectrum;
        default ``sa:1.0``), ``restitution``, ``free_motion_s``, ``g``, ``seed`` (of the
        bootstrap over records), ``hazard`` (a hazard curve or its file: the risk; its IMT
        sets ``im``), ``site_location`` (lon, lat [degrees] in a file of several sites),
        ``risk_target`` (probability of overturning in 50 years, default 0.01),
        ``limit_state`` (``SLV``, ``SLC`` or ``both``, the default: the limit state the site's
        values are for, of a guideline that names its own, NTC 2018); how:
        ``jobs``, ``scheduler``.

    Returns
    -------
    CheckResult
    """
    from audit.api import design_suite
    from audit.api.inputs import procedures_of, split, suite_of
    from audit.engine.check import run_check
    from audit.engine.check_settings import CHECK_FIELDS, CheckSettings
    from audit.engine.progress import Progress
    from audit.engine.runtime import Runtime
    values, how = split(options, CHECK_FIELDS, ("jobs", "scheduler"))
    settings = CheckSettings.parse(**values)
    chosen_objects = _objects(objects, settings.g)
    try:
        sxs_g, sx1_g = (float(v) for v in site)
    except (TypeError, ValueError):
        raise InputError(f"site: expected (S_XS, S_X1) in g, got {site!r}", "site") from None
    if progress not in (True, False) and not callable(progress):
        raise InputError(f"progress: expected True, False or progress(done, total, record_id, "
                         f"how), got {progress!r}", "progress")
    runtime = Runtime.parse(**how, progress=progress if callable(progress) else None)
    chosen = procedures_of(procedures)
    # each record is scaled on its own to the site and the stripes (audit.engine.check), so no
    # suite scaling first: the records as given
    suite = design_suite(suite_of(records), site=(sxs_g, sx1_g), site_override=True,
                         scale_to_site=False, ntc_site=ntc_site)
    bar = Progress(len(suite), "record") if progress is True else None
    try:
        run = run_check(chosen, suite, chosen_objects, settings,
                        replace(runtime, progress=bar) if bar else runtime)
    finally:
        if bar is not None:
            bar.done()
    return CheckResult(run)


__all__ = ["check", "CheckResult", "object_by_slenderness", "parse_block_text", "read_objects"]
