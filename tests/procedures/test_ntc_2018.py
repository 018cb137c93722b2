"""NTC 2018 / Circolare 2019 plug-in and the check contract.

Expected numbers come from the worked example of the guideline synthesis
(``../shared/reference/guideline-procedures.md`` §2.6), from the NTC formulas written out again
here in plain scalar arithmetic, or from the exact rocking solver; never from the code under test.
"""

import math

import numpy as np
import pytest

from audit import G
from audit.engine.run.pipeline import audit_in_memory
from audit.engine.shared.verdicts import check_verdicts, exact_exceeded
from procedures.context import RecordContext
from audit.errors import InputError
from audit.physics.ntc2018_spectrum import NTC2018Spectrum
from audit.physics.response_spectra import response_spectra
from audit.physics.rocking import DEFAULT_FREE_MOTION_S, rocking_spectrum
from procedures import available_procedures, get_procedures
from procedures.base import EXACT_ROTATION, EXACT_UPLIFT, Check, Procedure
from procedures.ntc_2018 import NTC2018, running_maximum, spectral_acceleration
from records import RecordEntry, RecordSuite, one_pulse

# The worked example: b = 0.2 m, h = 1.0 m.
B, H = 0.2, 1.0
RADIUS = math.hypot(B, H)
ALPHA = math.atan2(B, H)
P = math.sqrt(3 * G / (4 * RADIUS))


def ntc_site(ag_g, f0=2.4, tc_star_s=0.30, soil="B", topography="T1"):
    return {"ntc_ag_g": ag_g, "ntc_f0": f0, "ntc_tc_star_s": tc_star_s, "ntc_soil": soil,
            "ntc_topography": topography}


def site_entry(ag_g, **site):
    return RecordEntry("site", None, missing_reason="no file", site=ntc_site(ag_g, **site))


# --- worked example (§2.6) -----------------------------------------------------------------


@pytest.mark.parametrize("linear, t_slv, t_slc", [(False, 1.385, 1.932), (True, 1.376, 1.916)])
def test_worked_example_periods(linear, t_slv, t_slc):
    thresholds = NTC2018(linear_curve=linear).thresholds(np.array([P]), ALPHA)
    assert thresholds["SLV"][0][0] == pytest.approx(0.080, abs=1e-12)
    assert thresholds["SLC"][0][0] == pytest.approx(0.120, abs=1e-12)
    assert thresholds["SLV"][1][0] == pytest.approx(t_slv, abs=6e-4)
    assert thresholds["SLC"][1][0] == pytest.approx(t_slc, abs=6e-4)


def test_worked_example_capacity_curve():
    """a₀ = 1.962, a(d_SLV) = 1.162, a(d_SLC) = 0.772 m/s² on the exact curve; the linear curve
    is a₀(1 − d/b); e* = 0.75 raises a by 1/0.75 (Eq. C8.7.1.3)."""
    d = np.array([0.0, 0.08, 0.12])
    np.testing.assert_allclose(spectral_acceleration(d, ALPHA, RADIUS), [1.962, 1.162, 0.772],
                               atol=6e-4)
    np.testing.assert_allclose(spectral_acceleration(d, ALPHA, RADIUS, linear=True),
                               G * B / H * (1 - d / B), rtol=1e-12)
    np.testing.assert_allclose(spectral_acceleration(d, ALPHA, RADIUS, e_star=0.75),
                               spectral_acceleration(d, ALPHA, RADIUS) / 0.75, rtol=1e-12)


def test_linear_periods_follow_the_closed_forms_in_h():
    """Linear curve, FC = 1: T_SLV = 1.68π√(2h/(3g)), T_SLC = 1.56π√(1.5h/g), whatever b."""
    h = np.array([0.3, 1.0, 2.5])
    alpha = math.radians(12)
    radius = h / math.cos(alpha)
    p = np.sqrt(3 * G / (4 * radius))
    thresholds = NTC2018(linear_curve=True).thresholds(p, alpha)
    np.testing.assert_allclose(thresholds["SLV"][1], 1.68 * np.pi * np.sqrt(2 * h / (3 * G)),
                               rtol=1e-12)
    np.testing.assert_allclose(thresholds["SLC"][1], 1.56 * np.pi * np.sqrt(1.5 * h / G),
                               rtol=1e-12)


# a_g [g], S, T_D [s], SLV demand S_De(1.376 s, 8 %), SLC demand S_De(1.916 s, 10 %) [m]
DEMAND_TABLE = [(0.15, 1.20, 2.2, 0.054, 0.071), (0.25, 1.16, 2.6, 0.088, 0.114),
                (0.35, 1.064, 3.0, 0.113, 0.146)]


@pytest.mark.parametrize("ag_g, soil_factor, t_d, slv, slc", DEMAND_TABLE)
def test_worked_example_demand_table(ag_g, soil_factor, t_d, slv, slc):
    spectrum = NTC2018Spectrum(ag_g, 2.4, 0.30, "B", "T1")
    assert spectrum.soil_factor == pytest.approx(soil_factor, abs=1e-12)
    _, t_c, t_d_code = spectrum.corner_periods()
    assert t_c == pytest.approx(0.420, abs=6e-4) and t_d_code == pytest.approx(t_d, abs=1e-12)
    assert spectrum.displacement(1.376, 0.08) == pytest.approx(slv, abs=6e-4)
    assert spectrum.displacement(1.916, 0.10) == pytest.approx(slc, abs=6e-4)


@pytest.mark.parametrize("ag_g, slv_passes, slc_passes, sld_passes",
                         [(0.15, True, True, True), (0.25, False, True, False),
                          (0.35, False, False, False)])
def test_worked_example_verdicts(ag_g, slv_passes, slc_passes, sld_passes):
    """Passes SLV at 0.15 g only, SLC at 0.15 and 0.25 g; the q-check passes all three; SLD
    passes while a_g·S ≤ tan α = 0.2 (0.18, 0.29, 0.372 g)."""
    checks = {c.limit_state: c for c in NTC2018(linear_curve=True).checks(
        site_entry(ag_g), np.array([P]), ALPHA, 0.888, None)}
    assert list(checks) == ["SLD", "SLV-linear", "SLV", "SLC"]
    assert checks["SLD"].passes[0] == sld_passes
    assert checks["SLV-linear"].passes[0]
    assert checks["SLV"].passes[0] == slv_passes
    assert checks["SLC"].passes[0] == slc_passes
    assert checks["SLD"].exact_event == EXACT_UPLIFT
    assert checks["SLV"].exact_event == checks["SLC"].exact_event == EXACT_ROTATION
    # θ limits: θ(0.4b)/α = 0.4025 (§1), θ(0.6b) by the inverse written out here
    assert checks["SLV"].theta_limit_rad[0] / ALPHA == pytest.approx(0.4025, abs=6e-5)
    assert checks["SLV-linear"].theta_limit_rad[0] == checks["SLV"].theta_limit_rad[0]
    assert checks["SLC"].theta_limit_rad[0] == pytest.approx(
        ALPHA - math.asin(math.sin(ALPHA) - 0.12 / RADIUS), rel=1e-12)
    demand = checks["SLV"].demand_m[0]
    assert checks["SLV"].demand_theta_rad[0] == pytest.approx(
        ALPHA - math.asin(math.sin(ALPHA) - demand / RADIUS), rel=1e-12)


def test_estimate_is_the_rotation_at_the_slv_demand():
    """θ(d_dem(T_SLV)) where the block rocks; 0 (no uplift) at 0.15 g; T_SLV as period."""
    procedure = NTC2018(linear_curve=True)
    quiet = procedure.evaluate(site_entry(0.15), np.array([P]), ALPHA, 0.888, None).estimate
    assert quiet.outcome[0] == "no-uplift" and quiet.theta[0] == 0.0
    strong = procedure.evaluate(site_entry(0.35), np.array([P]), ALPHA, 0.888, None).estimate
    assert strong.outcome[0] == "converged" and strong.damping == 0.08
    assert strong.period_s[0] == pytest.approx(1.376, abs=6e-4)
    assert strong.theta[0] == pytest.approx(ALPHA - math.asin(math.sin(ALPHA) - 0.113 / RADIUS),
                                            abs=1e-3)
    # a demand beyond d₀ = b is overturning
    overturn = procedure.evaluate(site_entry(0.35), np.array([P * 4]), ALPHA, 0.888, None).estimate
    assert overturn.outcome[0] == "overturn" and np.isnan(overturn.theta[0])


# --- NTC 2018 spectrum against the formulas written out by hand ------------------------------


def hand_ntc(period, ag_g, f0, tc_star, xi_pct, s_t=1.0):
    """Soil B, Eqs. 3.2.2–3.2.12 in scalar arithmetic: (S_e [g], S_De [m])."""
    s_s = min(max(1.40 - 0.40 * f0 * ag_g, 1.00), 1.20)
    s = s_s * s_t
    eta = max(math.sqrt(10 / (5 + xi_pct)), 0.55)
    t_c = 1.10 * tc_star ** -0.20 * tc_star
    t_b, t_d, t_e, t_f = t_c / 3, 4 * ag_g + 1.6, 5.0, 10.0
    if period < t_b:
        se = ag_g * s * eta * f0 * (period / t_b + (1 - period / t_b) / (eta * f0))
    elif period < t_c:
        se = ag_g * s * eta * f0
    elif period < t_d:
        se = ag_g * s * eta * f0 * t_c / period
    else:
        se = ag_g * s * eta * f0 * t_c * t_d / period ** 2
    d_g = 0.025 * ag_g * G * s * t_c * t_d
    if period <= t_e:
        sde = se * G * (period / (2 * math.pi)) ** 2
    elif period <= t_f:
        sde = d_g * (f0 * eta + (1 - f0 * eta) * (period - t_e) / (t_f - t_e))
    else:
        sde = d_g
    return se, sde


@pytest.mark.parametrize("ag_g, xi_pct, topography, s_t",
                         [(0.25, 5, "T1", 1.0), (0.10, 8, "T2", 1.2), (0.40, 10, "T4", 1.4),
                          (0.25, 40, "T3", 1.2)])
def test_spectrum_matches_the_code_formulas(ag_g, xi_pct, topography, s_t):
    periods = [0.0, 0.05, 0.3, 1.0, 2.9, 4.0, 5.5, 8.0, 12.0]
    spectrum = NTC2018Spectrum(ag_g, 2.5, 0.35, "B", topography)
    expected = np.array([hand_ntc(t, ag_g, 2.5, 0.35, xi_pct, s_t) for t in periods])
    np.testing.assert_allclose(spectrum.acceleration(periods, xi_pct / 100), expected[:, 0],
                               rtol=1e-12)
    np.testing.assert_allclose(spectrum.displacement(periods, xi_pct / 100), expected[:, 1],
                               rtol=1e-12)


def test_soil_factor_bounds_of_table_3_2_iv():
    # soil D: 2.40 − 1.50·F₀·a_g/g, between 0.90 and 1.80; soil C's C_C = 1.05 T_C*^−0.33
    assert NTC2018Spectrum(0.35, 2.5, 0.3, "D").soil_factor == pytest.approx(1.0875)
    assert NTC2018Spectrum(0.50, 2.5, 0.3, "D").soil_factor == pytest.approx(0.90)
    assert NTC2018Spectrum(0.05, 2.5, 0.3, "D").soil_factor == pytest.approx(1.80)
    assert NTC2018Spectrum(0.2, 2.5, 0.4, "C").corner_periods()[1] == pytest.approx(
        1.05 * 0.4 ** -0.33 * 0.4)


@pytest.mark.parametrize("field, kwargs", [("a_g", {"ag_g": 0.0}), ("F0", {"f0": -1.0}),
                                           ("soil", {"soil": "F"}),
                                           ("topography", {"topography": "T5"})])
def test_bad_ntc_site_is_an_input_error(field, kwargs):
    values = {"ag_g": 0.2, "f0": 2.4, "tc_star_s": 0.3, "soil": "B", "topography": "T1",
              **kwargs}
    with pytest.raises(InputError, match=field):
        NTC2018Spectrum(**values)


# --- the check contract ------------------------------------------------------------------------


def test_check_verdicts_truth_table():
    verdicts = check_verdicts([True, True, False, False], [False, True, True, False])
    assert list(verdicts) == ["agrees-safe", "missed", "agrees-unsafe", "false-alarm"]
    assert list(verdicts) == ["agrees-safe", "missed", "agrees-unsafe", "false-alarm"]


def test_exact_exceeded_per_event():
    nan = np.full(4, np.nan)
    limit = np.full(4, 0.1)
    rotation = Check("SLV", EXACT_ROTATION, np.ones(4, bool), nan, nan, nan, nan, nan, limit,
                     nan, "")
    uplift = Check("SLD", EXACT_UPLIFT, np.ones(4, bool), nan, nan, nan, nan, nan, nan, nan, "")
    theta = np.array([0.05, 0.1, 0.2, 0.02])
    overturned = np.array([False, False, False, True])
    uplifted = np.array([False, True, True, True])
    assert list(exact_exceeded(rotation, theta, overturned, uplifted)) == [False, True, True, True]
    assert list(exact_exceeded(uplift, theta, overturned, uplifted)) == [False, True, True, True]
    assert list(exact_exceeded(uplift, theta, overturned, ~uplifted)) == [True, False, False,
                                                                          False]


def test_other_procedures_have_no_checks():
    for name in ("priestley1978", "fema356"):
        assert get_procedures(name)[0].checks(None, np.array([1.0]), ALPHA, 0.9, None) == []
    assert Procedure.checks is not NTC2018.checks


def test_registry_and_requirements():
    assert "ntc2018" in available_procedures()
    assert "ntc2018" in [p.name for p in get_procedures("all")]
    procedure = NTC2018()
    motion = one_pulse("sine", 0.5, 1.0)
    with_motion = RecordEntry("pulse", motion)
    assert procedure.demand_variant(with_motion) == "record"
    assert procedure.unmet_requirements(with_motion) is None
    assert procedure.demand_variant(site_entry(0.2)) == "code-spectrum"
    assert procedure.unmet_requirements(site_entry(0.2)) is None
    partial = RecordEntry("partial", motion, site={"ntc_ag_g": 0.2})
    assert procedure.demand_variant(partial) == "code-spectrum"
    assert "ntc_f0" in procedure.unmet_requirements(partial)
    nothing = RecordEntry("nothing", None, missing_reason="no public file")
    assert procedure.unmet_requirements(nothing).startswith("no record file")
    assert NTC2018(demand="record").unmet_requirements(site_entry(0.2)).startswith("no record")
    with pytest.raises(InputError, match="demand"):
        NTC2018(demand="both")


def test_running_maximum_matches_dense_sampling():
    rng = np.random.default_rng(3)
    periods = np.concatenate(([0.0], np.sort(rng.uniform(0.01, 5.0, 40))))
    values = rng.uniform(0.0, 1.0, periods.size)
    upto = np.array([0.0, 0.3, 1.7, 4.99, 7.0])
    dense = [np.interp(np.linspace(0.0, u, 200001), periods, values).max() for u in upto]
    # dense samples fall a little short of the true maximum at a tabulated period
    maximum = running_maximum(periods, values, upto)
    assert np.all(maximum >= dense)
    np.testing.assert_allclose(maximum, dense, rtol=1e-4)


# --- real records ------------------------------------------------------------------------------


def _uplift_grid(motion):
    """Slendernesses whose g tan α straddles the record's PGA (all below 45°)."""
    factors = np.array([0.5, 0.9, 0.99, 1.01, 1.1, 1.5])
    alpha = np.arctan(motion.pga_g * factors)
    return alpha[alpha < math.radians(44)]


def test_sld_equals_the_exact_uplift_criterion(seed_suite):
    """With e* = FC = 1, SLD passes exactly where the exact solver's block does not uplift."""
    procedure = NTC2018()
    sizes = np.array([0.5, 1.0, 2.0, 4.0])
    p = 2 * np.pi / sizes
    compared, uplifted = 0, []
    for entry in [e for e in seed_suite if e.motion is not None]:
        alpha = _uplift_grid(entry.motion)
        exact = rocking_spectrum(entry.motion, sizes, alpha)
        context = RecordContext(entry, DEFAULT_FREE_MOTION_S)
        for i, a in enumerate(alpha):
            sld = procedure.checks(entry, p, a, 0.9, context)[0]
            assert sld.limit_state == "SLD"
            np.testing.assert_array_equal(sld.passes, ~exact.uplifted[i])
            verdicts = check_verdicts(sld.passes, exact_exceeded(sld, exact.theta_peak[i],
                                                                 exact.overturned[i],
                                                                 exact.uplifted[i]))
            assert set(verdicts) <= {"agrees-safe", "agrees-unsafe"}
            compared += sizes.size
        uplifted.extend(exact.uplifted.ravel())
    # both sides of the criterion were met, on every record with a file
    assert any(uplifted) and not all(uplifted) and compared >= 5 * sizes.size


def test_record_demand_is_the_largest_sd_up_to_t_slv(seed_suite):
    """Record-based SLV demand = max of Sd(T, 8 %) over (0, T_SLV], here on periods computed
    directly by the oscillator, independent of the runner's period table."""
    entry = seed_suite.get("rinaldi_1994")
    procedure = NTC2018()
    p = np.array([2 * np.pi / 1.5, 2 * np.pi / 4.0])
    alpha = math.radians(10)
    context = RecordContext(entry, DEFAULT_FREE_MOTION_S)
    slv = procedure.checks(entry, p, alpha, 0.9, context)[2]
    assert slv.limit_state == "SLV"
    for demand, t_slv in zip(slv.demand_m, slv.period_s):
        periods = np.linspace(0.02, t_slv, 300)
        direct = response_spectra(entry.motion, periods, [0.08], DEFAULT_FREE_MOTION_S).sd[0]
        assert demand == pytest.approx(direct.max(), rel=0.02)


def test_runner_audits_the_rotation_on_a_pulse():
    """The existing runner takes the plug-in as it is: one row per block, θ compared."""
    suite = RecordSuite((RecordEntry("pulse", one_pulse("sine", 0.5, 1.0)),), "one pulse")
    run = audit_in_memory([NTC2018()], suite, alpha_deg=[10.0, 30.0], size_s=np.array([1.0, 3.0]))
    rows = run.results
    assert len(rows) == 4 and set(rows["procedure"]) == {"ntc2018"}
    # α = 30°: g tan α = 0.577 g > 0.5 g: neither rocks
    assert set(rows.loc[rows["alpha_deg"] == 30.0, "verdict"]) == {"no-uplift"}
    assert np.allclose(rows.loc[rows["alpha_deg"] == 10.0, "beta_pct"], 8.0)


def test_design_spectrum_cli_prints_the_ntc_spectrum(capsys):
    from audit.cli import main
    assert main(["design-spectrum", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
                 "--soil", "B", "--topography", "T2", "--damping", "5,8",
                 "--periods", "0:6:0.5"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "period_s,damping_pct,sa_g,sd_m"
    for line in lines[1:]:
        period, damping_pct, sa_g, sd = map(float, line.split(","))
        se, sde = hand_ntc(period, 0.25, 2.4, 0.3, damping_pct, s_t=1.2)
        assert sa_g == pytest.approx(se, rel=1e-6) and sd == pytest.approx(sde, rel=1e-6, abs=1e-9)
    assert len(lines) == 1 + 2 * 13


def test_runner_audits_every_check_against_its_exact_event(seed_suite):
    """checks.csv: SLD against the exact uplift, SLV/SLC against θ(0.4 b)/θ(0.6 b) or overturning.

    The expected events are recomputed here from the exact peak rotations of results.csv
    with θ(k·b) = α − asin((1 − k) sin α) (d = R[sin α − sin(α − θ)], b = R sin α), and the
    procedure's SLD from the recorded PGA, not from the plug-in.
    """
    from procedures import get_procedures
    from records import RecordSuite
    suite = RecordSuite((seed_suite.get("sylmar_1994"),), "one record")
    run = audit_in_memory(get_procedures("ntc2018"), suite, alpha_deg=[10.0, 20.0],
                    size_s=np.arange(0.5, 8.01, 0.5))
    checks, results = run.checks, run.results.set_index(["alpha_deg", "size_s"])
    assert set(checks["limit_state"]) == {"SLD", "SLV-linear", "SLV", "SLC"}
    assert len(checks) == 4 * len(results)
    pga = seed_suite.get("sylmar_1994").motion.pga
    for (limit, alpha_deg), rows in checks.groupby(["limit_state", "alpha_deg"]):
        alpha = math.radians(alpha_deg)
        exact = results.loc[[(alpha_deg, s) for s in rows["size_s"]]]
        if limit == "SLD":
            assert (rows["exact_exceeded"].to_numpy() == exact["exact_uplifted"].to_numpy()).all()
            assert (rows["procedure_passes"] == (pga <= 9.81 * math.tan(alpha))).all()
            continue
        k = {"SLV-linear": 0.4, "SLV": 0.4, "SLC": 0.6}[limit]
        limit_theta = alpha - math.asin((1 - k) * math.sin(alpha))
        expected = ((exact["exact_theta_rad"].to_numpy() >= limit_theta)
                    | exact["exact_overturned"].to_numpy().astype(bool))
        assert (rows["exact_exceeded"].to_numpy() == expected).all(), limit
    unsafe = checks["verdict"] == "missed"
    assert (checks.loc[unsafe, "procedure_passes"] & checks.loc[unsafe, "exact_exceeded"]).all()
