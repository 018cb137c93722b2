"""The documentation site builds with warnings as errors, its API reference lists the entry
points, and its front page (the README) opens in headless Chromium with every link resolved.

The notebook is rendered here from its saved outputs (``nb_execution_mode=off``):
``tests/test_notebook.py`` executes it, and CI (``.ci/run``) builds the site executing it.
Skips when the docs extra is not installed, except under CI.
"""

from __future__ import annotations

import importlib
import os
import re
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

from conftest import REQUIRE_DOCS, unavailable

#: End to end: the site built by sphinx, the front page opened in headless Chromium.
pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parents[1]
#: The entry points the API reference must list (``docs/api.rst``).
ENTRY_POINTS = ("audit.rock", "audit.run", "audit.margins", "records.load")


def _require_docs_extra():
    for module in ("sphinx", "pydata_sphinx_theme", "numpydoc", "myst_nb"):
        try:
            importlib.import_module(module)
        except ImportError:
            unavailable(REQUIRE_DOCS, f"{module} is not installed (pip install -e '.[docs]')")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    _require_docs_extra()
    out = tmp_path_factory.mktemp("docs")
    done = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "-q", "-b", "html", "-D", "nb_execution_mode=off",
         "-d", str(out / "doctrees"), str(REPO / "docs"), str(out / "html")],
        capture_output=True, text=True, timeout=900, env={**os.environ, "PYTHONPATH": str(REPO)})
    assert done.returncode == 0, (done.stdout + done.stderr)[-3000:]
    return out / "html"


def test_api_reference_lists_the_entry_points_each_with_its_page(site):
    api = (site / "api.html").read_text(encoding="utf-8")
    for name in ENTRY_POINTS:
        assert f'href="generated/{name}.html' in api, name
        page = (site / "generated" / f"{name}.html").read_text(encoding="utf-8")
        assert f'id="{name}"' in page  # the object's own description, with its signature
    run = (site / "generated" / "audit.run.html").read_text(encoding="utf-8")
    assert "Parameters" in run and "alpha_deg" in run  # numpydoc's sections, from the docstring


def test_front_page_is_the_readme_and_opens_in_chromium(site, browse):
    done = browse(site / "index.html", "--dump-dom")
    page = done.stdout
    # the theme's script ran (it sets the colour scheme on the document)
    assert re.search(r'<html[^>]*data-theme="(light|dark)"', page), done.stderr[-2000:]
    errors = [line for line in done.stderr.splitlines()
              if "CONSOLE" in line and (":ERROR:" in line or "Uncaught" in line)]
    assert not errors, errors[:5]
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    for heading in re.findall(r"^## (.+)$", readme, flags=re.M):
        assert re.sub(r"`", "", heading) in re.sub(r"<[^>]+>", "", page), heading
    # the README's links to docs/NAME become links to the site's pages, and every one resolves
    linked = set(re.findall(r"\]\(docs/([\w.-]+)\.(?:md|rst|ipynb)\)", readme))
    assert {"records", "columns", "margins", "api", "quickstart"} <= linked
    hrefs = set(re.findall(r'href="([^"]+)"', page))
    assert {f"{name}.html" for name in linked} <= hrefs
    for href in hrefs:
        parts = urlsplit(href)
        if not parts.scheme and parts.path:
            assert (site / unquote(parts.path)).is_file(), href
    images = re.findall(r'<img[^>]+src="([^"]+)"', page)
    assert images and all((site / unquote(src)).is_file() for src in images)
