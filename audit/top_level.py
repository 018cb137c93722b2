"""The installed top-level names ``records``, ``reports`` and ``procedures`` are this
distribution's, or ``import audit`` says which one is not and what to do.

The layout fixes these names, and they are generic: PyPI has a popular ``records``, and a
user's own ``reports.py`` or ``procedures/`` package in the working folder comes first on
``sys.path``. Python takes the first it finds, so a foreign one would otherwise surface much
later as an ``ImportError`` of some name inside ``audit``, or as wrong behaviour. The four
packages are installed side by side (one folder of site-packages, or the checkout of an
editable install), so each must be found beside ``audit``. Finding the specs imports nothing.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

#: The top-level packages of this distribution besides ``audit``.
SIBLINGS = ("records", "reports", "procedures")
DISTRIBUTION = "rocking-audit"


def _folder(spec) -> Path | None:
    """The folder a top-level package's spec was found in; None for a namespace package (a
    folder without ``__init__.py``, never ours) or a package with no file."""
    if spec is None or spec.origin is None or not spec.has_location:
        return None
    return Path(spec.origin).resolve().parent.parent


def _owners(name: str) -> str:
    """The installed distributions that provide the top-level ``name``, as words."""
    from importlib.metadata import packages_distributions
    others = sorted(set(packages_distributions().get(name, ())) - {DISTRIBUTION})
    return ", ".join(others)


def check_siblings(home: Path | None = None) -> None:
    """ImportError naming the first of :data:`SIBLINGS` that is not found beside ``audit``
    (in ``home``, the folder holding ``audit``), where it was found and what to do."""
    home = (home or Path(__file__).resolve().parent.parent)
    for name in SIBLINGS:
        spec = importlib.util.find_spec(name)
        if _folder(spec) == home:
            continue
        where = (f"is taken from {spec.origin}" if spec is not None and spec.origin
                 else "is not found" if spec is None else "is a folder without __init__.py")
        owners = _owners(name) if spec is not None else ""
        fix = (f"uninstall {owners} (python -m pip uninstall {owners.split(', ')[0]}) or "
               f"install {DISTRIBUTION} in a virtual environment of its own"
               if owners else
               f"rename or move it out of the way (the working folder and PYTHONPATH come "
               f"first on sys.path), or reinstall {DISTRIBUTION}")
        raise ImportError(
            f"{DISTRIBUTION}: the package '{name}' {where}, not from {home / name} beside "
            f"audit" + (f" (it belongs to {owners})" if owners else "") + f"; {fix}",
            name=name)
