"""Bad input, third corpus (issue 47): one test per KIND of failure, on small files made here.

Malformed structure (ragged CSV rows, corrupt compressed streams, motions too short or with
implausible steps for their processing), values whose units are easily confused (a site in
per cent of g, a motion in cm/s² under a g header), the cost guard of ``check``, and the
noticed items (text records with a header line or commas, a campaign where every test
overturned, a very small block's width). Each refusal is one line naming the file and the row
or field, exit 2, nothing written (the house pattern of tests/cli/test_bad_input.py).
"""

import gzip
import math
import warnings
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from scipy.signal import butter, sosfiltfilt

from audit import G
from audit.cli import main
from audit.engine.shared.design_site import MAX_SITE_G, Site
from audit.errors import InputError
from records import ENV_VARIABLE, GroundMotion, read_columns
from records.campaign import read_campaign, read_table_motion
from records.hazard.openquake import read_openquake_curve


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """An empty working folder, with no record suite from the environment."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    return tmp_path


def _tree(folder):
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


def _refused(folder, capsys, argv, *words) -> str:
    """Run the command line; assert one error line holding ``words``, exit 2, nothing new."""
    before = _tree(folder)
    status = main(argv)
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert status == 2, err
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert "Traceback" not in err
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert _tree(folder) == before, "files were written"
    return lines[0]


# --- ragged CSV rows --------------------------------------------------------------------------

def test_inventory_row_with_more_fields_than_its_header(workdir, capsys):
    (workdir / "inventory.csv").write_text("name,width_m,height_m\n"
                                           "cabinet,0.6,1.8\n"
                                           "shelf, tall,0.4,2.0\n")  # an unquoted comma
    _refused(workdir, capsys, ["check", "--objects", "inventory.csv", "--site", "1.5,0.9"],
             "--objects", "inventory.csv", "row 3", "4 fields", "header has 3")


def test_inventory_trailing_empty_field_is_not_an_extra_field(tmp_path):
    from audit.engine.check.objects import read_objects
    (tmp_path / "inv.csv").write_text("name,width_m,height_m\ncabinet,0.6,1.8,\n")
    [cabinet] = read_objects(tmp_path / "inv.csv")
    assert (cabinet.width_m, cabinet.height_m) == (0.6, 1.8)


OQ_HEAD = ("#,,,,\"generated_by='OpenQuake engine 3.26.2', kind='mean', "
           "investigation_time=50.0, imt='SA(1.0)'\"\n"
           "lon,lat,depth,poe-0.1,poe-0.2\n"
           "-1.0,1.0,0.0,0.5,0.1\n"
           "1.3,0.0,0.0,0.4,0.05\n")


def test_openquake_export_with_a_ragged_extra_row(tmp_path):
    path = tmp_path / "hazard_curve-mean-SA(1.0)_2.csv"
    path.write_text(OQ_HEAD + "2.0,1.0\n")
    with pytest.raises(InputError, match=r"row 5: 2 fields, expected 5") as refused:
        read_openquake_curve(path, (1.3, 0.0))
    assert str(path) in str(refused.value)
    # the same file without the ragged row reads: λ = −ln(1 − poe)/50 yr, by hand
    path.write_text(OQ_HEAD + "\n")
    curve = read_openquake_curve(path, (1.3, 0.0))
    assert curve.annual_rate == pytest.approx([-math.log(0.6) / 50, -math.log(0.95) / 50])


def test_openquake_ragged_row_refused_by_check_before_any_record(workdir, capsys):
    (workdir / "oq.csv").write_text(OQ_HEAD + "2.0,1.0,0.0,0.3\n")
    _refused(workdir, capsys, ["check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                               "--hazard", "oq.csv", "--site-location", "1.3,0.0"],
             "oq.csv", "row 5", "4 fields, expected 5")


# --- shake-table campaigns: corrupt streams, implausible steps and units, short motions -------

def _motion_csv(time_s, acc_g) -> str:
    return "time_s,acc_g\n" + "\n".join(f"{t:.6g},{a:.6g}" for t, a in zip(time_s, acc_g))


def _campaign(folder, motion_text=None, raw=None, n_tests=6):
    """A campaign of ``n_tests`` tests on as many ground motions; the first test's motion
    file is ``motion_text`` (or the bytes ``raw`` of a .gz file), the others a valid 0.2 g
    sine of 8 s at 100 Hz."""
    (folder / "motions").mkdir(parents=True)
    t = np.arange(800) * 0.01
    good = _motion_csv(t, 0.2 * np.sin(2 * np.pi * 2.0 * t))
    rows = ["test,ground_motion,motion_file,s1_overturned"]
    for i in range(n_tests):
        name = f"motions/T{i}.csv" + (".gz" if i == 0 and raw is not None else "")
        if i == 0 and raw is not None:
            (folder / name).write_bytes(raw)
        else:
            (folder / name).write_text(motion_text if i == 0 and motion_text else good)
        rows.append(f"T{i},gm{i},{name},{i % 2}")
    (folder / "tests.csv").write_text("\n".join(rows) + "\n")


def test_campaign_motion_corrupt_inside_its_gzip_stream(workdir, capsys):
    t = np.arange(2000) * 0.005
    packed = bytearray(gzip.compress(_motion_csv(t, 0.2 * np.sin(t)).encode()))
    for i in range(200, 260):  # inside the deflate stream: zlib.error, not an OSError
        packed[i] ^= 0xFF
    _campaign(workdir / "camp", raw=bytes(packed))
    _refused(workdir, capsys, ["validate", "camp", "--out", "out"],
             "T0.csv.gz", "motion_file of test T0", "unreadable")


def test_campaign_time_column_in_milliseconds(workdir, capsys):
    t_ms = np.arange(800) * 10.0  # 10 ms steps written as 0, 10, 20, ...
    _campaign(workdir / "camp", _motion_csv(t_ms, 0.2 * np.sin(t_ms / 100.0)))
    _refused(workdir, capsys, ["validate", "camp", "--out", "out"],
             "T0.csv", "time_s", "step of 10 s", "milliseconds")


def test_campaign_motion_in_cm_s2_under_a_g_column(workdir, capsys):
    # a weak 0.05 g table motion written in cm/s²: peak 0.05 × 980.665 = 49.03 "g"
    t = np.arange(800) * 0.01
    _campaign(workdir / "camp", _motion_csv(t, 0.05 * G * 100 * np.sin(2 * np.pi * t)))
    line = _refused(workdir, capsys, ["validate", "camp", "--out", "out"],
                    "T0.csv", "acc_g", "49 g", "cm/s²")
    assert "(0.05 g)" in line  # what it is in g if the column holds cm/s²


def test_campaign_in_m_s2_under_a_g_column_is_warned(tmp_path):
    from audit.errors import InputWarning
    # 0.2 g written in m/s² reads as 1.96 "g": a possible, if strong, shake-table test
    t = np.arange(800) * 0.01
    folder = tmp_path / "camp"
    _campaign(folder)
    for path in (folder / "motions").iterdir():
        path.write_text(_motion_csv(t, 0.2 * G * np.sin(2 * np.pi * t)))
    with pytest.warns(InputWarning, match=r"tests\.csv: acc_g: the median peak .* m/s²"):
        read_campaign(folder)


def test_campaign_motion_too_short_for_the_band_pass(workdir, capsys):
    t = np.arange(12) * 0.01
    _campaign(workdir / "camp", _motion_csv(t, 0.2 * np.sin(t)))
    _refused(workdir, capsys, ["validate", "camp", "--out", "out"],
             "T0.csv", "12 samples", "too short", "band-pass")


def test_band_pass_refuses_exactly_what_scipy_cannot_filter():
    # the oracle is scipy's own zero-phase filter on the same design: it raises ValueError
    # for a signal no longer than its padding; the guard must refuse exactly those lengths
    from audit.engine.validation.grid import band_passed
    from audit.engine.validation.settings import ValidationSettings
    settings = ValidationSettings()
    sos = butter(4, [settings.highpass_hz, settings.lowpass_hz], "bandpass", fs=100.0,
                 output="sos")
    for n in range(2, 60):
        motion = GroundMotion("m", np.sin(np.arange(n) * 0.3), 0.01, source=f"m{n}.csv")
        try:
            sosfiltfilt(sos, motion.acceleration)
            scipy_filters = True
        except ValueError:
            scipy_filters = False
        if scipy_filters:
            assert np.all(np.isfinite(band_passed(motion, settings).acceleration))
        else:
            with pytest.raises(InputError, match=rf"^m{n}\.csv: {n} samples .* too short"):
                band_passed(motion, settings)


def test_band_pass_above_the_nyquist_frequency_is_refused():
    from audit.engine.validation.grid import band_passed
    from audit.engine.validation.settings import ValidationSettings
    motion = GroundMotion("m", np.sin(np.arange(500) * 0.3), 0.04, source="m.csv")
    # Nyquist 1/(2 × 0.04 s) = 12.5 Hz, below a 20 Hz high-pass
    with pytest.raises(InputError, match=r"^m\.csv: .*Nyquist frequency 12\.5 Hz"):
        band_passed(motion, ValidationSettings(highpass_hz=20.0, lowpass_hz=30.0))


def test_a_valid_small_campaign_still_reads(tmp_path):
    _campaign(tmp_path / "camp")
    campaign = read_campaign(tmp_path / "camp")
    assert campaign.motions[0].dt == pytest.approx(0.01)
    # the sine's samples nearest its crest, t = 0.12 s and 0.13 s: 0.2 sin(0.48 π)
    assert campaign.motions[0].pga_g == pytest.approx(0.2 * math.sin(0.48 * math.pi), rel=1e-5)


def test_table_motion_of_a_strong_but_real_peak_is_read(tmp_path):
    # 4 g, about the largest ever recorded, is not taken for cm/s²
    t = np.arange(400) * 0.005
    (tmp_path / "m.csv").write_text(_motion_csv(t, 4.0 * np.sin(2 * np.pi * 3 * t)))
    assert read_table_motion(tmp_path / "m.csv", "m").pga_g == pytest.approx(4.0, rel=1e-3)


# --- a site in per cent of g -------------------------------------------------------------------

def test_site_in_per_cent_of_g_refused_with_the_value_it_meant(workdir, capsys):
    (workdir / "inv.csv").write_text("name,width_m,height_m\ncabinet,0.6,1.8\n")
    _refused(workdir, capsys, ["check", "--objects", "inv.csv", "--site", "150,90"],
             "--site", "150, 90 g", "per cent of g (1.5, 0.9)")


def test_run_site_in_per_cent_of_g_refused(workdir, capsys):
    _refused(workdir, capsys, ["run", "fema356", "--records", "pulses", "--site", "40,20"],
             "--site", "(0.4, 0.2)")


def test_site_bound_in_the_api():
    with pytest.raises(InputError) as refused:
        Site.parse((1.5, 90.0))
    assert refused.value.fields == ("site",)
    # the largest mapped design values (S_XS about 4 g) stay accepted
    assert Site.parse((4.0, 2.4)).values_g == (4.0, 2.4)
    assert Site.parse(Site(MAX_SITE_G, MAX_SITE_G)).values_g == (MAX_SITE_G, MAX_SITE_G)


# --- check's cost guard --------------------------------------------------------------------------

def test_width_search_halvings_by_hand():
    from audit.engine.check.costs import width_halvings
    # scan 0.03 h to 0.95 h in 12 widths: neighbours (0.95/0.03)^(1/11) = 1.3690 apart;
    # halving ln 1.3690 = 0.31412 down to ln 1.005 = 0.0049875 takes ⌈log2 62.98⌉ = 6
    assert width_halvings() == 6


def _entries(n_records, samples, dt=0.01):
    return [SimpleNamespace(motion=GroundMotion(f"r{i}", np.zeros(samples), dt))
            for i in range(n_records)]


def test_check_cost_counts_objects_stripes_and_widths():
    from audit.engine.shared import guards
    from audit.engine.check.costs import check_cost
    procedures = [SimpleNamespace(requires_motion=True), SimpleNamespace(requires_motion=False)]
    settings = SimpleNamespace(hazard=None, free_motion_s=0.0)
    runtime = SimpleNamespace(jobs=1)
    cost = check_cost(procedures, _entries(3, 1000), 2, settings, runtime)
    # per object and record: 15 stripes (the 14 of the lattice √2 apart, 0.0625–5.66 g, and
    # the site's) × (the object + 12 scanned widths + 2 targets × 6 halvings) = 375 blocks; 10 periods × (1 + 16 widths tried) for the 1 procedure reading
    # the record = 170 oscillators
    assert cost.work.startswith("750 blocks and 340 oscillators × 3 record(s)")
    assert cost.seconds == pytest.approx(3000 * 750 / guards.ROCKING_SAMPLES_PER_S
                                         + 3000 * 340 / guards.OSCILLATOR_SAMPLES_PER_S)
    with_hazard = check_cost(procedures, _entries(3, 1000), 2,
                             SimpleNamespace(hazard=object(), free_motion_s=0.0), runtime)
    # a third target (the risk) and each procedure's width: 15 × (1 + 12 + 3 × 6 + 2) = 495
    assert with_hazard.work.startswith("990 blocks")
    # one of the two objects read from an atlas: its width search not solved, 15 × 1 for it
    from_atlas = check_cost(procedures, _entries(3, 1000), 2, settings, runtime, searched=1)
    assert from_atlas.work.startswith("390 blocks and 340 oscillators")


def test_ten_thousand_objects_refused_with_the_estimate_and_force(workdir, capsys):
    rows = "\n".join(f"o{i},{0.3 + 1e-4 * i:.4f},{1.5 + 2e-4 * i:.4f}" for i in range(10_000))
    (workdir / "inventory.csv").write_text("name,width_m,height_m\n" + rows + "\n")
    line = _refused(workdir, capsys, ["check", "--objects", "inventory.csv", "--site", "1.5,0.9",
                                      "--out", "out"],
                    "work: 3,750,000 blocks", "record(s)", "would take about",
                    "--objects, 10,000 of them", "--force")
    assert "force=True" not in line


def test_long_width_search_passes_report_each_record(monkeypatch):
    import records
    from audit.engine.check import widths as check_widths
    from audit.engine.check.settings import CheckSettings
    from audit.engine.shared.solver import Solver
    monkeypatch.setattr(check_widths, "PROGRESS_BLOCKS", 2)  # 1,000 blocks, made small
    pulse = records.one_pulse("cosine", 0.3, 1.0)
    entries = [SimpleNamespace(id=f"p{i}", motion=pulse) for i in range(2)]
    calls = []
    family = check_widths.Family(entries, np.array([0.1, 0.2]), {"p0": 0.3, "p1": 0.3},
                                 CheckSettings.parse(solver=Solver(free_motion_s=1.0)), 1, "local",
                                 lambda done, total, what, how: calls.append((done, total, what)))
    family.overturned([1.0], [0.2])  # one block: a short pass says nothing
    assert calls == []
    family.overturned([1.0, 1.0], [0.2, 0.3])
    assert calls == [(1, 2, "p0"), (2, 2, "p1")]


# --- noticed: text records, a campaign that all overturned, a tiny block -----------------------

TIMES = np.arange(200) * 0.01
ACC_G = 0.3 * np.sin(6.0 * TIMES)


def test_text_record_with_an_uncommented_header_line(tmp_path):
    path = tmp_path / "rec.txt"
    path.write_text("time acc(g)\n" + "\n".join(f"{t:.2f} {a:.5f}" for t, a in zip(TIMES, ACC_G)))
    motion = read_columns(path)
    assert motion.dt == pytest.approx(0.01) and motion.metadata["units"] == "g"
    assert motion.acceleration == pytest.approx(np.round(ACC_G, 5) * G)


def test_comma_separated_text_record(tmp_path):
    path = tmp_path / "rec.csv"
    path.write_text("% accelerations in g\n"
                    + "\n".join(f"{t:.2f}, {a:.5f}" for t, a in zip(TIMES, ACC_G)))
    motion = read_columns(path)
    assert motion.dt == pytest.approx(0.01)
    assert motion.acceleration == pytest.approx(np.round(ACC_G, 5) * G)


def test_comma_separated_header_without_units_says_units(tmp_path):
    path = tmp_path / "rec.csv"
    path.write_text("time_s,acc\n" + "\n".join(f"{t:.2f},{a:.5f}" for t, a in zip(TIMES, ACC_G)))
    with pytest.raises(InputError, match=r"units: not stated"):
        read_columns(path)


def test_decimal_commas_refused_as_such(tmp_path):
    path = tmp_path / "rec.txt"
    path.write_text("% in g, dt = 0.01\n" + "\n".join(f"{a:.5f}".replace(".", ",") for a in ACC_G))
    with pytest.raises(InputError, match=r"line 2: .* decimal commas"):
        read_columns(path)


def test_validation_page_of_a_campaign_where_every_test_overturned():
    from reports.validation_page import _fifty_percent_line
    rng = np.random.default_rng(1)
    tests = pd.DataFrame({"pga_g": rng.uniform(0.05, 0.8, 30),
                          "pgv_pga_s": rng.uniform(0.02, 0.3, 30),
                          "p_model": np.full(30, 0.995)})  # the model: all overturn
    fit = SimpleNamespace(alpha_deg=8.0, p_rad_s=3.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's "overflow encountered in exp" fails here
        assert _fifty_percent_line(tests, fit) is None  # no 50 % line crosses these tests
        # where the model's probabilities straddle 50 %, the line is drawn
        straddling = tests.assign(p_model=np.where(tests["pga_g"] > 0.4, 0.9, 0.1))
        line = _fifty_percent_line(straddling, fit)
    assert line is not None and np.all(np.isfinite(line["y"]))


def test_small_widths_printed_with_significant_figures():
    from audit.engine.check.words import metres
    assert metres(1e-5) == "1e-05 m"  # 10 µm, not "0.00 m"
    assert metres(0.0123) == "0.012 m"
    assert metres(0.6) == "0.60 m"  # centimetres from 10 cm, as before
