"""Shared fixtures: the real records of ``../shared/records`` via ``ROCKING_AUDIT_RECORDS``.

Tests that need the real records (or a browser) skip with a reason where they are not there,
as on a user's machine or a GitHub runner (which sets ``CI=true``). The project's own CI,
``.ci/run``, provides them and says so with the variables below: there such a test fails
instead, so a missing record directory cannot pass silently.
"""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from records import ENV_VARIABLE, load_records

#: Set to 1 by ``.ci/run``: the real-record tests must run.
REQUIRE_RECORDS = "ROCKING_AUDIT_REQUIRE_RECORDS"
#: Set to 1 by ``.ci/run``, which installs chromium: the browser tests must run.
REQUIRE_CHROMIUM = "ROCKING_AUDIT_REQUIRE_CHROMIUM"
#: Set to 1 by .ci/run, which installs the docs extra: the documentation test must run.
REQUIRE_DOCS = "ROCKING_AUDIT_REQUIRE_DOCS"
#: Set to 1 by .ci/run in its environment with the pelicun extra: the pelicun tests must run.
REQUIRE_PELICUN = "ROCKING_AUDIT_REQUIRE_PELICUN"


def unavailable(required_by: str, reason: str):
    """Skip the test for ``reason``, or fail it where the variable ``required_by`` is 1."""
    if os.environ.get(required_by) == "1":
        pytest.fail(f"{reason}, and {required_by}=1 requires it")
    pytest.skip(reason)


def _seed_manifest() -> Path:
    value = os.environ.get(ENV_VARIABLE)
    if not value:
        unavailable(REQUIRE_RECORDS, f"{ENV_VARIABLE} is not set: real-record tests need "
                                     "../shared/records")
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
    unavailable(REQUIRE_CHROMIUM, "chromium is not installed (apt-get install chromium)")


@pytest.fixture
def browse(tmp_path):
    """``browse(page, *flags)``: open the file ``page`` in headless Chromium with a fresh
    profile, no network services, console messages on stderr (CompletedProcess). Skips when
    Chromium is missing, except where ``.ci/run`` requires it."""
    executable = _chromium()

    def run(page: Path, *action):
        flags = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--disable-quic", f"--user-data-dir={tmp_path / 'profile'}",
                 "--enable-logging=stderr", "--v=0", "--virtual-time-budget=60000"]
        return subprocess.run([executable, *flags, *action, Path(page).as_uri()],
                              capture_output=True, text=True, timeout=300)
    return run


#: The folder of real hazard-curve files (OpenQuake's demo run and a USGS response).
HAZARD_VARIABLE = "ROCKING_AUDIT_HAZARD"


@pytest.fixture(scope="session")
def hazard_dir() -> Path:
    """The real hazard files' folder (``openquake-demo/``, ``usgs-example.json``), from
    ``ROCKING_AUDIT_HAZARD``: skipped when unset, failed where the project's CI requires the
    development data (``ROCKING_AUDIT_REQUIRE_RECORDS=1``)."""
    value = os.environ.get(HAZARD_VARIABLE)
    if not value:
        unavailable(REQUIRE_RECORDS, f"{HAZARD_VARIABLE} is not set: hazard-file tests need "
                                     "the shared hazard files")
    path = Path(value)
    if not (path / "usgs-example.json").is_file():
        pytest.fail(f"{HAZARD_VARIABLE}={value}: no usgs-example.json there")
    return path


@pytest.fixture(scope="session", autouse=True)
def no_user_atlas(tmp_path_factory):
    """Atlases in an empty folder of the test run's own: ``check`` reads an atlas where one is
    built (docs/atlas.md), and one in the user's cache would silently change what the tests of
    the direct check measure. A test that builds an atlas points the variable at its own."""
    before = os.environ.get("ROCKING_AUDIT_ATLAS_DIR")
    os.environ["ROCKING_AUDIT_ATLAS_DIR"] = str(tmp_path_factory.mktemp("no-atlas"))
    yield
    if before is None:
        del os.environ["ROCKING_AUDIT_ATLAS_DIR"]
    else:
        os.environ["ROCKING_AUDIT_ATLAS_DIR"] = before
