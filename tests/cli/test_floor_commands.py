"""Every command that rocks blocks takes the object's floor; ``floor-motion`` writes it."""

import json
from dataclasses import replace

import numpy as np
import pytest

import audit
from audit import G
from audit.cli import main
from audit.engine.shared.intensity import IntensityMeasure
from audit.errors import InputError
from tests.physics.test_floors import _state_space_floor


@pytest.fixture(scope="module")
def far_field():
    from records import p695_suite
    return p695_suite("p695-far-field")


@pytest.mark.parametrize("z_over_h", ["1.0", "0.5"])
def test_floor_motion_command_equals_state_space(tmp_path, capsys, far_field, z_over_h):
    out = tmp_path / "floor.csv"
    code = main(["floor-motion", "--record", "rsn1111_nis000", "--records", "p695-far-field",
                 "--building", "1.0", "--building-model", "shear:10", "--building-damping",
                 "0.05", "--floor", z_over_h, "--csv", str(out)])
    assert code == 0
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    assert open(out).readline().strip() == "time_s,acceleration_g"
    ground = far_field.get("rsn1111_nis000").motion
    reference = _state_space_floor(ground.acceleration, ground.dt, 10, 1.0, 0.05,
                                   float(z_over_h)) / G
    n = ground.acceleration.size
    np.testing.assert_allclose(table[:n, 0], np.arange(n) * ground.dt, atol=1e-9)
    assert np.max(np.abs(table[:n, 1] - reference)) <= 1e-3 * np.max(np.abs(reference))
    printed = capsys.readouterr().out
    # PFA printed is the peak of the CSV's column (within its 4 printed digits)
    pfa = float(printed.split("PFA = ")[1].split(" g")[0])
    assert pfa == pytest.approx(np.max(np.abs(table[:, 1])), rel=1e-3)
    assert "shear:10" in printed and f"z/H = {float(z_over_h):g}" in printed


def test_bad_floor_flags_stop_with_one_line_and_no_file(tmp_path, capsys):
    out = tmp_path / "floor.csv"
    for argv, flag in ((["--floor", "1.5", "--building", "1"], "--floor"),
                       (["--floor", "0.5"], "--building"),
                       (["--building", "1", "--building-model", "frame:3"], "--building-model"),
                       (["--building", "1", "--building-damping", "0"], "--building-damping")):
        code = main(["floor-motion", "--record", "rsn1111_nis000", "--records",
                     "p695-far-field", "--csv", str(out), *argv])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and flag in err[0], (argv, err)
        assert not out.exists()


def test_api_refuses_a_bad_floor_naming_the_field(far_field):
    block = audit.Block.from_dimensions(width_m=0.8, height_m=2.0)
    with pytest.raises(InputError) as info:
        audit.rock(block, "rsn1111_nis000", records=far_field, floor=audit.Floor(0.5))
    assert info.value.fields == ("floor.building",) or "floor.building" in str(info.value)
    with pytest.raises(InputError, match="floor"):
        audit.rock(block, "rsn1111_nis000", records=far_field,
                   floor=audit.Floor(-0.1, audit.Building(1.0)))


def test_floor_motion_is_linear_and_keeps_the_ground_intensity(far_field):
    from audit.physics.building.floor import Building, Floor
    from audit.physics.building.floor_motion import floor_motion
    ground = far_field.get("rsn1111_nis000").motion
    floor = Floor.parse(Floor(1.0, Building(1.0, "continuum:5")))
    on_roof = floor_motion(ground, floor)
    np.testing.assert_allclose(floor_motion(ground.scaled(2.5), floor).acceleration,
                               on_roof.scaled(2.5).acceleration, rtol=1e-12, atol=1e-12)
    for im in ("pga", "sa:1.0"):
        measure = IntensityMeasure.parse(im)
        assert measure.of_record(on_roof.scaled(1.7), 0.0) == pytest.approx(
            measure.of_record(ground.scaled(1.7), 0.0), rel=1e-12)
    with pytest.raises(InputError, match="already the motion of a floor"):
        floor_motion(on_roof, floor)


def test_rock_on_the_roof_rocks_on_the_floor_motion(far_field):
    block = audit.Block.from_dimensions(width_m=0.8, height_m=2.0)
    on_roof = audit.rock(block, "rsn1111_nis000", records=far_field,
                         floor=audit.Floor(1.0, audit.Building(1.0, "shear:10")))
    from audit.physics.building.floor import Building, Floor
    from audit.physics.building.floor_motion import floor_motion
    motion = floor_motion(far_field.get("rsn1111_nis000").motion,
                          Floor.parse(Floor(1.0, Building(1.0, "shear:10"))))
    direct = audit.rock(block, motion)
    assert on_roof.peak == direct.peak and on_roof.overturned == direct.overturned
    assert on_roof.as_dict()["floor"]["building_model"] == "shear:10"
    assert audit.rock(block, "rsn1111_nis000", records=far_field).as_dict()["floor"][
        "z_over_h"] == 0.0


def test_check_on_a_floor_names_it_and_reports_each_records_peaks(far_field):
    two = replace(far_field, entries=far_field.entries[:2])
    result = audit.check(["0.8x2.0"], site=(1.0, 0.6), procedures="fema356", records=two,
                         floor=audit.Floor(1.0, audit.Building(1.0, "shear:10")))
    floor = result.document["floor"]
    assert floor["z_over_h"] == 1.0 and floor["building_model"] == "shear:10"
    assert floor["building_period_s"] == 1.0 and floor["building_damping"] == 0.05
    assert set(floor["records"]) == {e.id for e in two.entries}
    # each record's PFA at the site: its floor motion, scaled so that its ground Sa(1 s) is S_X1
    from audit.physics.building.floor import Building, Floor
    from audit.physics.building.floor_motion import floor_motion
    measure = IntensityMeasure.parse("sa:1.0")
    for entry in two.entries:
        factor = 0.6 / measure.of_record(entry.motion, 10.0)
        on_floor = floor_motion(entry.motion.scaled(factor),
                                Floor.parse(Floor(1.0, Building(1.0, "shear:10"))))
        assert floor["records"][entry.id]["pfa_g"] == pytest.approx(on_floor.pga_g, rel=1e-9)
    assert "z/H = 1" in result.summary_text() and "shear:10" in result.summary_text()
    on_ground = audit.check(["0.8x2.0"], site=(1.0, 0.6), procedures="fema356", records=two)
    assert on_ground.document["floor"]["z_over_h"] == 0.0
    files = result.files()
    assert json.loads(files["check.json"])["floor"]["building_model"] == "shear:10"
    header, row = files["check.csv"].decode().splitlines()[:2]
    named = dict(zip(header.split(","), row.split(",")))
    assert (named["floor_z_over_h"], named["building_period_s"], named["building_model"]) == \
        ("1", "1", "shear:10")
    spectra = floor["spectra"]
    # the building amplifies near its first period: the roof's median Sa(1 s) well above the
    # ground's (which is S_X1 = 0.6 g for every record at the site, so its median too)
    at_1s = int(np.argmin(np.abs(np.array(spectra["period_s"]) - 1.0)))
    assert spectra["floor_median_sa_g"][at_1s] > 2 * spectra["ground_median_sa_g"][at_1s]
