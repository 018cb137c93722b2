"""The HTML report: sections, interactive figures drawn by a real browser (headless Chromium)
offline, a block looked up from the embedded figure data, the worst cases, the optional sections
fed by other parts of the audit, and files that describe themselves."""

import json
import math
import os
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import audit.api
from audit.engine.run.results import load_run
from audit.engine.run.suite import suite_summary
from audit.engine.shared.schemas import CHECK_COLUMNS, CLAIM_COLUMNS, SUITE_COLUMNS
from audit.engine.run.pipeline import audit_in_memory
from audit.engine.shared.verdicts import VERDICTS
from procedures import get_procedures
from records import pulse_suite
from reports import render_report

REPO = Path(__file__).resolve().parents[2]
#: The seed suite's page on the default grid: 7.9 MB before the maps' hovers named each cell's
#: block in metres (two numbers a cell, +0.25 MB), 8.1 MB since.
MAX_HTML_BYTES = 8_300_000


class ReportParser(HTMLParser):
    """Collects ids, links, tables, plot divs and the figure specifications of a page."""

    def __init__(self):
        super().__init__()
        self.ids, self.urls, self.tables, self.plots = set(), [], set(), []
        self.specs, self._spec = {}, None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "table" and "id" in attrs:
            self.tables.add(attrs["id"])
        if tag == "div" and attrs.get("class") == "plot":
            self.plots.append(attrs["id"])
        if tag == "script" and attrs.get("class") == "plot-spec":
            self._spec = attrs["data-target"]
        for key in ("src", "href", "action", "poster"):
            if key in attrs:
                self.urls.append(attrs[key])

    def handle_data(self, data):
        if self._spec is not None:
            self.specs[self._spec] = json.loads(data)

    def handle_endtag(self, tag):
        if tag == "script":
            self._spec = None


def _parse(html: str) -> ReportParser:
    parser = ReportParser()
    parser.feed(html)
    return parser


def _own_markup(html: str) -> str:
    """The page without the inlined plotly.js library (its source names URLs in comments)."""
    start = html.index("<script>")
    return html[:start] + html[html.index("</script>", start):]


@pytest.fixture(scope="module")
def seed_report(seed_suite, tmp_path_factory):
    """The report of ``run all`` on the real seed suite, written as the CLI writes it."""
    out = tmp_path_factory.mktemp("report") / "run"
    audit.api.run("all", seed_suite, out_dir=out, runtime=audit.Runtime(jobs=2))
    return out


@pytest.fixture(scope="module")
def html(seed_report):
    return (seed_report / "report.html").read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def parsed(html):
    return _parse(html)


@pytest.mark.slow  # end to end: the seed suite's run
def test_every_audited_record_has_its_section_and_figures(parsed):
    numbers = {"pacoima_dam_1971": 1, "el_centro_5_1979": 2, "los_gatos_1989": 3,
               "rinaldi_1994": 4, "sylmar_1994": 5, "erzincan_1992": 6, "takatori_1995": 7}
    for record in numbers:
        assert f"record-{record}" in parsed.ids
    for record in ("pacoima_dam_1971", "rinaldi_1994", "sylmar_1994", "erzincan_1992",
                   "takatori_1995"):
        n = numbers[record]
        assert {f"fig-5-{n}", f"fig-8-{n}-priestley1978"} <= set(parsed.plots), record
    for record in ("pacoima_dam_1971", "rinaldi_1994", "sylmar_1994"):
        assert f"fig-9-{numbers[record]}-fema356" in parsed.plots
    # FEMA estimates of the records without a file are in Figure 9.x, the exact ones are not
    assert "fig-9-2-fema356" in parsed.plots and "fig-5-2" not in parsed.plots
    assert "fig-9-6-fema356" not in parsed.plots  # Erzincan has no FEMA site parameters
    assert {"fig-7-1", "fig-sensitivity", "verdict-map-priestley1978",
            "verdict-map-fema356"} <= set(parsed.plots)
    assert {"verdict-priestley1978", "verdict-fema356"} <= parsed.ids
    # every plot div has its specification, and nothing else is drawn
    assert set(parsed.plots) == set(parsed.specs)


@pytest.mark.slow  # end to end: the seed suite's run
def test_bottom_line_counts_unsafe_and_uneconomic(parsed, html, seed_report):
    results = pd.read_csv(seed_report / "results.csv")
    for name in ("priestley1978", "fema356"):
        rows = results[results["procedure"] == name]
        unsafe = rows["verdict"].isin(["missed-overturn", "unconservative"]).sum()
        uneconomic = rows["verdict"].isin(["false-overturn", "conservative"]).sum()
        block = html[html.index(f'id="verdict-{name}"'):]
        block = block[:block.index("</div>")]
        assert f"unsafe for {unsafe} of {len(rows)} blocks" in block
        assert f"uneconomic for {uneconomic} " in block
        assert f"for {(rows['verdict'] == 'not-converged').sum()} (" in block
        # red only where the unsafe count is not zero
        assert ('class="unsafe"' in block) == (unsafe > 0), name
    # Priestley misses overturnings on the seed suite, so its worst case is one of them
    priestley = html[html.index('id="verdict-priestley1978"'):]
    worst = priestley[priestley.index("Worst case"):priestley.index("</p>")]
    assert "overturns" in worst and "missed-overturn" in worst


@pytest.mark.slow  # end to end: the seed suite's run
def test_worst_cases_link_to_drawn_time_histories(parsed, seed_report):
    assert "worst-table" in parsed.tables
    results = pd.read_csv(seed_report / "results.csv")
    summary = json.loads((seed_report / "summary.json").read_text())
    links = [u[1:] for u in parsed.urls if u.startswith("#th-")]
    assert links and all(link in parsed.ids for link in links)
    for link in links:
        assert link.removesuffix("-figure") in parsed.specs
    # the largest underestimate of Priestley over the suite (a robust exact response ranks
    # before a fragile one) has its time history drawn
    ratios = results[(results["procedure"] == "priestley1978")
                     & (results["verdict"] == "unconservative")]
    robust = ratios[~ratios["exact_fragile"]]
    worst = (robust if len(robust) else ratios).sort_values("ratio").iloc[0]
    reasons = [h["reason"] for h in summary["histories"]
               if h["record"] == worst["record"] and math.isclose(h["size_s"], worst["size_s"])
               and math.isclose(h["alpha_deg"], worst["alpha_deg"])]
    assert reasons and "largest underestimate, priestley1978" in reasons[0]
    # histories are not always α = 15°
    assert {h["alpha_deg"] for h in summary["histories"]} > {15.0}


@pytest.mark.slow  # end to end: the seed suite's run
def test_a_block_can_be_looked_up_by_hover(parsed, seed_report):
    """Every cell of a verdict map carries exact, guideline and verdict in its hover data, its
    panel's hover template the record; its axes give α and 2π/p; the verdict matches
    results.csv."""
    results = pd.read_csv(seed_report / "results.csv")
    summary = json.loads((seed_report / "summary.json").read_text())
    names = {r["id"]: r["name"] for r in summary["records"]}
    checked = 0
    for name in results["procedure"].unique():
        spec = parsed.specs[f"verdict-map-{name}"]
        rows = results[results["procedure"] == name]
        for trace in spec["data"]:
            if trace["type"] != "heatmap":
                continue
            assert "%{x" in trace["hovertemplate"] and "%{y" in trace["hovertemplate"]
            for i, alpha in enumerate(trace["y"]):
                for j, size in enumerate(trace["x"]):
                    exact, guideline, verdict, *block_m = trace["customdata"][i][j]
                    record = trace["hovertemplate"].split("<br>")[0]  # once per panel
                    assert exact and guideline and verdict in VERDICTS and len(block_m) == 2
                    rid = next(k for k, v in names.items() if v == record)
                    row = rows[(rows["record"] == rid) & np.isclose(rows["alpha_deg"], alpha)
                               & np.isclose(rows["size_s"], size)]
                    assert len(row) == 1 and row["verdict"].iloc[0] == verdict
                    checked += 1
    assert checked == len(results)


@pytest.mark.slow  # end to end: the seed suite's run
def test_tables_and_methods(parsed, html):
    assert {"table-3-1", "table-5-1", "verdict-table", "unauditable",
            "column-guide"} <= parsed.tables
    assert "records of manifest" in html and "Eq. 8.1" in html and "Eq. 7.10" in html
    assert "0.379" in html  # Table 5.1 PGA of El Centro, a missing record, still tabulated


@pytest.mark.slow  # end to end: the seed suite's run
def test_self_contained_and_small(parsed, html, seed_report):
    assert (seed_report / "report.html").stat().st_size <= MAX_HTML_BYTES
    assert html.count("<script>") == 2  # plotly.js once, the loader once
    assert all(url.startswith("#") for url in parsed.urls)
    own = _own_markup(html)
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", own)
    assert "@import" not in own and "url(" not in own and "<img" not in own


@pytest.mark.slow  # end to end: the seed suite's run
def test_results_csv_booleans_and_units(seed_report):
    frame = pd.read_csv(seed_report / "results.csv")
    for column in ("exact_overturned", "exact_uplifted", "exact_fragile", "approx_overturned"):
        assert frame[column].dtype == bool, column
    assert len(frame[frame.exact_overturned]) > 0
    guide = json.loads((seed_report / "columns.json").read_text())["results.csv"]
    assert list(guide) == list(frame.columns)


@pytest.mark.slow  # end to end: the seed suite's run
def test_rerendered_report_matches(seed_report, html):
    again = render_report(load_run(seed_report))
    strip = lambda text: re.sub(r"generated \d{4}-\d\d-\d\d \d\d:\d\d UTC", "", text)  # noqa: E731
    assert strip(again) == strip(html)


@pytest.mark.slow  # end to end: the seed suite's run, in headless Chromium
def test_report_renders_offline_in_headless_chromium(seed_report, parsed, tmp_path, browse):
    """Every figure is drawn (plotly's SVG in each figure div), with no console error."""
    moved = tmp_path / "elsewhere" / "report.html"  # alone: nothing beside it to load
    moved.parent.mkdir()
    shutil.copy(seed_report / "report.html", moved)
    done = browse(moved, "--dump-dom")
    assert f'data-plotted="{len(parsed.plots)}"' in done.stdout, done.stderr[-2000:]
    assert 'data-plot-error="' not in done.stdout
    drawn = re.findall(r'<div class="plot js-plotly-plot" id="([^"]+)"[^>]*>\s*'
                       r'<div class="plot-container', done.stdout)
    assert sorted(drawn) == sorted(parsed.plots)
    assert done.stdout.count('class="main-svg"') >= len(parsed.plots)
    console = [line for line in done.stderr.splitlines() if "CONSOLE" in line]
    assert not console, console[:5]
    shot = tmp_path / "report.png"
    browse(moved, f"--screenshot={shot}", "--window-size=1280,2400", "--hide-scrollbars")
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and shot.stat().st_size > 50_000


def _small_run():
    """A quick audit of the pulse suite on a small grid, with synthetic frames standing in for
    the limit-state checks, suite statistics and claims that other parts of the audit write."""
    run = audit_in_memory(get_procedures("priestley1978"), pulse_suite(), alpha_deg=(10.0, 15.0),
                    size_s=np.array([1.0, 2.0, 3.0]), robustness=0.0)
    records = ["pacoima_dam_1971", "rinaldi_1994"]
    checks = []
    verdicts = ["agrees-safe", "missed", "false-alarm", "agrees-unsafe", "missed", "agrees-safe"]
    for r, record in enumerate(records):
        for k, (alpha, size) in enumerate([(a, s) for a in (10.0, 15.0) for s in (1.0, 2.0, 3.0)]):
            verdict = verdicts[(k + r) % len(verdicts)]
            checks.append({"record": record, "procedure": "ntc2018", "alpha_deg": alpha,
                           "size_s": size, "limit_state": "SLV", "exact_event": "θ ≥ θ(0.4 b)",
                           "procedure_passes": verdict in ("agrees-safe", "missed"),
                           "exact_exceeded": verdict in ("agrees-unsafe", "missed"),
                           "verdict": verdict, "demand_m": 0.01, "capacity_m": 0.02})
    suite = []
    for alpha in (10.0, 15.0):
        for size, unsafe in ((1.0, 0.0), (2.0, 0.5), (3.0, 0.25)):
            row = {c: 0.0 for c in SUITE_COLUMNS}
            row.update(procedure="priestley1978", alpha_deg=alpha, size_s=size, records=4,
                       frac_unsafe=unsafe, frac_unconservative=unsafe,
                       frac_agrees=1.0 - unsafe, ratio_p16=0.6, ratio_p50=0.9, ratio_p84=1.3)
            suite.append(row)
    claims = [{"id": f"C{i}", "section": "8", "claim": f"claim {i}", "reference_value": "1",
               "tool_value": "1", "status": status, "note": ""}
              for i, status in enumerate(["agrees", "agrees", "close", "differs",
                                          "cannot-check"])]
    run.checks = pd.DataFrame(checks, columns=CHECK_COLUMNS)
    run.suite = pd.DataFrame(suite, columns=SUITE_COLUMNS)
    run.summary["suite"] = suite_summary(run.suite, {"priestley1978": "Priestley (1978)"})
    run.claims = pd.DataFrame(claims, columns=CLAIM_COLUMNS)
    return run


def test_sections_fed_by_other_parts_of_the_audit():
    run = _small_run()
    html = render_report(run)
    parsed = _parse(html)
    assert {"confusion-table", "claims-table"} <= parsed.tables
    assert "checks-ntc2018-SLV" in parsed.plots and "suite-unsafe" in parsed.plots
    assert "suite-ratio-priestley1978" in parsed.plots
    # confusion matrix of Pacoima: counted here from the synthetic verdicts
    expected = pd.Series([c for c in run.checks[run.checks["record"] == "pacoima_dam_1971"]
                          ["verdict"]]).value_counts()
    row = html[html.index("<td class=\"l\">SLV</td><td class=\"l\">San Fernando"):]
    row = row[:row.index("</tr>")]
    cells = re.findall(r"<td[^>]*>(\d+)</td>", row)
    assert [int(c) for c in cells] == [int(expected.get(c, 0)) for c in
                                       ("agrees-safe", "agrees-unsafe", "missed", "false-alarm")]
    tally = html[html.index('id="claims-tally"'):]
    assert "5 claims" in tally[:200] and "2 agrees, 1 close, 1 differs, 1 cannot-check" in tally
    # the quotable sentence: mean unsafe share at α = 15° is (0 + 0.5 + 0.25)/3 = 25.0 %
    # the quotable sentence of summary.json: (0 + 0.5 + 0.25)/3 = 25 % at α = 15°
    assert ("Over 4 records, Priestley (1978) is unsafe for 25 % of blocks with α = 15°, "
            "worst at 2π/p ≈ 2 s (50 % of records).") in html
    # hover of the checks map names the check of each cell
    spec = parsed.specs["checks-ntc2018-SLV"]
    assert spec["data"][0]["text"][0][0] in ("agrees-safe", "missed", "false-alarm",
                                            "agrees-unsafe")


@pytest.mark.slow  # end to end: runs of the command line
def test_empty_optional_sections_are_left_out():
    run = _small_run()
    run.checks = run.checks.iloc[0:0]
    run.suite = run.suite.iloc[0:0]
    run.claims = run.claims.iloc[0:0]
    parsed = _parse(render_report(run))
    assert not {"confusion-table", "claims-table", "suite", "checks", "claims"} & (
        parsed.ids | parsed.tables)


@pytest.mark.slow  # end to end: runs of the command line
def test_paths_do_not_depend_on_the_working_directory(seed_manifest, tmp_path):
    """Run from one folder with a relative --records and --out elsewhere: every path written
    is absolute (or relative to the output folder), none relative to the working directory."""
    cwd = tmp_path / "work"
    cwd.mkdir()
    records = os.path.relpath(seed_manifest, cwd)
    assert records.startswith("..")
    done = subprocess.run(
        [sys.executable, "-m", "audit", "run", "priestley1978", "--records", records,
         "--out", "../out", "--alpha", "15", "--size", "2:3:0.5", "--robustness", "0"],
        cwd=cwd, capture_output=True, text=True, timeout=900,
        env={**os.environ, "PYTHONPATH": str(REPO)})
    assert done.returncode == 0, done.stderr[-2000:]
    # a line per stage and per record although stderr is not a terminal
    assert "record 1/" in done.stderr and "writing the results" in done.stderr
    out = tmp_path / "out"
    summary = json.loads((out / "summary.json").read_text())
    sources = [r["source"] for r in summary["records"] if not r["missing"]]
    assert sources and all(Path(s).is_absolute() and Path(s).is_file() for s in sources)
    assert str(seed_manifest.resolve()) in summary["records_source"]
    for name in ("summary.json", "report.html"):
        text = (out / name).read_text(encoding="utf-8")
        assert records not in text and "../" + Path(sources[0]).parent.name not in text


def test_docs_column_guide_matches_columns_module():
    """docs/columns.md holds the guide as the schema has it (``python -m reports.guide
    docs/columns.md`` rewrites it)."""
    from reports.guide import generated_part, markdown
    page = (REPO / "docs" / "columns.md").read_text(encoding="utf-8")
    assert generated_part(page) == markdown()
    assert "| `exact_overturned` | bool | the exact response overturns |" in page


def test_column_guide_rewrite_replaces_only_the_generated_part(tmp_path):
    from reports.guide import END, START, generated_part, markdown, rewrite
    page = tmp_path / "columns.md"
    page.write_text(f"# Guide\n\nintro\n\n{START}\nstale table\n{END}\n\nafter\n", encoding="utf-8")
    rewrite(page)
    text = page.read_text(encoding="utf-8")
    assert generated_part(text) == markdown() and "stale" not in text
    assert text.startswith("# Guide\n\nintro\n\n") and text.endswith(f"{END}\n\nafter\n")


def test_large_suite_puts_statistics_first_and_details_only_where_asked():
    run = _small_run()
    copies = [dict(r, id=f"{r['id']}_b", name=f"{r['name']} (b)") for r in run.summary["records"]]
    run.summary["records"] = run.summary["records"] + copies
    run.results = pd.concat([run.results, run.results.assign(record=run.results["record"] + "_b")],
                            ignore_index=True)
    run.summary["detail_records"] = ["rinaldi_1994_b"]  # chosen by the engine, test below
    html = render_report(run)
    parsed = _parse(html)
    assert len(run.summary["records"]) > 10
    assert html.index('id="suite"') < html.index('id="worst"')
    sections = {i for i in parsed.ids if i.startswith("record-") and i != "record-source"}
    assert sections == {"record-rinaldi_1994_b"}
    assert f"{len(run.summary['records']) - 1} records of the suite have no detail section" in html


@pytest.mark.slow  # ~25 s: a large suite's report
def test_a_large_suite_details_the_records_asked_for_or_the_worst_and_reads_only_those(
        seed_suite, tmp_path):
    from dataclasses import replace

    from audit.engine.run.ranking import WORST_RECORDS
    from audit.engine.shared.verdicts import UNSAFE_VERDICTS
    from records import RecordSuite
    doubled = RecordSuite(tuple(seed_suite) + tuple(replace(e, id=f"{e.id}_b")
                                                    for e in seed_suite), "seed twice")
    ids = [entry.id for entry in doubled]
    grid = dict(alpha_deg=(10.0, 15.0, 20.0), robustness=0.0)
    asked = audit.api.run("priestley1978", doubled, detail=["rinaldi_1994_b"], **grid)
    assert asked.summary["detail_records"] == ["rinaldi_1994_b"]

    result = audit.api.run("priestley1978", doubled, out_dir=tmp_path / "run", **grid)
    results = result.results
    # the records with the most unsafe blocks, counted here from results.csv (suite order on
    # ties), are the sections
    unsafe = results[results["verdict"].isin(UNSAFE_VERDICTS)]["record"].value_counts()
    ranked = sorted(unsafe.index, key=lambda record: (-unsafe[record], ids.index(record)))
    assert len(doubled) > 10 and len(ranked) >= WORST_RECORDS
    assert result.summary["worst_records"] == ranked[:WORST_RECORDS]
    assert set(result.summary["detail_records"]) == set(ranked[:WORST_RECORDS])
    # the report, read back with only the rows it shows, ranks the same worst blocks as with all
    from audit.engine.run.results import load_run
    from reports.render import _worst_cases
    whole, shown = load_run(tmp_path / "run"), load_run(tmp_path / "run", shown=True)
    assert set(shown.results["record"]) == set(result.summary["shown_records"]) < set(ids)
    metas, procedures = whole.summary["histories"], whole.summary["procedures"]
    names = {r["id"]: r["name"] for r in whole.summary["records"]}
    def table(run):  # NaN ratios (missed overturning) compare equal as text
        return json.dumps(_worst_cases(run, procedures, names, metas), default=str)
    assert table(shown) == table(whole)
    assert any(table["rows"] for table in _worst_cases(whole, procedures, names, metas))


def test_procedure_figure_draws_cycles_and_repelling_fixed_points():
    """A cycle is a vertical band between its branches, a repelling fixed point is marked,
    and empty columns (no cycle, no fixed points) draw nothing."""
    from reports.spectra_figures import procedure_figure
    alpha = math.radians(10.0)
    rows = pd.DataFrame({
        "alpha_deg": 10.0, "size_s": [6.0, 8.0, 7.0], "beta_pct": 5.0,
        "exact_theta_rad": [0.5 * alpha, 0.3 * alpha, 0.4 * alpha],
        "exact_overturned": False, "approx_overturned": False,
        "approx_theta_rad": [np.nan, 0.2397 * alpha, 0.3 * alpha],
        "approx_period_s": [np.nan, 5.0, 5.5],
        "approx_outcome": ["not-converged", "converged", "converged"],
        "approx_cycle": ["0.5753;0.8854", "", ""],
        "approx_fixed_points": ["0.737u", "0.2397s;0.2551u;0.4821s", ""]})
    spectrum = pd.DataFrame({"alpha_deg": 10.0, "period_s": [0.0, 10.0], "sd_m": [0.0, 1.0]})
    spec = procedure_figure(rows, spectrum, "P")
    traces = {t.get("name"): t for t in spec["data"]}
    band = traces["cycle: band between its branches"]
    assert band["x"] == [6.0, 6.0, None] and band["y"] == [0.5753, 0.8854, None]
    repelling = traces["repelling fixed point (○)"]
    assert sorted(zip(repelling["x"], repelling["y"])) == [(6.0, 0.737), (8.0, 0.2551)]
    # every legend entry names a trace that draws something
    for trace in spec["data"]:
        if trace.get("showlegend", True) and trace.get("name"):
            assert any(v is not None and not (isinstance(v, float) and math.isnan(v))
                       for v in trace["y"]), trace["name"]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1,
                max_size=40))
def test_embedded_numbers_keep_four_significant_digits(values):
    """Every float of a figure reaches the page within half a unit of its 4th significant digit,
    as an int when integral, and as null when it is (or rounds to) NaN or ±inf: JSON has no
    NaN, and a value next to the largest double rounds to inf."""
    from reports.plots import to_json
    embedded = json.loads(to_json({"y": np.array(values), "z": np.array([values, values]),
                                   "alone": [[v, "text"] for v in values],
                                   "listed": [*values, None]}))
    assert embedded["z"] == [embedded["y"], embedded["y"]]
    # a float alone (hover data beside text) and a list of floats: the same digits
    assert [alone for alone, _ in embedded["alone"]] == embedded["y"]
    assert embedded["listed"] == [*embedded["y"], None]
    for value, got in zip(values, embedded["y"]):
        if not math.isfinite(value) or abs(value) > 1.7976e308:  # 1.798e308 overflows
            assert got is None
            continue
        if got is None:  # 1.7975e308 is the last value that may round either way
            assert abs(value) >= 1.7974e308
            continue
        assert abs(got - value) <= 5e-4 * abs(value)
        assert len(repr(float(got)).lstrip("-0.").split("e")[0].replace(".", "").rstrip("0")) <= 4
        assert isinstance(got, int) == (float(got).is_integer() and abs(got) < 1e15)


def test_record_drawn_but_audited_by_no_procedure():
    """FEMA 356 needs a design site; a record without one still has its exact response and a
    drawn history (the README's main command on Erzincan). The report shows that history with
    no estimate, and says why the procedure was not audited."""
    from records import RecordSuite
    no_site = RecordSuite(tuple(e for e in pulse_suite() if not e.site.get("sxs_g")), "no site")
    assert [e.id for e in no_site] == ["erzincan_1992", "takatori_1995"]
    run = audit_in_memory(get_procedures("fema356"), no_site, alpha_deg=[15.0],
                    size_s=np.arange(1.0, 8.01, 1.0))
    assert run.results.empty and len(run.histories)
    html = render_report(run)
    drawn = [key for key in _parse(html).specs if key.startswith("th-")]
    assert {key.split("-")[1] for key in drawn} == {"erzincan_1992", "takatori_1995"}
    assert "no FEMA 356 (2000) site parameters (sxs_g, sx1_g)" in html


def test_mechanics_figures_are_drawn_from_the_saved_files():
    # Figures 7.1 and 4.1/7.2 come from mechanics.csv: 16 free-rocking curves (θ₀/α 0.1…0.7 ×
    # n 2…8) and the two laws; three pulse amplitudes for the block and for the oscillator
    run = audit_in_memory(get_procedures("priestley1978"), pulse_suite(), alpha_deg=(15.0,),
                    size_s=np.array([2.0]), robustness=0.0, claims=False)  # read from its files
    specs = _parse(render_report(run)).specs
    names = [trace["name"] for trace in specs["fig-7-1"]["data"]]
    assert len(names) == 18 and names[-2:] == ["Eq. 7.10: β = −0.34 ln r",
                                               "Eq. 9.1: β = 0.4 (1 − √r)"]
    traces = specs["fig-sensitivity"]["data"]
    # 0.316 g overturns the block (Figure 4.1); its oscillator does not "overturn"
    assert [t["name"] for t in traces] == ["a_p = 0.310 g", "a_p = 0.315 g",
                                           "a_p = 0.316 g (overturns)", "a_p = 0.310 g",
                                           "a_p = 0.315 g", "a_p = 0.316 g"]
    # Eq. 7.10 at r = 0.8: β = −0.34 ln 0.8 = 7.587 %
    law = specs["fig-7-1"]["data"][16]
    assert law["y"][law["x"].index(0.8)] == pytest.approx(7.587, abs=1e-3)


@pytest.mark.slow  # end to end: the seed suite's run
def test_csv_text_is_the_bytes_pandas_writes(seed_report):
    """The fast CSV writer against pandas' own ``to_csv`` on every table of a real run, and on
    the cells that need care: quotes, commas, line breaks, NaN, None, ±inf, booleans, ints,
    repeated values and -0.0 beside 0.0."""
    from audit.engine.shared.csv_text import csv_bytes
    tricky = pd.DataFrame({
        "text": ['plain', 'a,b', 'say "x"', "two\nlines", None, ""],
        "number": [1.5, float("nan"), float("inf"), -float("inf"), 1e-7, 123456789012.0],
        "flag": [True, False, True, False, True, False],
        "count": [0, 1, -2, 3, 40, 500],
        "mixed": [True, "", 0.25, None, float("nan"), "x"],
        "repeated": [0.0, -0.0, 0.1, -0.0, float("nan"), 0.1],
    })
    for frame in [tricky] + [pd.read_csv(path, keep_default_na=False, na_values=[""])
                             for path in sorted(seed_report.glob("*.csv"))]:
        for digits in ("%.10g", "%.4g"):
            assert csv_bytes(frame, digits) == frame.to_csv(index=False,
                                                            float_format=digits).encode()


def test_grid_pivot_is_pandas_pivot_table():
    from reports.grid_figures import _pivot
    frame = pd.DataFrame({"alpha_deg": [10, 10, 20, 20, 10, 30, 20],
                          "size_s": [1.0, 2.0, 1.0, 1.0, 1.0, 3.0, 3.0],
                          "v": [np.nan, 0.5, 0.2, 0.9, 0.7, np.nan, np.inf]})
    pivot = frame.pivot_table(index="alpha_deg", columns="size_s", values="v", aggfunc="first")
    alphas, sizes, z = _pivot(frame, "v")
    assert np.array_equal(alphas, pivot.index.to_numpy(dtype=float))
    assert np.array_equal(sizes, pivot.columns.to_numpy(dtype=float))
    assert np.array_equal(z, pivot.to_numpy(dtype=float), equal_nan=True)


@pytest.mark.slow  # end to end: the seed suite's run
def test_suite_statistics_and_bottom_line_folded_record_by_record_equal_the_whole(seed_report):
    """The run folds each record's rows as it passes; over the same rows, any split into parts
    gives what the whole table gives (verdict counts, percentiles, the bottom line's worst
    block, which a stable ranking makes the first of equals)."""
    from audit.engine.run.results import load_run
    from audit.engine.run.suite import BottomLine, SuiteStatistics
    run = load_run(seed_report)
    procedures = [SimpleNamespace(name=p["name"]) for p in run.summary["procedures"]]
    whole_stats = SuiteStatistics().add(run.results).frame()
    whole_line = BottomLine(procedures).add(run.results, run.checks).lines()
    stats, line = SuiteStatistics(), BottomLine(procedures)
    records = list(dict.fromkeys(run.results["record"]))
    assert len(records) > 3
    for record in records:
        stats.add(run.results[run.results["record"] == record])
        line.add(run.results[run.results["record"] == record],
                 run.checks[run.checks["record"] == record])
    pd.testing.assert_frame_equal(stats.frame(), whole_stats, check_exact=True)
    assert json.dumps(line.lines(), sort_keys=True, default=str) == json.dumps(
        whole_line, sort_keys=True, default=str)
    assert any(entry["worst"] for entry in whole_line)


def test_templates_compile_once_across_processes(monkeypatch):
    """A page's template is compiled in one process and loaded compiled by the next (jinja2's
    bytecode cache): a fresh environment loads it, with the same blocks, without compiling."""
    from jinja2 import Environment
    from reports.html_parts import page_templates

    first = page_templates().get_template("report.html.j2")

    def compiled_again(*args, **kwargs):
        raise AssertionError("the template was compiled again")

    monkeypatch.setattr(Environment, "compile", compiled_again)
    again = page_templates().get_template("report.html.j2")
    assert again.blocks.keys() == first.blocks.keys()


@pytest.fixture
def own_temporary_directory(tmp_path, monkeypatch):
    """The temporary directory jinja2's cache folder goes in, moved to ``tmp_path`` (the
    process's cache object made afresh there, and again after the test)."""
    import tempfile
    from reports import html_parts

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    html_parts._bytecode_cache.cache_clear()
    yield tmp_path
    html_parts._bytecode_cache.cache_clear()


def test_pages_render_where_the_template_cache_folder_is_not_the_users(own_temporary_directory):
    """Something else at the cache folder's name (here a file; on a shared machine, another
    user's folder) turns the cache off; the page is still drawn."""
    from reports.html_parts import page_templates

    (own_temporary_directory / f"_jinja2-cache-{os.getuid()}").write_text("not a folder")
    env = page_templates()
    assert env.bytecode_cache is None
    assert "report.html.j2" == env.get_template("report.html.j2").name


def test_pages_render_where_the_template_cache_cannot_be_written(own_temporary_directory,
                                                                  monkeypatch):
    """A compiled template that cannot be saved (a full disk) is compiled again next time,
    not an error."""
    import jinja2.bccache
    from reports.html_parts import page_templates

    def disk_full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(jinja2.bccache.tempfile, "NamedTemporaryFile", disk_full)
    for _ in range(2):
        assert page_templates().get_template("check.html.j2").name == "check.html.j2"
    assert not any((own_temporary_directory / f"_jinja2-cache-{os.getuid()}").iterdir())
