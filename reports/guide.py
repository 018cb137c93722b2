"""The README's column guide, generated from :mod:`audit.engine.schemas` (a test keeps the two
in sync): ``python -m reports.guide`` prints it."""

from __future__ import annotations

from audit.engine.schemas import GUIDE


def markdown() -> str:
    """One Markdown table per output file: column, unit, meaning."""
    parts = []
    for name, columns in GUIDE.items():
        parts.append(f"`{name}`\n\n| column | unit | meaning |\n|---|---|---|")
        parts.extend("| `{}` | {} | {} |".format(column, unit, meaning.replace("|", r"\|"))
                     for column, (unit, meaning) in columns.items())
        parts.append("")
    return "\n".join(parts).strip() + "\n"


if __name__ == "__main__":
    print(markdown(), end="")
