"""The audit of a probabilistic procedure (FEMA P-58's fragilities) against the exact
overturning fragility: :func:`fragility` and its :class:`FragilityResult`."""

from __future__ import annotations

from audit.api.result_shape import Files, table_html, with_page
from audit.engine.shared.defaults import DEFAULT_FRAGILITY_RECORDS, DEFAULT_PROBABILISTIC_PROCEDURE
from audit.physics.building.floor import Floor

#: The page of the audit, drawn from its saved CSV files.
FRAGILITY_HTML = "fragility.html"


class FragilityResult(Files):
    """The tables of :func:`fragility` (``.tables``: file name → DataFrame; ``.table``, its
    components' fragilities), ``.summary``, ``.summary_text()``, ``.files()`` (the CSV files
    and ``fragility.html``), ``.write(folder)`` and ``.report(path)``."""

    PAGE = FRAGILITY_HTML

    def __init__(self, procedure, tables: dict, source: str):
        self.procedure, self.tables, self.source = procedure, tables, source

    @property
    def title(self) -> str:
        """What the audit is of."""
        return f"{self.procedure.title} against the exact fragility ({self.source})"

    @property
    def table(self):
        """One row per component of the procedure: its fragility against the exact one
        (``fragility-components.csv``)."""
        from audit.engine.fragility.pipeline import COMPONENTS_CSV
        return self.tables[COMPONENTS_CSV]

    @property
    def summary(self) -> dict:
        """The procedure, the records and the rows of each table."""
        return {"procedure": self.procedure.name, "title": self.procedure.title,
                "records_source": self.source,
                "rows": {name: len(table) for name, table in self.tables.items()}}

    def summary_text(self) -> str:
        """What was audited, and the files' rows."""
        return (f"{self.title}\n" + "".join(f"  {name}: {rows} rows\n"
                                           for name, rows in self.summary["rows"].items()))

    def files(self) -> dict[str, bytes]:
        """Every file of the audit, the page drawn from the CSV files as saved."""
        from reports.fragility_page import render_fragility_page
        files = {name: table.to_csv(index=False).encode() for name, table in self.tables.items()}
        return with_page(files, FRAGILITY_HTML,
                         lambda saved: render_fragility_page(saved, self.title))

    def exact_components(self) -> list:
        """The audited components with their *exact* lognormal fragility (the maximum-likelihood
        fit to the exact stripes), in PGV [m/s]: NaN where no fit exists."""
        from procedures.probabilistic import FragilityComponent, LognormalFragility
        from audit.engine.fragility.pipeline import COMPONENTS_CSV
        return [FragilityComponent(row.component, row.description, "PGV",
                                   LognormalFragility(row.exact_median_m_s, row.exact_beta),
                                   row.width_m, row.height_m)
                for row in self.tables[COMPONENTS_CSV].itertuples()]

    def pelicun_csv(self) -> bytes:
        """The exact fragilities in pelicun's FEMA P-58 library layout
        (:mod:`audit.engine.fragility.pelicun_export`): peak floor velocity, median [m/s] and β."""
        from audit.engine.fragility.pelicun_export import pelicun_fragility_csv
        return pelicun_fragility_csv(self.exact_components())

    def _repr_html_(self) -> str:
        return table_html(self.table, self.title)

    def __repr__(self) -> str:
        return (f"FragilityResult({self.procedure.name} on {self.source}: "
                f"{', '.join(f'{name} ({len(t)} rows)' for name, t in self.tables.items())})")


def fragility(procedure: str = DEFAULT_PROBABILISTIC_PROCEDURE, records=DEFAULT_FRAGILITY_RECORDS,
              *, progress: bool = False, floor: Floor | None = None,
              method: str | None = None) -> FragilityResult:
    """A probabilistic procedure's fragilities against the exact overturning fragility, by
    multiple PGV stripes (:mod:`audit.engine.fragility.pipeline`).

    Parameters
    ----------
    procedure : str
        A registered probabilistic procedure (``femap58``).
    records : Records, str, path or records.RecordSuite
        The suite (default the FEMA P695 far-field set), and how its files are read
        (:class:`~audit.engine.shared.record_request.Records`).
    progress : bool
        Say on standard error what is being computed.
    floor : Floor, optional
        Where the components stand (as for :func:`audit.rock`): the records are filtered to
        that floor, and the PGV stripes are then the floor's PFV, the demand P-58's
        unanchored-content fragilities are defined in.
    method : {None, "atlas", "direct"}
        Where the exact side comes from: ``atlas``, the atlas of these records in PGV on that
        floor (at its 14 stripes, 0.0625–5.66 m/s; InputError naming ``method`` where none
        answers: build it with ``python -m audit atlas build --im pgv``); ``direct``, the
        records solved at the 19 stripes 0.05–3.2 m/s; None, the atlas where one answers every
        component, else direct (:mod:`audit.engine.atlas.fragility_read`).

    Returns
    -------
    FragilityResult
    """
    from audit.api.inputs import floor_group, record_suite
    from audit.engine.fragility.pipeline import run_fragility
    from audit.engine.shared.blocks import Block
    from audit.engine.shared.progress import Progress
    from audit.errors import InputError
    from procedures.registry import available_procedures
    from audit.engine.shared import fields as check
    found = available_procedures(probabilistic=True)
    progress = check.flag("progress", progress)
    if not isinstance(procedure, str) or procedure not in found:
        raise InputError(f"procedure: unknown {procedure!r}, available: {', '.join(found)}",
                         "procedure")
    from audit.engine.shared.design_site import DesignSite
    from audit.api.atlas_lookup import atlas_reading
    from audit.engine.atlas.fragility_read import checked_method
    from audit.engine.shared.record_request import Records
    checked_method(method)
    site = DesignSite(None, floor_group(floor))
    request = Records.parse(records)
    read = record_suite(request)
    suite = site.apply(read)
    entries = [entry for entry in suite.entries if entry.motion is not None]
    if not entries:
        raise InputError(f"records: {suite.description} has no record with a motion", "records")
    chosen = found[procedure]()
    blocks = [c for c in chosen.components if c.has_block and c.intensity_measure == "PGV"]
    shapes = [Block.of_dimensions(c.depth_m, c.height_m) for c in blocks]
    atlas = atlas_reading(method, read, ([b.alpha_deg for b in shapes],
                                         [b.size_s for b in shapes]), im="pgv",
                          floor=site.floor, named=request.source)
    if progress:
        Progress(0, "step").stage(
            f"{chosen.title}: exact overturning of its components under {len(entries)} records "
            + ("scaled to each PGV stripe" if atlas is None
               else f"read from the atlas {atlas.key[:12]} at its {atlas.levels.size} PGV stripes"))
    tables = run_fragility(chosen, [e.id for e in entries], [e.motion for e in entries],
                           atlas=atlas)
    return FragilityResult(chosen, tables, request.source if isinstance(request.source, str)
                           and site.floor.on_ground else suite.description)


__all__ = ["fragility", "FragilityResult", "FRAGILITY_HTML"]
