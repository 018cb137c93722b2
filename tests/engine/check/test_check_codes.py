"""The engineer's own code inputs in ``check`` (issue 55): the NTC site read by NTC 2018 and EN
1998-1, the provisions' parameters, the anchorage forces; every expected value worked by hand
from the codes' formulas written out again here."""

from __future__ import annotations

import math

import pytest

import audit
from audit import G
from audit.cli import main
from audit.errors import InputError
from tests.engine.check.pulses import eight_pulses

NTC = (0.35, 2.4, 0.35, "B", "T1")


def _check(**keywords):
    result = audit.check(["0.4x1.8"], keywords.pop("site", (1.0, 0.6)), procedures=["ntc2018"],
                         records=eight_pulses(), im="pga", solver=audit.Solver(free_motion_s=5.0),
                         **keywords)
    (obj,) = result.document["objects"]
    return result, obj


def _ntc_slv_displacement() -> float:
    """S_De(T_SLV, ξ = 8 %) [m] of the site NTC for the 0.4 × 1.8 m block, by hand."""
    b, h = 0.2, 0.9
    radius, alpha = math.hypot(b, h), math.atan2(b, h)
    d_slv = 0.4 * b                                        # d_SLV = 0.4 d₀, d₀ = b
    alpha_minus_theta = math.asin(math.sin(alpha) - d_slv / radius)  # d = R[sin α − sin(α − θ)]
    a_d = math.tan(alpha_minus_theta) * G                  # a(d) = tan(α − θ)·g, e* = FC = 1
    t_slv = 1.68 * math.pi * math.sqrt(d_slv / a_d)        # [C8.7.1.10]
    a_g, f0, tc_star = 0.35, 2.4, 0.35
    s = min(max(1.40 - 0.40 * f0 * a_g, 1.0), 1.2) * 1.0   # soil B (Tab. 3.2.IV), T1: S_T = 1
    t_c = 1.10 * tc_star ** -0.20 * tc_star                # C_C·T_C*
    t_d = 4.0 * a_g + 1.6
    eta = math.sqrt(10.0 / (5.0 + 8.0))
    assert t_c < t_slv < t_d                               # the constant-velocity branch
    s_e = a_g * s * eta * f0 * t_c / t_slv                 # [g]
    return s_e * G * (t_slv / (2.0 * math.pi)) ** 2        # S_De = S_e·(T/2π)²


@pytest.fixture(scope="module")
def without_and_with_ntc():
    return _check(), _check(site=audit.Site(1.0, 0.6, ntc=NTC))


def test_ntc_site_read_by_ntc_2018(without_and_with_ntc):
    (_, plain), (_, sited) = without_and_with_ntc
    slv = {e["limit_state"]: e for e in sited["procedures"]}["SLV"]
    plain_slv = {e["limit_state"]: e for e in plain["procedures"]}["SLV"]
    assert slv["demand"] == pytest.approx(_ntc_slv_displacement(), rel=1e-6)
    assert plain_slv["demand"] != pytest.approx(slv["demand"], rel=1e-3)
    assert "NTC 2018 elastic spectrum" in slv["spectrum_read"]
    assert "record's own" in plain_slv["spectrum_read"]
    # the width it requires is where SLV's demand meets 0.4 d₀, not where NTC sees overturning:
    # wider than the 0.4 m that fails
    assert slv["verdict"] == "fails" and slv["required_width_m"] > 0.4


def test_ntc_site_read_by_en_1998_1(without_and_with_ntc):
    (_, plain), (_, sited) = without_and_with_ntc
    en, en_plain = ({e["key"]: e for e in obj["component_provisions"]}["en1998_1"]
                    for obj in (sited, plain))
    # a_g·S = 0.35·(1.40 − 0.40·2.4·0.35) = 0.35·1.064 = 0.3724 g; /q_a = 2: 0.1862;
    # without it 0.4·S_XS/2 = 0.2: 0.931 ×
    assert en["demand"] == pytest.approx(0.1862)
    assert en["demand"] / en_plain["demand"] == pytest.approx(0.931)


def test_importance_param_multiplies_asce_on_a_roof():
    # roof of a T1 = 1 s building, S_DS = 1: H_f = 2.84, R_μ = √(8.8/3) = 1.712698:
    # F_p/W_p = 0.4·I_p·(2.84/1.712698)/1.5 = 0.442187·I_p; I_p = 1.5: 0.663281
    def asce(params):
        result = audit.check(["0.4x1.8"], (1.0, 0.6), procedures=["fema356"],
                             records=eight_pulses(), im="pga", params=params, mass_kg=100,
                             floor=audit.Floor(1.0, audit.Building(1.0)),
                             solver=audit.Solver(free_motion_s=5.0))
        (obj,) = result.document["objects"]
        return result, {e["key"]: e for e in obj["component_provisions"]}["asce7_22"]
    _, plain = asce(None)
    result, important = asce({"asce7_22": {"I_p": 1.5}})
    assert plain["demand"] == pytest.approx(0.442187, abs=2e-6)
    assert important["demand"] == pytest.approx(0.663281, abs=2e-6)
    assert important["demand"] / plain["demand"] == pytest.approx(1.5)
    used = {p["key"]: p for p in result.document["parameters"]["asce7_22"]}
    assert used["I_p"]["value"] == "1.5" and used["I_p"]["given"]
    # the anchorage in the printed table: V = 0.663281 W, 100 kg: W = 0.981 kN, V = 0.651 kN
    table = result.summary_text()
    (row,) = [line for line in table.splitlines() if "its anchorage" in line
              and "Ω0p 2" in line]
    assert "V 0.663 W = 0.651 kN" in row


def test_param_refused_by_name(capsys):
    argv = ["check", "--block", "0.4x1.8", "--site", "1.0,0.6", "--records", "/nonexistent"]
    assert main([*argv, "--param", "asce7_22.I_q=1.5"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["error: --param: asce7_22 has no parameter 'I_q' (it takes I_p, C_AR, R_po, R, "
                   "Omega_0, I_e, T_a, E_v, Omega_0p)"]
    with pytest.raises(InputError, match="^params") as caught:
        audit.check(["0.4x1.8"], (1.0, 0.6), records=eight_pulses(),
                    params={"asce7_22": {"I_q": 1.5}})
    assert caught.value.fields == ("params",)
