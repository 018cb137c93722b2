"""``audit check``: its files' fields, its numbers against independent paths (closed forms, the
slow single fit, the procedure evaluated directly), the bootstrap over records and the width
search against closed forms, and bad objects refused before any work."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.stats import binom, norm

import audit
from audit.cli import main
from audit.engine.shared.blocks import Block
from audit.engine.check.summary import CSV_COLUMNS
from audit.engine.check.widths import required_width
from audit.engine.design.bootstrap import bootstrap_lognormal
from audit.engine.design.lognormal_fit import fit_lognormal
from audit.errors import InputError
from audit.physics.block import coefficient_of_restitution
from procedures import get_procedures
from procedures.context import RecordContext
from records import RecordEntry
from tests.engine.check.pulses import eight_pulses

G = 9.81
SITE = (1.5, 0.9)  # PGA of the design spectrum 0.4 S_XS = 0.6 g
# the 0.6 m × 1.8 m cabinet, and the same block typed by (α, 2π/p) worked by hand:
# α = atan(0.6/1.8); R = ½√(0.6² + 1.8²); p = √(3g/(4R)); 2π/p
ALPHA_DEG = math.degrees(math.atan(0.6 / 1.8))
RADIUS_M = 0.5 * math.hypot(0.6, 1.8)
SIZE_S = 2.0 * math.pi / math.sqrt(3.0 * G / (4.0 * RADIUS_M))



@pytest.fixture(scope="module")
def result():
    by_slenderness = Block(alpha_deg=ALPHA_DEG, size_s=SIZE_S, name="by-alpha")
    return audit.check(["0.6x1.8", by_slenderness], SITE, procedures=["fema356", "housner1963"],
                       records=eight_pulses(), im="pga", solver=audit.Solver(free_motion_s=5.0))


def test_check_json_has_the_fields_of_the_issue(result, tmp_path):
    result.write(tmp_path)
    document = json.loads((tmp_path / "check.json").read_text())
    assert document["site"]["sxs_g"] == 1.5 and "hazard level" in document["site"]["hazard_level"]
    assert document["im"] == "pga" and document["im_unit"] == "g"
    for obj in document["objects"]:
        assert {"name", "width_m", "height_m", "alpha_deg", "size_s", "exact", "procedures",
                "sentence", "risk"} <= set(obj)
        assert obj["risk"] is None  # reserved for the hazard curve
        assert {"median_g", "beta", "p_overturn_at_site", "p_band", "im", "site_im_g",
                "required_width_m_10pct", "required_width_m_50pct"} <= set(obj["exact"])
        assert obj["exact"]["site_im_g"] == pytest.approx(0.4 * 1.5)
        assert [(p["key"], p["limit_state"]) for p in obj["procedures"]] == [
            ("fema356", "overturning"), ("housner1963", "overturning")]
        for proc in obj["procedures"]:
            assert {"procedure", "key", "limit_state", "verdict", "demand", "capacity", "unit",
                    "basis", "share_of_records_overturning", "factors",
                    "anchorage_force_over_weight", "exact_p_exceed", "required_width_m",
                    "reason", "risk_p50"} <= set(proc)
            assert proc["verdict"] in ("passes", "fails")
    csv = (tmp_path / "check.csv").read_text().splitlines()
    assert csv[0].split(",") == CSV_COLUMNS and len(csv) == 1 + 2 * 2
    assert "check.html" in {p.name for p in tmp_path.iterdir()}
    assert "0.6x1.8" in result._repr_html_() and "CheckResult(2 object(s)" in repr(result)


def test_a_block_by_dimensions_equals_the_block_by_alpha_and_size(result):
    by_dimensions, by_slenderness = result.document["objects"]
    assert by_slenderness["width_m"] == pytest.approx(0.6, rel=1e-12)
    assert by_slenderness["height_m"] == pytest.approx(1.8, rel=1e-12)
    assert by_dimensions["alpha_deg"] == pytest.approx(ALPHA_DEG, rel=1e-12)
    assert by_dimensions["size_s"] == pytest.approx(SIZE_S, rel=1e-12)
    assert by_dimensions["exact"]["stripes"] == by_slenderness["exact"]["stripes"]
    assert by_dimensions["exact"]["p_overturn_at_site"] == pytest.approx(
        by_slenderness["exact"]["p_overturn_at_site"], rel=1e-9)
    for a, b in zip(by_dimensions["procedures"], by_slenderness["procedures"]):
        assert a["verdict"] == b["verdict"] and a["demand"] == pytest.approx(b["demand"])


def test_p_at_the_site_is_the_lattice_fragility_or_the_count_it_contradicts(result):
    exact = result.document["objects"][0]["exact"]
    stripes = exact["stripes"]
    fitted = np.asarray(stripes["fitted"])
    levels = np.asarray(stripes["im"])
    # the fragility is fitted on the lattice's stripes only: 2^(k/4), k even
    assert np.allclose(levels[fitted], 2.0 ** (np.arange(-16, 11, 2) / 4))
    site = int(np.argmin(np.abs(levels - 0.6)))  # the site's own stripe, 0.4 S_XS
    assert levels[site] == exact["site_im_g"] == pytest.approx(0.6) and not fitted[site]
    fit = fit_lognormal(levels[fitted], np.full(fitted.sum(), stripes["records"]),
                        np.asarray(stripes["overturned"])[fitted])
    assert exact["median_g"] == pytest.approx(fit.median, rel=1e-9)
    at = exact["p_at_site"]
    model = norm.cdf(math.log(0.6 / exact["median_g"]) / exact["beta"])
    assert at["model"]["p"] == pytest.approx(model, rel=1e-9)
    k, n = stripes["overturned"][site], stripes["records"]
    assert (at["count"]["overturned"], at["count"]["records"]) == (k, n)
    # the records at the site reject the lognormal when its P lies outside the count's exact
    # band: the central exact binomial test at 10 %, either tail below 5 %
    rejected = min(binom.cdf(k, n, model), binom.sf(k - 1, n, model)) < 0.05
    expected = "count" if k in (0, n) or rejected else "lognormal"
    assert at["estimator"] == expected
    assert exact["p_overturn_at_site"] == pytest.approx(k / n if expected == "count" else model,
                                                        rel=1e-9)
    low, high = exact["p_band"]
    assert low <= exact["p_overturn_at_site"] <= high


def test_fema356_verdict_is_its_estimate_on_the_site_design_spectrum(result):
    # FEMA 356 reads only the site: its verdict is its iteration on the unscaled design spectrum
    fema = get_procedures("fema356")[0]
    entry = RecordEntry("site", None, site={"sxs_g": 1.5, "sx1_g": 0.9})
    alpha = math.atan(0.6 / 1.8)
    estimate = fema.evaluate(entry, np.array([2 * math.pi / SIZE_S]), alpha,
                             float(coefficient_of_restitution(alpha)),
                             RecordContext(entry)).estimate
    answer = result.document["objects"][0]["procedures"][0]
    assert answer["verdict"] == ("fails" if estimate.outcome[0] == "overturn" else "passes")
    assert answer["capacity"] == pytest.approx(ALPHA_DEG)


def test_bootstrap_band_contains_the_binomial_estimate_and_resamples_fit_as_the_slow_fit():
    rng = np.random.default_rng(7)
    levels = np.geomspace(0.25, 4.0, 9)
    capacity = np.exp(rng.normal(0.0, 0.5, 40))  # each record's overturning level
    overturned = levels[None, :] > capacity[:, None]
    boot = bootstrap_lognormal(levels, overturned, resamples=400, seed=3)
    for j in (3, 4, 5):
        low, high = boot.probability_band(levels[j])
        assert low <= overturned[:, j].mean() <= high
    # seeded: the same band again
    again = bootstrap_lognormal(levels, overturned, resamples=400, seed=3)
    np.testing.assert_array_equal(again.medians, boot.medians)
    # every resample's fit is the maximum fit_lognormal finds for its counts
    rows = np.random.default_rng(3).integers(0, 40, size=(400, 40))
    for k in (0, 17, 399):
        counts = overturned[rows[k]].sum(axis=0)
        slow = fit_lognormal(levels, np.full(levels.size, 40), counts)
        assert boot.medians[k] == pytest.approx(slow.median, rel=1e-6)
        assert boot.betas[k] == pytest.approx(slow.beta, rel=1e-5)


def test_bootstrap_of_a_block_that_never_overturns_gives_zero():
    boot = bootstrap_lognormal(np.geomspace(0.5, 2, 5), np.zeros((10, 5), dtype=bool))
    assert boot.probability_band(1.0) == (0.0, 0.0)


def test_required_width_is_the_closed_form_root_and_monotone():
    # P(w) = Φ(ln(S/θ(w))/β), θ = k·w/h: wider is safer; P = t at w = h·S/(k·exp(β Φ⁻¹(t)))
    site, k, beta = 0.9, 6.0, 0.4

    def probability(heights, widths):
        return norm.cdf(np.log(site * heights / (k * widths)) / beta)

    heights = np.array([1.0, 1.8, 3.0])
    targets = (0.05, 0.10, 0.50)
    widths = required_width(probability, heights, targets)
    expected = heights[:, None] * site / (k * np.exp(beta * norm.ppf(np.array(targets))))
    np.testing.assert_allclose(widths, expected, rtol=0.006)
    assert np.all(widths >= expected * (1 - 1e-12))  # the answer is on the safe side
    assert np.all(np.diff(widths, axis=1) < 0) and np.all(np.diff(widths, axis=0) > 0)


def test_required_width_when_no_width_or_every_width_is_safe_enough():
    widths = required_width(lambda h, w: np.full(np.size(w), 0.9), [2.0], (0.1,))
    assert math.isnan(widths[0, 0])
    widths = required_width(lambda h, w: np.zeros(np.size(w)), [2.0], (0.1,))
    assert widths[0, 0] == pytest.approx(0.03 * 2.0)


@pytest.mark.parametrize("block, field", [("0x1.8", "width_m"), ("0.6x-1", "height_m"),
                                          ("20x1", "width_m"), ("0.5x60", "height_m"),
                                          ("0.6x", "height_m")])
def test_bad_blocks_are_refused_in_one_line_before_any_work(block, field, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["check", "--block", block, "--site", "1.5,0.9", "--out", str(out)]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and f"--block {block}" in error[0] and field in error[0]
    assert not out.exists()


def test_an_inventory_with_a_bad_row_is_refused_naming_file_row_and_field(tmp_path, capsys):
    inventory = tmp_path / "objects.csv"
    inventory.write_text("name,width_m,height_m\ncabinet,0.6,1.8\nshelf,abc,2.0\n")
    assert main(["check", "--objects", str(inventory), "--site", "1.5,0.9",
                 "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err.strip()
    assert "objects.csv: row 3 (shelf): width_m" in error and "\n" not in error
    assert not (tmp_path / "out").exists()


def test_api_names_the_argument():
    with pytest.raises(InputError, match=r"objects\[1\].*height_m"):
        audit.check(["0.6x1.8", ("shelf", 0.4, 0.0)], SITE)
    with pytest.raises(InputError, match=r"objects\[0\].*width_m"):
        audit.check(["3x1"], SITE)
    with pytest.raises(InputError, match="im"):
        audit.check(["0.6x1.8"], SITE, im="pgv")


def test_a_grid_cell_is_named_as_the_object_it_is():
    from reports.block_metres import describe_block
    # the 0.6 m × 1.8 m cabinet's (α, 2π/p), worked by hand above
    assert describe_block(ALPHA_DEG, SIZE_S) == "a 0.60 m × 1.80 m block"
    # α = 15°, 2π/p = 2 s: p = π rad/s, R = 3g/(4π²) = 0.7455 m; 2R sin 15° = 0.386 m,
    # 2R cos 15° = 1.440 m
    assert describe_block(15.0, 2.0) == "a 0.39 m × 1.44 m block"


def test_an_inventory_row_may_give_alpha_and_size(tmp_path):
    from argparse import Namespace

    from audit.cli.check import objects_of
    inventory = tmp_path / "objects.csv"
    inventory.write_text("name,width_m,height_m,alpha_deg,size_s\n"
                         f"cabinet,0.6,1.8,,\nsame,,,{ALPHA_DEG!r},{SIZE_S!r}\n")
    args = Namespace(block=["0.4x1.2"], objects=str(inventory), alpha="15", size="2")
    objects = objects_of(args)
    assert [o.name for o in objects] == ["0.4x1.2", "cabinet", "same", "α=15°, 2π/p=2 s"]
    assert objects[2].width_m == pytest.approx(0.6, rel=1e-12)
    assert objects[2].height_m == pytest.approx(1.8, rel=1e-12)
    # α = 15°, 2π/p = 2 s: R = 3g/(4π²)
    radius = 3 * G / (4 * math.pi ** 2)
    assert objects[3].width_m == pytest.approx(2 * radius * math.sin(math.radians(15)))
    args = Namespace(block=["0.4x1.2", "0.4x1.2"], objects=None, alpha=None, size=None)
    with pytest.raises(InputError, match="given twice"):
        objects_of(args)


def test_accepted_width_is_the_order_statistic_of_the_records_widths():
    # records with known narrowest accepted widths c_r: the guideline accepts w when at most
    # half of them have c_r > w, i.e. from the ⌈n/2⌉-th smallest c_r on
    from audit.engine.check.guideline_search import accepted_width, guideline_brackets
    rng = np.random.default_rng(5)
    for n in (1, 7, 44):
        c = rng.uniform(0.2, 1.4, n)
        obj = Block.of_dimensions(0.6, 1.8, name="x")
        tries = []

        def refine(which, widths, c=c):
            tries.append(len(which))
            return [w < c[k] for k, w in zip(which, widths)]

        # one object per record, all stepped together
        brackets = list(zip(*guideline_brackets(lambda which, w, c=c: w < c[which], [obj] * n,
                                                0.6 < c)))
        assert all(low < r <= high <= 1.5 * low for (low, high), r in zip(brackets, c))
        width = accepted_width(*zip(*brackets), refine)
        expected = np.sort(c)[math.ceil(n / 2) - 1]
        assert expected <= width <= expected * 1.02
        assert sum(tries) < 7 * n  # only the brackets near the order statistic were halved


def test_a_guideline_that_rejects_every_width_requires_none():
    from audit.engine.check.guideline_search import accepted_width, guideline_brackets
    obj = Block.of_dimensions(0.6, 1.8, name="x")
    (low,), (high,) = guideline_brackets(lambda which, w: np.ones(len(which), bool), [obj], [True])
    assert (low, high) == (pytest.approx(0.99 * 1.8), math.inf)
    assert math.isinf(accepted_width([low], [high], lambda which, widths: [True] * len(which)))
    (low,), (high,) = guideline_brackets(lambda which, w: np.zeros(len(which), bool), [obj],
                                         [False])
    assert (low, high) == (0.0, pytest.approx(0.018))
    assert accepted_width([low], [high], None) == pytest.approx(0.018)


def test_the_metres_axis_labels_each_size_with_its_blocks_height():
    from reports.block_metres import describe_block, metres_axis
    axis = metres_axis(20.0, [0.5, 8.0], "x2", "y2")
    assert axis["overlaying"] == "x2" and axis["side"] == "top" and len(axis["tickvals"]) >= 3
    for size, text in zip(axis["tickvals"], axis["ticktext"]):
        height = float(text.removesuffix(" m"))
        # the block of that size at α = 20° is that tall (h = 2R cos α, R = 3g/(4p²))
        assert describe_block(20.0, size).endswith(f"× {height:.2f} m block")


def test_a_dask_cluster_gives_the_same_answers(result):
    """The check's records on a Dask LocalCluster of two worker processes: every object's
    answer as in this process (the width search sends its records with no procedure, and the
    check's work sets its stripes' solver threads)."""
    dask = audit.check(["0.6x1.8", Block(alpha_deg=ALPHA_DEG, size_s=SIZE_S, name="by-alpha")],
                       SITE, procedures=["fema356", "housner1963"], records=eight_pulses(),
                       im="pga", solver=audit.Solver(free_motion_s=5.0),
                       runtime=audit.Runtime(jobs=2, scheduler="dask"))
    assert "LocalCluster of 2" in dask.document["scheduler"]
    assert dask.document["objects"] == result.document["objects"]


def test_an_objects_exact_answer_does_not_depend_on_the_objects_checked_beside_it():
    # objects of one height share their width search: beside a narrower object of its height
    # and one of another height, the cabinet's exact answer (required widths, the family fitted
    # on each solved width once, bands) is the one it gets alone
    alone = audit.check(["0.6x1.8"], SITE, procedures=["fema356"], records=eight_pulses(),
                        im="pga", solver=audit.Solver(free_motion_s=5.0))
    beside = audit.check(["0.6x1.8", "0.45x1.8", "0.5x1.2"], SITE, procedures=["fema356"],
                         records=eight_pulses(), im="pga", solver=audit.Solver(free_motion_s=5.0))
    assert beside.document["objects"][0]["exact"] == alone.document["objects"][0]["exact"]


def test_the_page_shows_each_component_provisions_static_row(result, tmp_path):
    # the page's table carries the static checks of check.json beside the guidelines, each
    # with its own verdict and F/W demand and capacity in g
    import re
    result.write(tmp_path)
    document = json.loads((tmp_path / "check.json").read_text())
    page = (tmp_path / "check.html").read_text()
    provisions = document["objects"][0]["component_provisions"]
    assert len(provisions) == 3
    for entry in provisions:
        row = re.search(re.escape(f"<td class=\"l\">{entry['procedure']} (static)</td>")
                        + r".*?</tr>", page, re.S)
        assert row is not None, entry["procedure"]
        assert f">{entry['verdict']}</td>" in row.group(0)
        assert f"{entry['capacity']:.3g}" in row.group(0) and ">g</td>" in row.group(0)
