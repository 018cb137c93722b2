"""Resumable runs: a real process interrupted by real signals, then resumed to the same results."""

import json
import os
import pickle
import re
import signal
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import pytest

import audit.api
from audit.engine.shared.grid import size_grid
from audit.engine.shared.partial import PARTIAL_DIR, PartialStore
from audit.engine.run.record_audit import audit_record
from audit.engine.run.settings import AuditSettings
from procedures import get_procedures
from records import load_records

ROOT = Path(__file__).resolve().parents[3]
#: Six real records: NGA AT2 files and FEMA P695 text files (dt and units from SOURCES.md).
RECORDS = [
    ("pacoima_dam_1971", "raw/RSN77_SFERN_PUL164.AT2", "peer-at2", None),
    ("sylmar_fn", "derived/P695NF_RSN1086_NORTHR_SYL_032.txt", "columns", 0.02),
    ("takatori_1995", "raw/RSN1120_KOBE_TAK090.AT2", "peer-at2", None),
    ("erzincan_fn", "derived/P695NF_RSN821_ERZIKAN_ERZ_032.txt", "columns", 0.005),
    ("rinaldi_1994_at2", "raw/Rinaldi228.AT2", "peer-at2", None),
    ("rinaldi_fn", "derived/P695NF_RSN1063_NORTHR_RRS_032.txt", "columns", 0.01),
]
GRID = ["--alpha", "15", "--size", "3:8:0.25", "--jobs", "1"]
FINAL_FILES = ("results.csv", "summary.json", "suite.csv", "report.html", "rocking.csv")


@pytest.fixture(scope="module")
def manifest(records_dir, tmp_path_factory):
    lines = []
    for record_id, file, fmt, dt in RECORDS:
        lines += ["[[record]]", f'id = "{record_id}"', f'file = "{records_dir / file}"',
                  f'format = "{fmt}"']
        lines += [f"dt = {dt}", 'units = "g"', "column = 1"] if dt else []
    path = tmp_path_factory.mktemp("manifest") / "six.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def _start(manifest, out, *extra):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        filter(None, [str(ROOT), os.environ.get("PYTHONPATH", "")]))}
    return subprocess.Popen([sys.executable, "-m", "audit", "run", "priestley1978", "--records",
                             str(manifest), "--out", str(out), *GRID, *extra],
                            cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def _parts(out) -> dict:
    """Record id → file of the complete per-record results in ``out/.partial``."""
    parts = {}
    for path in (out / PARTIAL_DIR).glob("*.pkl"):
        with open(path, "rb") as file:
            parts[pickle.load(file)["record"]] = path
    return parts


def _interrupt_after(process, out, more_than: int, sig) -> dict:
    """Send ``sig`` once ``out/.partial`` holds more than ``more_than`` record results."""
    deadline = time.monotonic() + 300
    while len(list((out / PARTIAL_DIR).glob("*.pkl"))) <= more_than:
        assert process.poll() is None, process.communicate()[1]
        assert time.monotonic() < deadline, "no record result appeared"
        time.sleep(0.02)
    process.send_signal(sig)
    process.communicate(timeout=120)
    assert process.returncode != 0
    return _parts(out)


def _staging(out):
    return [p for p in out.parent.iterdir() if p.name.startswith(f".{out.name}-")]


def _assert_no_final_file(out, killed=False):
    """Only the parts in ``out``; beside it no staging folder, except, after a SIGKILL, the
    one the killed run was writing its files into (the next run removes it)."""
    assert [p.name for p in out.iterdir()] == [PARTIAL_DIR]
    assert len(_staging(out)) <= (1 if killed else 0)


def test_killed_run_resumes_to_identical_results(manifest, tmp_path):
    out = tmp_path / "run"
    # Ctrl-C after the first record, then SIGKILL a resumed run after one more
    first = _interrupt_after(_start(manifest, out), out, 0, signal.SIGINT)
    _assert_no_final_file(out)
    assert 1 <= len(first) < len(RECORDS), "the run ended before it could be interrupted"
    second = _interrupt_after(_start(manifest, out, "--resume"), out, len(first), signal.SIGKILL)
    _assert_no_final_file(out, killed=True)
    assert set(first) < set(second) and len(second) < len(RECORDS)
    assert all(second[record] == path for record, path in first.items())

    resumed = _start(manifest, out, "--resume")
    stdout, stderr = resumed.communicate(timeout=600)
    assert resumed.returncode == 0, stderr
    summary = json.loads((out / "summary.json").read_text())
    assert sorted(summary["resumed"]) == sorted(second)
    # progress lines: "[  1.2 s] record 3/6: ID (computed in 0.8 s)"
    computed = re.findall(r"record \d+/\d+: (\S+) \(computed", stderr)
    assert sorted(computed) == sorted(set(r[0] for r in RECORDS) - set(second))
    assert not (out / PARTIAL_DIR).exists()
    assert not _staging(out)  # the killed run's staging folder removed too

    # the same run uninterrupted, in this process
    whole = tmp_path / "whole"
    audit.api.run("priestley1978", load_records(manifest), alpha_deg=[15.0],
                  size_s=size_grid(3.0, 8.0, 0.25),
                  out_dir=whole)
    for name in ("results.csv", "suite.csv", "rocking.csv"):
        assert (out / name).read_bytes() == (whole / name).read_bytes(), name


@pytest.fixture(scope="module")
def pacoima(seed_suite):
    return seed_suite.get("pacoima_dam_1971")


def test_parts_are_reused_only_for_the_same_settings_and_record(pacoima, tmp_path):
    procedures = get_procedures("priestley1978")
    settings = AuditSettings(alpha_deg=(20.0,), size_s=(5.0, 6.0))
    part = audit_record(pacoima, procedures, settings)
    PartialStore(tmp_path, procedures, settings, resume=False).save(pacoima, part)
    assert [p.suffix for p in tmp_path.iterdir()] == [".pkl"]   # no temporary file left
    same = PartialStore(tmp_path, procedures, settings, resume=True).load(pacoima)
    assert same.results.equals(part.results)
    for other in (replace(settings, agree_band=0.2), replace(settings, size_s=(5.0,)),
                  replace(settings, robustness=0.0)):
        assert PartialStore(tmp_path, procedures, other, resume=True).load(pacoima) is None
    assert PartialStore(tmp_path, get_procedures("all"), settings, resume=True).load(pacoima) is None
    scaled = replace(pacoima, motion=replace(pacoima.motion,
                                             acceleration=pacoima.motion.acceleration * 1.01))
    assert PartialStore(tmp_path, procedures, settings, resume=True).load(scaled) is None
    resited = replace(pacoima, site={**pacoima.site, "sxs_g": 1.0})
    assert PartialStore(tmp_path, procedures, settings, resume=True).load(resited) is None
    # a jobs count is not a setting of the results
    assert PartialStore(tmp_path, procedures, replace(settings, jobs=4),
                        resume=True).load(pacoima) is not None


def test_corrupt_part_is_recomputed_and_a_fresh_run_clears_the_folder(pacoima, tmp_path):
    procedures = get_procedures("priestley1978")
    settings = AuditSettings(alpha_deg=(20.0,), size_s=(6.0,))
    store = PartialStore(tmp_path / PARTIAL_DIR, procedures, settings, resume=False)
    store.save(pacoima, audit_record(pacoima, procedures, settings))
    [path] = (tmp_path / PARTIAL_DIR).iterdir()
    path.write_bytes(path.read_bytes()[:100])                  # truncated by hand
    assert PartialStore(tmp_path / PARTIAL_DIR, procedures, settings, True).load(pacoima) is None
    PartialStore(tmp_path / PARTIAL_DIR, procedures, settings, resume=False)
    assert not (tmp_path / PARTIAL_DIR).exists()
