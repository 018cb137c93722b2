"""Evaluators of the claims (:mod:`audit.engine.claims.evaluators`) that the physics answers
without the run: the report's closed forms, one block or one oscillator under the one-cosine pulse
of Figures 4.1, 4.2 and 7.2, and free rocking against Housner's Eq. 7.5.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np

from audit import G
from audit.engine.claims.value import CLAIMS_FILE, Value
from audit.engine.shared.blocks import Block
from audit.errors import InputError
from audit.physics.block import coefficient_of_restitution, radius_from_p
from audit.physics.damping import (damping_fema356, damping_free_rocking, damping_priestley,
                                   housner_peak_ratio, housner_period)
from audit.physics.response_spectra import response_spectra
from audit.physics.rocking import simulate
from records import GroundMotion, one_pulse

#: Duration of the one-cosine pulses of Figures 4.1, 4.2 and 7.2 [s] and the free motion after.
PULSE_PERIOD_S = 2.0
PULSE_FREE_MOTION_S = 8.0


def closed_form(ctx, quantity: str, **params) -> Value:
    """A value of the report's closed forms (Eqs. 4.8, 7.9, 7.10, 9.1, R = 3g/(4p²)).

    Parameters
    ----------
    ctx : ClaimContext
        The run (its ``g`` [m/s²]).
    quantity : str
        ``restitution``, ``half_height_m``, ``half_width_m``, ``radius_m``, ``tan``, ``radians``,
        ``damping_priestley_pct``, ``damping_fema_pct``, ``fema_to_priestley_damping`` or
        ``eq79_max_deviation``.
    **params
        What the quantity reads: ``alpha_deg`` [degrees], ``p_rad_s`` [rad/s], ``size_s`` [s],
        ``theta0_ratio`` (θ0/α [-]) and ``n_impacts``.
    """
    alpha = np.radians(params.get("alpha_deg", 0.0))
    r = coefficient_of_restitution(alpha)
    if quantity == "restitution":
        return Value(float(r))
    if quantity in ("half_height_m", "half_width_m"):
        block = _block(params["p_rad_s"], params["alpha_deg"], ctx.g)
        return Value(block.height_m / 2 if quantity == "half_height_m" else block.width_m / 2)
    if quantity == "radius_m":
        return Value(float(radius_from_p(2.0 * math.pi / params["size_s"], ctx.g)))
    if quantity == "tan":
        return Value(float(np.tan(alpha)))
    if quantity == "radians":
        return Value(float(alpha))
    if quantity == "damping_priestley_pct":
        return Value(100.0 * float(damping_priestley(r)))
    if quantity == "damping_fema_pct":
        return Value(100.0 * float(damping_fema356(r)))
    if quantity == "fema_to_priestley_damping":
        return Value(float(np.mean(damping_fema356(r) / damping_priestley(r))))
    if quantity == "eq79_max_deviation":
        x0, n, rr = np.meshgrid(params["theta0_ratio"], params["n_impacts"], r, indexing="ij")
        return Value(float(np.max(np.abs(damping_free_rocking(x0, n, rr)
                                         / damping_priestley(rr) - 1.0))))
    raise InputError(f"{CLAIMS_FILE}: closed_form: unknown quantity '{quantity}'")


def _block(p_rad_s: float, alpha_deg: float, g: float) -> Block:
    """The claims' block of frequency parameter p [rad/s] (2π/(2π/p) is p again for the p of
    claims.toml, 1 and 2 rad/s)."""
    return Block(alpha_deg=alpha_deg, size_s=2.0 * math.pi / p_rad_s, g=g)


@cache
def _pulse_response(p_rad_s: float, alpha_deg: float, amplitude_g: float):
    motion = one_pulse("cosine", amplitude_g, PULSE_PERIOD_S)
    return simulate(_block(p_rad_s, alpha_deg, G).rigid, motion, PULSE_FREE_MOTION_S)


def pulse_block(ctx, quantity: str, p_rad_s: float, alpha_deg: float,
                amplitude_g: float) -> Value:
    """One block under the 2-s one-cosine pulse of Figures 4.1/4.2 (Eq. 4.9), 8 s after it.

    Quantities: ``overturned``; ``impacts_after_pulse``; ``free_peak_ratio`` (largest |θ|/α at a
    turning point after the pulse); ``first_free_cycle_s`` (first full cycle, two impacts,
    after the pulse [s]); ``fraction_cycles_shortening`` (share of successive free cycles no
    longer than the one before).

    Parameters
    ----------
    ctx : ClaimContext
        The run.
    quantity : str
        One of the quantities above.
    p_rad_s : float
        Frequency parameter p [rad/s].
    alpha_deg : float
        Slenderness α [degrees].
    amplitude_g : float
        Pulse amplitude [g].
    """
    response = _pulse_response(p_rad_s, alpha_deg, amplitude_g)
    end = response.excitation_end
    if quantity == "overturned":
        return Value(response.overturned)
    if response.overturned:
        return Value(None, f"the block overturns at t = {response.overturn_time:.2f} s")
    impacts = response.impact_times[response.impact_times > end]
    if quantity == "impacts_after_pulse":
        return Value(int(impacts.size))
    if quantity == "free_peak_ratio":
        peak = response.peak_rotation_free_vibration
        return Value(peak / response.block.alpha if math.isfinite(peak) else None)
    cycles = impacts[2::2] - impacts[:-2:2]
    if quantity == "first_free_cycle_s":
        return Value(float(cycles[0]) if cycles.size else None)
    if quantity == "fraction_cycles_shortening":
        if cycles.size < 2:
            return Value(None, "fewer than two free cycles")
        return Value(float(np.mean(cycles[1:] <= cycles[:-1] * (1.0 + 1e-9))))
    raise InputError(f"{CLAIMS_FILE}: pulse_block: unknown quantity '{quantity}'")


def oscillator_pulse(ctx, period_s: float, damping_pct: float, amplitude_g: float) -> Value:
    """Peak |u| [m] of the linear oscillator (Eq. 3.2) under the pulse of Figure 7.2.

    Parameters
    ----------
    ctx : ClaimContext
        The run.
    period_s : float
        Oscillator period [s].
    damping_pct : float
        Damping ratio [%].
    amplitude_g : float
        Pulse amplitude [g].
    """
    motion = one_pulse("cosine", amplitude_g, PULSE_PERIOD_S)
    spectra = response_spectra(motion, [period_s], [damping_pct / 100.0], PULSE_FREE_MOTION_S)
    return Value(float(spectra.sd[0, 0]))


def free_rocking(ctx, alpha_deg: float, size_s: float, theta0_ratio: float,
                 n_impacts: int) -> Value:
    """Simulated θn/α of free rocking from θ0 at rest, over Housner's Eq. 7.5, minus 1.

    Parameters
    ----------
    ctx : ClaimContext
        The run (its ``g`` [m/s²]).
    alpha_deg : float
        Slenderness α [degrees].
    size_s : float
        Size 2π/p [s].
    theta0_ratio : float
        Initial rotation θ0/α [-].
    n_impacts : int
        The impact n after which θn is read.
    """
    block = Block(alpha_deg=alpha_deg, size_s=size_s, g=ctx.g).rigid
    # enough time for n impacts: each half-cycle is shorter than a quarter of T(θ0) × 2
    duration = (n_impacts + 2) * float(housner_period(theta0_ratio, block.p))
    still = GroundMotion("free rocking", np.zeros(2), dt=1e-3)
    response = simulate(block, still, duration, initial_rotation=theta0_ratio * block.alpha)
    if response.n_impacts < n_impacts + 1:
        return Value(None, f"only {response.n_impacts} impacts")
    after = response.turning_times > response.impact_times[n_impacts - 1]
    simulated = abs(response.turning_rotations[after][0]) / block.alpha
    return Value(float(simulated / housner_peak_ratio(theta0_ratio, n_impacts, block.r) - 1.0))
