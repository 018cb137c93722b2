"""The component provisions (ASCE 7-22 §13.3, EN 1998-1 §4.3.5.2, NZS 1170.5 §8) against worked
examples computed by hand, the arithmetic written out beside each expected value."""

from __future__ import annotations

from importlib.metadata import entry_points

import pytest

from audit.engine.check.component_checks import component_entries
from audit.errors import InputError
from audit.physics.building.floor import Building, Floor
from procedures.asce_7_22 import ASCE722
from procedures.component import ComponentSite
from procedures.en_1998_1 import EN19981
from procedures.nzs_1170_5 import NZS11705
from procedures.registry import COMPONENT_ENTRY_POINT_GROUP, available_component_provisions

ROOF_1S = Floor.parse(Floor(1.0, Building(1.0, "shear:10")))
GROUND = Floor()
SITE = ComponentSite.from_design_site((1.0, 0.6))  # S_XS = 1.0 g, S_X1 = 0.6 g
# The cabinet of check's example: 0.8 m wide, 2.0 m tall: b = 0.4 m, h = 1.0 m, b/h = 0.4.
WIDTH, HEIGHT = 0.8, 2.0


def test_site_mapping():
    # S_DS = S_XS = 1.0; a_g·S = C(0) = 0.4·S_XS = 0.4 (FEMA 356 Eq. 1-8 at T = 0)
    assert (SITE.s_ds_g, SITE.ag_s_g, SITE.c0_g) == pytest.approx((1.0, 0.4, 0.4))
    # NTC site a_g = 0.25 g, F0 = 2.5, soil A, T1 topography: S = S_S·S_T = 1·1 = 1,
    # a_g·S = 0.25; alone its plateau gives S_DS = 0.25·2.5 = 0.625
    ntc = (0.25, 2.5, 0.3, "A", "T1")
    alone = ComponentSite.from_design_site(ntc_site=ntc)
    assert (alone.s_ds_g, alone.ag_s_g, alone.c0_g) == pytest.approx((0.625, 0.25, 0.25))
    both = ComponentSite.from_design_site((1.0, 0.6), ntc)
    assert (both.s_ds_g, both.ag_s_g, both.c0_g) == pytest.approx((1.0, 0.25, 0.4))
    with pytest.raises(InputError, match="site"):
        ComponentSite.from_design_site()


def test_asce_7_22_roof_of_a_1s_building():
    code = ASCE722()
    result = code.check(WIDTH, HEIGHT, SITE, ROOF_1S)
    # H_f: a1 = min(1/1, 2.5) = 1, a2 = max(1 − (0.4/1)², 0) = 0.84; H_f = 1 + 1 + 0.84 = 2.84
    assert result.factors["H_f"] == pytest.approx(2.84, abs=1e-12)
    # R_μ = √(1.1·8/(1·3)) = √2.933333 = 1.712698 (> 1.3)
    assert result.factors["R_mu"] == pytest.approx(1.712698, abs=1e-6)
    # F_p/W_p = 0.4·1.0·1.0·(2.84/1.712698)·(1.0/1.5) = 1.658203·0.266667 = 0.442187,
    # inside [0.3, 1.6]·S_DS·I_p
    assert result.force_over_weight == pytest.approx(0.442187, abs=2e-6)
    # 0.9D − 0.2·S_DS·D = 0.7 D resists: capacity 0.7·0.4 = 0.28 < 0.442: fails
    assert result.capacity_over_weight == pytest.approx(0.28)
    assert not result.passes and result.anchorage_force_over_weight == result.force_over_weight
    assert (result.factors["C_AR"], result.factors["R_po"], result.factors["I_p"]) == (1.0, 1.5, 1.0)


def test_asce_7_22_branches_and_bounds():
    code = ASCE722()
    # T1 = 0.3 s: a1 = min(3.33, 2.5) = 2.5, a2 = max(1 − 1.78, 0) = 0; z/h = 0.5: H_f = 2.25
    assert code.height_factor(0.5, 0.3) == pytest.approx(2.25)
    # T_a unknown (Eq. 13.3-5) on the roof: 1 + 2.5 = 3.5
    assert ASCE722().height_factor(1.0, None) == pytest.approx(3.5)
    unknown = ASCE722(approximate_period="unknown").check(WIDTH, HEIGHT, SITE, ROOF_1S)
    # F_p/W_p = 0.4·1·(3.5/1.712698)/1.5 = 0.4·2.043560/1.5 = 0.544949
    assert unknown.factors["H_f"] == pytest.approx(3.5)
    assert unknown.force_over_weight == pytest.approx(0.544949, abs=2e-6)
    # T_a = 0.5 s given (not the modal 1 s): a1 = 2, a2 = 1 − 0.64 = 0.36, H_f = 3.36 on the roof
    assert ASCE722(approximate_period=0.5).check(WIDTH, HEIGHT, SITE, ROOF_1S).factors["H_f"] \
        == pytest.approx(3.36)
    # the supporting structure not known: R_μ = 1.3
    assert ASCE722(building_omega0=None).ductility_reduction() == 1.3
    # on the ground 0.4·1·(1/1.712698)/1.5 = 0.1557 < 0.3: the lower bound 0.3·S_DS·I_p binds
    assert code.check(WIDTH, HEIGHT, SITE, GROUND).force_over_weight == pytest.approx(0.3)
    # C_AR = 2.8, R_po = 1: 0.4·2.84/1.712698·2.8 = 1.8572 > 1.6: the upper bound 1.6 binds
    assert ASCE722(resonance=2.8, strength=1.0).check(WIDTH, HEIGHT, SITE, ROOF_1S).force_over_weight \
        == pytest.approx(1.6)
    # R = 1.5, Ω0 = 1.5: √1.1 = 1.0488 < 1.3, so R_μ = 1.3; E_v left out: capacity 0.9·0.4
    loose = ASCE722(building_r=1.5, building_omega0=1.5, vertical_coefficient=0.0)
    assert loose.ductility_reduction() == 1.3
    assert loose.check(WIDTH, HEIGHT, SITE, ROOF_1S).capacity_over_weight == pytest.approx(0.36)


def test_en_1998_1_rigid_object_on_the_roof():
    result = EN19981().check(WIDTH, HEIGHT, SITE, ROOF_1S)
    # T_a = 0: S_a/(αS) = 3(1 + 1)/(1 + (1 − 0)²) − 0.5 = 6/2 − 0.5 = 2.5
    assert result.factors["S_a_over_alpha_S"] == pytest.approx(2.5, abs=1e-12)
    # F_a/W_a = a_g·S·2.5·γ_a/q_a = 0.4·2.5·1/2 = 0.5 > 1.0·b/h = 0.4: fails
    assert result.force_over_weight == pytest.approx(0.5)
    assert result.capacity_over_weight == pytest.approx(0.4) and not result.passes


def test_en_1998_1_flexible_object_and_lower_bound():
    mid = Floor.parse(Floor(0.5, Building(1.0)))
    # T_a = 0.5 s, T1 = 1 s, z/H = 0.5: 3·1.5/(1 + 0.25) − 0.5 = 3.6 − 0.5 = 3.1
    assert EN19981(object_period_s=0.5).check(WIDTH, HEIGHT, SITE, mid).factors["S_a_over_alpha_S"] \
        == pytest.approx(3.1)
    # T_a = 3 s on the ground of a 1 s building: 3/(1 + 4) − 0.5 = 0.1 < 1: the bound α·S
    ground_of = Floor.parse(Floor(0.0, Building(1.0)))
    assert EN19981(object_period_s=3.0).amplification(0.0, 1.0) == 1.0
    # on the ground without a building, T_a > 0 cannot be judged
    assert EN19981(object_period_s=3.0).unmet_requirements(ground_of) is not None


def test_nzs_1170_5():
    code = NZS11705()
    # roof of a T1 = 1 s building: h_n = 35 m, h_i = 35 m ≥ 12 m and ≥ 0.2·35 = 7 m: C_Hi = 3.0;
    # C_i(0) = 2.0; C_p = 0.4·3.0·2.0·1·1 = 2.4 ≤ 3.6
    result = code.check(WIDTH, HEIGHT, SITE, ROOF_1S)
    assert (result.factors["C_Hi"], result.factors["C_i"]) == (3.0, 2.0)
    assert result.force_over_weight == pytest.approx(2.4) and not result.passes
    # stability (AS/NZS 1170.0 §4.2.1): 0.9G resists, capacity 0.9·0.4 = 0.36
    assert result.capacity_over_weight == pytest.approx(0.36)
    # h_n = 10 m given: h_i = 10 m < 12 m, ≥ 0.2·10 = 2 m: the lesser of 1 + 10/6 = 2.666667 and
    # 3.0: C_p = 0.4·2.666667·2 = 2.133333
    assert NZS11705(building_height_m=10.0).check(WIDTH, HEIGHT, SITE, ROOF_1S).force_over_weight \
        == pytest.approx(2.133333, abs=1e-6)
    # a low building, h_n = 7 m: at h_i = 0.7 m (< 1.4 m = 0.2·h_n, < 12 m) the lesser of
    # 1 + 0.7/6 = 1.116667 and 1 + 10·0.7/7 = 2.0; on its roof the lesser of 1 + 7/6 = 2.166667
    # and 3.0
    assert code.height_coefficient(0.7, 7.0) == pytest.approx(1.116667, abs=1e-6)
    assert code.height_coefficient(7.0, 7.0) == pytest.approx(2.166667, abs=1e-6)
    # h_n = 100 m: at h_i = 15 m (≥ 12, < 20 = 0.2·h_n) 1 + 10·15/100 = 2.5
    assert code.height_coefficient(15.0, 100.0) == pytest.approx(2.5)
    # C_i: T_p = 1.0 s: 2·(1.75 − 1.0) = 1.5; T_p = 2 s: 0.5
    assert NZS11705(object_period_s=1.0).spectral_shape() == pytest.approx(1.5)
    assert NZS11705(object_period_s=2.0).spectral_shape() == 0.5
    # S_XS = 2.0 g: C(0) = 0.8; 0.8·3·2 = 4.8 > 3.6: capped
    strong = ComponentSite.from_design_site((2.0, 1.0))
    assert code.check(WIDTH, HEIGHT, strong, ROOF_1S).force_over_weight == pytest.approx(3.6)
    # on the ground C_Hi = 1: 0.4·1·2 = 0.8
    assert code.check(WIDTH, HEIGHT, SITE, GROUND).force_over_weight == pytest.approx(0.8)


def test_registered_as_plug_ins():
    names = {point.name for point in entry_points(group=COMPONENT_ENTRY_POINT_GROUP)}
    assert {"asce7_22", "en1998_1", "nzs1170_5"} <= names
    assert list(available_component_provisions()) == ["asce7_22", "en1998_1", "nzs1170_5"]


def test_entries_in_the_agreed_shape():
    entries = component_entries(0.8, 2.0, site=(1.0, 0.6), floor=ROOF_1S)
    keys = {"procedure", "key", "limit_state", "verdict", "demand", "capacity", "unit", "basis",
            "share_of_records_overturning", "factors", "anchorage_force_over_weight",
            "exact_p_exceed", "required_width_m", "anchorage", "spectrum_read", "parameters"}
    by_key = {entry["key"]: entry for entry in entries}
    assert all(set(entry) == keys for entry in entries)
    for entry in entries:
        assert entry["verdict"] == ("passes" if entry["demand"] <= entry["capacity"] else "fails")
    assert by_key["asce7_22"]["factors"]["H_f"] == pytest.approx(2.84)
    assert by_key["en1998_1"]["factors"]["S_a_over_alpha_S"] == pytest.approx(2.5)
    assert set(by_key["nzs1170_5"]["factors"]) >= {"C_Hi", "C_i"}
    # ASCE: the width at which 0.7·b/h = 0.442187: 2·1.0·0.442187/0.7 = 1.263393 m
    assert by_key["asce7_22"]["required_width_m"] == pytest.approx(1.263393, abs=1e-6)
    assert by_key["asce7_22"]["anchorage_force_over_weight"] == pytest.approx(0.442187, abs=2e-6)
    # a squat block passes every code on the ground: b/h = 2: capacity 1.4 (ASCE), 2 (EN),
    # 1.8 (NZS)
    squat = component_entries(2.0, 1.0, site=(1.0, 0.6))
    assert {entry["verdict"] for entry in squat} == {"passes"}
    assert {entry["anchorage_force_over_weight"] for entry in squat} == {None}
    with pytest.raises(InputError, match="width_m"):
        component_entries(0.0, 1.0, site=(1.0, 0.6))


def test_check_lists_the_provisions():
    from records import RecordEntry, RecordSuite, one_pulse
    import audit
    pulses = RecordSuite(tuple(RecordEntry(f"cosine_{t:g}s", one_pulse("cosine", 0.5, t,
                                                                       record_id=f"c{t:g}"))
                               for t in (0.5, 1.0, 2.0)), "three one-cosine pulses")
    result = audit.check(["0.6x1.8"], (1.5, 0.9), procedures=["fema356"], records=pulses, im="pga",
                         solver=audit.Solver(free_motion_s=5.0))
    (obj,) = result.document["objects"]
    by_key = {entry["key"]: entry for entry in obj["component_provisions"]}
    # on the ground, S_DS = 1.5 g: ASCE's 0.4·1.5/1.712698/1.5 = 0.2335 < 0.3·1.5 = 0.45, the
    # lower bound; capacity (0.9 − 0.2·1.5)·0.3/0.9 = 0.6/3 = 0.2: fails
    assert (by_key["asce7_22"]["demand"], by_key["asce7_22"]["capacity"]) \
        == pytest.approx((0.45, 0.2))
    # EN: a_g·S = 0.4·1.5 = 0.6; 0.6·1·1/2 = 0.3 ≤ 1/3: passes. NZS: 0.6·1·2 = 1.2 > 0.9/3: fails
    assert [by_key[k]["verdict"] for k in ("asce7_22", "en1998_1", "nzs1170_5")] \
        == ["fails", "passes", "fails"]
    assert by_key["en1998_1"]["demand"] == pytest.approx(0.3)
    assert by_key["nzs1170_5"]["demand"] == pytest.approx(1.2)
    assert {entry["exact_p_exceed"] for entry in obj["component_provisions"]} \
        == {obj["exact"]["p_overturn_at_site"]}
    (line,) = [row for row in result.summary_text().splitlines()
               if "ASCE 7-22 §13.3 (static)" in row]
    # the width at which 0.6·b/h = 0.45: 2·0.9·0.45/0.6 = 1.35 m
    words = line.split()
    assert words[words.index("overturning"):][:9] == ["overturning", "fails", "F/W", "0.45",
                                                      "vs", "0.2", "g", "1.35", "m"]
