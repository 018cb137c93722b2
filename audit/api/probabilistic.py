"""The audit of a probabilistic procedure (FEMA P-58's fragilities) against the exact
overturning fragility: :func:`fragility` and its :class:`FragilityResult`."""

from __future__ import annotations

from pathlib import Path

from audit.engine.defaults import DEFAULT_FRAGILITY_RECORDS, DEFAULT_PROBABILISTIC_PROCEDURE
from audit.physics.building.floor import DEFAULT_BUILDING_DAMPING

#: The page of the audit, drawn from its saved CSV files.
FRAGILITY_HTML = "fragility.html"


class FragilityResult:
    """The tables of :func:`fragility` (``.tables``: file name → DataFrame), ``.files()`` (the
    CSV files and ``fragility.html``) and ``.write(folder)``."""

    def __init__(self, procedure, tables: dict, source: str):
        self.procedure, self.tables, self.source = procedure, tables, source

    def files(self) -> dict[str, bytes]:
        """Every file of the audit, the page drawn from the CSV files as saved."""
        from audit.api.design_level import with_page
        from reports.fragility_page import render_fragility_page
        files = {name: table.to_csv(index=False).encode() for name, table in self.tables.items()}
        title = f"{self.procedure.title} against the exact fragility ({self.source})"
        return with_page(files, FRAGILITY_HTML, lambda saved: render_fragility_page(saved, title))

    def write(self, out_dir) -> Path:
        """Write the files and ``fragility.html`` into ``out_dir`` (atomically, together)."""
        from audit.files import write_files_atomically
        write_files_atomically(Path(out_dir), self.files())
        return Path(out_dir)

    def __repr__(self) -> str:
        return (f"FragilityResult({self.procedure.name} on {self.source}: "
                f"{', '.join(f'{name} ({len(t)} rows)' for name, t in self.tables.items())})")


def fragility(procedure: str = DEFAULT_PROBABILISTIC_PROCEDURE, records=DEFAULT_FRAGILITY_RECORDS,
              progress: bool = False, floor: float = 0.0, building: float | None = None,
              building_model: str | None = None,
              building_damping: float = DEFAULT_BUILDING_DAMPING) -> FragilityResult:
    """A probabilistic procedure's fragilities against the exact overturning fragility, by
    multiple PGV stripes (:mod:`audit.engine.fragility_audit`).

    Parameters
    ----------
    procedure : str
        A registered probabilistic procedure (``femap58``).
    records : str, path or records.RecordSuite
        The suite (default the FEMA P695 far-field set).
    progress : bool
        Say on standard error what is being computed.
    floor, building, building_model, building_damping :
        Where the components stand (as for :func:`audit.rock`): the records are filtered to
        that floor, and the PGV stripes are then the floor's PFV, the demand P-58's
        unanchored-content fragilities are defined in.
    """
    from audit.api.inputs import suite_of
    from audit.engine.fragility_audit import audit_procedure
    from audit.engine.progress import Progress
    from audit.errors import InputError
    from procedures.registry import available_procedures
    found = available_procedures(probabilistic=True)
    if procedure not in found:
        raise InputError(f"procedure: unknown {procedure!r}, available: {', '.join(found)}",
                         "procedure")
    from audit.engine.floors import on_floor
    from audit.physics.building.floor import Floor
    where = Floor.parse(floor=floor, building=building, building_model=building_model,
                        building_damping=building_damping)
    suite = on_floor(suite_of(records), where)
    entries = [entry for entry in suite.entries if entry.motion is not None]
    if not entries:
        raise InputError(f"records: {suite.description} has no record with a motion", "records")
    chosen = found[procedure]()
    if progress:
        Progress(0, "step").stage(f"{chosen.title}: exact overturning of its components under "
                                  f"{len(entries)} records scaled to each PGV stripe")
    tables = audit_procedure(chosen, [e.id for e in entries], [e.motion for e in entries])
    return FragilityResult(chosen, tables, records if isinstance(records, str) and where.on_ground
                           else suite.description)


__all__ = ["fragility", "FragilityResult", "FRAGILITY_HTML"]
