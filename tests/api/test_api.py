"""The Python API is the engine the command line runs: same results, same claims."""

from __future__ import annotations

import math
import re

import numpy as np
import pandas as pd
import pytest

import audit
import records
from audit import G
from audit.cli import main
from audit.errors import InputError
from records import ENV_VARIABLE

GRID = ["--alpha", "15,20", "--size", "1:3:0.5"]


@pytest.mark.slow  # end to end: a run by the API and by the command line
def test_run_from_python_gives_the_command_line_results_and_claims(tmp_path, monkeypatch):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    assert main(["run", "fema356", *GRID, "--out", str(tmp_path / "cli")]) == 0
    result = audit.run("fema356", alpha_deg=[15, 20], size_s=np.arange(1.0, 3.01, 0.5),
                       runtime=audit.Runtime(jobs=1))
    result.write(tmp_path / "api")
    for name in ("results.csv", "checks.csv", "suite.csv", "claims.csv", "rocking.csv"):
        assert (tmp_path / "api" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    cli = pd.read_csv(tmp_path / "cli" / "claims.csv")
    assert len(result.claims) == len(cli) > 50  # the engine, not the CLI, evaluates the claims
    line = result.bottom_line.set_index("procedure").loc["fema356"]
    counts = result.results["verdict"].value_counts()
    assert line["blocks"] == len(result.results) == 2 * 5 * result.results["record"].nunique()
    assert line["unsafe_pct"] == pytest.approx(
        100 * (counts.get("missed-overturn", 0) + counts.get("unconservative", 0))
        / len(result.results))
    html = result._repr_html_()
    assert "FEMA 356 (2000)" in html and "<table" in html


def test_block_from_dimensions_is_the_half_diagonal_block():
    block = audit.Block.from_dimensions(width_m=0.4, height_m=2.0)
    radius = math.hypot(0.2, 1.0)
    assert block.alpha_deg == pytest.approx(math.degrees(math.atan(0.2)), rel=1e-12)
    assert block.p_rad_s == pytest.approx(math.sqrt(3 * G / (4 * radius)), rel=1e-12)
    assert (block.width_m, block.height_m) == (pytest.approx(0.4), pytest.approx(2.0))
    # Eq. 4.8, r = (1 − 1.5 sin²α)²
    assert block.restitution == pytest.approx((1 - 1.5 * math.sin(math.atan(0.2)) ** 2) ** 2)
    with pytest.raises(InputError, match="alpha"):
        audit.Block(alpha_deg=50.0, size_s=2.0)


def test_rock_reproduces_figure_4_1():
    # the block p = 2 rad/s, α = 15° of Figure 4.1 survives a one-cosine pulse of 0.3148 g and
    # T_p = 2 s and overturns at 0.3152 g
    block = audit.Block(alpha_deg=15.0, size_s=math.pi)
    survives = audit.rock(block, records.one_pulse("cosine", 0.3148, 2.0),
                          solver=audit.Solver(free_motion_s=8.0))
    overturns = audit.rock(block, records.one_pulse("cosine", 0.3152, 2.0),
                           solver=audit.Solver(free_motion_s=8.0))
    assert not survives.overturned and overturns.overturned
    history = survives.history
    assert list(history.columns) == ["time_s", "theta_rad", "theta_dot_rad_s", "ground_acc_g"]
    assert history["theta_rad"].abs().max() == pytest.approx(survives.peak, rel=1e-12)
    assert survives.peak_ratio == pytest.approx(survives.peak / math.radians(15.0))
    assert history["ground_acc_g"].abs().max() == pytest.approx(0.3148, rel=1e-9)


def test_a_plug_in_written_in_python_is_audited():
    from procedures.priestley_1978 import PriestleyEvisonCarr1978

    class HalfDamped(PriestleyEvisonCarr1978):
        name, title = "half", "Half-damped Priestley"

        def damping(self, r):
            return 0.5 * super().damping(r)

    suite = records.load("pulses")
    result = audit.run([HalfDamped, "priestley1978"], suite, alpha_deg=[15], size_s=[1.0, 2.0],
                       robustness=0.0, runtime=audit.Runtime(jobs=1))
    beta = result.results.groupby("procedure")["beta_pct"].first()
    assert beta["half"] == pytest.approx(0.5 * beta["priestley1978"])



def test_command_line_defaults_are_the_engines():
    from audit.cli import build_parser
    from audit.engine.shared import defaults
    from audit.engine.shared.grid import size_grid
    from audit.cli import options
    args = build_parser().parse_args(["run", "all"])
    assert list(options.alphas_deg(args.alpha)) == list(defaults.DEFAULT_ALPHA_DEG)
    np.testing.assert_array_equal(options.sizes(args.size), size_grid(*defaults.DEFAULT_SIZES))
    assert (args.jobs, args.free_motion, args.agree_band, args.robustness, args.scheduler) == (
        defaults.DEFAULT_JOBS, defaults.DEFAULT_FREE_MOTION_S, defaults.DEFAULT_AGREE_BAND,
        defaults.DEFAULT_ROBUSTNESS, defaults.DEFAULT_SCHEDULER)
    spectrum = build_parser().parse_args(["spectrum", "--pulse", "cosine", "--amplitude", "0.3",
                                          "--pulse-period", "1"])
    assert (spectrum.alpha, spectrum.size) == (defaults.alpha_text(), defaults.sizes_text())
    rock = build_parser().parse_args(["rock", "--p", "2", "--alpha", "15", "--pulse", "cosine",
                                      "--amplitude", "0.3", "--pulse-period", "2"])
    assert rock.free_motion == defaults.DEFAULT_FREE_MOTION_S


def _keywords(function) -> dict:
    import inspect
    return {name: parameter.default
            for name, parameter in inspect.signature(function).parameters.items()}


@pytest.mark.parametrize("name", ["check", "run", "margins", "rock", "fragility", "validate",
                                  "rocking_spectrum", "response_spectra", "design_spectrum",
                                  "design_suite", "risk", "read_hazard", "load_result"])
def test_every_entry_point_shows_its_keywords_each_documented(name):
    import inspect
    function = getattr(audit, name)
    parameters = inspect.signature(function).parameters.values()
    assert not [p for p in parameters if p.kind in (p.VAR_KEYWORD, p.VAR_POSITIONAL)]
    documented = function.__doc__.split("Parameters\n    ----------\n")[1].split("\n\n")[0]
    for parameter in parameters:  # numpydoc: a line "name :" or "a, name, b :"
        assert re.search(rf"^    (\w+, )*{parameter.name}(, \w+)* :", documented, re.M), \
            (name, parameter.name)


@pytest.mark.parametrize(("function", "parse", "from_site"), [
    ("check", "audit.engine.check.settings:CheckSettings", {"limit_state"}),
    ("run", "audit.engine.run.settings:AuditSettings", set()),
    ("margins", "audit.engine.design.settings:MarginsSettings", {"site_level"})])
def test_the_keywords_are_the_settings_fields_with_their_defaults(function, parse, from_site):
    """Adding a setting is one field, one keyword of its parse, one keyword here (or a field of
    a group), one flag: the function's keyword is the parse's, named and defaulted alike (the
    function hands it on by name); what the site says (its limit state, its hazard level) is
    read from the function's ``site``."""
    import importlib
    module, _, name = parse.partition(":")
    fields = _keywords(getattr(importlib.import_module(module), name).parse)
    keywords = _keywords(getattr(audit, function))
    assert set(fields) & set(keywords) == set(fields) - from_site and from_site <= set(fields)
    assert {name: keywords[name] for name in set(fields) - from_site} == \
        {name: fields[name] for name in set(fields) - from_site}


@pytest.mark.parametrize("name", ["CheckResult", "AuditResult", "MarginsResult",
                                  "FragilityResult", "ValidationResult", "RockingResponse"])
def test_every_result_has_one_shape(name):
    kind = getattr(audit, name)
    for member in ("table", "summary", "summary_text", "write", "report", "_repr_html_"):
        assert hasattr(kind, member) or member in ("table", "summary"), (name, member)
    assert callable(kind.summary_text) and callable(kind.write) and callable(kind.report)


def test_a_rocking_response_has_the_shape_of_every_result(tmp_path):
    pulse = records.one_pulse("cosine", 0.5, 1.0)  # a_p = 0.5 g > g tan 15°: it rocks
    response = audit.rock(audit.Block.from_dimensions(width_m=0.6, height_m=1.8), pulse)
    assert list(response.table.columns) == ["time_s", "theta_rad", "theta_dot_rad_s",
                                            "ground_acc_g"]
    assert response.summary["alpha_deg"] == pytest.approx(math.degrees(math.atan(0.3 / 0.9)))
    assert response.summary_text().startswith("Block p = ")
    assert response.summary_text(show_dimensions=True).startswith("Block 0.6x1.8 m")
    written = response.write(tmp_path / "out")
    assert sorted(p.name for p in written.iterdir()) == ["history.csv", "rocking.html",
                                                         "rocking.json", "rocking.png"]
    page = response.report(tmp_path / "page.html").read_text(encoding="utf-8")
    assert "data:image/png;base64," in page and "impacts" in page
    assert "<pre>" in response._repr_html_()
