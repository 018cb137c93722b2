"""The import structure: no cycles, one-way layers, every module importable alone.

Layers, lowest first: records → physics → procedures → engine → reports → API → command line;
a module imports only from its own layer or lower ones. ``audit`` (G, the version),
``audit.errors``, ``audit.files`` and ``audit.top_level`` are below every layer. Every import
counts, including the ones inside functions that keep start-up light: an import deferred into
a function still ties the two modules together.
"""

from __future__ import annotations

import ast
import importlib
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
PACKAGES = ("audit", "procedures", "reports", "records")
BASE = {"audit", "audit.errors", "audit.files", "audit.top_level"}
LAYERS = (("records",), ("audit.physics",), ("procedures",), ("audit.engine",), ("reports",),
          ("audit.api",), ("audit.cli", "audit.__main__"))


def _modules() -> dict[str, Path]:
    found = {}
    for package in PACKAGES:
        for path in sorted((REPO / package).rglob("*.py")):
            parts = path.relative_to(REPO).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            found[name] = path
    return found


MODULES = _modules()


def _imports(name: str, path: Path) -> set[str]:
    """Project modules ``name`` imports anywhere in its body (function-level included), except
    the re-export of the API by ``audit/__init__.py`` (its last import, after G and the
    version every module reads from it)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            # ``from package import module`` imports the module; ``from module import name``
            # the module
            modules = [f"{node.module}.{alias.name}" for alias in node.names
                       if f"{node.module}.{alias.name}" in MODULES]
            targets = modules if len(modules) == len(node.names) else [node.module, *modules]
        else:
            continue
        out |= {target for target in targets if target in MODULES}
    if name == "audit":
        out -= {"audit.api"}
    out.discard(name)
    return out


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


def _layer(name: str) -> int:
    if name in BASE:
        return -1
    for level, prefixes in enumerate(LAYERS):
        if any(name == prefix or name.startswith(prefix + ".") for prefix in prefixes):
            return level
    raise AssertionError(f"{name}: in no layer")


def test_no_import_cycles():
    state, stack, cycles = {}, [], []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for target in sorted(GRAPH[node]):
            if state.get(target) == "open":
                cycles.append(stack[stack.index(target):] + [target])
            elif target not in state:
                visit(target)
        stack.pop()
        state[node] = "done"

    for name in sorted(GRAPH):
        if name not in state:
            visit(name)
    assert not cycles, "import cycles: " + "; ".join(" → ".join(c) for c in cycles)


def test_imports_go_one_way_down_the_layers():
    upward = [f"{name} → {target}" for name, targets in GRAPH.items() for target in targets
              if _layer(target) > _layer(name)]
    assert not upward, "imports against the layers: " + "; ".join(sorted(upward))


def test_the_graph_sees_imports():
    # the checks above would pass on an empty graph: these edges are known to exist
    assert "procedures.base" in GRAPH["audit.engine.shared.verdicts"]
    assert "audit.engine.shared.runtime" in GRAPH["audit.engine.shared.scheduler"]
    assert _layer("audit.cli.run") > _layer("audit.api") > _layer("reports.render")


#: The engine's workflows: each a room of its own, with its settings and its pipeline (``design``
#: is ``audit margins``'), and the claims the run checks.
WORKFLOWS = ("check", "design", "run", "validation", "fragility")
#: Each workflow's pipeline entry: ``run_<name>`` in its ``pipeline.py``.
PIPELINES = {"check": "run_check", "design": "run_margins", "run": "run_audit",
             "validation": "run_validation", "fragility": "run_fragility"}


def test_the_engine_shared_room_imports_no_workflow():
    """``audit.engine.shared`` holds what every workflow uses; a workflow's own things (its
    costs, its unit of work, its result files) live in its room."""
    into = [f"{name} → {target}" for name, targets in GRAPH.items()
            if name.startswith("audit.engine.shared") for target in targets
            if any(target.startswith(f"audit.engine.{room}") for room in (*WORKFLOWS, "claims"))]
    assert not into, "engine/shared into a workflow: " + "; ".join(sorted(into))
    # the check sees shared's imports
    assert "audit.engine.shared.runtime" in GRAPH["audit.engine.shared.scheduler"]


@pytest.mark.parametrize("room", WORKFLOWS)
def test_every_workflow_has_its_settings_and_one_pipeline_entry_named_alike(room):
    """``settings.py`` holds its Settings (a class whose name ends so), ``pipeline.py`` its one
    entry, named ``run_<workflow>`` in every room."""
    folder = REPO / "audit" / "engine" / room
    settings = ast.parse((folder / "settings.py").read_text(encoding="utf-8"))
    assert any(isinstance(node, ast.ClassDef) and node.name.endswith("Settings")
               for node in settings.body)
    pipeline = ast.parse((folder / "pipeline.py").read_text(encoding="utf-8"))
    entries = [node.name for node in pipeline.body if isinstance(node, ast.FunctionDef)
               and node.name.startswith("run_")]
    assert entries == [PIPELINES[room]]


def test_one_road_for_a_floor():
    """Every command's floor goes through :meth:`DesignSite.parse` (the one call of
    ``Floor.parse``; a floor given one value at a time too, :func:`audit.api.inputs.floor_of`)
    and :meth:`DesignSite.apply` (the one call of ``on_floor``, the filter): no command parses a
    floor or filters records on its own."""
    calls = {"Floor.parse": [], "on_floor": []}
    for name, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call):
                called = ast.unparse(node.func)
                if called in calls:
                    calls[called].append(name)
    assert calls == {"Floor.parse": ["audit.engine.shared.design_site"],
                     "on_floor": ["audit.engine.shared.design_site"]}


#: What the command line may import besides the base modules: the API (the defaults its
#: ``--help`` shows too) and itself; never the engine, the records, the
#: reports, the physics or the procedures (a command is argparse → one API call → print).
CLI_MAY_IMPORT = ("audit.api", "audit.cli")
#: The packages below the API the command line must not reach into.
BELOW_THE_API = ("audit.engine", "records", "reports", "procedures")


def test_the_command_line_goes_through_the_api():
    around = [f"{name} → {target}" for name, targets in GRAPH.items()
              if _layer(name) == _layer("audit.cli") for target in targets
              if target not in BASE and not any(target == prefix or target.startswith(prefix + ".")
                                                for prefix in CLI_MAY_IMPORT)]
    assert not around, "the command line around the API: " + "; ".join(sorted(around))
    # the check sees the command line's imports
    assert "audit.api" in GRAPH["audit.cli.run"] and "audit.cli.options" in GRAPH["audit.cli.run"]
    # through its front door: ``from audit.api import check``, never a module behind it
    behind = [f"{name} → {target}" for name, targets in GRAPH.items()
              if _layer(name) == _layer("audit.cli") for target in targets
              if target.startswith("audit.api.")]
    assert not behind, "the command line behind the API's front: " + "; ".join(sorted(behind))


def _imported_names(path: Path) -> set[str]:
    """Every module name an ``import`` or ``from … import`` of ``path`` names, function-level
    included, whether or not it is a module of the project."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names |= {node.module, *(f"{node.module}.{alias.name}" for alias in node.names)}
    return names


def test_the_command_line_imports_nothing_below_the_api():
    """No module of ``audit/cli`` imports from the engine, the records, the reports or the
    procedures: records are read, sites parsed and summaries written below the API."""
    cli = sorted((REPO / "audit" / "cli").glob("*.py"))
    below = [f"{path.name} → {name}" for path in cli for name in sorted(_imported_names(path))
             if any(name == top or name.startswith(top + ".") for top in BELOW_THE_API)]
    assert not below, "the command line below the API: " + "; ".join(below)
    # the parse sees imports inside functions and from-imports of names
    assert "audit.api.run" in _imported_names(REPO / "audit" / "cli" / "run.py")


def _import_alone(name: str) -> tuple[str, str]:
    done = subprocess.run([sys.executable, "-c", f"import {name}"], cwd=REPO,
                          capture_output=True, text=True)
    return name, done.stderr.strip().splitlines()[-1] if done.returncode else ""


@pytest.mark.slow  # ~200 s: an interpreter started for each module
def test_every_module_imports_alone_in_a_fresh_interpreter():
    with ThreadPoolExecutor(2) as pool:
        failed = [f"{name}: {error}" for name, error in pool.map(
            _import_alone, sorted(set(MODULES) - {"audit.__main__"})) if error]
    assert not failed, "\n".join(failed)


def test_audit_report_imports_no_solver(tmp_path):
    # `audit report DIR` reads a run back and renders it: no numba, no rocking solver, no
    # oscillator kernels
    import audit.api
    from records import pulse_suite
    audit.api.run("priestley1978", pulse_suite(), alpha_deg=(15.0,), size_s=[2.0],
                  robustness=0.0, out_dir=tmp_path / "run")
    probe = ("import sys; from audit.cli import main; "
             f"status = main(['report', {str(tmp_path / 'run')!r}]); "
             "print(status, sorted(m for m in sys.modules if m.startswith(('numba', "
             "'audit.physics.rocking', 'audit.physics.oscillator', "
             "'audit.physics.response_spectra', 'audit.physics.peaks_between_samples', "
             "'audit.physics.spectrum_kernel'))))")
    done = subprocess.run([sys.executable, "-c", probe], cwd=REPO, capture_output=True,
                          text=True, check=True)
    assert done.stdout.strip().splitlines()[-1] == "0 []"


def test_no_api_name_is_shadowed_by_a_module_of_the_api_package():
    """``audit.api``'s names are loaded lazily from its modules; a module named like one of
    them (``audit/api/risk.py`` for ``audit.risk``) would replace the name by the module once
    imported."""
    import importlib
    import inspect

    import audit
    import audit.api
    for module in (REPO / "audit" / "api").glob("*.py"):
        importlib.import_module(f"audit.api.{module.stem}")
    shadowed = [name for name in audit.api.__all__ if inspect.ismodule(getattr(audit, name, None))
                or inspect.ismodule(getattr(audit.api, name))]
    assert not shadowed


def test_no_engine_folder_holds_three_modules_of_one_name_prefix():
    """Modules that share a name prefix (``check_*``) are a room of their own: a sub-package.
    Counted on the first word of each module's name in every folder of the engine."""
    from collections import Counter
    crowded = {}
    for folder in [REPO / "audit" / "engine", *(REPO / "audit" / "engine").glob("*/")]:
        words = Counter(path.stem.split("_")[0] for path in folder.glob("*.py")
                        if path.stem != "__init__")
        crowded.update({f"{folder.name}/{word}_*": n for word, n in words.items() if n >= 3})
    assert not crowded


#: What the front door must not load: the scientific stack and the layers that import it.
HEAVY_AT_THE_DOOR = ("numpy", "pandas", "scipy", "numba", "matplotlib", "plotly", "records",
                     "procedures", "reports")


@pytest.mark.parametrize("package", ["audit", "audit.api"])
def test_the_front_door_imports_its_names_plainly(package):
    """Every public name of ``audit`` and ``audit.api`` is bound by a plain ``from … import``
    at module level (no ``__getattr__`` table), so an IDE or a static tool follows
    ``from audit.api import check`` to its module."""
    path = MODULES[package]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    assert not [node.name for node in tree.body if isinstance(node, ast.FunctionDef)]
    bound = {alias.asname or alias.name for node in tree.body
             if isinstance(node, ast.ImportFrom) for alias in node.names}
    bound |= {target.id for node in tree.body if isinstance(node, ast.Assign)
              for target in node.targets if isinstance(target, ast.Name)}
    public = importlib.import_module(package).__all__
    assert set(public) <= bound, set(public) - bound
    assert "check" in public and "Block" in public


def test_the_front_door_is_light():
    """``import audit`` (and with it ``audit.api``) loads neither the scientific stack nor the
    records, procedures or reports: each API module imports them inside its functions."""
    probe = ("import sys, audit, audit.api; print(sorted({m.split('.')[0] for m in sys.modules} "
             f"& set({HEAVY_AT_THE_DOOR!r})))")
    done = subprocess.run([sys.executable, "-c", probe], cwd=REPO, capture_output=True,
                          text=True, check=True)
    assert done.stdout.strip() == "[]"


def test_the_solver_block_is_made_only_through_block():
    """One class per concept: above the physics, a rocking block is a
    :class:`~audit.engine.shared.blocks.Block` and the solver's ``RigidBlock`` comes from its
    one conversion (``Block.rigid``); only the physics (below Block's layer) and Block itself
    build one."""
    builders = ("RigidBlock", "RigidBlock.from_size", "RigidBlock.from_dimensions")
    built = sorted(name for name, path in MODULES.items()
                   if not name.startswith("audit.physics") and name != "audit.engine.shared.blocks"
                   for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
                   if isinstance(node, ast.Call) and ast.unparse(node.func) in builders)
    assert built == []
    # the walk sees the calls: Block's own conversion is one
    assert any(isinstance(node, ast.Call) and ast.unparse(node.func) == "RigidBlock.from_size"
               for node in ast.walk(ast.parse(MODULES["audit.engine.shared.blocks"].read_text(
                   encoding="utf-8"))))


#: A command-line flag in a text: ``--friction``, ``--records FOLDER`` (pip's own aside).
FLAG = re.compile(r"(?<![\w-])(?<!pip install )--[a-z][\w-]*")


def _texts(path: Path):
    """``(line, text)`` of the string literals of a module, docstrings aside (they document
    the code for its developers, and name the flag a parameter comes from), or of the lines of
    a template."""
    if path.suffix != ".py":
        yield from enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        return
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docs = {id(node.body[0].value) for node in ast.walk(tree)
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
            and node.body and isinstance(node.body[0], ast.Expr)
            and isinstance(node.body[0].value, ast.Constant)}
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            yield node.lineno, node.value


def test_no_text_below_the_command_line_names_a_flag():
    """Messages, column descriptions, hints and pages written below the command line name the
    argument (``friction``, ``scale_to_site``), never a flag (``--friction``): the API's user
    has no flags, and the command line maps arguments to its flags in one table
    (:data:`audit.cli.flags.FLAGS`)."""
    below = [path for name, path in MODULES.items() if _layer(name) < _layer("audit.cli")]
    below += sorted((REPO / "reports" / "templates").glob("*"))
    found = [f"{path.relative_to(REPO)}:{line}: {FLAG.findall(text)}" for path in below
             for line, text in _texts(path) if FLAG.search(text)]
    assert not found, "\n".join(found)
    # the scan sees flags: the command line's own texts name them
    assert any(FLAG.search(text) for _, text in _texts(MODULES["audit.cli.rock"]))
    assert not FLAG.search("pip install --force-reinstall")
