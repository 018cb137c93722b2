"""Tests that need the development records skip where they are not (a user's machine, a GitHub
runner, which sets CI=true) and fail only where the project's CI requires them."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import REQUIRE_RECORDS
from records import ENV_VARIABLE

ROOT = Path(__file__).resolve().parents[2]
NEEDS_RECORDS = "tests/records/test_records.py::test_at2_header_layouts_and_counts"


def _pytest(**env):
    environment = {k: v for k, v in os.environ.items()
                   if k not in (ENV_VARIABLE, REQUIRE_RECORDS, "CI")}
    environment.update(env, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           NEEDS_RECORDS], cwd=ROOT, env=environment, capture_output=True,
                          text=True, timeout=300)


@pytest.mark.parametrize("env, passes, word", [
    ({}, True, "1 skipped"),
    ({"CI": "true"}, True, "1 skipped"),  # as on GitHub Actions
    ({REQUIRE_RECORDS: "1"}, False, "1 error"),  # as .ci/run sets it
    ({REQUIRE_RECORDS: "1", "CI": "true"}, False, "1 error"),
])
def test_real_record_tests_skip_unless_the_project_ci_requires_them(env, passes, word):
    done = _pytest(**env)
    assert (done.returncode == 0) == passes and word in done.stdout, done.stdout
    if not passes:
        assert f"{REQUIRE_RECORDS}=1 requires it" in done.stdout


def test_ci_run_requires_the_records():
    assert f"export {REQUIRE_RECORDS}=1" in (ROOT / ".ci" / "run").read_text()
