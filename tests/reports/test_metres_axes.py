"""The metres axes of the figures over block size 2π/p: each tick sits at the size of a block of
its labelled length, R = 3g/(4p²) worked here in closed form, on an axis aligned with the 2π/p
axis it tops; every 2π/p axis of the run report and of the margins page has one; a map's hover
names the block of each cell in metres."""

import json
import math
import re

import numpy as np
import pandas as pd
import pytest

import audit.api
from audit import G
from reports.block_metres import DIAGONAL_TITLE, metres_axis
from reports.margins_figures import cmr_figure, required_figure
from reports.margins_risk_section import _alpha_figure, _map_figure

SIZES_S = np.round(np.arange(0.5, 8.01, 0.5), 2)
ALPHAS_DEG = (10.0, 20.0)


def _length_m(size_s: float, alpha_deg: float | None) -> float:
    """The block's diagonal 2R (``alpha_deg`` None) or height 2R cos α [m] at size 2π/p."""
    p = 2.0 * math.pi / size_s
    radius = 3.0 * G / (4.0 * p * p)
    return 2.0 * radius * (1.0 if alpha_deg is None else math.cos(math.radians(alpha_deg)))


def _ticks(axis) -> list[tuple[float, float]]:
    """(size [s], labelled length [m]) of each tick of a metres axis."""
    return [(size, float(text.removesuffix(" m")))
            for size, text in zip(axis["tickvals"], axis["ticktext"], strict=True)]


@pytest.mark.parametrize("alpha_deg", [None, 10.0, 30.0])
@pytest.mark.parametrize("log", [False, True])
def test_each_tick_is_at_the_size_of_a_block_of_its_length(alpha_deg, log):
    span = [0.4, 8.5]
    axis = metres_axis(alpha_deg, span, "x3", "y3", log=log)
    ticks = _ticks(axis)
    assert len(ticks) >= 4
    for size, length in ticks:
        assert _length_m(size, alpha_deg) == pytest.approx(length, rel=1e-12)
        # round lengths: 1, 2 or 5 times a power of ten
        assert round(length / 10 ** math.floor(math.log10(length)), 9) in (1, 2, 5)
    # the same range as the 2π/p axis, in the axis' own coordinates (decades when log)
    assert axis["range"] == pytest.approx(np.log10(span) if log else span, rel=1e-12)
    assert axis.get("type", "linear") == ("log" if log else "linear")
    assert axis["overlaying"] == "x3" and axis["anchor"] == "y3" and axis["side"] == "top"
    # ticks inside the span, an eighth of it apart on the drawn scale
    drawn = np.log10([s for s, _ in ticks]) if log else np.array([s for s, _ in ticks])
    low, high = axis["range"]
    assert low <= drawn.min() and drawn.max() <= high
    assert np.diff(drawn).min() >= (high - low) / 8 - 1e-12
    # over several α the axis says which length it is, and how the height follows
    assert ("title" in axis) == (alpha_deg is None)


def test_the_diagonal_over_a_short_span_keeps_only_the_lengths_inside_it():
    # 2π/p = 1.5 … 2.5 s: diagonals 0.84 … 2.33 m, so 1 m (1.64 s) and 2 m (2.32 s) only
    axis = metres_axis(None, [1.5, 2.5], "x", "y")
    assert axis["ticktext"] == ["1 m", "2 m"]
    assert axis["tickvals"] == pytest.approx([2 * math.pi * math.sqrt(2 * d / (3 * G))
                                              for d in (1.0, 2.0)], rel=1e-12)


def _two_pi_p_groups(layout) -> list[set[str]]:
    """The x axes over 2π/p, grouped with the axes they match (a stack of panels shares one
    range: only its bottom axis is titled)."""
    ids = {key: "x" + key[5:] for key in layout if key.startswith("xaxis")}
    groups = []
    for key, axis_id in ids.items():
        title = (layout[key].get("title") or {}).get("text") or ""
        if "2π/p" in title:
            group = {axis_id}
            target = layout[key].get("matches")
            group |= {target} if target else set()
            group |= {i for k, i in ids.items() if layout[k].get("matches") in group}
            groups.append(group)
    return groups


def _check_metres_axes(spec, name, diagonal_only=True) -> int:
    """Assert that each 2π/p axis (group) of the figure ``spec`` carries a metres axis over
    the same range, each tick where the block of its length is; the number of ticks checked."""
    layout = spec["layout"]
    groups = _two_pi_p_groups(layout)
    assert groups, f"{name}: no 2π/p axis"
    checked = 0
    for group in groups:
        over = [axis for key, axis in layout.items() if key.startswith("xaxis")
                and axis.get("overlaying") in group]
        assert over, f"{name}: the 2π/p axis {sorted(group)} has no metres axis"
        for axis in over:
            primary = layout["xaxis" + axis["overlaying"][1:]]
            assert primary["range"] == axis["range"], name
            assert primary.get("type", "linear") == axis.get("type", "linear"), name
            assert all(t.endswith(" m") for t in axis["ticktext"]), name
            diagonal = (axis.get("title") or {}).get("text") == DIAGONAL_TITLE
            assert diagonal or not diagonal_only, name
            # the axis is drawn: an (empty) trace sits on it
            axis_id = "x" + next(k for k, a in layout.items() if a is axis)[5:]
            assert any(trace.get("xaxis") == axis_id for trace in spec["data"]), name
            if diagonal:
                for size, length in _ticks(axis):
                    # sizes carry the page's 4 significant digits: 2R ∝ size²
                    assert _length_m(size, None) == pytest.approx(length, rel=1.2e-3), name
                    checked += 1
    return checked


def _plot_specs(page: str) -> dict:
    return {target: json.loads(text) for target, text in re.findall(
        r'<script type="application/json" class="plot-spec" data-target="([^"]+)">(.*?)'
        r'</script>', page, re.S)}


@pytest.fixture(scope="module")
def report(seed_suite, tmp_path_factory):
    out = tmp_path_factory.mktemp("metres") / "run"
    audit.api.run("all", seed_suite, alpha_deg=ALPHAS_DEG, size_s=list(SIZES_S),
                  robustness=0.0, out_dir=out)
    return out


def test_every_2pi_p_axis_of_the_run_report_has_a_metres_axis(report):
    specs = _plot_specs((report / "report.html").read_text(encoding="utf-8"))
    over_size = {name: spec for name, spec in specs.items() if _two_pi_p_groups(spec["layout"])}
    kinds = {re.sub(r"-.*", "", name) for name in over_size}
    # verdict maps, the rocking spectra (Fig. 5.x), the procedures' Figs 8.x/9.x, the suite's
    # maps and bands, the limit-state checks
    assert {"verdict", "fig", "suite", "checks"} <= kinds
    # a procedure's figure (fig-SERIES-RECORD-PROCEDURE) has one α per row: the height there
    per_alpha = {name for name in over_size if re.fullmatch(r"fig-[^-]+-[^-]+-.+", name)}
    assert per_alpha and len(per_alpha) < len(over_size)
    ticks = 0
    for name, spec in over_size.items():
        ticks += _check_metres_axes(spec, name, diagonal_only=name not in per_alpha)
    assert ticks >= 3 * (len(over_size) - len(per_alpha))


def test_a_map_names_the_block_of_each_cell_in_metres(report):
    specs = _plot_specs((report / "report.html").read_text(encoding="utf-8"))
    maps = [spec for name, spec in specs.items() if name.startswith(("verdict-map", "checks",
                                                                     "suite-unsafe"))]
    checked = 0
    for spec in maps:
        for trace in (t for t in spec["data"] if t["type"] == "heatmap"):
            first = int(re.search(r"a %\{customdata\[(\d)\]:\.2f\} m × %\{customdata\[(\d)\]"
                                  r":\.2f\} m block", trace["hovertemplate"]).group(1))
            for alpha, row in zip(trace["y"], trace["customdata"]):
                for size, cell in zip(trace["x"], row):
                    if cell is None:
                        continue
                    width, height = cell[first], cell[first + 1]
                    diagonal = _length_m(size, None)
                    assert width == pytest.approx(diagonal * math.sin(math.radians(alpha)),
                                                  abs=0.006)
                    assert height == pytest.approx(diagonal * math.cos(math.radians(alpha)),
                                                   abs=0.006)
                    checked += 1
    assert checked >= 2 * len(SIZES_S) * len(maps)


def test_the_margins_charts_over_size_have_a_metres_axis():
    grid = pd.DataFrame([(a, s) for a in (10.0, 15.0, 20.0) for s in SIZES_S],
                        columns=["alpha_deg", "size_s"])
    required = pd.DataFrame({"procedure": "exact@0.10", "size_s": SIZES_S,
                             "required_alpha_deg": np.linspace(25, 8, SIZES_S.size),
                             "exact_overturning_share": 0.1})
    fragility = grid.assign(width_m=np.nan, height_m=np.nan, cmr=np.linspace(0.5, 3, len(grid)), cmr_bound="")
    risk = grid.assign(width_m=np.nan, height_m=np.nan, annual_rate_fit=np.geomspace(1e-5, 1e-2, len(grid)))
    risk_alpha = required.assign(procedure="exact@risk", p50=0.01)
    figures = {"required": required_figure(required, [], {}), "cmr": cmr_figure(fragility),
               "risk-alpha": _alpha_figure(risk_alpha, {}, lambda name: "#000", 0.01),
               "risk-map": _map_figure(risk, 2e-4)}
    for name, figure in figures.items():
        spec = json.loads(json.dumps(figure, default=lambda v: v.tolist()))
        assert _check_metres_axes(spec, name) >= 4, name
    # a heatmap's axis spans its cells, half a step beyond the first and the last size
    assert figures["cmr"]["layout"]["xaxis"]["range"] == pytest.approx([0.25, 8.25])
    # the hover names each cell's block: 2R sin α × 2R cos α
    cell = figures["cmr"]["data"][0]["customdata"][1][3]  # α = 15°, 2π/p = 2 s
    assert cell[:2] == pytest.approx([0.39, 1.44])  # R = 3g/(4π²) = 0.7455 m
