"""The ground truth's assumptions in an audit: friction, jumping, model sensitivity and vertical
records, checked against invariants that do not go through the flags' own code."""

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from audit import G
from audit.cli import main
from audit.engine.shared.ground_truth import GroundTruth, alternatives, parse_sensitivity
from audit.errors import InputError
from records import load_records

GRID = ["--size", "1:4:0.5", "--alpha", "10,30,40"]


def _run(tmp_path, name, seed_manifest, *extra):
    out = tmp_path / name
    assert main(["run", "priestley1978", "--records", str(seed_manifest), *GRID, *extra,
                 "--out", str(out)]) == 0
    return pd.read_csv(out / "results.csv"), json.loads((out / "summary.json").read_text())


def test_sensitivity_words():
    assert parse_sensitivity(["restitution=0.9x,x0.8", "vertical", "restitution=x0.9"]) == (
        "restitution=x0.9", "restitution=x0.8", "vertical")
    models = alternatives(GroundTruth("housner", False), ("restitution=0.7", "vertical"))
    assert models == [GroundTruth("0.7", False), GroundTruth("housner", True)]
    for bad in ("restitution=", "restitution=1.5", "gravity=2", "x0.9"):
        with pytest.raises(InputError, match="^sensitivity: "):  # the field; the CLI its flag
            parse_sensitivity([bad])


def test_friction_jumps_and_model_sensitivity_in_results(seed_manifest, tmp_path, capsys):
    housner, summary = _run(tmp_path, "a", seed_manifest, "--friction", "0.3",
                            "--sensitivity", "restitution=x0.8")
    capsys.readouterr()
    settings = summary["settings"]
    assert (settings["restitution"], settings["friction"], settings["sensitivity"]) == (
        "housner", 0.3, ["restitution=x0.8"])
    # a block that never uplifts rests on its base all along: it needs exactly PGA / g
    pga = {r["id"]: r["pga_g"] * G for r in summary["records"] if r.get("pga_g")}
    still = housner[~housner["exact_uplifted"]]
    assert len(still)
    expected = still["record"].map(pga) / summary["settings"]["g"]
    assert np.allclose(still["exact_required_friction"], expected, rtol=1e-9)
    # every block that uplifts needs at least tan α
    rocking = housner[housner["exact_uplifted"]]
    assert np.all(rocking["exact_required_friction"]
                  >= np.tan(np.radians(rocking["alpha_deg"])) * (1 - 1e-12))
    assert housner["exact_slides"].equals(housner["exact_required_friction"] > 0.3)
    # the alternative model solved on its own: where its exact overturning differs, the verdict
    # class must change (overturning and surviving verdicts are disjoint classes); where its
    # exact response is the same, it cannot
    other, _ = _run(tmp_path, "b", seed_manifest, "--restitution", "x0.8")
    keys = ["record", "alpha_deg", "size_s"]
    both = housner.merge(other[keys + ["exact_overturned", "exact_theta_rad"]], on=keys,
                         suffixes=("", "_other"))
    flipped = ((both["exact_overturned"] != both["exact_overturned_other"])
               & (both["verdict"] != "not-converged"))
    same = both["exact_theta_rad"] == both["exact_theta_rad_other"]
    assert flipped.any() and both.loc[flipped, "exact_model_sensitive"].all()
    assert not both.loc[same, "exact_model_sensitive"].any()
    # the bottom line counts them apart
    (line,) = summary["bottom_line"]
    assert line["model_sensitive"] == int(housner["exact_model_sensitive"].sum())
    assert line["slides"] == int(housner["exact_slides"].sum())
    assert line["jumps"] == int(housner["exact_jumps"].sum())


def test_without_the_options_nothing_is_checked(seed_manifest, tmp_path, capsys):
    results, summary = _run(tmp_path, "plain", seed_manifest)
    capsys.readouterr()
    assert results["exact_slides"].isna().all()
    assert results["exact_model_sensitive"].isna().all()
    (line,) = summary["bottom_line"]
    assert line["slides"] is None and line["model_sensitive"] is None


def test_manifest_vertical_component(records_dir, tmp_path):
    # two components of one station: the fault-parallel file stands in as a 'vertical' one
    for name in ("Rinaldi228.AT2", "Rinaldi318.AT2"):
        shutil.copy(records_dir / "raw" / name, tmp_path / name)
    manifest = tmp_path / "m.toml"
    manifest.write_text('[[record]]\nid = "r"\nfile = "Rinaldi228.AT2"\nformat = "peer-at2"\n'
                        'vertical_file = "Rinaldi318.AT2"\nvertical_positive = "down"\n')
    motion = load_records(manifest).entries[0].motion
    other = load_records(tmp_path / "Rinaldi318.AT2").entries[0].motion
    assert np.array_equal(motion.vertical, -other.acceleration)
    assert main(["rock", "--records", str(manifest), "--record", "r", "--size", "2", "--alpha",
                 "15", "--vertical", "--json"]) == 0


def test_vertical_and_sensitivity_bad_input(records_dir, tmp_path, capsys):
    assert main(["rock", "--pulse", "cosine", "--amplitude", "0.3", "--pulse-period", "1",
                 "--size", "2", "--alpha", "15", "--vertical"]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "--vertical" in err
    assert main(["run", "all", "--sensitivity", "gravity=2", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "--sensitivity" in err
    assert not (tmp_path / "x").exists()
    manifest = tmp_path / "m.toml"
    manifest.write_text('[[record]]\nid = "r"\nfile = "a.AT2"\nformat = "peer-at2"\n'
                        'vertical_positive = "sideways"\n')
    with pytest.raises(InputError, match="vertical_positive"):
        load_records(manifest)
