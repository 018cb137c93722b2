"""Readers, manifests, pulses and bad input, against the published facts of SOURCES.md."""

import math

import numpy as np
import pytest

from audit import G
from audit.errors import InputError
from records import (ENV_VARIABLE, load_manifest, load_records, one_pulse, pulse_suite,
                     read_at2, read_columns, record_facts)

# SOURCES.md, "Computed PGA g / PGV m/s" (g = 9.80665 for cm/s² files; PGV by the same processing)
SOURCES_FACTS = [
    ("raw/RSN77_SFERN_PUL164.AT2", "at2", None, 1.219, 1.144),
    ("raw/Rinaldi228.AT2", "at2", None, 0.874, 1.479),
    ("raw/Rinaldi318.AT2", "at2", None, 0.472, 0.747),
    ("raw/NGA_no_1063_RRS228.AT2", "at2", None, 0.825, 1.601),
    ("raw/RSN1120_KOBE_TAK090.AT2", "at2", None, 0.671, 1.229),
    ("raw/RSN879_LANDERS_LCN260.AT2", "at2", None, 0.725, 1.334),
    ("raw/RSN879_LANDERS_LCN345.AT2", "at2", None, 0.789, 0.281),
    ("raw/RSN181_IMPVALL.H_H-E06230.AT2", "at2", None, 0.449, 1.135),
    ("raw/RSN181_IMPVALL.H_H-E06140.AT2", "at2", None, 0.447, 0.670),
    ("raw/rinaldi.txt", "cols", (1, 0.005, "cm/s2"), 0.840, 1.596),
    ("raw/rinaldi.txt", "cols", (2, 0.005, "cm/s2"), 0.476, 0.751),
    ("raw/sylmar.txt", "cols", (1, 0.005, "cm/s2"), 0.875, 1.292),
    ("raw/erzikan.txt", "cols", (1, 0.005, "cm/s2"), 0.515, 0.839),
    ("raw/erzikan.txt", "cols", (2, 0.005, "cm/s2"), 0.496, 0.647),
    ("raw/jiji.txt", "cols", (1, 0.005, "cm/s2"), 0.512, 3.243),
    ("raw/newhall.txt", "cols", (1, 0.005, "cm/s2"), 0.736, 1.180),
    ("derived/P695NF_RSN1086_NORTHR_SYL_032.txt", "cols", (1, None, None), 0.733, 1.227),
    ("derived/P695NF_RSN1063_NORTHR_RRS_032.txt", "cols", (1, None, None), 0.870, 1.670),
    ("derived/P695NF_RSN821_ERZIKAN_ERZ_032.txt", "cols", (1, None, None), 0.486, 0.956),
]


@pytest.mark.parametrize("name,kind,columns,pga_g,pgv", SOURCES_FACTS)
def test_every_shared_file_matches_sources(records_dir, name, kind, columns, pga_g, pgv):
    path = records_dir / name
    motion = read_at2(path) if kind == "at2" else read_columns(path, *columns)
    # SOURCES.md converts with g = 9.80665; the tool's g is 9.81 (SPEC §2)
    assert motion.pga_g * G / 9.80665 == pytest.approx(pga_g, rel=0.005)
    assert motion.pgv == pytest.approx(pgv, rel=0.005)
    assert len(motion.sha256) == 64


def test_at2_header_layouts_and_counts(records_dir):
    west2 = read_at2(records_dir / "raw/RSN1120_KOBE_TAK090.AT2")
    west1 = read_at2(records_dir / "raw/NGA_no_1063_RRS228.AT2")
    poles = read_at2(records_dir / "raw/Rinaldi228.AT2")
    assert (west2.acceleration.size, west2.dt) == (4096, 0.01)
    assert (west1.acceleration.size, west1.dt) == (1991, 0.01)
    assert (poles.acceleration.size, poles.dt) == (1991, 0.01)
    # first value of the Kobe file is .2668067E-02 g (no leading zero)
    assert west2.acceleration[0] == pytest.approx(0.002668067 * G, rel=1e-12)


def test_derived_header_gives_dt_units_and_npts(records_dir):
    motion = read_columns(records_dir / "derived/P695NF_RSN1086_NORTHR_SYL_032.txt")
    assert motion.dt == 0.02 and motion.acceleration.size == 2000
    assert motion.acceleration[0] == pytest.approx(8.4189550e-03 * G)


def test_seed_manifest_keeps_missing_records(seed_suite):
    ids = [entry.id for entry in seed_suite]
    assert ids == ["pacoima_dam_1971", "el_centro_5_1979", "los_gatos_1989", "rinaldi_1994",
                   "sylmar_1994", "erzincan_1992", "takatori_1995"]
    assert [e.id for e in seed_suite if e.missing] == ["el_centro_5_1979", "los_gatos_1989"]
    assert seed_suite.get("pacoima_dam_1971").site == {"site_class": "B", "sxs_g": 1.59,
                                                       "sx1_g": 0.50}
    assert seed_suite.get("erzincan_1992").site == {}


def test_extras_manifest(records_dir):
    suite = load_manifest(records_dir / "extras.toml")
    assert len(suite) == 6 and not any(e.missing for e in suite)


def test_folder_of_at2_files(records_dir):
    # the folder holds Pacoima Dam's PEER file (RSN 77, PUL164): the seven seed records, that
    # one read from the folder under its catalogue id, then the eight other .AT2 files
    suite = load_records(records_dir / "raw")
    assert len(suite) == 7 + 8
    pacoima = suite.get("pacoima_dam_1971")
    assert pacoima.motion.pga_g == pytest.approx(1.219 * 9.80665 / G, rel=0.005)
    assert pacoima.metadata == {"rsn": 77, "peer_file": "RSN77_SFERN_PUL164.AT2"}
    assert suite.get("RSN1120_KOBE_TAK090").motion.pga_g == pytest.approx(0.671 * 9.80665 / G,
                                                                          rel=0.005)


def test_unit_conversion(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("% test\n981\t-4.905\n0 0\n")
    assert read_columns(path, 1, 0.01, "cm/s2").acceleration[0] == pytest.approx(9.81)
    assert read_columns(path, 2, 0.01, "m/s2").acceleration[0] == pytest.approx(-4.905)
    assert read_columns(path, 2, 0.01, "g").pga_g == pytest.approx(4.905)


def test_wrong_units_are_caught(records_dir, tmp_path):
    """A cm/s² file declared in g would be an 84 g record: refused, naming file and field."""
    with pytest.raises(InputError, match=r"rinaldi.txt: units: read as 'g', the PGA would be 8"):
        read_columns(records_dir / "raw/rinaldi.txt", 1, 0.005, "g")
    manifest = tmp_path / "m.toml"
    manifest.write_text(f'[[record]]\nid = "r"\nfile = "{records_dir / "raw/rinaldi.txt"}"\n'
                        'format = "columns"\ndt = 0.005\nunits = "m/s2"\n')
    with pytest.raises(InputError, match="units: read as 'm/s2'"):
        load_manifest(manifest)


def test_pulse_shapes():
    cosine = one_pulse("cosine", 0.5, 2.0)
    t, a = cosine.time, cosine.acceleration
    assert a[0] == pytest.approx(0.5 * G)
    assert np.interp(1.0, t, a) == pytest.approx(-0.5 * G)
    assert cosine.duration == pytest.approx(2.0)
    # velocity of a one-cosine pulse peaks at a_p T_p / (2π)
    assert cosine.pgv == pytest.approx(0.5 * G * 2.0 / (2 * math.pi), rel=1e-5)
    sine = one_pulse("sine", 0.3, 1.0)
    assert np.interp(0.25, sine.time, sine.acceleration) == pytest.approx(0.3 * G)
    assert np.interp(0.75, sine.time, sine.acceleration) == pytest.approx(-0.3 * G)
    assert sine.acceleration[0] == 0.0


def test_pulse_suite_is_table_5_1():
    suite = pulse_suite()
    assert suite.is_pulse_idealised and len(suite) == 7
    rinaldi = suite.get("rinaldi_1994").motion
    assert rinaldi.pga_g == pytest.approx(0.838) and rinaldi.pulse.period_s == 1.0
    takatori = suite.get("takatori_1995")
    assert takatori.motion.pulse.period_s == 1.0 and "assumed" in takatori.component


def test_source_precedence(monkeypatch, tmp_path):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    assert [e.id for e in load_records() if not e.missing] == ["rinaldi_1994", "sylmar_1994",
                                                               "erzincan_1992"]
    manifest = tmp_path / "m.toml"
    data = tmp_path / "x.txt"
    data.write_text("1\n2\n3\n")
    manifest.write_text('[[record]]\nid = "x"\nfile = "x.txt"\nformat = "columns"\ndt = 0.01\n'
                        'units = "g"\n')
    monkeypatch.setenv(ENV_VARIABLE, str(manifest))
    assert [e.id for e in load_records()] == ["x"]
    assert load_records(None).get("x").motion.pga_g == pytest.approx(3.0)
    explicit = tmp_path / "y.txt"
    explicit.write_text("% Acc. in cm/sec^2 and dt=0.02 sec.\r\n981\r\n0\r\n")
    chosen = load_records(explicit).get("y").motion  # an explicit path wins over the variable
    assert chosen.dt == 0.02 and chosen.pga_g == pytest.approx(1.0)
    with pytest.raises(InputError, match="not found"):
        load_records(tmp_path / "nope.toml")


AT2_HEADER = ("PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 90\n"
              "ACCELERATION TIME SERIES IN UNITS OF G\n")


@pytest.mark.parametrize("content,message", [
    (AT2_HEADER, "truncated header"),
    (AT2_HEADER + "NPTS=    3, DT=   .0100 SEC,\n .1 .2\n", "header says 3 values, the file holds 2"),
    (AT2_HEADER + "NPTS=    3, DT=   .0100 SEC,\n .1 abc .3\n", "'abc' is not a number"),
    (AT2_HEADER + "NPTS=    3, DT=   .0100 SEC,\n .1 NaN .3\n", "not finite"),
    (AT2_HEADER + "NPTS=    3, DT=   .0100 SEC,\n .1 inf .3\n", "not finite"),
    (AT2_HEADER + "NPTS=    3, DT=   0.0 SEC,\n .1 .2 .3\n", "dt: must be a positive"),
    (AT2_HEADER + "NPTS=    3, DT=   -.01 SEC,\n .1 .2 .3\n", "dt: must be a positive"),
    (AT2_HEADER.replace("UNITS OF G", "UNITS OF FURLONGS") + "NPTS= 1, DT= .01 SEC,\n.1\n",
     "cannot tell the units"),
    (AT2_HEADER + "3 values follow\n .1 .2 .3\n", "line 4: expected"),
    ("", "file is empty"),
])
def test_bad_at2_files(tmp_path, content, message):
    path = tmp_path / "bad.AT2"
    path.write_text(content)
    with pytest.raises(InputError, match=message) as info:
        read_at2(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("content,kwargs,message", [
    ("1 2\n3\n", {"column": 2, "dt": 0.01, "units": "g"}, "line 2: column 2 missing"),
    ("1\n2\n", {"dt": 0.01, "units": "furlongs"}, "units: unknown 'furlongs'"),
    ("1\n2\n", {"units": "g"}, "dt: not stated"),
    ("1\n2\n", {"dt": 0.01}, "units: not stated"),
    ("1\n2\n", {"dt": -1.0, "units": "g"}, "dt: must be a positive"),
    ("% only comments\n", {"dt": 0.01, "units": "g"}, "no data lines"),
    ("1\nnan\n", {"dt": 0.01, "units": "g"}, "not finite"),
    ("# units: g ; dt = 0.01 s ; npts = 3\n1\n2\n", {}, "header says 3 values"),
])
def test_bad_column_files(tmp_path, content, kwargs, message):
    path = tmp_path / "bad.txt"
    path.write_text(content)
    with pytest.raises(InputError, match=message) as info:
        read_columns(path, **kwargs)
    assert str(path) in str(info.value)


@pytest.mark.parametrize("entry,message", [
    ('id = "a"\nfile = "a.txt"\nformat = "mseed"', "format: unknown 'mseed'"),
    ('id = "a"\nfile = "nothere.txt"\nformat = "columns"', "file: .*nothere.txt not found"),
    ('id = "a"\nformat = "columns"', "file: missing"),
    ('file = "a.txt"', "id: missing"),
    ('id = "a"\nfile = "a.txt"\nformat = "columns"\ncolum = 2', "unknown field"),
])
def test_bad_manifests(tmp_path, entry, message):
    (tmp_path / "a.txt").write_text("1\n2\n")
    manifest = tmp_path / "m.toml"
    manifest.write_text(f"[[record]]\n{entry}\n")
    with pytest.raises(InputError, match=message) as info:
        load_manifest(manifest)
    assert str(manifest) in str(info.value)


def test_malformed_toml_and_unknown_id(tmp_path):
    manifest = tmp_path / "m.toml"
    manifest.write_text("[[record]\nid=")
    with pytest.raises(InputError, match="not valid TOML"):
        load_manifest(manifest)
    with pytest.raises(InputError, match="unknown 'nope'"):
        record_facts("nope")
    with pytest.raises(InputError, match="unknown 'nope'"):
        pulse_suite().get("nope")


# --- records as users have them: a time column, dt and units given, a suite name misspelt -----

def _time_file(path, times, values, header="# time [s]  acceleration [g]"):
    path.write_text(header + "\n" + "\n".join(f"{t}\t{v:.6e}" for t, v in zip(times, values))
                    + "\n")
    return path


SINE_G = 0.3 * np.sin(2 * np.pi * np.arange(600) * 0.005)  # 3 s at 200 Hz, PGA 0.3 g


def test_a_time_column_gives_the_step_and_is_not_read_as_acceleration(tmp_path):
    times = [f"{0.005 * i:.3f}" for i in range(SINE_G.size)]
    motion = read_columns(_time_file(tmp_path / "t.txt", times, SINE_G))
    assert motion.dt == pytest.approx(0.005, rel=1e-12)
    np.testing.assert_allclose(motion.acceleration, SINE_G * G, rtol=1e-6)
    assert motion.metadata["column"] == 2
    # the same through load_records, a manifest without column, and a dt that agrees
    assert load_records(tmp_path / "t.txt").get("t").motion.dt == pytest.approx(0.005)
    (tmp_path / "m.toml").write_text('[[record]]\nid = "t"\nfile = "t.txt"\n'
                                     'format = "columns"\ndt = 0.005\n')
    assert load_manifest(tmp_path / "m.toml").get("t").motion.pga_g == pytest.approx(0.3,
                                                                                    rel=1e-5)


def test_times_printed_coarser_than_the_tolerance_are_read_at_their_mean_step(tmp_path):
    # 300 Hz printed to 3 decimals: each time off by up to 0.5 ms, 15 % of a step
    times = [f"{i / 300:.3f}" for i in range(SINE_G.size)]
    motion = read_columns(_time_file(tmp_path / "t.txt", times, SINE_G))
    assert motion.dt == pytest.approx(float(times[-1]) / (SINE_G.size - 1), rel=1e-12)


@pytest.mark.parametrize("change, kwargs, message", [
    ({300: "1.502"}, {}, r"line 302: time: 1\.502 s is 0\.002 s off the uniform step 0\.005 s"),
    ({300: "1.495"}, {}, r"line 302: time: 1\.495 s does not come after 1\.495 s"),
    ({}, {"dt": 0.01}, r"dt: 0\.01 s given, the time column steps 0\.005 s"),
])
def test_a_bad_time_column_is_refused_naming_the_line(tmp_path, change, kwargs, message):
    times = [change.get(i, f"{0.005 * i:.3f}") for i in range(SINE_G.size)]
    path = _time_file(tmp_path / "t.txt", times, SINE_G)
    with pytest.raises(InputError, match=message) as info:
        read_columns(path, **kwargs)
    assert str(info.value).startswith(f"{path}: ")


def test_two_acceleration_columns_are_not_a_time_column(records_dir):
    # rinaldi.txt: FN and FP accelerations, dt and units in its comments (SOURCES.md)
    motion = read_columns(records_dir / "raw/rinaldi.txt")
    assert motion.metadata["column"] == 1 and motion.dt == 0.005
    assert motion.pga_g * G / 9.80665 == pytest.approx(0.840, rel=0.005)


def test_dt_and_units_of_a_single_column_file(tmp_path, monkeypatch):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    path = tmp_path / "one.txt"
    path.write_text("\n".join(f"{v * 981:.6e}" for v in SINE_G) + "\n")  # cm/s², no header
    with pytest.raises(InputError, match="one.txt: dt: not stated in the file"):
        load_records(path)
    with pytest.raises(InputError, match="one.txt: units: not stated in the file"):
        load_records(path, dt=0.005)
    motion = load_records(path, dt=0.005, units="cm/s2").get("one").motion
    assert motion.dt == 0.005 and motion.pga_g == pytest.approx(0.3 * 9.81 / G, rel=1e-5)
    for source in ("pulses", None):  # they state their own
        with pytest.raises(InputError, match="^dt: given for the suite"):
            load_records(source, dt=0.005)
    with pytest.raises(InputError, match="^units: given for the suite pulses"):
        load_records("pulses", units="g")


@pytest.mark.parametrize("name, suggestion", [
    ("p695-farfield", "p695-far-field"), ("p695-near-field-nopulse", "p695-near-field-no-pulse"),
    ("pulse", "pulses"),
])
def test_a_misspelt_suite_name_suggests_the_nearest(tmp_path, monkeypatch, name, suggestion):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError, match=f"^{name}: no such file or built-in suite; did you mean "
                                         f"'{suggestion}'\\?$"):
        load_records(name)
    with pytest.raises(InputError, match="^far-away.toml: file not found$"):
        load_records("far-away.toml")


def test_a_suite_counted_in_words_never_says_records_twice():
    """The pages' "N records of …" over every kind of description a suite gets: a manifest's
    ("records of manifest …") is not prefixed again."""
    from records.suite import counted_records
    assert counted_records(44, "the FEMA P695 far-field record set") == (
        "44 records of the FEMA P695 far-field record set")
    assert counted_records(5, "records of manifest suite.toml") == (
        "5 records of manifest suite.toml")
    assert counted_records(1, "the record file a.AT2") == "1 record of the record file a.AT2"
    assert counted_records(1, "records of manifest one.toml") == "1 record of manifest one.toml"
