"""The front door's groups (FRONTDOOR.md): each checked once by its own ``parse``, which takes
its shorthand, names ``argument.field`` in its messages, and refuses a field the command does
not read; the command line shows its flag for every field a message names."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import audit
from audit.api import Building, Floor, Hazard, Records, Runtime, Site, Solver
from audit.cli.flags import FLAGS, with_flags
from audit.errors import InputError

REPO = Path(__file__).resolve().parents[2]


def _refused(name, call, *args, **kwargs) -> str:
    """The message of the InputError ``call`` raises, which must start with ``name`` and name
    it among its fields."""
    with pytest.raises(InputError) as caught:
        call(*args, **kwargs)
    message = str(caught.value)
    assert message.startswith(f"{name}:") or message.startswith(f"{name} "), message
    assert name in caught.value.fields, (message, caught.value.fields)
    return message


def test_the_groups_are_exported_from_audit_and_audit_api():
    from audit.engine.shared.design_site import Site as EngineSite
    from audit.physics.building.floor import Floor as PhysicsFloor
    from audit.engine.shared.record_request import Records as Request
    assert audit.Floor is Floor is PhysicsFloor and audit.Site is Site is EngineSite
    assert audit.Records is Records is Request
    for name in ("Building", "Floor", "Site", "Hazard", "Solver", "Runtime", "Records"):
        assert name in audit.api.__all__ and name in dir(audit)


# --- Floor and Building ------------------------------------------------------------------------

def test_floor_shorthand_is_the_ground_only():
    assert Floor.parse(None) == Floor.parse(0) == Floor.parse(0.0) == Floor()
    assert Floor().on_ground and Floor().building is None
    assert "Building(period_s" in _refused("floor", Floor.parse, 0.5)
    _refused("floor", Floor.parse, "roof")
    _refused("floor", Floor.parse, True)


def test_floor_fields_checked_and_named():
    _refused("floor.z_over_h", Floor.parse, Floor(1.5, Building(1.0)))
    _refused("floor.z_over_h", Floor.parse, Floor(math.nan, Building(1.0)))
    _refused("floor.building", Floor.parse, Floor(0.5))
    assert "needs T1" in _refused("floor.building.period_s", Floor.parse,
                                  Floor(0.5, Building(None)))
    _refused("floor.building.period_s", Floor.parse, Floor(0.5, Building(0.0)))
    _refused("floor.building.period_s", Floor.parse, Floor(0.5, Building(25.0)))
    _refused("floor.building.model", Floor.parse, Floor(0.5, Building(1.0, "frame:3")))
    # 0 < ζ < 1: critical damping and none are refused
    for damping in (0.0, 1.0, -0.1):
        assert "(0, 1)" in _refused("floor.building.damping", Floor.parse,
                                    Floor(1.0, Building(1.0, damping=damping)))
    # another argument's name where the floor is given as another argument
    _refused("where.building.model", Floor.parse, Floor(1.0, Building(1.0, "shear:0")), "where")


def test_a_malformed_building_is_refused_on_the_ground_too():
    _refused("floor.building.model", Floor.parse, Floor(0.0, Building(None, "shear:abc")))
    # a well-formed one is forgotten there: the ground has no building filter
    assert Floor.parse(Floor(0.0, Building(1.0, "shear:5"))) == Floor()


def test_a_parsed_floor_holds_its_building_typed():
    roof = Floor.parse(Floor(np.float64(1.0), Building(np.int64(2), "shear:10",
                                                       np.float32(0.5))))
    assert (roof.z_over_h, roof.building.period_s, roof.building.damping) == (1.0, 2.0, 0.5)
    assert type(roof.building.period_s) is float and type(roof.z_over_h) is float
    assert str(roof.building.model) == "shear:10" and not roof.on_ground
    # the default model, and the model None means
    assert str(Floor.parse(Floor(0.5, Building(1.0))).building.model) == "continuum:10"
    assert str(Floor.parse(Floor(0.5, Building(1.0, None))).building.model) == "continuum:10"
    assert roof.describe() == "at z/H = 1 of a building with T1 = 2 s (shear:10, ζ = 0.5)"
    assert Floor.parse(roof) == roof  # parsed twice, unchanged


def test_building_alone_and_not_a_building():
    assert Building.parse(Building(1.0)).period_s == 1.0
    _refused("building", Building.parse, 1.0)
    _refused("building.damping", Building.parse, Building(1.0, damping=2))


# --- Site --------------------------------------------------------------------------------------

def test_site_shorthand():
    assert Site.parse((1.5, 0.9)) == Site.parse("1.5,0.9") == Site.parse(Site(1.5, 0.9)) \
        == Site(1.5, 0.9)
    assert Site.parse(None) is None
    assert Site.parse("1.5,0.9").values_g == (1.5, 0.9)
    _refused("site", Site.parse, "1.5")
    _refused("site", Site.parse, "abc")
    _refused("site", Site.parse, (1.5, -0.9))
    _refused("site", Site.parse, 1.5)
    # per cent of g, or m/s², refused with the values in g
    assert "(1.5, 0.9)" in _refused("site", Site.parse, (150, 90))


def test_site_fields_checked_and_named():
    ntc = (0.25, 2.4, 0.3, "b", " t1 ")
    assert Site.parse(Site(1.5, 0.9, ntc=ntc)).ntc == (0.25, 2.4, 0.3, "B", "T1")
    _refused("site.ntc", Site.parse, Site(1.5, 0.9, ntc=(0.25, 2.4)))
    _refused("site.ntc", Site.parse, Site(1.5, 0.9, ntc="0.25,2.4,0.3,B,T1"))
    assert Site.parse(Site(1.5, 0.9, limit_state="slv")).limit_state == "SLV"
    assert Site.parse(Site(1.5, 0.9, limit_state="Both")).limit_state == "both"
    _refused("site.limit_state", Site.parse, Site(1.5, 0.9, limit_state="ULS"))
    _refused("site.level", Site.parse, Site(1.5, 0.9, level="MCE"))
    _refused("site.override", Site.parse, Site(1.5, 0.9, override="yes"))
    assert "needs site.scale_records" in _refused(
        "site.anchor_period_s", Site.parse, Site(1.5, 0.9, anchor_period_s=2.0))
    _refused("site.anchor_period_s", Site.parse,
             Site(1.5, 0.9, scale_records=True, anchor_period_s=0))
    # an NTC 2018 site alone: no FEMA 356 values, so nothing to scale to or override with
    alone = Site.parse(Site(None, None, ntc=ntc))
    assert alone.values_g is None and alone.ntc[0] == 0.25
    _refused("site.override", Site.parse, Site(None, None, ntc=ntc, scale_records=True))
    _refused("site", Site.parse, Site(None, None))


@pytest.mark.parametrize("command, site, name, readers", [
    ("check", Site(1.5, 0.9, level="design"), "site.level", "margins only"),
    ("check", Site(1.5, 0.9, scale_records=True), "site.scale_records", "run and margins only"),
    ("check", Site(1.5, 0.9, override=True), "site.override", "run only"),
    ("run", Site(1.5, 0.9, limit_state="SLV"), "site.limit_state", "check only"),
    ("margins", Site(1.5, 0.9, override=True), "site.override", "run only"),
])
def test_a_site_field_the_command_does_not_read_is_refused(command, site, name, readers):
    assert _refused(name, Site.parse, site, command).endswith(readers)


def test_a_site_field_at_its_default_is_accepted_by_every_command():
    for command in ("check", "run", "margins"):
        assert Site.parse(Site(1.5, 0.9, limit_state="both", level="mce"), command).sxs_g == 1.5


# --- Hazard ------------------------------------------------------------------------------------

def test_hazard_shorthand_and_fields(tmp_path):
    curve = tmp_path / "curve.csv"
    assert Hazard.parse(str(curve)) == Hazard(curve)
    assert Hazard.parse(None) is None
    read = Hazard.parse(Hazard(curve, imt="SA(1.0)", location="-118,34", poe="2%",
                               risk_target="1%"))
    assert (read.location, read.poe, read.risk_target) == ((-118.0, 34.0), 0.02, 0.01)
    _refused("hazard", Hazard.parse, 42)
    _refused("hazard.curve", Hazard.parse, Hazard(42))
    _refused("hazard.location", Hazard.parse, Hazard(curve, location=(-118, 134)))
    _refused("hazard.imt", Hazard.parse, Hazard(curve, imt=1.0))
    _refused("hazard.risk_target", Hazard.parse, Hazard(curve, risk_target=1.5))
    _refused("hazard.return_period", Hazard.parse, Hazard(curve, return_period=1))
    _refused("hazard.return_period", Hazard.parse, Hazard(curve, return_period=2475, poe=0.02))


def test_hazard_without_a_curve_reads_nothing_on_it():
    # the risk target alone is checked (the command line gives it whatever the curve)
    assert Hazard.parse(Hazard(None, risk_target="2%")).risk_target == 0.02
    _refused("hazard.risk_target", Hazard.parse, Hazard(None, risk_target="two"))
    for field in ("imt", "location", "return_period", "poe"):
        assert "no curve given" in _refused(f"hazard.{field}", Hazard.parse,
                                            Hazard(None, **{field: "SA(1.0)"}))


def test_hazard_return_period_is_check_only(tmp_path):
    assert Hazard.parse(Hazard(tmp_path, return_period=2475), "check").return_period == 2475
    assert _refused("hazard.return_period", Hazard.parse, Hazard(tmp_path, return_period=2475),
                    "margins").endswith("check only")
    _refused("hazard.poe", Hazard.parse, Hazard(tmp_path, poe="2%"), "margins")


# --- Solver ------------------------------------------------------------------------------------

def test_solver_defaults_and_fields():
    from audit.physics.block import Restitution
    solver = Solver.parse(None)
    assert solver.restitution == Restitution() and (solver.g, solver.vertical) == (audit.G, False)
    assert str(Solver.parse(Solver("x0.9")).restitution) == "x0.9"
    _refused("solver.restitution", Solver.parse, Solver("elastic"))
    _refused("solver.free_motion_s", Solver.parse, Solver(free_motion_s=-1))
    _refused("solver.g", Solver.parse, Solver(g=0))
    _refused("solver.vertical", Solver.parse, Solver(vertical="no"))
    _refused("solver", Solver.parse, "housner")
    # a function whose own keywords are the fields names them alone
    _refused("restitution", Solver.parse, Solver("elastic"), None, None)


def test_vertical_is_read_by_run_only():
    assert Solver.parse(Solver(vertical=True), "run").vertical
    for command in ("check", "margins"):
        assert _refused("solver.vertical", Solver.parse, Solver(vertical=True),
                        command).endswith("run only")


# --- Runtime -----------------------------------------------------------------------------------

def test_runtime_fields(tmp_path):
    runtime = Runtime.parse(Runtime(jobs=np.int64(3), force=True, progress=True,
                                    partial_dir=str(tmp_path), resume=True))
    assert (runtime.jobs, runtime.force, runtime.progress, runtime.partial_dir) == \
        (3, True, True, tmp_path)
    assert Runtime.parse(None) == Runtime() and Runtime.parse(Runtime(progress=False)).progress \
        is None
    _refused("runtime.jobs", Runtime.parse, Runtime(jobs=0))
    _refused("runtime.scheduler", Runtime.parse, Runtime(scheduler="cluster"))
    _refused("runtime.force", Runtime.parse, Runtime(force="yes"))
    _refused("runtime.progress", Runtime.parse, Runtime(progress="bar"))
    _refused("runtime.resume", Runtime.parse, Runtime(resume=True))
    _refused("runtime", Runtime.parse, 2)
    _refused("jobs", Runtime.parse, Runtime(jobs=1.5), None)


# --- Records -----------------------------------------------------------------------------------

def test_records_shorthand_and_reading_options():
    assert Records.parse("pulses") == Records("pulses") and Records.parse(None) == Records()
    assert Records.parse(Records("f.txt", dt_s=np.float32(0.5), units="g")).dt_s == 0.5
    _refused("records.dt_s", Records.parse, Records("f.txt", dt_s="0.01 s"))
    _refused("records.dt_s", Records.parse, Records("f.txt", dt_s=0))
    _refused("records.units", Records.parse, Records("f.txt", units="gal"))
    _refused("records.skip_bad_records", Records.parse, Records("f", skip_bad_records="yes"))
    _refused("dt_s", Records.parse, Records("f.txt", dt_s=-1), None)


def test_record_suite_reads_a_records_request(tmp_path):
    from audit.api.inputs import record_suite
    record = tmp_path / "rec.txt"
    record.write_text("\n".join(f"{0.1 * (i % 5):g}" for i in range(50)) + "\n")
    suite = record_suite(Records(record, dt_s=0.02, units="g"))
    assert len(suite) == 1 and suite.entries[0].motion.dt == 0.02
    with pytest.raises(InputError, match="dt: not stated"):  # no time step stated or given
        record_suite(record)


# --- the command line's flags ------------------------------------------------------------------

GROUP_FIELDS = {
    "floor": ("z_over_h", "building", "building.period_s", "building.model", "building.damping"),
    "site": ("ntc", "limit_state", "level", "override", "scale_records", "anchor_period_s"),
    "hazard": ("curve", "imt", "location", "return_period", "poe", "risk_target"),
    "solver": ("restitution", "free_motion_s", "vertical"),
    "runtime": ("jobs", "scheduler", "resume", "partial_dir", "force"),
    "records": ("dt_s", "units", "skip_bad_records"),
}


def test_every_group_field_a_flag_carries_has_its_flag():
    for argument, fields in GROUP_FIELDS.items():
        for field in fields:
            name = f"{argument}.{field}"
            assert FLAGS[name].startswith("--"), name
            assert with_flags(f"{name}: bad", (name,)) == f"{FLAGS[name]}: bad"


def test_a_group_field_is_replaced_whole():
    message = ("site.override and site.scale_records need site (S_XS, S_X1); "
               "floor.building.model: shear:abc")
    assert with_flags(message, ("site.override", "site.scale_records", "site",
                                "floor.building.model")) == (
        "--site-override and --scale-to-site need --site (S_XS, S_X1); "
        "--building-model: shear:abc")
    assert with_flags("floor.building.period_s: needs T1", ("floor", "floor.building.period_s")) \
        == "--building: needs T1"


# --- a narrow front door -----------------------------------------------------------------------

@pytest.mark.parametrize("name", ["check", "run", "margins"])
def test_check_run_margins_take_at_most_15_parameters_none_of_them_open(name):
    import inspect
    parameters = inspect.signature(getattr(audit, name)).parameters.values()
    assert len(parameters) <= 15, (name, len(parameters))
    assert not [p for p in parameters if p.kind in (p.VAR_KEYWORD, p.VAR_POSITIONAL)]


@pytest.mark.parametrize("settings", ["audit.engine.check.settings:CheckSettings",
                                      "audit.engine.run.settings:AuditSettings",
                                      "audit.engine.design.settings:MarginsSettings"])
def test_each_settings_parse_takes_explicit_keywords(settings):
    import importlib
    import inspect
    module, _, name = settings.partition(":")
    parameters = inspect.signature(getattr(importlib.import_module(module), name).parse) \
        .parameters.values()
    assert parameters and all(p.kind is p.KEYWORD_ONLY for p in parameters), settings


def test_no_module_of_the_api_reads_its_locals():
    """A keyword reaches its settings by name, never through ``locals()``."""
    import ast
    for path in sorted((REPO / "audit" / "api").glob("*.py")):
        calls = [node.lineno for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
                 if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                 and node.func.id in ("locals", "vars")]
        assert not calls, (path.name, calls)


def test_check_needs_the_fema_values_of_its_site():
    for site in (None, Site(None, None, ntc=(0.25, 2.4, 0.3, "B", "T1"))):
        assert "required" in _refused("site", audit.check, ["0.6x1.8"], site, records="pulses")
