"""Writing the outputs of the commands that print or save one table or figure: checked before
any work, written all or nothing."""

from __future__ import annotations

import sys
from pathlib import Path


def checked(*, files=None, folders=None, inputs=None) -> dict[str, Path | None]:
    """Every output of a command, checked before any work against its inputs and each other
    (:func:`audit.files.check_outputs`): option → path, None for standard output."""
    from audit.files import check_outputs
    return check_outputs(files=files, folders=folders, inputs=inputs)


def csv_text(table) -> tuple[str, int]:
    """CSV text and row count of ``table``: a pandas DataFrame or, for commands that need no
    pandas, a dict of equal-length numeric columns; numbers written with ``%.8g`` either way."""
    if isinstance(table, dict):
        columns = list(table.values())
        text = "".join([",".join(table) + "\n"] + [",".join(f"{value:.8g}" for value in row) + "\n"
                                                  for row in zip(*columns)])
        return text, len(columns[0]) if columns else 0
    return table.to_csv(index=False, float_format="%.8g"), len(table)


def write_csv(table, path: Path | None, extra: dict[Path, bytes] | None = None) -> None:
    """``table`` (see :func:`csv_text`) as CSV to ``path`` or standard output (None), with the
    ``extra`` files, all or nothing."""
    text, rows = csv_text(table)
    files = dict(extra or {})
    if path is not None:
        files[path] = text.encode()
    from audit.files import write_atomically
    write_atomically(files)
    if path is None:
        sys.stdout.write(text)
    else:
        print(f"Wrote {rows} rows to {path}", file=sys.stderr)


__all__ = ["checked", "csv_text", "write_csv"]
