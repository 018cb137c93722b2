"""Bad input, fourth corpus (issue 56): one test per KIND of failure, on small files made here.

Outputs that would overwrite an input or each other (refused before any record is read), the
inventory's guards before the work, floors and hazard curves at the front door, messages that
name what the user typed, and Ctrl-C at several moments of each long command. Each refusal is
one line naming the option, exit 2, nothing written (the house pattern of
tests/cli/test_bad_input.py).
"""

import os
import re
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import audit
from audit.cli import main
from audit.cli.interrupts import EXIT_INTERRUPTED
from audit.errors import InputError
from records import ENV_VARIABLE, load_records
from records.hazard import read_hazard

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """An empty working folder, with no record suite from the environment."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    return tmp_path


def _tree(folder):
    return {str(p.relative_to(folder)): (p.read_bytes() if p.is_file() else None)
            for p in folder.rglob("*")}


def _refused(folder, capsys, argv, *words) -> str:
    """Run the command line; assert one error line holding ``words``, exit 2, nothing new
    and nothing changed."""
    before = _tree(folder)
    status = main(argv)
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert status == 2, err
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert _tree(folder) == before, "files were written or changed"
    return lines[0]


def _text_record(path: Path) -> Path:
    """A text record of one column (0.2 g sine, 4 s at 100 Hz), stating dt and units."""
    t = np.arange(400) * 0.01
    path.write_text("# dt = 0.01 s, units: g\n"
                    + "\n".join(f"{a:.6g}" for a in 0.2 * np.sin(2 * np.pi * t)) + "\n")
    return path


# --- 1. no output over an input, or over another output ---------------------------------------

def test_floor_motion_csv_over_its_own_record(workdir, capsys):
    record = _text_record(workdir / "rec.txt")
    _refused(workdir, capsys, ["floor-motion", "--record", "rec.txt", "--building", "1",
                               "--csv", "rec.txt"], "--csv", "--record", "input")
    # the same file by another spelling of its path
    _refused(workdir, capsys, ["floor-motion", "--record", str(record), "--building", "1",
                               "--csv", "./sub/../rec.txt"], "--csv", "--record")


def test_two_outputs_on_one_file(workdir, capsys):
    _text_record(workdir / "rec.txt")
    _refused(workdir, capsys, ["spectrum", "--record", "rec.txt", "--kind", "response",
                               "--csv", "a.png", "--plot", "a.png"], "--plot", "--csv")


def test_pelicun_export_over_a_file_of_its_out_folder(workdir, capsys):
    (workdir / "f").mkdir()
    _refused(workdir, capsys, ["fragility", "--records", "pulses", "--out", "f",
                               "--pelicun", "f/fragility-components.csv"], "--pelicun", "--out")


def test_pelicun_export_on_the_out_folder_itself(workdir, capsys):
    # the folder does not exist yet: the run would make it, then fail to write the export
    _refused(workdir, capsys, ["fragility", "--records", "pulses", "--out", "f",
                               "--pelicun", "f"], "--pelicun", "--out")


def test_pelicun_export_on_an_existing_folder(workdir, capsys):
    (workdir / "g").mkdir()
    _refused(workdir, capsys, ["fragility", "--records", "pulses", "--out", "f",
                               "--pelicun", "g"], "--pelicun", "folder")


def test_check_out_folder_would_overwrite_the_inventory(workdir, capsys):
    (workdir / "out").mkdir()
    (workdir / "out" / "check.csv").write_text("name,width_m,height_m\ncab,0.6,1.8\n")
    _refused(workdir, capsys, ["check", "--objects", "out/check.csv", "--site", "1.5,0.9",
                               "--records", "pulses", "--out", "out"], "--out", "--objects")


def test_validate_out_folder_is_the_campaign(workdir, capsys):
    (workdir / "campaign").mkdir()
    (workdir / "campaign" / "tests.csv").write_text("test,ground_motion,motion_file\n")
    _refused(workdir, capsys, ["validate", "campaign", "--out", "campaign"], "--out", "FOLDER")


def test_run_out_folder_is_the_records_folder(workdir, capsys):
    (workdir / "recs").mkdir()
    _refused(workdir, capsys, ["run", "all", "--records", "recs", "--out", "recs"],
             "--out", "--records")


def test_an_input_beside_the_outputs_is_not_refused(tmp_path):
    """An inventory in the --out folder under a name the command does not write is kept."""
    from audit.files import check_outputs
    (tmp_path / "inventory.csv").write_text("x")
    paths = check_outputs(folders={"--out": (tmp_path, ("check.csv",))},
                          inputs={"--objects": tmp_path / "inventory.csv"})
    assert paths["--out"] == tmp_path


# --- 2. guards before the work, linear in their input -----------------------------------------

def test_duplicate_names_of_a_large_inventory(workdir, capsys):
    rows = [f"obj{i},0.6,1.8" for i in range(20_000)] + ["obj7,0.5,1.5"]
    (workdir / "inv.csv").write_text("name,width_m,height_m\n" + "\n".join(rows) + "\n")
    _refused(workdir, capsys, ["check", "--objects", "inv.csv", "--site", "1.5,0.9",
                               "--records", "pulses"], "--objects", "obj7", "already used")


def test_block_given_twice_across_options(workdir, capsys):
    (workdir / "inv.csv").write_text("name,width_m,height_m\n0.6x1.8,0.6,1.8\n")
    _refused(workdir, capsys, ["check", "--objects", "inv.csv", "--block", "0.6x1.8",
                               "--site", "1.5,0.9", "--records", "pulses"], "given twice")


# --- 5. floors and hazard ----------------------------------------------------------------------

def test_building_damping_help_and_check_agree(workdir, capsys):
    from audit.cli import build_parser
    help_text = " ".join(build_parser()._subparsers._group_actions[0].choices["check"]
                         .format_help().split())
    assert "0 < ζ < 1" in help_text
    for value in ("1", "0", "5"):
        _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                                   "--building-damping", value], "--building-damping",
                 "(0, 1)")
    # the API's floor takes the same range, numpy scalars too
    from audit.physics.building.floor import Building, Floor
    assert Floor.parse(Floor(np.float64(1.0), Building(np.int64(1), damping=np.float32(0.999)))
                       ).building.period_s == 1.0
    with pytest.raises(InputError, match=r"^floor.building.damping: expected a number in \(0, 1\)"):
        Floor.parse(Floor(1.0, Building(1.0, damping=1.0)))
    # a function that takes the floor whole names the argument and the field
    with pytest.raises(InputError, match=r"^floor.building.damping: expected a number in \(0, 1\)"):
        audit.floor_motion((np.zeros(8), 0.01), Floor(1.0, Building(1.0, damping=1.0)))


def test_malformed_building_values_refused_on_the_ground(workdir, capsys):
    _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                               "--building-model", "shear:abc"], "--building-model", "shear:abc")
    from audit.physics.building.floor import Building, Floor
    with pytest.raises(InputError, match="^floor.building.period_s:"):
        Floor.parse(Floor(0.0, Building(-1.0)))


def test_numpy_integers_where_whole_numbers_are_asked(tmp_path):
    from records import read_columns
    path = tmp_path / "two.txt"
    path.write_text("# dt = 0.01 s, units: g\n" + "\n".join(f"0 {0.1 * (i % 7):g}"
                                                            for i in range(200)) + "\n")
    motion = read_columns(path, column=np.int64(2))
    assert motion.acceleration.size == 200


def _usgs_pga_only(path):
    import json
    document = json.loads((Path(os.environ.get("ROCKING_AUDIT_HAZARD", REPO))
                           / "usgs-example.json").read_text())
    document["response"] = [r for r in document["response"]
                            if r["metadata"]["imt"]["value"] == "PGA"]
    path.write_text(json.dumps(document))
    return path


def _openquake_one_imt(path):
    """An OpenQuake export of SA(1.0) at one site (λ = −ln(1 − poe)/50)."""
    levels = [0.05, 0.1, 0.2, 0.4, 0.8]
    poes = [0.6, 0.3, 0.1, 0.02, 0.002]
    path.write_text(
        "#,,,,,,,,\"generated_by='OpenQuake engine 3.26.2', kind='mean', "
        "investigation_time=50.0, imt='SA(1.0)'\"\n"
        "lon,lat,depth," + ",".join(f"poe-{x:.7f}" for x in levels) + "\n"
        "-1.0,1.0,0.0," + ",".join(f"{p:.6E}" for p in poes) + "\n")
    return path


def test_hazard_imt_that_the_file_does_not_hold(workdir, capsys):
    curve = _openquake_one_imt(workdir / "oq.csv")
    assert read_hazard(curve).im_name == "SA(1.0)"
    _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                               "--records", "pulses", "--hazard", "oq.csv",
                               "--hazard-imt", "PGA"], "--hazard-imt", "PGA", "SA(1.0)")


def test_return_period_on_a_flat_stretch_takes_its_highest_level(tmp_path):
    """docs/risk.md, records/hazard/curve.py: on a flat stretch at λ the highest level of
    that rate. Rates 1/400 at 0.2 g and 0.4 g: 400 years reads 0.4 g; between the stretch
    and the next level the power law from 0.4 g."""
    path = tmp_path / "flat.csv"
    path.write_text("# imt=PGA\nim_g,annual_rate\n0.1,0.01\n0.2,0.0025\n0.4,0.0025\n"
                    "0.8,0.0001\n")
    curve = read_hazard(path)
    assert curve.im_at_rate(1 / 400) == pytest.approx(0.4, rel=1e-12)
    # the power law λ = 0.0025 (im/0.4)^k between (0.4 g, 0.0025) and (0.8 g, 1e-4)
    k = np.log(1e-4 / 0.0025) / np.log(2.0)
    assert curve.im_at_rate(1e-3) == pytest.approx(0.4 * (1e-3 / 0.0025) ** (1 / k), rel=1e-9)
    assert curve.im_at_rate(1e-4) == pytest.approx(0.8, rel=1e-12)
    assert curve.im_at_rate(0.005) == pytest.approx(np.sqrt(0.1 * 0.2), rel=1e-9)


def test_hazard_curve_in_cm_s2_refused(workdir, capsys):
    (workdir / "cms.csv").write_text("# imt=PGA\nim_g,annual_rate\n5,0.1\n50,0.01\n500,0.001\n"
                                     "2000,0.0001\n")
    _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                               "--records", "pulses", "--hazard", "cms.csv"],
             "cms.csv", "cm/s²", "levels")


# --- 6. messages name what the user typed -----------------------------------------------------

def test_limit_state_named_as_the_flag(workdir, capsys):
    line = _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                                      "--records", "pulses", "--limit-state", "SLD"],
                    "--limit-state", "SLD")
    assert "limit_state" not in line


def test_poe_off_the_curve_names_poe(workdir, capsys):
    _openquake_one_imt(workdir / "oq.csv")
    line = _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                                      "--records", "pulses", "--hazard", "oq.csv",
                                      "--poe", "1e-7"], "--poe")
    assert "--return-period" not in line
    _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                               "--records", "pulses", "--hazard", "oq.csv",
                               "--return-period", "1e9"], "--return-period")


@pytest.mark.skipif(not (Path(os.environ.get("ROCKING_AUDIT_HAZARD", "/nonexistent"))
                         / "usgs-example.json").is_file(),
                    reason="needs $ROCKING_AUDIT_HAZARD/usgs-example.json")
def test_usgs_file_without_the_im_names_the_flag_that_chooses(workdir, capsys):
    _usgs_pga_only(workdir / "pga.json")
    _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                               "--records", "pulses", "--hazard", "pga.json", "--im", "sa:1.0"],
             "pga.json", "SA(1.0)", "PGA", "--im", "--hazard-imt")


def test_rock_size_beyond_the_records_names_size(workdir, capsys):
    line = _refused(workdir, capsys, ["rock", "--size", "1000", "--alpha", "10", "--pulse",
                                      "sine", "--amplitude", "0.3", "--pulse-period", "1"],
                    "--size 1000", "2π/p")
    assert "--block" not in line


def test_an_alias_is_named_as_typed(workdir, capsys):
    line = _refused(workdir, capsys, ["run", "all", "--records", "pulses", "--sizes", "1:0:1",
                                      "--out", "out"], "--sizes", "1:0:1")
    assert "--size:" not in line
    _refused(workdir, capsys, ["run", "all", "--records", "pulses", "--size", "1:0:1",
                               "--out", "out"], "--size:")


def test_records_load_dt_as_text(tmp_path):
    path = tmp_path / "acc.txt"
    path.write_text("0.1\n0.2\n-0.1\n0.05\n")
    with pytest.raises(InputError, match=r"^dt: .*'0.01 s'"):
        load_records(path, dt="0.01 s", units="g")
    assert load_records(path, dt=np.float64(0.01), units="g").entries[0].motion.dt == 0.01


# --- 3. Ctrl-C at three moments of each long command ------------------------------------------

#: Each command with a workload long enough to be interrupted, its --out's file an earlier
#: run left, and the stderr lines after which SIGINT is sent: before the first record
#: (loading, compiling), mid-solve, and while the last results are put together and written.
LONG_COMMANDS = {
    "run": (["run", "all", "--records", "pulses", "--size", "0.5:6:0.005",
             "--alpha", "5,10,15,20", "--force"], "report.html",
            (r"^\[", r"record 2/", r"writing the results")),
    "margins": (["margins", "all", "--records", "pulses", "--size", "0.5:4:0.05",
                 "--force"], "margins.html", (r"^\[", r"record 2/", r"record 7/7")),
    "check": (["check", "--alpha", "5,10,15,20", "--size", "0.5:6:0.05", "--site", "1.5,0.9",
               "--records", "pulses", "--force"], "check.json",
              (r"^\[", r"record 2/", r"the width each guideline")),
    "validate": (["validate", os.environ.get("ROCKING_AUDIT_CAMPAIGN", "/nonexistent")],
                 "validation.html", (r"^\[", r"test 2/", r"test 20/")),
}


def _interrupt_when(argv, cwd, pattern):
    """Start ``python -m audit ARGV``, send SIGINT once a stderr line matches ``pattern``;
    the return code and the whole stderr."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    env.pop(ENV_VARIABLE, None)
    process = subprocess.Popen([sys.executable, "-m", "audit", *argv], cwd=cwd, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = []
    for line in process.stderr:
        lines.append(line)
        if re.search(pattern, line):
            process.send_signal(signal.SIGINT)
            break
    lines += process.stderr.read().splitlines(keepends=True)
    process.wait(timeout=600)
    return process.returncode, "".join(lines)


@pytest.mark.slow
@pytest.mark.parametrize("command", sorted(LONG_COMMANDS))
def test_ctrl_c_at_three_moments_exits_130_without_a_crash(command, tmp_path):
    argv, earlier_name, moments = LONG_COMMANDS[command]
    if command == "validate" and not Path(argv[1]).is_dir():
        pytest.skip("needs $ROCKING_AUDIT_CAMPAIGN")
    for k, pattern in enumerate(moments):
        out = tmp_path / f"out{k}"
        out.mkdir()
        earlier = out / earlier_name
        earlier.write_text("an earlier run's file\n")
        code, err = _interrupt_when([*argv, "--out", str(out)], tmp_path, pattern)
        assert code >= 0 and "Segmentation fault" not in err and "Traceback" not in err, \
            (command, pattern, code, err)
        assert "interrupted" in err.splitlines()[-1] or code == 0, (command, pattern, err)
        if code == 0:  # the last moment may come after the work: then all is written
            assert k == len(moments) - 1, (command, pattern, err)
            continue
        assert code == EXIT_INTERRUPTED, (command, pattern, code, err)
        # the earlier file intact; nothing else but the parts kept for --resume; no staging
        assert earlier.read_text() == "an earlier run's file\n"
        left = {p.name for p in out.iterdir()} - {earlier_name, ".partial"}
        assert not left, (command, pattern, left)
        assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")], \
            (command, pattern, list(tmp_path.iterdir()))


def test_stop_kernels_waits_for_running_chunks_and_starts_none():
    """In a process of its own (the stop is for the process's life): the chunk running when
    the stop comes is waited for, and a later call starts nothing (KeyboardInterrupt)."""
    script = """
import threading, time
from audit.physics.kernel_threads import run_chunks, stop_kernels
done, started = [], threading.Event()
def work(chunk):
    started.set()
    time.sleep(0.5)
    done.append(chunk)
caller = threading.Thread(target=lambda: run_chunks(work, [1]), daemon=True)
caller.start()
started.wait(60)
assert stop_kernels(30.0) and done == [1], done
try:
    run_chunks(work, [2])
except KeyboardInterrupt:
    print("stopped", done)
"""
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            env={**os.environ, "PYTHONPATH": str(REPO)}, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "stopped [1]"
