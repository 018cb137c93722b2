"""The API as a new user meets it: every bad argument of the held-out corpus raises InputError
naming the argument, before any work; no message below the command line names a flag; the
command line reaches the engine through the API only."""

from __future__ import annotations

import ast
import math
import re
from pathlib import Path

import numpy as np
import pytest

import audit
import records
from audit.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
BLOCK = dict(alpha_deg=15.0, size_s=2.0)


def _raises(field, call, *args, **kwargs):
    with pytest.raises(InputError, match=rf"^{field}\b") as caught:
        call(*args, **kwargs)
    assert field in caught.value.fields
    return str(caught.value)


def test_rock_with_a_bare_array_asks_for_its_dt():
    assert "dt" in _raises("motion", audit.rock, audit.Block(**BLOCK), np.ones(100))


def test_rock_with_a_name_for_a_block():
    _raises("block", audit.rock, "cabinet", records.one_pulse("cosine", 0.3, 1.0))


def test_margins_block_not_a_block():
    _raises("blocks", audit.margins, "fema356", "pulses", blocks=[123])


def test_margins_no_stripes():
    _raises("stripes", audit.margins, "fema356", "pulses", stripes=[])


def test_margins_negative_stripe():
    _raises("stripes", audit.margins, "fema356", "pulses", stripes=[-1, 1])


def test_margins_repeated_stripes():
    assert "increasing" in _raises("stripes", audit.margins, "fema356", "pulses",
                                   stripes=[0.5, 0.5, 0.5])


def test_from_dimensions_text():
    _raises("width_m", audit.Block.from_dimensions, "0.8", 2)


def test_from_dimensions_none():
    _raises("width_m", audit.Block.from_dimensions, None, 2)


def test_from_dimensions_millimetres_refused_above_100_m():
    assert "100 m" in _raises("width_m", audit.Block.from_dimensions, 600, 1800)


def test_from_dimensions_tall_block_warned_above_10_m():
    with pytest.warns(audit.errors.InputWarning, match="height_m"):
        block = audit.Block.from_dimensions(2.0, 12.0)
    assert block.height_m == pytest.approx(12.0)


def test_run_a_number_for_procedures():
    _raises("procedures", audit.run, 42)


def test_run_no_procedures():
    _raises("procedures", audit.run, [])


def test_run_friction_text():
    _raises("friction", audit.run, "fema356", "pulses", friction="abc")


def test_run_friction_negative():
    _raises("friction", audit.run, "fema356", "pulses", friction=-1)


def test_run_friction_nan():
    _raises("friction", audit.run, "fema356", "pulses", friction=math.nan)


def test_run_site_one_value():
    _raises("site", audit.run, "fema356", "pulses", site=(1.5,))


def test_run_no_jobs():
    _raises("jobs", audit.run, "fema356", "pulses", jobs=0)


def test_run_negative_agree_band():
    _raises("agree_band", audit.run, "fema356", "pulses", agree_band=-1)


def test_run_empty_suite():
    _raises("records", audit.run, "fema356", records.RecordSuite((), "nothing"))


def test_run_unknown_argument():
    _raises("sizes", audit.run, "fema356", "pulses", sizes=[1.0])


def _plug_in(**attributes):
    from procedures.priestley_1978 import PriestleyEvisonCarr1978
    return type("PlugIn", (PriestleyEvisonCarr1978,), {"name": "plug", **attributes})


def test_plug_in_damping_returns_text():
    message = _raises("procedures", audit.run, _plug_in(damping=lambda self, r: "0.05"),
                      "pulses")
    assert "'plug'" in message and "damping" in message


def test_plug_in_damping_returns_two_values():
    _raises("procedures", audit.run, _plug_in(damping=lambda self, r: np.array([0.05, 0.1])),
            "pulses")


def test_plug_in_without_a_name():
    assert "PlugIn" in _raises("procedures", audit.run, _plug_in(name=""), "pulses")


def test_plug_in_named_like_a_registered_procedure():
    assert "fema356" in _raises("procedures", audit.run, _plug_in(name="fema356"), "pulses")


def test_the_new_user_surface():
    assert {"Block", "rock", "run", "margins", "fragility"} <= set(dir(audit))
    with pytest.raises(TypeError):
        audit.Block(0.6, 1.8)  # keyword-only: α and 2π/p are not told apart by position
    suite = records.load("pulses")
    first = suite.ids[0]
    assert suite[first].id == first and suite[0].id == first
    motion = suite[first].motion
    # a motion as an id, a GroundMotion and an (array, dt) pair: the same response
    by_id = audit.rock(audit.Block(**BLOCK), first, records=suite)
    by_pair = audit.rock(audit.Block(**BLOCK), (motion.acceleration, motion.dt))
    assert by_id.peak == pytest.approx(audit.rock(audit.Block(**BLOCK), motion).peak, rel=0)
    assert motion.pulse is not None or by_pair.peak == pytest.approx(by_id.peak, rel=1e-12)


def _message_strings(path: Path):
    """The string parts of InputError(...) and warnings.warn(...) calls of a module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "id", getattr(node.func, "attr", "")) \
                in ("InputError", "warn", "ArgumentTypeError"):
            for part in ast.walk(node):
                if isinstance(part, ast.Constant) and isinstance(part.value, str):
                    yield node.lineno, part.value


def test_no_message_below_the_command_line_names_a_flag():
    lower = [*sorted((ROOT / "audit" / "engine").rglob("*.py")),
             *sorted((ROOT / "audit" / "physics").rglob("*.py")),
             *sorted((ROOT / "procedures").rglob("*.py")), *sorted((ROOT / "records").rglob("*.py")),
             *sorted((ROOT / "reports").rglob("*.py")), *sorted((ROOT / "audit" / "api").rglob("*.py"))]
    assert len(lower) > 40
    found = [f"{path.relative_to(ROOT)}:{line}: {text!r}" for path in lower
             for line, text in _message_strings(path)
             if re.search(r"(?<!pip install )--\w", text)]  # pip's own flags aside
    assert not found, "\n".join(found)


def test_the_message_grep_sees_flags():
    # the check above would pass on a grep that finds nothing: the CLI's own messages name flags
    assert any(re.search(r"(?<!pip install )--\w", text)
               for _, text in _message_strings(ROOT / "audit" / "cli" / "rock.py"))
