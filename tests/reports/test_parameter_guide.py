"""docs/procedures.md holds the parameters tables as the plug-ins declare them
(``python -m reports.parameter_guide docs/procedures.md`` rewrites them)."""

from pathlib import Path

from reports.parameter_guide import END, START, generated_part, markdown, rewrite

REPO = Path(__file__).resolve().parents[2]


def test_docs_parameter_tables_match_the_declarations():
    page = (REPO / "docs" / "procedures.md").read_text(encoding="utf-8")
    assert generated_part(page) == markdown()
    # one row checked by hand against the declaration it comes from
    assert ("| `I_p` | component importance factor | - | a number in [1, 1.5] | 1 | §13.1.3: 1.0 "
            "unless the component is needed for life safety (1.5) | the text |") in page
    for name in ("asce7_22", "en1998_1", "nzs1170_5", "ntc2018"):
        assert f"### `{name}`" in page


def test_rewrite_replaces_only_the_generated_part(tmp_path):
    page = tmp_path / "procedures.md"
    page.write_text(f"# P\n\n{START}\nstale\n{END}\n\nafter\n", encoding="utf-8")
    rewrite(page)
    text = page.read_text(encoding="utf-8")
    assert generated_part(text) == markdown() and "stale" not in text
    assert text.startswith("# P\n\n") and text.endswith(f"{END}\n\nafter\n")
