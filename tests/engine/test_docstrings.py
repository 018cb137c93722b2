"""Every public function and method of the engine names each of its parameters in a numpydoc
``Parameters`` section, and names no parameter it does not take.

Public: no leading underscore, defined in the engine module that holds it (not imported into
it); ``self`` and ``cls`` are not documented. The docstrings are read by numpydoc's own parser
(``numpydoc.docscrape``), the one the documentation site uses.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import audit.engine
from conftest import REQUIRE_DOCS, unavailable


def _engine_modules():
    for info in pkgutil.walk_packages(audit.engine.__path__, "audit.engine."):
        yield importlib.import_module(info.name)


def _public_callables(module):
    """(qualified name, function) of each public function and method defined in ``module``."""
    for name, value in vars(module).items():
        if name.startswith("_"):
            continue
        if inspect.isclass(value) and value.__module__ == module.__name__:
            for member_name, member in vars(value).items():
                if member_name.startswith("_"):
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                if inspect.isfunction(member):
                    yield f"{module.__name__}.{name}.{member_name}", member
        elif callable(value) and not inspect.isclass(value):
            function = inspect.unwrap(value)
            if inspect.isfunction(function) and function.__module__ == module.__name__:
                yield f"{module.__name__}.{name}", function


def _signature(function) -> tuple[set[str], str | None]:
    """The parameters' names but ``self``/``cls``, and the name of the ``**`` one if any."""
    parameters = list(inspect.signature(function).parameters.values())
    if parameters and parameters[0].name in ("self", "cls"):
        parameters = parameters[1:]
    keywords = next((p.name for p in parameters if p.kind is p.VAR_KEYWORD), None)
    return {p.name for p in parameters}, keywords


def _documented_names(function, docscrape) -> set[str]:
    doc = docscrape.NumpyDocString(inspect.getdoc(function) or "")
    names = set()
    for parameter in doc["Parameters"]:  # "a, b : float" documents a and b
        names.update(part.strip().lstrip("*") for part in parameter.name.split(","))
    return names - {""}


def test_every_public_engine_function_documents_its_parameters():
    try:
        from numpydoc import docscrape
    except ImportError:
        unavailable(REQUIRE_DOCS, "numpydoc is not installed (pip install -e '.[test]')")
    checked, wrong = 0, []
    for module in _engine_modules():
        for qualified, function in _public_callables(module):
            expected, keywords = _signature(function)
            if not expected:
                continue
            checked += 1
            documented = _documented_names(function, docscrape)
            if keywords and documented - expected:
                # ``parse(**values)`` may document the fields it takes by their names instead
                documented = (documented & expected) | {keywords}
            if documented != expected:
                missing, extra = sorted(expected - documented), sorted(documented - expected)
                wrong.append(f"{qualified}: missing {missing}" + (f", not taken {extra}"
                                                                  if extra else ""))
    assert checked > 100  # the walk found the engine (about 260 functions take parameters)
    assert not wrong, f"{len(wrong)} of {checked}:\n" + "\n".join(wrong)
