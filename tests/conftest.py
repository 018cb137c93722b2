"""Shared fixtures: the real records of ``../shared/records`` via ``ROCKING_AUDIT_RECORDS``.

Tests that need real records skip with a reason when the variable is unset outside CI; under
CI (``CI=true``) they fail instead, so a missing record directory cannot pass silently.
"""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from records import ENV_VARIABLE, load_records


def _seed_manifest() -> Path:
    value = os.environ.get(ENV_VARIABLE)
    if not value:
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(f"{ENV_VARIABLE} is not set under CI: the real-record tests cannot run")
        pytest.skip(f"{ENV_VARIABLE} is not set: real-record tests need ../shared/records")
    path = Path(value)
    if not path.is_file():
        pytest.fail(f"{ENV_VARIABLE}={value}: no such manifest")
    return path


@pytest.fixture(scope="session")
def seed_manifest() -> Path:
    """Path of ``seed-suite.toml``."""
    return _seed_manifest()


@pytest.fixture(scope="session")
def records_dir(seed_manifest) -> Path:
    """The shared records directory (``raw/``, ``derived/``, manifests)."""
    return seed_manifest.parent


@pytest.fixture(scope="session")
def seed_suite(seed_manifest):
    """The seed suite loaded from the real files."""
    return load_records(seed_manifest)


def _chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail("chromium is not installed: .ci/run installs it with apt-get")
    pytest.skip("chromium is not installed (apt-get install chromium)")


@pytest.fixture
def browse(tmp_path):
    """``browse(page, *flags)``: open the file ``page`` in headless Chromium with a fresh
    profile, no network services, console messages on stderr (CompletedProcess). Skips when
    Chromium is missing, except under CI."""
    executable = _chromium()

    def run(page: Path, *action):
        flags = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--disable-quic", f"--user-data-dir={tmp_path / 'profile'}",
                 "--enable-logging=stderr", "--v=0", "--virtual-time-budget=60000"]
        return subprocess.run([executable, *flags, *action, Path(page).as_uri()],
                              capture_output=True, text=True, timeout=300)
    return run
