"""The parameters tables of the documentation (``docs/procedures.md``), generated from each
plug-in's declared :attr:`parameters` (:mod:`procedures.parameters`; a test keeps the two in
sync).

``python -m reports.parameter_guide`` prints them; ``python -m reports.parameter_guide
docs/procedures.md`` rewrites the generated part of that page, between its two markers.
"""

from __future__ import annotations

import sys
from pathlib import Path

from procedures.parameters import parameter_defaults
from procedures.registry import available_component_provisions, available_procedures
from reports.generated_page import between, main, rewrite_between

#: The lines between which a page holds the generated tables.
START, END = "<!-- parameters: start -->", "<!-- parameters: end -->"


def markdown() -> str:
    """One table per plug-in that declares parameters: key, unit, what it takes, default, the
    clause of the default and whether the default is the text's or an assumption."""
    parts = []
    for name, cls in {**available_procedures(), **available_component_provisions()}.items():
        if not cls.parameters:
            continue
        defaults = parameter_defaults(cls)
        parts.append(f"### `{name}` ({cls.title})\n\n"
                     "| key | meaning | unit | takes | default | the default's clause | "
                     "default from |\n|---|---|---|---|---|---|---|")
        for p in cls.parameters:
            cells = (f"`{p.key}`", p.meaning, p.unit, p.expected(), p.shown(defaults[p.key]),
                     p.clause, "the text" if p.from_text else "an assumption")
            parts.append("| " + " | ".join(c.replace("|", r"\|") for c in cells) + " |")
        parts.append("")
    return "\n".join(parts).strip() + "\n"


def generated_part(page: str) -> str:
    """The text of ``page`` between the markers, without them."""
    return between(page, (START, END))


def rewrite(path: Path) -> None:
    """Replace the generated part of the page at ``path`` by the tables as declared."""
    rewrite_between(path, (START, END), markdown())


if __name__ == "__main__":
    main(sys.argv[1:], (START, END), markdown)
