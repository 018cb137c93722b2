"""Guideline procedures: the shared iteration on spectra with known answers, requirements,
the registry, and the published facts of SPEC §5–6 on the real records."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from audit.physics.block import coefficient_of_restitution, radius_from_p
from audit.physics.damping import housner_period
from audit.errors import InputError
from audit.engine.shared.grid import size_grid
from audit.engine.run.pipeline import audit_in_memory
from audit.engine.shared.runtime import Runtime
from procedures.context import RecordContext
from procedures import available_procedures, get_procedures, iterate_rotation
from procedures.fema_356 import FEMA356
from procedures.priestley_1978 import PriestleyEvisonCarr1978
from records import RecordEntry, RecordSuite, one_pulse, pulse_suite

ALPHA = math.radians(15)


def test_constant_spectrum_has_the_closed_form_fixed_point():
    """Sd = D ⇒ θ = D/(R cos α) after one step (Eq. 8.2)."""
    p = np.array([1.0, 2.0, 4.0])
    radius = radius_from_p(p)
    target = 0.4 * ALPHA * radius * math.cos(ALPHA)
    ratio, outcome, iterations, _, _ = iterate_rotation(
        lambda period: np.full(np.shape(period), 1.0) * target, p, ALPHA)
    np.testing.assert_allclose(ratio, 0.4, rtol=1e-12)
    assert list(outcome) == ["converged"] * 3 and list(iterations) == [2, 2, 2]


def test_linear_spectrum_fixed_point_matches_root_finding():
    """Sd = c·T: the fixed point solves x = c·T(x)/(R cos α α), found here by brentq.

    With c = 0.1 m/s the lower fixed point is stable, near θ/α = 0.29."""
    p, c = 1.5, 0.1
    radius = float(radius_from_p(p))

    def residual(x):
        return c * housner_period(x, p) / (radius * math.cos(ALPHA) * ALPHA) - x

    expected = brentq(residual, 0.05, 0.6)
    ratio, outcome, _, _, _ = iterate_rotation(lambda period: c * period, np.array([p]), ALPHA)
    assert outcome[0] == "converged"
    assert ratio[0] == pytest.approx(expected, abs=1e-5)


def test_overturn_and_oscillation_are_reported():
    big = iterate_rotation(lambda period: np.full(np.shape(period), 100.0), np.array([2.0]), ALPHA)
    assert big[1][0] == "overturn" and big[0][0] == 1.0
    # a spectrum that falls steeply with T makes the iteration alternate between two values
    p = 2.0
    scale = float(radius_from_p(p)) * math.cos(ALPHA) * ALPHA
    t_low, t_high = housner_period(0.3, p), housner_period(0.7, p)

    def falling(period):
        return np.where(np.asarray(period) < 0.5 * (t_low + t_high), 0.7, 0.3) * scale

    ratio, outcome, iterations, detail, cycle = iterate_rotation(falling, np.array([p]), ALPHA)
    # 0.1 → 0.7 → 0.3 → 0.7 → 0.3: a cycle counts once a whole period has repeated
    assert outcome[0] == "not-converged" and iterations[0] == 4
    assert "2-cycle between θ/α = 0.3000 and 0.7000" in detail[0] and cycle[0] == "0.3000;0.7000"


def test_slowly_alternating_iteration_converges():
    """Slope −0.99 at the fixed point: alternating, contracting, converges within the cap."""
    p = 2.0
    scale = float(radius_from_p(p)) * math.cos(ALPHA) * ALPHA

    def spectrum(period):
        x = 1.0 - 1.0 / np.cosh(p * np.asarray(period) / 4.0)  # invert Eq. 8.1
        return (0.5 - 0.99 * (x - 0.5)) * scale

    ratio, outcome, iterations, _, _ = iterate_rotation(spectrum, np.array([p]), ALPHA)
    assert outcome[0] == "converged" and 200 < iterations[0] < 2000
    assert ratio[0] == pytest.approx(0.5, abs=1e-4)


def test_requirements_are_declared_and_checked(seed_suite):
    fema, priestley = FEMA356(), PriestleyEvisonCarr1978()
    assert fema.unmet_requirements(seed_suite.get("erzincan_1992")).startswith("no FEMA 356")
    assert fema.unmet_requirements(seed_suite.get("el_centro_5_1979")) is None
    assert priestley.unmet_requirements(seed_suite.get("el_centro_5_1979")).startswith("no record")
    assert priestley.unmet_requirements(seed_suite.get("takatori_1995")) is None


def test_fema_depends_on_the_site_not_the_motion():
    entry = pulse_suite().get("sylmar_1994")
    strong = RecordEntry("x", one_pulse("cosine", 2.0, 1.0), site=entry.site)
    p = 2 * np.pi / size_grid(0.5, 8.0, 0.5)
    r = float(coefficient_of_restitution(ALPHA))
    a = FEMA356().evaluate(entry, p, ALPHA, r, None).estimate
    b = FEMA356().evaluate(strong, p, ALPHA, r, None).estimate
    np.testing.assert_array_equal(a.theta, b.theta)
    assert a.damping == pytest.approx(0.4 * (1 - math.sqrt(r)))


def test_no_uplift_below_the_uplift_acceleration():
    entry = RecordEntry("weak", one_pulse("cosine", 0.1, 1.0))
    context = RecordContext(entry, 10.0)
    estimate = PriestleyEvisonCarr1978().evaluate(entry, np.array([2.0, 3.0]), ALPHA,
                                                  0.8, context).estimate
    assert list(estimate.outcome) == ["no-uplift"] * 2 and np.all(estimate.theta == 0.0)


def test_prefetched_spectra_are_the_record_spectra_computed_once(monkeypatch):
    """Spectra started on a pool ahead of use (as the audit does for Figures 5.x) are the
    record's spectra computed directly, and a later displacement-only read is served by them."""
    from concurrent.futures import ThreadPoolExecutor

    import procedures.context
    from procedures.base import SPECTRUM_PERIODS_S
    response_spectra = procedures.context.response_spectra  # the kernel, called directly
    motion = one_pulse("sine", 0.5, 0.8)
    direct = response_spectra(motion, SPECTRUM_PERIODS_S, [0.05], 2.0)
    calls = []
    monkeypatch.setattr(procedures.context, "response_spectra",
                        lambda *args, **kwargs: calls.append(kwargs) or response_spectra(
                            *args, **kwargs))
    context = RecordContext(RecordEntry("pulse", motion), 2.0, jobs=2)
    with ThreadPoolExecutor(1) as pool:
        context.prefetch(0.05, pool)
        spectra = context.true_spectra(0.05)
    for name in ("sd", "sv", "sa"):
        np.testing.assert_array_equal(getattr(spectra, name), getattr(direct, name))
    sd = context.true_displacement(0.05)(SPECTRUM_PERIODS_S)
    np.testing.assert_array_equal(sd, direct.sd[0])
    assert len(calls) == 1


def test_registry():
    found = available_procedures()
    assert list(found)[:2] == ["priestley1978", "fema356"]
    assert [p.name for p in get_procedures("all")][:2] == ["priestley1978", "fema356"]
    with pytest.raises(InputError, match="unknown 'fema', available: priestley1978, fema356"):
        get_procedures("fema")


@pytest.fixture(scope="module")
def seed_audit(seed_suite):
    return audit_in_memory(get_procedures("all"), seed_suite, runtime=Runtime(jobs=2))


def test_fema_predicts_overturning_of_every_slender_block(seed_audit):
    """SPEC §6 / Section 9: FEMA 356 overturns every α = 10° block up to 2π/p = 8 s."""
    rows = seed_audit.results
    fema = rows[(rows["procedure"] == "fema356") & (rows["alpha_deg"] == 10.0)]
    assert set(fema["record"]) == {"pacoima_dam_1971", "rinaldi_1994", "sylmar_1994"}
    assert fema["approx_overturned"].all() and len(fema) == 3 * 151


def test_priestley_is_over_conservative_for_small_blocks_on_pacoima(seed_audit):
    rows = seed_audit.results
    small = rows[(rows["procedure"] == "priestley1978") & (rows["record"] == "pacoima_dam_1971")
                 & (rows["alpha_deg"] == 20.0) & (rows["size_s"] < 5.0)
                 & (rows["verdict"] == "conservative")]
    assert len(small) > 20 and small["ratio"].min() > 2.0


def test_missing_and_unauditable_records_are_named(seed_audit):
    reasons = {(u["procedure"], u["record"]) for u in seed_audit.summary["unauditable"]}
    assert ("fema356", "erzincan_1992") in reasons and ("fema356", "takatori_1995") in reasons
    assert ("priestley1978", "el_centro_5_1979") in reasons
    assert ("priestley1978", "los_gatos_1989") in reasons
    # FEMA 356 estimates without the file; those rows have no exact response and no verdict
    missing = seed_audit.estimates_only
    assert set(missing["record"]) == {"el_centro_5_1979", "los_gatos_1989"}
    assert set(missing["procedure"]) == {"fema356"} and set(missing["verdict"]) == {""}
    audited = seed_audit.results
    assert not audited["record"].isin(["el_centro_5_1979", "los_gatos_1989"]).any()
    assert set(audited[audited["procedure"] == "priestley1978"]["record"]) == {
        "pacoima_dam_1971", "rinaldi_1994", "sylmar_1994", "erzincan_1992", "takatori_1995"}


def test_verdicts_agree_with_their_definitions(seed_audit):
    rows = seed_audit.results
    exact_over = rows["exact_overturned"].astype(bool)
    for verdict, expected in {
        "both-overturn": exact_over & rows["approx_overturned"],
        "false-overturn": ~exact_over & rows["approx_overturned"],
        "missed-overturn": exact_over & ~rows["approx_overturned"]
        & (rows["approx_outcome"] != "not-converged"),
    }.items():
        assert ((rows["verdict"] == verdict) == expected).all(), verdict
    survivors = rows[rows["verdict"].isin(["agrees", "conservative", "unconservative"])]
    ratio = survivors["approx_theta_rad"] / survivors["exact_theta_rad"]
    assert ((ratio > 1.1) == (survivors["verdict"] == "conservative")).all()
    assert ((ratio < 0.9) == (survivors["verdict"] == "unconservative")).all()
    assert ((abs(ratio - 1) <= 0.1) == (survivors["verdict"] == "agrees")).all()
    # as saved: every number to 10 significant digits (each within 5e-10 of its value)
    np.testing.assert_allclose(survivors["ratio"], ratio, rtol=1.5e-9)


def test_an_audit_of_an_empty_suite_is_empty():
    run = audit_in_memory(get_procedures("all"), RecordSuite((), "nothing"))
    assert run.results.empty and run.summary["unauditable"] == []
