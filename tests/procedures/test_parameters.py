"""The plug-ins' declared parameters: checked when constructed, given by ``params`` /
``--param``, refused by name; and the front door of ``component_entries``."""

from __future__ import annotations

import math

import numpy as np
import pytest

from audit.engine.check.component_checks import component_entries, component_provisions
from audit.errors import InputError
from audit.engine.shared.design_site import Site
from audit.physics.building.floor import Building, Floor
from procedures.asce_7_22 import ASCE722
from procedures.en_1998_1 import EN19981
from procedures.ntc_2018 import NTC2018
from procedures.nzs_1170_5 import NZS11705
from procedures.parameters import parameter_defaults, parse_params
from procedures.registry import available_component_provisions, available_procedures

TAKERS = {**available_procedures(), **available_component_provisions()}


@pytest.mark.parametrize("make, attribute", [
    (lambda: ASCE722(importance=-1.0), "importance"),
    (lambda: ASCE722(building_omega0="x"), "building_omega0"),
    (lambda: ASCE722(approximate_period=0.0), "approximate_period"),
    (lambda: NZS11705(building_height_m=0.0), "building_height_m"),
    (lambda: NZS11705(stabilising=math.nan), "stabilising"),
    (lambda: EN19981(behaviour=0.0), "behaviour"),
    (lambda: EN19981(importance=True), "importance"),
    (lambda: NTC2018(behaviour_factor=0.0), "behaviour_factor"),
])
def test_refused_when_constructed(make, attribute):
    with pytest.raises(InputError, match=f"^{attribute}: expected") as caught:
        make()
    assert caught.value.fields == (attribute,)


def test_numpy_scalars_and_words():
    code = ASCE722(importance=np.float64(1.5), building_r=np.int64(6))
    assert (code.importance, code.building_r) == (1.5, 6.0)
    assert type(code.importance) is float and type(code.building_r) is float
    assert NZS11705(building_height_m="estimate").building_height_m is None
    assert EN19981(object_period_s="t1").object_period_s == "T1"


def test_parse_params_by_key():
    parsed = parse_params({"asce7_22": {"I_p": 1.5, "Omega_0": "unknown"},
                           "nzs1170_5": {"h_n": np.float32(28.0)}}, TAKERS)
    assert parsed == {"asce7_22": {"importance": 1.5, "building_omega0": None},
                      "nzs1170_5": {"building_height_m": 28.0}}
    # the command line's texts
    assert parse_params(["en1998_1.q_a=1", "en1998_1.T_a=T1"], TAKERS) \
        == {"en1998_1": {"behaviour": 1.0, "object_period_s": "T1"}}


@pytest.mark.parametrize("params, words", [
    ({"asce7_22": {"I_q": 1.5}}, "asce7_22 has no parameter 'I_q'"),
    ({"asce7": {"I_p": 1.5}}, "unknown procedure 'asce7'"),
    ({"fema356": {"x": 1}}, "fema356 declares no parameters"),
    ({"asce7_22": {"I_p": 2.0}}, r"asce7_22.I_p: expected a number in \[1, 1.5\]"),
    ({"asce7_22": 1.5}, "asce7_22: expected"),
    (["asce7_22.I_p"], "expected PROCEDURE.KEY=VALUE"),
    (["asce7_22.I_p=1", "asce7_22.I_p=1.5"], "given twice"),
])
def test_unknown_or_bad_refused_by_name(params, words):
    with pytest.raises(InputError, match=words) as caught:
        parse_params(params, TAKERS)
    assert caught.value.fields == ("params",)


def test_defaults_declared_for_every_parameter():
    for cls in (ASCE722, EN19981, NZS11705, NTC2018):
        defaults = parameter_defaults(cls)
        assert list(defaults) == [p.key for p in cls.parameters]
        for parameter in cls.parameters:
            assert parameter.clause and parameter.meaning
            # each default is a value its own declaration accepts
            assert parameter.value(defaults[parameter.key], "x") == defaults[parameter.key]


def test_importance_multiplies_the_force():
    # on the roof of a T1 = 1 s building, S_DS = 1: F_p/W_p = 0.4·I_p·(2.84/1.712698)/1.5;
    # I_p = 1: 0.442187, I_p = 1.5: 0.663281 (inside [0.3, 1.6]·S_DS·I_p either way)
    roof = Floor.parse(Floor(1.0, Building(1.0, "shear:10")))
    plain, important = (
        {e["key"]: e for e in component_entries(
            0.8, 2.0, site=(1.0, 0.6), floor=roof,
            provisions=component_provisions(parse_params(params, TAKERS)))}["asce7_22"]
        for params in (None, {"asce7_22": {"I_p": 1.5}}))
    assert plain["demand"] == pytest.approx(0.442187, abs=2e-6)
    assert important["demand"] == pytest.approx(0.663281, abs=2e-6)
    used = {p["key"]: p for p in important["parameters"]}
    assert used["I_p"]["value"] == "1.5" and used["I_p"]["given"]
    assert used["R_po"]["value"] == "1.5" and not used["R_po"]["given"]


def test_anchorage_forces():
    # 0.4 × 1.8 m on the ground, S_DS = 1: ASCE F/W = 0.3 (the lower bound), k = 0.9 − 0.2 = 0.7,
    # b = 0.2 m, h = 0.9 m: T/W = (0.3·0.9 − 0.7·0.2)/(2·0.2) = 0.13/0.4 = 0.325; ×Ω0p = 2:
    # V/W = 0.6, T/W = (0.6·0.9 − 0.14)/0.4 = 1.0; 200 kg at the tool's g = 9.81: W = 1.962 kN
    entries = {e["key"]: e for e in component_entries(0.4, 1.8, site=(1.0, 0.6), mass_kg=200)}
    anchorage = entries["asce7_22"]["anchorage"]
    assert (anchorage["shear"], anchorage["tension"]) == pytest.approx((0.3, 0.325))
    assert (anchorage["shear_omega"], anchorage["tension_omega"]) == pytest.approx((0.6, 1.0))
    assert anchorage["tension_omega_kN"] == pytest.approx(1.962)
    # NZS (no Ω0p): F/W = 0.4·2 = 0.8, k = 0.9: T/W = (0.72 − 0.18)/0.4 = 1.35
    nzs = entries["nzs1170_5"]["anchorage"]
    assert nzs["tension"] == pytest.approx(1.35) and "shear_omega" not in nzs


def test_ntc_site_read_by_en_1998_1():
    # soil B, a_g = 0.35 g, F0 = 2.4: S_S = 1.40 − 0.40·2.4·0.35 = 1.064 (within [1, 1.2]),
    # S_T = 1 (T1): a_g·S = 0.3724 g; F/W = 0.3724/2 = 0.1862, against 0.4·1.0/2 = 0.2 without
    with_ntc = {e["key"]: e for e in component_entries(
        0.4, 1.8, site=Site(1.0, 0.6, ntc=(0.35, 2.4, 0.35, "B", "T1")))}
    without = {e["key"]: e for e in component_entries(0.4, 1.8, site=(1.0, 0.6))}
    assert with_ntc["en1998_1"]["demand"] == pytest.approx(0.1862)
    assert with_ntc["en1998_1"]["demand"] / without["en1998_1"]["demand"] \
        == pytest.approx(0.931)
    assert "NTC 2018 site" in with_ntc["en1998_1"]["spectrum_read"]
    assert "FEMA 356 site" in without["en1998_1"]["spectrum_read"]


@pytest.mark.parametrize("keywords, name", [
    ({"site": (math.nan, 0.6)}, "site"),
    ({"site": "abc"}, "site"),
    ({"site": (1.0, 0.6), "floor": 1.0}, "floor"),
    ({"site": Site(1.0, 0.6, ntc=(0.35, 2.4, 0.35, "Z", "T1"))}, "site.ntc"),
    ({"site": (1.0, 0.6), "mass_kg": -1.0}, "mass_kg"),
    ({"site": (1.0, 0.6), "provisions": [1]}, "provisions"),
    ({}, "site"),
])
def test_component_entries_front_door(keywords, name):
    with pytest.raises(InputError, match=f"^{name}") as caught:
        component_entries(0.4, 1.8, **keywords)
    assert name in caught.value.fields


def test_component_entries_takes_numpy_and_text_site():
    # the API's site text "S_XS,S_X1" reads both numbers (S_XS = 1.5 g), numpy scalars as numbers
    entries = component_entries(np.float64(0.4), np.int64(2), site="1.5,0.9")
    assert {e["key"]: e for e in entries}["asce7_22"]["demand"] == pytest.approx(0.45)


def test_parameters_of_a_command():
    from audit.api.inputs import parameters_of, procedures_of
    chosen = procedures_of(["ntc2018", "fema356"])
    # run and margins: the procedures' parameters, applied to the instances (checked again)
    procedures, provision_params = parameters_of(["ntc2018.q=1.5"], chosen, provisions=False)
    assert procedures[0].behaviour_factor == 1.5 and provision_params == {}
    assert type(procedures[1]) is type(chosen[1])
    with pytest.raises(InputError, match="asce7_22 is a component provision"):
        parameters_of({"asce7_22": {"I_p": 1.5}}, chosen, provisions=False)
    with pytest.raises(InputError, match="priestley1978 is not among the procedures chosen"):
        parameters_of(["priestley1978.x=1"], chosen)
    # check: the provisions' too, returned by attribute
    _, provision_params = parameters_of({"nzs1170_5": {"k": 1.0}}, chosen)
    assert provision_params == {"nzs1170_5": {"stabilising": 1.0}}
