"""A documentation page's generated part, between two marker lines (the column guide of
:mod:`reports.guide`, the parameter tables of :mod:`reports.parameter_guide`): read back for
the tests that keep it in sync, rewritten from the declarations, and the command line of both."""

from __future__ import annotations

import sys
from pathlib import Path


def between(page: str, markers: tuple[str, str]) -> str:
    """The text of ``page`` between ``markers`` (start, end), without them."""
    start, end = page.index(markers[0]), page.index(markers[1])
    return page[start + len(markers[0]):end].strip() + "\n"


def rewrite_between(path: Path, markers: tuple[str, str], text: str) -> None:
    """Replace the part of the page at ``path`` between ``markers`` by ``text``."""
    page = path.read_text(encoding="utf-8")
    start, end = page.index(markers[0]), page.index(markers[1])
    path.write_text(f"{page[:start]}{markers[0]}\n{text}\n{page[end:]}", encoding="utf-8")


def main(argv, markers: tuple[str, str], markdown) -> None:
    """``python -m MODULE`` prints ``markdown()``; ``python -m MODULE PAGE`` rewrites PAGE."""
    if argv:
        rewrite_between(Path(argv[0]), markers, markdown())
    else:
        sys.stdout.write(markdown())
