"""Sphinx configuration of the documentation site: ``python -m sphinx -W -b html docs OUT``.

The front page is the repository's README.md; the method notes and guides are the Markdown
pages beside this file (MyST); the quick-start notebook is executed at every build (myst-nb);
the API reference is generated from the docstrings (autosummary + numpydoc, ``api.rst``).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))  # the checkout's packages, installed or not

import audit  # noqa: E402  (after the path)

project = "Rocking Audit"
author = "Rocking Audit contributors"
release = version = audit.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
]
templates_path = ["_templates"]
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}

# API reference: one page per object listed in api.rst, written at build time
autosummary_generate = True
autodoc_typehints = "none"  # numpydoc's Parameters sections say the types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False  # members are documented on the class page by autodoc
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# MyST: the README's links to docs/NAME.md become links to the page NAME (see index.md)
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
nb_execution_mode = "force"  # the notebook runs at every build, so its outputs are current
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True

html_theme = "pydata_sphinx_theme"
html_title = "Rocking Audit"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 5,
}
# the section navigation only where a page has sub-pages (the API reference): none beside the
# guides, the method notes and the notebook
html_sidebars = {page.stem: [] for page in (*HERE.glob("*.md"), *HERE.glob("*.ipynb"))}
smartquotes = False  # "--friction" stays two hyphens, as typed
html_show_sourcelink = False
html_static_path: list[str] = []


#: A magnitude as the docstrings write it, ``|θ|``, ``|F'|``, ``|approx/exact − 1|``: read in
#: the source as in a paper, but reStructuredText takes it for a substitution.
_MAGNITUDE = re.compile(r"(?<![\w|\\`])\|([^|`\s](?:[^|`]*?[^|`\s])?)\|(?![\w|`])")


def _escape_magnitudes(app, what, name, obj, options, lines):
    """Escape the bars of magnitudes in a docstring, outside its ``literals``."""
    for i, line in enumerate(lines):
        parts = line.split("``")
        parts[::2] = [_MAGNITUDE.sub(r"\\|\1\\|", part) for part in parts[::2]]
        lines[i] = "``".join(parts)


def setup(app):
    app.connect("autodoc-process-docstring", _escape_magnitudes)
