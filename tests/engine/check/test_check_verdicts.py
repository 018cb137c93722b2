"""``audit check`` judges each guideline by its own acceptance criterion: one entry per
(procedure, limit state) whose verdict is what its demand against its capacity says; NTC 2018
by d against d_SLV = 0.4 d₀ and d_SLC = 0.6 d₀ with the mean over records, recomputed here from
an independent linear-oscillator solution (scipy's lsim) and the capacity curve worked by hand;
the exact P of exceeding each limit at least P(overturn)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import lsim

import audit
from audit.engine.check.limits import suite_demand
from tests.engine.check.pulses import PERIODS_S, eight_pulses

G = 9.81
SITE = (1.0, 0.6)  # PGA of the design spectrum 0.4 S_XS = 0.4 g: every pulse scaled to it
WIDTH_M, HEIGHT_M = 0.4, 1.8  # the vitrine



@pytest.fixture(scope="module")
def vitrine():
    return audit.check([f"{WIDTH_M}x{HEIGHT_M}"], SITE,
                       procedures=["ntc2018", "fema356", "housner1963"], records=eight_pulses(),
                       im="pga", solver=audit.Solver(free_motion_s=5.0))


def _peak_displacement(amplitude_g: float, pulse_s: float, period_s: float,
                       damping: float) -> float:
    """max |u| of a linear oscillator under a one-cosine pulse a·cos(2πt/T_p), 0 ≤ t ≤ T_p,
    and 5 s of free motion: scipy's lsim on a fine grid, not the project's kernel."""
    t = np.arange(0.0, pulse_s + 5.0, min(pulse_s, period_s) / 400.0)
    ground = np.where(t <= pulse_s, amplitude_g * G * np.cos(2 * np.pi * t / pulse_s), 0.0)
    omega = 2 * np.pi / period_s
    system = ([1.0], [1.0, 2 * damping * omega, omega ** 2])
    _, u, _ = lsim(system, -ground, t)
    return float(np.max(np.abs(u)))


def _ntc_by_hand(ratio: float, coefficient: float, damping: float) -> tuple[float, float]:
    """(mean over the pulses of d_dem, d_LS) [m] for the vitrine: b = 0.2 m, h = 0.9 m,
    R = √(b² + h²), α = atan(b/h); d_LS = ratio·b; θ(d) = α − asin(sin α − d/R);
    a(d) = g·tan(α − θ(d)) [C8.7.1.3]; T_LS = c·π·√(d_LS/a(d_LS)); each pulse's demand the
    largest Sd at ξ over (0, T_LS] of the pulse scaled to PGA 0.4 g."""
    b, h = WIDTH_M / 2, HEIGHT_M / 2
    radius, alpha = math.hypot(b, h), math.atan(b / h)
    d_ls = ratio * b
    theta = alpha - math.asin(math.sin(alpha) - d_ls / radius)
    period = coefficient * math.pi * math.sqrt(d_ls / (G * math.tan(alpha - theta)))
    periods = np.linspace(0.05, period, 40)
    demands = [max(_peak_displacement(0.4, pulse, t, damping) for t in periods)
               for pulse in PERIODS_S]
    return float(np.mean(demands)), d_ls


def test_every_verdict_is_what_demand_against_capacity_says(vitrine):
    obj = vitrine.document["objects"][0]
    p_overturn = obj["exact"]["p_overturn_at_site"]
    for entry in obj["procedures"]:
        demand, capacity = entry["demand"], entry["capacity"]
        if demand is not None and capacity is not None:
            assert entry["verdict"] == ("passes" if demand <= capacity else "fails"), entry
        else:  # only a rotation estimate reaching α leaves the demand empty
            assert entry["unit"] == "deg" and entry["verdict"] == "fails"
        assert entry["exact_p_exceed"] >= p_overturn
        assert entry["basis"]


@pytest.mark.slow  # ~30 s: scipy's lsim is the reference
def test_ntc_judges_the_vitrine_by_its_own_slv_and_slc_on_d(vitrine):
    obj = vitrine.document["objects"][0]
    ntc = {e["limit_state"]: e for e in obj["procedures"] if e["key"] == "ntc2018"}
    assert set(ntc) == {"SLV", "SLC"}
    for state, ratio, coefficient, damping in (("SLV", 0.4, 1.68, 0.08),
                                               ("SLC", 0.6, 1.56, 0.10)):
        entry = ntc[state]
        demand, capacity = _ntc_by_hand(ratio, coefficient, damping)
        assert entry["unit"] == "m" and entry["capacity"] == pytest.approx(capacity, rel=1e-9)
        assert entry["demand"] == pytest.approx(demand, rel=0.03)
        assert entry["verdict"] == ("passes" if demand <= capacity else "fails")
        assert "mean of the 8 records" in entry["basis"]
        # the limit is below α, so exceeding it is likelier than overturning
        assert entry["exact_p_exceed"] >= obj["exact"]["p_overturn_at_site"]


def test_only_the_limit_state_asked_for_is_reported():
    result = audit.check(["0.4x1.8"], audit.Site(*SITE, limit_state="slc"), procedures=["ntc2018"],
                         records=eight_pulses(), im="pga", solver=audit.Solver(free_motion_s=5.0))
    assert [e["limit_state"] for e in result.document["objects"][0]["procedures"]] == ["SLC"]
    with pytest.raises(audit.errors.InputError, match="limit_state"):
        audit.check(["0.4x1.8"], audit.Site(*SITE, limit_state="SLD"))


def test_a_suite_rule_makes_the_records_demands_one():
    # by hand: mean, largest, and the ⌈n/2⌉-th smallest (an overturning +inf counts as any)
    assert suite_demand([1.0, 2.0, 6.0], "mean") == pytest.approx(3.0)
    assert suite_demand([1.0, 2.0, 6.0], "max") == 6.0
    assert suite_demand([3.0, math.inf, 1.0, 2.0], "median") == 2.0
    assert suite_demand([math.inf, math.inf, 1.0], "median") == math.inf
