"""The column guide of the documentation (``docs/columns.md``), generated from
:mod:`audit.engine.shared.schemas` (a test keeps the two in sync).

``python -m reports.guide`` prints it; ``python -m reports.guide docs/columns.md`` rewrites the
generated part of that page, between its two markers.
"""

from __future__ import annotations

import sys
from pathlib import Path

from audit.engine.shared.schemas import GUIDE
from reports.generated_page import between, main, rewrite_between

#: The lines between which a page holds the generated guide.
START, END = "<!-- column guide: start -->", "<!-- column guide: end -->"


def markdown() -> str:
    """One section per output file, a Markdown table in each: column, unit, meaning."""
    parts = []
    for name, columns in GUIDE.items():
        parts.append(f"## `{name}`\n\n| column | unit | meaning |\n|---|---|---|")
        parts.extend("| `{}` | {} | {} |".format(column, unit, meaning.replace("|", r"\|"))
                     for column, (unit, meaning) in columns.items())
        parts.append("")
    return "\n".join(parts).strip() + "\n"


def generated_part(page: str) -> str:
    """The text of ``page`` between the markers, without them."""
    return between(page, (START, END))


def rewrite(path: Path) -> None:
    """Replace the generated part of the page at ``path`` by the guide as the schema has it."""
    rewrite_between(path, (START, END), markdown())


if __name__ == "__main__":
    main(sys.argv[1:], (START, END), markdown)
