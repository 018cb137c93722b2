"""The light commands import neither matplotlib, pandas nor the audit runner (issue 10, item 3).

Each command runs through ``main`` in a fresh interpreter, which then reports the modules it
loaded; the commands' own output goes to a file so it cannot be mistaken for the report.
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("matplotlib", "pandas", "audit.engine.run.pipeline")
PROBE = """
import contextlib, json, sys
from audit.cli import main
with open(sys.argv[1], "w") as out, contextlib.redirect_stdout(out):
    status = main(sys.argv[2:])
print(json.dumps({"status": status, "modules": sorted(sys.modules)}))
"""


def loaded_modules(tmp_path, *argv):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", PROBE, str(tmp_path / "stdout.txt"), *argv],
                          capture_output=True, text=True, env=env, cwd=tmp_path, check=True)
    report = json.loads(done.stdout)
    assert report["status"] == 0, done.stderr
    return report["modules"], (tmp_path / "stdout.txt").read_text()


@pytest.mark.parametrize("argv", [
    ["rock", "--p", "2", "--alpha", "15", "--pulse", "cosine", "--amplitude", "0.3",
     "--pulse-period", "2", "--json"],
    ["design-spectrum", "fema356", "--sxs", "1.59", "--sx1", "0.50", "--damping", "2,5"],
    ["design-spectrum", "ubc97", "--csv", "spectrum.csv"],
    ["list"],
])
def test_light_commands_skip_heavy_imports(tmp_path, argv):
    modules, output = loaded_modules(tmp_path, *argv)
    heavy = [m for m in modules if m.split(".")[0] in HEAVY or m.startswith(HEAVY)]
    assert heavy == []
    assert output or (tmp_path / "spectrum.csv").is_file()  # the command did its work


def test_rock_output_is_unchanged_by_the_light_path(tmp_path):
    """Independent fact: SPEC §2 — a_p = 0.30 g < 0.310 g, p = 2, α = 15°: the block survives."""
    _, output = loaded_modules(tmp_path, "rock", "--p", "2", "--alpha", "15", "--pulse", "cosine",
                               "--amplitude", "0.3", "--pulse-period", "2", "--json")
    result = json.loads(output)
    assert result["uplifted"] is True and result["overturned"] is False


def test_design_spectrum_csv_without_pandas(tmp_path):
    """FEMA 356, S_XS = 1.59 g, S_X1 = 0.50 g, 5 %: the plateau is S_XS/B_S = 1.59 g."""
    _, output = loaded_modules(tmp_path, "design-spectrum", "fema356", "--sxs", "1.59",
                               "--sx1", "0.50", "--periods", "0.2,2")
    lines = output.splitlines()
    assert lines[0] == "period_s,damping_pct,sa_g,sd_m"
    period, damping, sa_g, _ = map(float, lines[1].split(","))
    assert (period, damping, sa_g) == (0.2, 5.0, 1.59)
    assert float(lines[2].split(",")[2]) == pytest.approx(0.50 / 2.0)


def test_spectrum_csv_loads_no_figures_and_no_procedures(tmp_path):
    """A CSV of rocking spectra needs pandas (the table) but neither matplotlib (no --plot) nor
    the procedures' registry (scipy.optimize): half of the command's start-up. Independent
    fact (SPEC §2): a block of p = 2 rad/s (2π/p = π s), α = 15° rocks and survives a 0.30 g,
    2 s cosine pulse (a_p < 0.310 g)."""
    modules, _ = loaded_modules(tmp_path, "spectrum", "--pulse", "cosine", "--amplitude", "0.3",
                                "--pulse-period", "2", "--alpha", "15", "--size", str(math.pi),
                                "--csv", "spectrum.csv")
    loaded = [m for m in modules if m.startswith(("matplotlib", "scipy.optimize", "procedures"))]
    assert loaded == []
    header, row = (tmp_path / "spectrum.csv").read_text().splitlines()[:2]
    values = dict(zip(header.split(","), row.split(",")))
    assert values["overturned"] == "False" and 0.0 < float(values["theta_ratio"]) < 1.0
