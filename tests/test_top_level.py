"""A foreign ``records``, ``reports`` or ``procedures`` found before this distribution's is
named at ``import audit``, with what to do (:mod:`audit.top_level`)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]


def _import_audit(cwd: Path, pythonpath: Path | None = None) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    # the checkout stays importable (as under an editable install) after the foreign folder
    env["PYTHONPATH"] = os.pathsep.join(str(p) for p in (pythonpath, REPO) if p)
    return subprocess.run([sys.executable, "-c", "import audit"], cwd=cwd, env=env,
                          capture_output=True, text=True)


@pytest.mark.parametrize("name", ["records", "reports", "procedures"])
def test_a_foreign_package_first_on_the_path_is_named(tmp_path, name):
    (tmp_path / name).mkdir()
    (tmp_path / name / "__init__.py").write_text("")
    done = _import_audit(tmp_path)  # the working folder comes first on sys.path
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: rocking-audit: the package ")
    assert f"'{name}' is taken from {(tmp_path / name / '__init__.py').resolve()}" in last
    assert f"not from {REPO / name} beside audit" in last
    assert "rename or move it out of the way" in last


def test_a_foreign_distribution_is_named_with_its_uninstall_command(tmp_path):
    # an installed distribution "records" (as PyPI's): a module and its metadata
    site = tmp_path / "site"
    (site / "records").mkdir(parents=True)
    (site / "records" / "__init__.py").write_text("")
    info = site / "records-0.6.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: records\nVersion: 0.6.0\n")
    (info / "top_level.txt").write_text("records\n")
    done = _import_audit(tmp_path, pythonpath=site)
    last = done.stderr.strip().splitlines()[-1]
    assert done.returncode == 1
    assert "(it belongs to records); uninstall records (python -m pip uninstall records)" in last


def test_a_data_folder_named_records_does_not_shadow(tmp_path):
    # a user's folder of record files, no __init__.py: a namespace portion, which a regular
    # package later on the path wins over
    (tmp_path / "records").mkdir()
    (tmp_path / "records" / "rinaldi.at2").write_text("")
    done = _import_audit(tmp_path)
    assert done.returncode == 0, done.stderr
