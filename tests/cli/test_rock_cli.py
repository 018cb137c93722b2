"""The free-vibration peak and the time history of one block (issue 9, item 4).

Checked against the independent ``solve_ivp`` solver's turning points, Housner's closed form
for free rocking (Eq. 7.5) and the impact law (Eq. 4.6–4.8)."""

import csv
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from audit.cli import main
from audit.physics.block import RigidBlock
from audit.physics.damping import housner_peak_ratio
from audit.physics.reference import simulate_reference
from audit.physics.rocking import simulate
from records import one_pulse
from records.motion import GroundMotion

ROOT = Path(__file__).resolve().parents[2]
ALPHA_15 = math.radians(15)
PULSE = ["rock", "--p", "2", "--alpha", "15", "--pulse", "cosine", "--pulse-period", "2",
         "--free-motion", "8"]


def test_free_vibration_peak_of_the_pulse_anchor_matches_the_reference_solver():
    """SPEC §2: p = 2, α = 15°, one-cosine pulse T_p = 2 s of 0.310 g survives with a post-pulse
    peak of roughly 0.3–0.4 α: the largest turning point after t = T_p."""
    block, motion = RigidBlock(2.0, ALPHA_15), one_pulse("cosine", 0.310, 2.0)
    response = simulate(block, motion, 8.0)
    reference = simulate_reference(block, motion, 8.0)
    after = reference["turning_times"] > 2.0
    expected = np.max(np.abs(reference["turning_rotations"][after]))
    assert not reference["overturned"] and after.sum() > 20  # "more than 20 impacts"
    assert response.peak_rotation_free_vibration == pytest.approx(expected, rel=1e-3)
    assert 0.3 < response.peak_rotation_free_vibration / ALPHA_15 < 0.4


def test_free_vibration_peak_is_a_turning_point_not_the_value_at_the_end_of_the_excitation():
    """Released from θ₀ = 0.3α at rest, a slender block's first peak after the first impact is
    θ₁/α = 1 − sqrt(1 − r[1 − (1 − θ₀/α)²]) (Eq. 7.5, n = 1); the excitation (two zero samples)
    ends while the block still leans at ≈ θ₀, the peak *after the excitation* by the old key."""
    block = RigidBlock(2.0, math.radians(10))
    still = GroundMotion("still", np.zeros(2), 0.01)
    response = simulate(block, still, 10.0, initial_rotation=0.3 * block.alpha)
    assert response.peak_rotation_after_excitation / block.alpha == pytest.approx(0.3, abs=1e-3)
    assert response.peak_rotation_free_vibration / block.alpha == pytest.approx(
        housner_peak_ratio(0.3, 1, block.r), rel=1e-3)


def test_no_free_vibration_peak_when_the_block_overturns():
    response = simulate(RigidBlock(2.0, ALPHA_15), one_pulse("cosine", 0.316, 2.0), 8.0)
    assert response.overturned and math.isnan(response.peak_rotation_free_vibration)


def test_rock_json_and_text_report_the_free_vibration_peak(capsys):
    assert main(PULSE + ["--amplitude", "0.310", "--json"]) == 0
    survives = json.loads(capsys.readouterr().out)
    block, motion = RigidBlock(2.0, ALPHA_15), one_pulse("cosine", 0.310, 2.0)
    assert survives["peak_rotation_free_vibration"] == pytest.approx(
        simulate(block, motion, 8.0).peak_rotation_free_vibration, rel=1e-12)
    assert "peak_rotation_after_excitation" in survives
    assert main(PULSE + ["--amplitude", "0.316", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["peak_rotation_free_vibration"] is None
    assert main(PULSE + ["--amplitude", "0.316"]) == 0
    text = capsys.readouterr().out
    assert "OVERTURNS" in text
    assert "after excitation  n/a" in text and "free-vibration peak |θ|    n/a" in text


def read_history(path):
    with open(path, newline="") as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["time_s", "theta_rad", "theta_dot_rad_s", "ground_acc_g"]
    return np.array(rows[1:], dtype=float)


def test_history_holds_the_grid_every_turning_point_and_both_sides_of_every_impact(tmp_path):
    out = tmp_path / "sub" / "history.csv"
    assert main(PULSE + ["--amplitude", "0.310", "--json", "--history", str(out)]) == 0
    time, theta, omega, ground_g = read_history(out).T
    block, motion = RigidBlock(2.0, ALPHA_15), one_pulse("cosine", 0.310, 2.0)
    response = simulate(block, motion, 8.0)
    assert np.all(np.diff(time) >= 0) and time[-1] == pytest.approx(10.0)
    # the one-cosine pulse: a_p cos(2πt/T_p) up to T_p, zero after
    inside = time <= 2.0
    np.testing.assert_allclose(ground_g[inside], 0.310 * np.cos(np.pi * time[inside]), atol=1e-9)
    assert np.all(ground_g[~inside] == 0.0)
    # every impact twice at θ = 0, θ' scaled by sqrt(r) across it (Eq. 4.6–4.8), but the last
    # one, after which the block rests
    impacts = np.flatnonzero((theta[:-1] == 0) & (theta[1:] == 0) & (time[:-1] == time[1:])
                             & (time[:-1] > 0))
    assert impacts.size == response.n_impacts > 0
    np.testing.assert_allclose(omega[impacts[:-1] + 1] / omega[impacts[:-1]], math.sqrt(block.r),
                               rtol=1e-8)
    assert omega[impacts[-1]] != 0 and np.all(omega[impacts[-1] + 1:] == 0)
    # turning points: θ' = 0 away from rest; the largest after the pulse is the reported peak
    turning = (omega == 0) & (theta != 0)
    assert turning.sum() == response.turning_times.size
    assert np.max(np.abs(theta[turning & (time > 2.0)])) == pytest.approx(
        response.peak_rotation_free_vibration, rel=1e-8)
    assert len(time) == response.time.size + turning.sum() + 2 * impacts.size


def test_history_stops_at_overturning(tmp_path):
    out = tmp_path / "falls.csv"
    assert main(PULSE + ["--amplitude", "0.316", "--history", str(out)]) == 0
    time, theta, _, _ = read_history(out).T
    response = simulate(RigidBlock(2.0, ALPHA_15), one_pulse("cosine", 0.316, 2.0), 8.0)
    assert time[-1] < response.overturn_time and np.all(np.abs(theta) < ALPHA_15)


def test_rock_with_history_does_not_load_pandas(tmp_path):
    """The rock command stays light: one simulation and a CSV need numpy and numba only."""
    code = ("import sys; from audit.cli import main; "
            f"main({PULSE + ['--amplitude', '0.31', '--json', '--history', str(tmp_path / 'h.csv')]!r}); "
            "sys.exit('pandas' in sys.modules)")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        filter(None, [str(ROOT), os.environ.get("PYTHONPATH", "")]))}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                            cwd=ROOT, timeout=600)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "h.csv").is_file()


def test_rock_a_block_given_by_its_dimensions(capsys):
    """--block 0.4x2.0: α = atan(b/h) = atan(0.2), p = √(3g/(4R)) with R = √(0.2² + 1²) [m]."""
    assert main(["rock", "--block", "0.4x2.0", "--pulse", "cosine", "--amplitude", "0.3",
                 "--pulse-period", "2", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["alpha_deg"] == pytest.approx(math.degrees(math.atan(0.2)), rel=1e-12)
    assert result["p"] == pytest.approx(math.sqrt(3 * 9.81 / (4 * math.hypot(0.2, 1.0))),
                                        rel=1e-12)
    assert result["R_m"] == pytest.approx(math.hypot(0.2, 1.0))
    assert (result["width_m"], result["height_m"]) == (0.4, 2.0)
    for extra in (["--alpha", "10"], ["--size", "2"]):
        assert main(["rock", "--block", "0.4x2", *extra, "--pulse", "cosine", "--amplitude",
                     "0.3", "--pulse-period", "2"]) == 2
        assert "--block" in capsys.readouterr().err


def test_rock_json_gives_the_dimensions_of_a_block_given_by_size(capsys):
    """--size 2 --alpha 15: p = π rad/s, R = 3g/(4p²), width 2R sin α, height 2R cos α [m]."""
    assert main(["rock", "--size", "2", "--alpha", "15", "--pulse", "cosine", "--amplitude",
                 "0.3", "--pulse-period", "2", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    radius = 3 * 9.81 / (4 * math.pi ** 2)
    assert result["width_m"] == pytest.approx(2 * radius * math.sin(math.radians(15)), rel=1e-9)
    assert result["height_m"] == pytest.approx(2 * radius * math.cos(math.radians(15)), rel=1e-9)


def test_rock_reads_a_text_record_with_dt_and_units_given_or_a_time_column(tmp_path, capsys):
    """One text record three ways — one column with --dt/--units, a time column, the values in
    g with a 'units' comment — all the exact response of the motion built here directly."""
    dt = 0.005
    t = np.arange(int(8.0 / dt)) * dt
    pulse_g = np.where(t < 2.0, 0.310 * np.cos(2 * np.pi * t / 2.0), 0.0)
    expected = simulate(RigidBlock(2.0, ALPHA_15),
                        GroundMotion("x", pulse_g * 9.81, dt), 8.0).peak_rotation
    (tmp_path / "one.txt").write_text("\n".join(f"{a * 981:.9e}" for a in pulse_g) + "\n")
    (tmp_path / "timed.txt").write_text("% time [s], acceleration (g)\n" + "\n".join(
        f"{time:.3f} {a:.9e}" for time, a in zip(t, pulse_g)) + "\n")
    block = ["rock", "--p", "2", "--alpha", "15", "--free-motion", "8", "--json"]
    for record in (["--record", str(tmp_path / "one.txt"), "--dt", "0.005", "--units", "cm/s2"],
                   ["--record", str(tmp_path / "timed.txt")]):
        assert main(block + record) == 0
        assert json.loads(capsys.readouterr().out)["peak_rotation"] == pytest.approx(
            expected, rel=1e-6)
