"""A PEER NGA-West2 download folder as --records: the ``.AT2`` files and the
``_SearchResults.csv`` the PEER ground-motion database writes beside them.

The CSV opens with the search criteria, then a table headed ``Result ID``: one row per record
with its sequence number (RSN), the scale factor of the search, seismological facts and the
file names of its two horizontal components and its vertical one. The table ends at the first
blank row (the notes and the spectra follow). Header names carry leading spaces in PEER's
files; they are compared here without case and extra spaces.

The ``.AT2`` files are written unscaled: each horizontal component listed becomes one record
scaled by the listed factor. Vertical components are not records of their own: each horizontal
component carries its station's, which the exact solver reads with ``--vertical``; the file
name is kept in the metadata.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

from audit.errors import InputError
from records.manifest import collect
from records.at2_reader import read_at2
from records.suite import RecordEntry, RecordSuite

#: Name of the file PEER writes beside the records of a search.
SEARCH_RESULTS = "_SearchResults.csv"
#: First cell of the header row of the records table.
TABLE_START = "Result ID"
#: Columns every table must have, as PEER spells them.
RSN_COLUMN = "Record Sequence Number"
SCALE_COLUMN = "Scale Factor"
HORIZONTAL_COLUMNS = ("Horizontal-1 Acc. Filename", "Horizontal-2 Acc. Filename")
#: Column of the vertical component's file, kept in the metadata only.
VERTICAL_COLUMN = "Vertical Acc. Filename"
#: Metadata key → column holding text.
TEXT_COLUMNS = {"event": "Earthquake Name", "station": "Station Name", "mechanism": "Mechanism"}
#: Metadata key → column holding a number (empty or dashes where PEER has none).
NUMBER_COLUMNS = {"year": "Year", "magnitude": "Magnitude", "rjb_km": "Rjb (km)",
                  "rrup_km": "Rrup (km)", "vs30_m_s": "Vs30 (m/sec)",
                  "pulse_period_s": "Tp-Pulse Period (sec)"}


@dataclass(frozen=True)
class SearchRecord:
    """One row of the records table of a ``_SearchResults.csv``.

    Attributes
    ----------
    rsn : int
        NGA-West2 record sequence number.
    scale_factor : float
        Factor of the search on the unscaled files [-].
    horizontal_files : tuple of str
        File names of the horizontal components listed (none where PEER lists none).
    vertical_file : str or None
        File name of the vertical component.
    metadata : dict
        Event, year, station, magnitude, mechanism, distances [km], Vs30 [m/s] and pulse
        period [s], where the table gives them.
    """

    rsn: int
    scale_factor: float
    horizontal_files: tuple[str, ...]
    vertical_file: str | None
    metadata: dict = field(default_factory=dict)


def search_results_file(folder: Path) -> Path | None:
    """The ``_SearchResults.csv`` of ``folder`` (any case), or None."""
    return next((p for p in sorted(folder.iterdir())
                 if p.name.lower() == SEARCH_RESULTS.lower() and p.is_file()), None)


def _cell(text: str) -> str:
    """A cell without the spaces and the doubled quotes PEER puts around names."""
    return text.strip().strip('"').strip()


def _heading(text: str) -> str:
    return " ".join(text.split()).lower()


def _is_blank(value: str) -> bool:
    """Whether a cell says nothing: empty or dashes (PEER's mark for "none")."""
    return not value.strip("-")


def _number(value: str, path: Path, line: int, column: str) -> float:
    try:
        number = float(value)
    except ValueError:
        raise InputError(f"{path}: line {line}: {column}: '{value}' is not a number") from None
    if not math.isfinite(number):
        raise InputError(f"{path}: line {line}: {column}: '{value}' is not finite")
    return number


def _table(path: Path) -> tuple[dict[str, int], list[tuple[int, list[str]]]]:
    """Column index by heading, and the rows (line number, cells) of the records table.

    A damaged file is refused rather than read in part: a table with no rows, a row that
    stops before the last column read (a cut or hand-shortened row), or a table that runs to
    the end of the file without PEER's closing blank row (a truncated download, whose
    records past the cut would otherwise be read unscaled, their vertical files as
    horizontal records).
    """
    try:
        text = path.read_bytes().decode("utf-8-sig", errors="replace")
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from None
    reader = csv.reader(text.splitlines())
    columns, header_line, closed = None, 0, False
    rows = []
    for cells in reader:
        if columns is None:
            if cells and _heading(cells[0]) == _heading(TABLE_START):
                columns = {_heading(name): i for i, name in enumerate(cells) if name.strip()}
                header_line = reader.line_num
            continue
        if not any(cell.strip() for cell in cells):
            closed = True
            break
        rows.append((reader.line_num, [_cell(cell) for cell in cells]))
    if columns is None:
        raise InputError(f"{path}: Result ID: no table headed 'Result ID' (is it the "
                         f"{SEARCH_RESULTS} of a PEER NGA-West2 download?)")
    for name in (RSN_COLUMN, SCALE_COLUMN, *HORIZONTAL_COLUMNS):
        if _heading(name) not in columns:
            raise InputError(f"{path}: {name}: no such column in the table headed "
                             f"'{TABLE_START}'")
    if not rows:
        raise InputError(f"{path}: line {header_line}: the table headed '{TABLE_START}' lists "
                         f"no records; is the file truncated?")
    if not closed:
        raise InputError(f"{path}: line {rows[-1][0]}: the table headed '{TABLE_START}' runs "
                         f"to the end of the file without the blank row PEER closes it with; "
                         f"is the file truncated?")
    read = [name for name in (RSN_COLUMN, SCALE_COLUMN, *TEXT_COLUMNS.values(),
                              *NUMBER_COLUMNS.values(), *HORIZONTAL_COLUMNS, VERTICAL_COLUMN)
            if _heading(name) in columns]
    last = max(read, key=lambda name: columns[_heading(name)])
    for line, cells in rows:
        if len(cells) <= columns[_heading(last)]:
            missing = min((name for name in read if columns[_heading(name)] >= len(cells)),
                          key=lambda name: columns[_heading(name)])
            raise InputError(f"{path}: line {line}: {missing}: the row ends after "
                             f"{len(cells)} cells, before this column; is the file truncated "
                             f"or the row cut short?")
    return columns, rows


def read_search_results(path: str | Path) -> list[SearchRecord]:
    """The records table of a PEER ``_SearchResults.csv``.

    InputError naming the file, the line and the column for a table that is not there, a
    column that is missing, an RSN that is not a whole number, a scale factor that is not a
    positive number, or a metadata number that is not one.
    """
    path = Path(path)
    columns, rows = _table(path)

    def value(cells: list[str], name: str) -> str:
        index = columns.get(_heading(name))
        return cells[index] if index is not None and index < len(cells) else ""

    records = []
    for line, cells in rows:
        rsn_text = value(cells, RSN_COLUMN)
        if not rsn_text.isdigit():
            raise InputError(f"{path}: line {line}: {RSN_COLUMN}: '{rsn_text}' is not a whole "
                             f"number")
        scale_text = value(cells, SCALE_COLUMN)
        scale = _number(scale_text, path, line, SCALE_COLUMN)
        if scale <= 0:
            raise InputError(f"{path}: line {line}: {SCALE_COLUMN}: must be positive, got "
                             f"'{scale_text}'")
        metadata = {key: value(cells, name) for key, name in TEXT_COLUMNS.items()
                    if not _is_blank(value(cells, name))}
        for key, name in NUMBER_COLUMNS.items():
            text = value(cells, name)
            if not _is_blank(text):
                number = _number(text, path, line, name)
                metadata[key] = int(number) if key == "year" else number
        horizontals = (value(cells, name) for name in HORIZONTAL_COLUMNS)
        vertical = value(cells, VERTICAL_COLUMN)
        records.append(SearchRecord(int(rsn_text), scale,
                                    tuple(name for name in horizontals if not _is_blank(name)),
                                    None if _is_blank(vertical) else vertical, metadata))
    return records


def pointing_down(file_name: str) -> bool:
    """Whether a PEER vertical file counts positive down: its name ends in ``DWN`` (``UP``
    and ``-V`` files count positive up)."""
    return Path(file_name).stem.upper().endswith("DWN")


def is_vertical(file_name: str) -> bool:
    """Whether a PEER file is a vertical component: its name ends in ``UP``, ``DWN`` or
    ``-V``."""
    return Path(file_name).stem.upper().endswith(("UP", "DWN", "-V"))


def record_id(rsn: int, file_name: str) -> str:
    """Id of a component: its file's stem, as for any ``.AT2`` file of a folder, with
    ``RSN<n>_`` put in front where the stem does not start with it."""
    stem = Path(file_name).stem
    return stem if stem.upper().startswith(f"RSN{rsn}_") else f"RSN{rsn}_{stem}"


def _component(record: SearchRecord, number: int, file_name: str, search_results: Path,
               files: dict[str, Path]) -> tuple[str, str, object]:
    """The (record, file, read) of :func:`records.manifest.collect` for one horizontal
    component: its file scaled by the record's factor, or a missing entry."""
    entry_id = record_id(record.rsn, file_name)
    component = (f"horizontal {number} of RSN {record.rsn} ({file_name}) × "
                 f"{record.scale_factor:g}, the scale factor of the PEER search")
    metadata = {"rsn": record.rsn, **record.metadata, "scale_factor": record.scale_factor,
                "peer_file": file_name, "search_results": str(search_results)}
    if record.vertical_file:
        metadata["vertical_file"] = record.vertical_file
    file = files.get(file_name.lower())
    if file is None:
        return entry_id, "", lambda: RecordEntry(
            entry_id, None, component=component, metadata=metadata,
            missing_reason=f"{file_name} is listed in {search_results.name} but not in the "
                           f"folder")
    vertical = files.get((record.vertical_file or "").lower())

    def read():
        motion = read_at2(file, entry_id)
        if vertical is not None:  # the station's vertical component, for --vertical
            motion = motion.with_vertical(read_at2(vertical), down=pointing_down(vertical.name))
        return RecordEntry(entry_id, motion.scaled(record.scale_factor, component),
                           component=component, metadata=metadata)

    return entry_id, str(file), read


def search_folder(search_results: Path, files: list[Path], read_other,
                  skip_bad: bool = False) -> RecordSuite:
    """The records of a PEER download folder.

    Parameters
    ----------
    search_results : Path
        The folder's ``_SearchResults.csv``.
    files : list of Path
        The folder's ``.AT2`` files.
    read_other : callable
        Path → RecordEntry, for ``.AT2`` files the table does not list: they are records of
        their own, unscaled, as in any folder.
    skip_bad : bool
        See :func:`records.manifest.load_manifest`.

    Returns
    -------
    RecordSuite
        Each horizontal component listed, in the order of the table, scaled by its record's
        factor (missing where its file is not in the folder), then the folder's other
        ``.AT2`` files. Vertical components are not records of their own: each horizontal one
        carries its station's (UP, or DWN with the sign turned), for ``--vertical``.
    """
    records = read_search_results(search_results)
    by_name = {file.name.lower(): file for file in files}
    readers, seen = [], set()
    for record in records:
        for number, file_name in enumerate(record.horizontal_files, start=1):
            reader = _component(record, number, file_name, search_results, by_name)
            if reader[0] in seen:
                raise InputError(f"{search_results}: {file_name}: listed twice")
            seen.add(reader[0])
            readers.append(reader)
    listed = {name.lower() for record in records
              for name in (*record.horizontal_files, record.vertical_file) if name}
    others = [file for file in files if file.name.lower() not in listed]
    vertical = next((file for file in others if is_vertical(file.name)), None)
    if vertical is not None:  # a vertical component is never a horizontal record of its own
        raise InputError(f"{search_results}: {vertical.name}: a vertical component (its name "
                         f"ends in UP, DWN or -V) that the table does not list; list its record "
                         f"or move the file out of the folder")
    readers += [(file.stem, str(file), lambda file=file: read_other(file)) for file in others]
    missing = sum(1 for _, file, _ in readers if not file)
    notes = [f"{missing} listed file(s) not in the folder" if missing else "",
             f"{len(others)} other .AT2 file(s) of the folder, unscaled" if others else ""]
    return collect(readers, "; ".join([
        f"the PEER NGA-West2 search results {search_results}: {len(readers) - len(others)} "
        f"horizontal component(s) of {len(records)} record(s), each scaled by its listed scale "
        f"factor, vertical components carried (for vertical)", *filter(None, notes)]), skip_bad)
