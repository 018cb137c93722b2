"""Property: every public function of the API, given one argument of a wrong type (text with
units where a number is expected, None, a dict, a one-element or one-string pair, a number
where a path is expected, ...), or one field of a group (``solver.g``, ``floor.building.period_s``)
of a wrong type, raises InputError naming that argument or field, at the front door.

The work each function would start is replaced by a sentinel that raises: a wrong value that
slipped through the front door shows as that sentinel (or as a TypeError from inside), never as
a long computation."""

from __future__ import annotations


import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import audit
from audit.errors import InputError

UNIT_TEXTS = st.sampled_from(["0.01 s", "0.95 g", "1.5,0.9", "", " ", ".", "yes", "nan",
                              "1e400", "2 m"])
TEXTS = UNIT_TEXTS | st.text(max_size=6)
JUNK = st.sampled_from([{"a": 1}, {"median": "x"}, object(), 1 + 2j, b"0.5", Ellipsis])
NUMBERS = st.integers(-3, 3) | st.floats(allow_nan=False, allow_infinity=False, width=32)

NUMBER = TEXTS | JUNK | st.booleans() | st.lists(NUMBERS, min_size=1, max_size=2)
NUMBER_OR_NONE = NUMBER | st.none()
SEQUENCE = TEXTS | JUNK | st.booleans() | st.lists(TEXTS, min_size=1, max_size=2)
PAIR = (TEXTS | JUNK | NUMBERS | st.booleans() | st.tuples(NUMBERS)
        | st.tuples(NUMBERS, NUMBERS, NUMBERS) | st.tuples(UNIT_TEXTS, NUMBERS)
        | st.tuples(NUMBERS, UNIT_TEXTS))
FLAG = TEXTS | JUNK | st.none() | st.floats(0.1, 0.9) | st.just(2)
WHOLE = TEXTS | JUNK | st.none() | st.booleans() | st.floats(0.1, 0.9)
PATH = JUNK | NUMBERS | st.booleans() | st.lists(NUMBERS, min_size=1, max_size=2)
CALLBACK = TEXTS | JUNK | NUMBERS | st.none()
CHOICE = JUNK | NUMBERS | st.lists(st.just("pga"), min_size=1, max_size=2)
OBJECTS = st.none() | NUMBERS | JUNK
FRAGILITY = TEXTS | JUNK | st.none() | st.tuples(UNIT_TEXTS, NUMBERS) | st.tuples(NUMBERS)
NTC = TEXTS | JUNK | NUMBERS | st.tuples(UNIT_TEXTS, NUMBERS, NUMBERS, st.just("B"),
                                         st.just("T1"))
#: A design site: "S_XS,S_X1" text is one too, as ``--site`` passes it.
SITE_PAIR = PAIR.filter(lambda v: not _lon_lat_text(v))
#: How records are read: the time step [s] and units of a text record file, skipping the bad.
READING = {"dt_s": NUMBER, "units": CHOICE | UNIT_TEXTS, "skip_bad_records": FLAG}
READING_GROUP = {f"records.{name}": values for name, values in READING.items()}


class Started(Exception):
    """The work began: the argument passed the front door."""


def _start(*args, **kwargs):
    raise Started


@pytest.fixture(autouse=True)
def _no_work(monkeypatch):
    """The work of every function raises :class:`Started` instead."""
    import audit.engine.check.pipeline
    import audit.engine.fragility.pipeline
    import audit.engine.design.pipeline
    import audit.engine.run.pipeline
    import audit.engine.validation.pipeline
    import audit.physics.response_spectra
    import audit.physics.rocking
    import records.campaign
    for module, name in ((audit.engine.check.pipeline, "run_check"),
                         (audit.engine.run.pipeline, "run_audit"),
                         (audit.engine.design.pipeline, "run_margins"),
                         (audit.engine.validation.pipeline, "run_validation"),
                         (audit.engine.fragility.pipeline, "run_fragility"),
                         (audit.physics.rocking, "simulate"),
                         (audit.physics.rocking, "rocking_spectrum"),
                         (audit.physics.response_spectra, "response_spectra"),
                         (records.campaign, "read_campaign")):
        monkeypatch.setattr(module, name, _start)


def _lon_lat_text(value) -> bool:
    try:
        return isinstance(value, str) and len([float(v) for v in value.split(",")]) == 2
    except ValueError:
        return False


def _pulse():
    import records
    return records.one_pulse("cosine", 0.3, 1.0)


SITE = (1.5, 0.9)
ROOF = audit.Floor(1.0, audit.Building(1.0))
RUN = {"procedures": "fema356", "records": "pulses"}
#: A progress that is not one: None is the default (no progress).
PROGRESS = CALLBACK.filter(lambda v: v is not None)
#: How a wrong value of a group's field is given: the group with that field, the rest valid.
GROUPS = {
    "solver": lambda field, value: audit.Solver(**{field: value}),
    "runtime": lambda field, value: audit.Runtime(**{field: value}),
    "records": lambda field, value: audit.Records("pulses", **{field: value}),
    "hazard": lambda field, value: audit.Hazard("missing.csv", **{field: value}),
    "site": lambda field, value: audit.Site(*SITE, **{
        field: value, **({"scale_records": True} if field == "anchor_period_s" else {})}),
    "floor": lambda field, value: (
        audit.Floor(value, audit.Building(1.0)) if field == "z_over_h" else
        audit.Floor(1.0, audit.Building(**{"period_s": 1.0,
                                           field.removeprefix("building."): value}))),
}
#: The groups' fields every command reads alike.
SOLVER = {"solver": JUNK, "solver.restitution": JUNK, "solver.free_motion_s": NUMBER,
          "solver.g": NUMBER}
RUNTIME = {"runtime": JUNK | NUMBERS, "runtime.jobs": WHOLE, "runtime.scheduler": CHOICE,
           "runtime.progress": PROGRESS, "runtime.force": FLAG}
RECORDS = {"records.dt_s": NUMBER, "records.units": CHOICE | UNIT_TEXTS,
           "records.skip_bad_records": FLAG}
FLOOR = {"floor": NUMBER, "floor.z_over_h": NUMBER, "floor.building.period_s": NUMBER,
         "floor.building.damping": NUMBER, "floor.building.model": JUNK | NUMBERS | TEXTS}
#: function → (valid arguments, {argument: values of a wrong type}).
CASES = {
    "check": (audit.check, {"objects": ["0.6x1.8"], "site": SITE, "records": "pulses"}, {
        **READING_GROUP, "objects": OBJECTS, "site": SITE_PAIR, "procedures": OBJECTS,
        "records": PATH, "im": CHOICE, "seed": WHOLE.filter(lambda v: v is not None),
        "hazard": PATH, "site.ntc": NTC, "site.limit_state": CHOICE, **SOLVER, **RUNTIME,
        **FLOOR}),
    "check with a hazard": (audit.check, {"objects": ["0.6x1.8"], "site": SITE,
                                          "records": "pulses", "hazard": "missing.csv"},
                            # "LON,LAT" text is a site too (west and south negative)
                            {"hazard.location": PAIR.filter(lambda v: not _lon_lat_text(v)),
                             "hazard.risk_target": NUMBER, "hazard.imt": CHOICE,
                             "hazard.return_period": NUMBER, "hazard.poe": NUMBER}),
    "run": (audit.run, RUN, {
        "procedures": OBJECTS, "records": PATH, "alpha_deg": SEQUENCE, "size_s": SEQUENCE,
        "agree_band": NUMBER, "robustness": NUMBER, "friction": NUMBER, "sensitivity": CHOICE,
        "solver.vertical": FLAG, "site": SITE_PAIR, "site.override": FLAG,
        "site.scale_records": FLAG, "site.ntc": NTC, **READING_GROUP,
        "detail": JUNK | NUMBERS, "out_dir": PATH, "runtime.partial_dir": PATH,
        "runtime.resume": FLAG, **SOLVER, **RUNTIME, **FLOOR}),
    "run scaled": (audit.run, RUN, {"site.anchor_period_s": NUMBER}),
    "margins": (audit.margins, RUN, {
        "procedures": OBJECTS, "records": PATH, "im": CHOICE, "stripes": SEQUENCE,
        "alpha_deg": SEQUENCE, "size_s": SEQUENCE, "required": FLAG, "site.level": CHOICE,
        "hazard": PATH, "site": SITE_PAIR, "site.ntc": NTC, **READING_GROUP,
        "runtime.partial_dir": PATH, "runtime.resume": FLAG, **SOLVER, **RUNTIME, **FLOOR}),
    "margins with a hazard": (audit.margins, {**RUN, "hazard": "missing.csv"},
                              {"hazard.risk_target": NUMBER, "hazard.imt": CHOICE}),
    "rock": (audit.rock, {"block": audit.Block(alpha_deg=15.0, size_s=2.0), "motion": _pulse()},
             {"block": OBJECTS | TEXTS, "motion": OBJECTS, "solver": JUNK | TEXTS,
              "solver.free_motion_s": NUMBER, "solver.restitution": JUNK,
              "solver.vertical": FLAG, "solver.g": NUMBER.filter(lambda v: v != 9.81),
              "friction": NUMBER, "runtime": JUNK | TEXTS, "runtime.force": FLAG,
              "runtime.jobs": st.just(3), "floor": NUMBER, **RECORDS}),
    "rock by id": (audit.rock, {"block": audit.Block(alpha_deg=15.0, size_s=2.0),
                                "motion": "pacoima_dam_1971"}, {"records": PATH}),
    "Block": (audit.Block, {"alpha_deg": 15.0, "size_s": 2.0},
              {"alpha_deg": NUMBER_OR_NONE, "size_s": NUMBER_OR_NONE, "r": NUMBER,
               "g": NUMBER_OR_NONE}),
    "Block.from_dimensions": (audit.Block.from_dimensions, {"width_m": 0.6, "height_m": 1.8},
                              {"width_m": NUMBER_OR_NONE, "height_m": NUMBER_OR_NONE,
                               "r": NUMBER, "g": NUMBER_OR_NONE}),
    "fragility": (audit.fragility, {"records": "pulses"},
                  {"procedure": CHOICE, "records": PATH, **RECORDS, "progress": FLAG,
                   "floor": NUMBER}),
    "validate": (audit.validate, {"folder": "campaign"},
                 {"folder": PATH | st.none(), "geometry": PATH, "folds": WHOLE, "jobs": WHOLE,
                  "free_motion_s": NUMBER, "band_pass": FLAG, "progress": CALLBACK,
                  "settings": JUNK | TEXTS | NUMBERS}),
    "rocking_spectrum": (audit.rocking_spectrum, {"motion": _pulse(), "size_s": [1.0],
                                                  "alpha_deg": [15.0]},
                         {"motion": OBJECTS, "size_s": SEQUENCE | st.none(),
                          "alpha_deg": SEQUENCE | st.none(), "solver.restitution": JUNK,
                          "solver.free_motion_s": NUMBER, "solver.g": NUMBER,
                          "solver.vertical": FLAG, "runtime.jobs": WHOLE, "runtime.force": FLAG,
                          "floor": NUMBER, **RECORDS}),
    "rocking_spectrum by id": (audit.rocking_spectrum, {"motion": "pacoima_dam_1971",
                                                        "size_s": [1.0], "alpha_deg": [15.0]},
                               {"records": PATH}),
    "response_spectra": (audit.response_spectra, {"motion": _pulse(), "periods_s": [1.0]},
                         {"motion": OBJECTS, "periods_s": SEQUENCE | st.none(),
                          "damping_pct": SEQUENCE | st.none(), "free_motion_s": NUMBER,
                          "runtime.force": FLAG, "runtime.jobs": st.just(3), "floor": NUMBER,
                          **RECORDS}),
    "response_spectra by id": (audit.response_spectra, {"motion": "pacoima_dam_1971",
                                                        "periods_s": [1.0]}, {"records": PATH}),
    "design_suite": (audit.design_suite, {"suite": None, "site": SITE},
                     {"site": SITE_PAIR, "site.override": FLAG, "site.scale_records": FLAG,
                      "site.ntc": NTC, "site.level": st.just("design"), **FLOOR}),
    "design_spectrum": (audit.design_spectrum, {"code": "fema356", "periods_s": [0.5],
                                                "site": SITE},
                        {"code": CHOICE, "periods_s": SEQUENCE | st.none(),
                         "damping_pct": SEQUENCE | st.none(), "site": SITE_PAIR}),
    "design_spectrum ubc97": (audit.design_spectrum, {"code": "ubc97", "periods_s": [0.5]},
                              {"near_source": PAIR, "site": st.just(SITE)}),
    "read_hazard": (audit.read_hazard, {"hazard": "missing.csv"},
                    {"hazard": PATH | st.none(), "site": PAIR, "imt": CHOICE}),
    "risk": (audit.risk, {"fragility": (0.5, 0.4), "hazard": "missing.csv"},
             {"fragility": FRAGILITY, "hazard": PATH | st.none(), "site": PAIR}),
    "load_result": (audit.load_result, {"folder": "audit-out"}, {"folder": PATH | st.none()}),
    "floor_motion": (audit.floor_motion, {"motion": _pulse(), "floor": ROOF},
                     {"motion": OBJECTS, "floor": NUMBER, **RECORDS}),
    "record_pulses": (audit.record_pulses, {"records": "pulses"},
                      {"records": PATH, "plot": FLAG, **RECORDS}),
    "floor_motion by id": (audit.floor_motion, {"motion": "pacoima_dam_1971", "floor": ROOF},
                           {"records": PATH}),
}


@pytest.mark.parametrize(("case", "argument"),
                         [(case, argument) for case, (_, _, wrong) in CASES.items()
                          for argument in wrong])
@settings(max_examples=12, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_a_wrong_type_is_refused_naming_the_argument(case, argument, data):
    function, valid, wrong = CASES[case]
    value = data.draw(wrong[argument], label=argument)
    group, _, field = argument.partition(".")
    given = {group: GROUPS[group](field, value)} if field else {argument: value}
    with pytest.raises(InputError) as caught:
        function(**{**valid, **given})
    assert argument in caught.value.fields, (case, argument, value, str(caught.value))
    assert str(caught.value).startswith(argument), str(caught.value)


def test_every_public_function_is_covered():
    """A public function added to ``audit`` without a case here fails this test."""
    functions = {name for name in audit.__all__
                 if callable(getattr(audit, name)) and not name[0].isupper()}
    covered = {case.split()[0] for case in CASES}
    assert functions <= covered | {"Block"}, functions - covered


@pytest.mark.parametrize("name", ["rock", "rocking_spectrum", "response_spectra",
                                  "design_spectrum", "fragility", "floor_motion", "design_suite",
                                  "atlas_settings"])
def test_the_other_public_functions_take_at_most_eight_parameters(name):
    """What travels together is one group (Solver, Runtime, Records, Floor, Site): no function of
    the API but check, run and margins (at most 15) takes more than 8 parameters, and none takes
    ``**options``."""
    import inspect

    import audit.api.atlas
    function = getattr(audit.api, name, None) or getattr(audit.api.atlas, name)
    parameters = inspect.signature(function).parameters.values()
    assert len(parameters) <= 8
    assert not [p for p in parameters if p.kind is inspect.Parameter.VAR_KEYWORD]
