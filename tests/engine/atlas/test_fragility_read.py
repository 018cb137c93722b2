"""``margins`` and ``fragility`` reading the atlas (``method="atlas"``) against their direct
solve on the same stripes (the atlas's 14): identical at a grid node, within the stated error
off the nodes; ``method="atlas"`` without an atlas refused, naming ``method`` and the build.

The atlases here are of the 3 seed records on the ground (the default grid: 1–2 s to build).
Off the nodes, measured with them (α 12.2° and 17°, 2π/p 1.13 s and 2.3 s): the fits' medians
within 7.1 % of the direct ones, P at every stripe within 0.18 of the direct fit's, each inside
the atlas's stated error there (0.07–0.40: 3 records make near-steps, β ≈ 0.04, whose P
between nodes is poorly known, and the stated error says so).
"""

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from scipy.stats import norm

import audit.api as api
from audit.api.atlas_lookup import atlas_reading
from audit.engine.atlas.store import ATLAS_DIR_ENV
from audit.engine.check.pipeline import LATTICE_EVERY
from audit.engine.fragility.pipeline import COMPONENTS_CSV, STRIPES_CSV, run_fragility
from audit.engine.fragility.settings import FragilitySettings
from audit.engine.shared.lattice import stripe_lattice
from audit.errors import InputError, NoAtlas
from procedures.probabilistic import (FragilityComponent, LognormalFragility,
                                      ProbabilisticProcedure)
from records import shipped_seed_suite

LATTICE = tuple(stripe_lattice(LATTICE_EVERY).tolist())
#: Nodes of the atlas's default grid (α 4 + 1.5 k°, 2π/p 0.4 · 2^(k/4) s), and points between.
NODES = ((10.0, 11.5), (0.8, 1.6))
OFF_NODES = ((12.2, 17.0), (1.13, 2.3))


@pytest.fixture(scope="module")
def suite():
    return shipped_seed_suite()


@pytest.fixture(scope="module")
def atlases(suite, tmp_path_factory):
    """An Sa(1 s) and a PGV atlas of the seed records, in a folder of their own."""
    before = os.environ.get(ATLAS_DIR_ENV)
    os.environ[ATLAS_DIR_ENV] = str(tmp_path_factory.mktemp("atlases"))
    api.build_atlas(suite, runtime=api.Runtime(jobs=2))
    api.build_atlas(suite, im="pgv", runtime=api.Runtime(jobs=2))
    yield os.environ[ATLAS_DIR_ENV]
    if before is None:
        del os.environ[ATLAS_DIR_ENV]
    else:
        os.environ[ATLAS_DIR_ENV] = before


def both(suite, blocks, **keywords):
    """``margins`` read from the atlas, and solved directly on the atlas's stripes."""
    common = dict(alpha_deg=blocks[0], size_s=blocks[1], site=(1.5, 0.9), required=False,
                  **keywords)
    return (api.margins("fema356", suite, method="atlas", **common),
            api.margins("fema356", suite, method="direct", stripes=LATTICE, **common))


def test_margins_at_nodes_is_the_direct_fit_on_the_same_stripes(atlases, suite):
    atlas, direct = both(suite, NODES)
    a, d = atlas.fragility, direct.fragility
    assert (a["exact_source"] == "atlas").all() and (d["exact_source"] == "direct").all()
    assert a["atlas_key"].str.len().eq(64).all() and d["atlas_error"].isna().all()
    assert np.isfinite(a["median"]).all()  # fits exist: the comparison is not of NaNs
    for column in ("median", "beta", "median_boot_low", "median_boot_high", "cmr"):
        np.testing.assert_allclose(a[column], d[column], rtol=1e-12, err_msg=column)
    np.testing.assert_allclose(atlas.capacity["achieved_p"], direct.capacity["achieved_p"],
                               rtol=1e-12)
    # the per-record outcomes are the stored ones: whole, the direct solve's
    np.testing.assert_array_equal(atlas.stripes["exact_overturned"].to_numpy(dtype=float),
                                  direct.stripes["exact_overturned"].to_numpy(dtype=float))
    source = atlas.summary["exact_source"]
    assert source["method"] == "atlas" and "from the atlas" in source["text"]
    assert atlas.scan is None and a["records_with_islands"].isna().all()  # not answered
    assert direct.summary["exact_source"] == {"method": "direct"}
    page = atlas.files()["margins.html"].decode()
    assert f"from the atlas {a['atlas_key'][0][:12]}" in page and "in P at most" in page


def test_margins_off_nodes_within_the_stated_error(atlases, suite):
    atlas, direct = both(suite, OFF_NODES)
    levels = np.array(LATTICE)
    for (_, a), (_, d) in zip(atlas.fragility.iterrows(), direct.fragility.iterrows()):
        assert a["median"] == pytest.approx(d["median"], rel=0.10)  # measured: ≤ 7.1 %
        p_atlas = norm.cdf(np.log(levels / a["median"]) / a["beta"])
        p_direct = norm.cdf(np.log(levels / d["median"]) / d["beta"])
        assert np.abs(p_atlas - p_direct).max() <= a["atlas_error"]
    # between the nodes an outcome is a probability, not 0 or 1
    over = atlas.stripes["exact_overturned"].to_numpy(dtype=float)
    assert ((over > 0) & (over < 1)).any()


def test_margins_default_reads_the_atlas_where_one_answers(atlases, suite):
    found = api.margins("fema356", suite, alpha_deg=NODES[0], size_s=NODES[1],
                        site=(1.5, 0.9), required=False)
    assert found.summary["exact_source"]["method"] == "atlas"
    assert found.summary["levels"] == pytest.approx(LATTICE)
    # stripes the atlas does not hold: the direct solve, or refused when the atlas is asked
    other = api.margins("fema356", suite, alpha_deg=NODES[0], size_s=NODES[1],
                        site=(1.5, 0.9), required=False, stripes=(0.3, 0.6))
    assert other.summary["exact_source"]["method"] == "direct"
    with pytest.raises(NoAtlas, match="stripes other than the atlas's .*; use method='direct'$") \
            as caught:
        api.margins("fema356", suite, alpha_deg=NODES[0], size_s=NODES[1], required=False,
                    stripes=(0.3, 0.6), method="atlas")
    assert caught.value.fields == ("method",)


class _AtNode(ProbabilisticProcedure):
    """One component whose block is a node of the atlas's grid (α 10°, 2π/p 0.8 s)."""

    name, title = "at_node", "a block at a node"
    _R = 3.0 * 9.81 / (4.0 * (2.0 * math.pi / 0.8) ** 2)  # p² = 3g/(4R)
    components = (FragilityComponent(
        "node", "α 10°, 2π/p 0.8 s", "PGV", LognormalFragility(0.3, 0.5),
        2.0 * _R * math.sin(math.radians(10.0)), 2.0 * _R * math.cos(math.radians(10.0))),)


def test_fragility_at_a_node_is_the_direct_fit_on_the_same_stripes(atlases, suite):
    entries = [e for e in suite if e.motion is not None]
    ids, motions = [e.id for e in entries], [e.motion for e in entries]
    reading = atlas_reading("atlas", suite, ([10.0], [0.8]), im="pgv")
    atlas = run_fragility(_AtNode(), ids, motions, atlas=reading)
    levels = tuple(reading.levels.tolist())
    direct = run_fragility(_AtNode(), ids, motions, FragilitySettings(levels_m_s=levels))
    a, d = atlas[COMPONENTS_CSV].iloc[0], direct[COMPONENTS_CSV].iloc[0]
    assert math.isfinite(d["exact_median_m_s"])
    assert a["exact_median_m_s"] == pytest.approx(d["exact_median_m_s"], rel=1e-9)
    assert a["exact_beta"] == pytest.approx(d["exact_beta"], rel=1e-9)
    # the Brier score's expectation over outcomes that are whole at a node: the plain score
    assert a["brier"] == pytest.approx(d["brier"], rel=1e-9)
    np.testing.assert_allclose(atlas[STRIPES_CSV]["overturned"], direct[STRIPES_CSV]["overturned"],
                               atol=1e-9)
    assert (a["exact_source"], a["atlas_key"]) == ("atlas", reading.key)
    assert d["exact_source"] == "direct"


def test_fragility_reads_the_pgv_atlas_and_says_so(atlases, suite):
    # P-58's components lie between the nodes; the atlas's stripes are its 14 in m/s
    result = api.fragility("femap58", suite, method="atlas")
    table = result.table
    assert (table["exact_source"] == "atlas").all()
    assert ((table["atlas_error"] > 0) & (table["atlas_error"] < 1)).all()
    assert sorted(result.tables[STRIPES_CSV]["pgv_m_s"].unique()) == pytest.approx(LATTICE)
    page = result.files()["fragility.html"].decode()
    assert "from the atlas" in page and "in P at most over the components" in page


def test_method_atlas_without_an_atlas_is_refused(suite, tmp_path, monkeypatch):
    monkeypatch.setenv(ATLAS_DIR_ENV, str(tmp_path / "none"))
    with pytest.raises(NoAtlas, match=r"build it with audit\.api\.build_atlas\(\)") as caught:
        api.margins("fema356", suite, alpha_deg=NODES[0], size_s=NODES[1], method="atlas")
    assert caught.value.fields == ("method",)
    assert caught.value.build["im"] == "sa:1"
    with pytest.raises(NoAtlas) as caught:
        api.fragility("femap58", suite, method="atlas")
    assert caught.value.build["im"] == "pgv"
    with pytest.raises(InputError, match="method: expected atlas or direct"):
        api.fragility("femap58", suite, method="exact")


@pytest.mark.parametrize("command", ["margins", "fragility"])
def test_cli_method_atlas_without_an_atlas_exits_2_with_one_line(command, tmp_path):
    env = {**os.environ, ATLAS_DIR_ENV: str(tmp_path / "none"), "PYTHONPATH": os.getcwd()}
    args = (["margins", "fema356", "--alpha", "10", "--size", "0.8:1.6:0.8"]
            if command == "margins" else ["fragility"])
    done = subprocess.run([sys.executable, "-m", "audit", *args, "--records", "pulses",
                           "--method", "atlas", "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: --method: atlas asked")
    assert "'python -m audit atlas build --records pulses" in lines[0]
    assert "use --method direct" in lines[0]
    assert not (tmp_path / "out").exists()
