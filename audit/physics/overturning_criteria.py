"""Closed-form overturning criteria of a rigid block: Housner (1963) and the pulse criteria of
Makris & Roussos (2000) and Zhang & Makris (2001), and their design inversions.

Amplitudes are returned as a_p0/(αg) [-] (small-angle, as published) against ω_p/p [-], with
ω_p = 2π/T_p the pulse's circular frequency and p = √(3g/(4R)) the block's frequency parameter.
The equations were transcribed from the papers by the project (Housner 1963, BSSA 53(2) eqs 12,
17, 17a; Makris & Roussos 2000, Géotechnique 50(3) eqs 27–29, 41–46; Zhang & Makris 2001, J. Eng.
Mech. 127(5) eqs 21, 47); the no-impact impulse criterion of :func:`impulse_minimum_amplitude`
is derived in ``docs/overturning-criteria.md``. Tests hold them to numbers worked independently.
"""

from __future__ import annotations

import math

import numpy as np

from audit import G

HALF_SINE, ONE_SINE, ONE_COSINE = "half-sine", "one-sine", "one-cosine"
PULSE_SHAPES = (HALF_SINE, ONE_SINE, ONE_COSINE)
#: β of the published linear approximations a_p0/(αg) ≈ 1 + β ω_p/p: Makris & Roussos 2000
#: eqs 28 (half-sine), 41 (one-sine, type A) and 43 (one-cosine, type B); Zhang & Makris 2001
#: eq 21.
LINEAR_BETA = {HALF_SINE: 0.5, ONE_SINE: 1.0 / 6.0, ONE_COSINE: 0.25}


def housner_critical_velocity(alpha_rad, p_rad_s, g: float = G):
    """Spectral velocity at which Housner (1963) gives a rectangular block a 50 % chance of
    overturning, S_v,cr = gα/p [m/s]: eq. 17, α = S_v √(MR/(I₀g)), with MR²/I₀ = 3/4.

    Parameters
    ----------
    alpha_rad : float or array
        Slenderness α [rad].
    p_rad_s : float or array
        Frequency parameter p [rad/s].
    g : float
        Acceleration of gravity [m/s²].
    """
    return g * np.asarray(alpha_rad, dtype=float) / np.asarray(p_rad_s, dtype=float)


def housner_critical_velocity_slender(alpha_rad, radius_m, g: float = G):
    """Housner's eq. 17a for slender structures (MR²/I₀ ≈ 1), S_v,cr = α √(gR) [m/s]: 13 % below
    eq. 17 for a rectangle.

    Parameters
    ----------
    alpha_rad : float or array
        Slenderness α [rad].
    radius_m : float or array
        Half-diagonal R [m].
    g : float
        Acceleration of gravity [m/s²].
    """
    return np.asarray(alpha_rad, dtype=float) * np.sqrt(g * np.asarray(radius_m, dtype=float))


def linear_minimum_amplitude(frequency_ratio, shape: str):
    """The published linear approximation a_p0/(αg) = 1 + β ω_p/p [-] (:data:`LINEAR_BETA`).

    Parameters
    ----------
    frequency_ratio : float or array
        ω_p/p [-].
    shape : str
        ``half-sine``, ``one-sine`` or ``one-cosine``.
    """
    return 1.0 + LINEAR_BETA[shape] * np.asarray(frequency_ratio, dtype=float)


def housner_half_sine_amplitude(frequency_ratio):
    """Housner (1963) eq. 12 for a half-sine pulse, a/(gα) = √(1 + (ω_p/p)²) [-]: the check
    Makris & Roussos (2000) showed to be unconservative (the block may overturn in the free
    motion after the pulse)."""
    ratio = np.asarray(frequency_ratio, dtype=float)
    return np.sqrt(1.0 + ratio ** 2)


def _solve_psi(frequency_ratio: float, span: float, sign: float) -> float:
    """ψ ∈ (0, π/2) of (ω/p) sin ψ − cos ψ = sign · exp[−(p/ω)(span − ψ)]; a_p0/(αg) = 1/sin ψ."""
    # kept local, as below: the procedures import this module, and scipy.optimize's ~0.5 s
    # import would hold up every run before its first record starts (a run's fixed-point
    # scan imports it later, in a worker beside the solver)
    from scipy.optimize import brentq
    ratio = float(frequency_ratio)

    def residual(psi):
        return ratio * math.sin(psi) - math.cos(psi) - sign * math.exp(-(span - psi) / ratio)

    return brentq(residual, 1e-12, math.pi / 2, xtol=1e-14)


def half_sine_minimum_amplitude(frequency_ratio):
    """Minimum overturning amplitude a_p0/(αg) [-] of the linearised block under a half-sine
    pulse, Makris & Roussos (2000) eq. 27: (ω_p/p) sin ψ − cos ψ = exp[−(p/ω_p)(π − ψ)],
    a_p0 = αg / sin ψ."""
    return np.vectorize(lambda ratio: 1.0 / math.sin(_solve_psi(ratio, math.pi, 1.0)))(
        frequency_ratio)


def one_sine_no_impact_amplitude(frequency_ratio):
    """Amplitude a_p/(αg) [-] above which a one-sine pulse overturns the linearised block
    without impact (mode 2), Zhang & Makris (2001) eq. 47: (ω_p/p) sin ψ − cos ψ =
    −exp[−(p/ω_p)(2π − ψ)], a_p = αg / sin ψ."""
    return np.vectorize(lambda ratio: 1.0 / math.sin(_solve_psi(ratio, 2 * math.pi, -1.0)))(
        frequency_ratio)


def _pulse_shape(shape: str, omega: float):
    """ü_g(t)/a_p of a pulse starting at t = 0, and its end [s]."""
    if shape == HALF_SINE:
        return (lambda t: math.sin(omega * t)), math.pi / omega
    if shape == ONE_SINE:
        return (lambda t: math.sin(omega * t)), 2 * math.pi / omega
    if shape == ONE_COSINE:
        return (lambda t: math.cos(omega * t)), 2 * math.pi / omega
    raise ValueError(f"pulse shape: unknown {shape!r}, expected one of {', '.join(PULSE_SHAPES)}")


def impulse_minimum_amplitude(frequency_ratio: float, shape: str) -> float:
    """Smallest a_p/(αg) [-] at which the linearised block, uplifted at the first instant
    ü_g = αg, overturns during the pulse or the free motion after it without an impact:

        p ∫_{t_u}^{T} (ü_g(s)/g) e^{−p(s − t_u)} ds ≥ α,

    the exponentially weighted impulse from uplift t_u to the pulse's end T (derivation in
    ``docs/overturning-criteria.md``; valid while the block does not return to θ = 0 before T).
    It reproduces eq. 27 for the half-sine and eq. 47 for the one-sine pulse, and applies to any
    pulse shape. Computed with p = 1 (only ω_p/p matters).
    """
    from scipy.integrate import quad  # kept local: scipy.integrate costs start-up to every run
    from scipy.optimize import brentq
    wave, end = _pulse_shape(shape, float(frequency_ratio))

    def weighted_impulse(amplitude):  # in units of αg: uplift where amplitude·wave(t) = 1
        times = np.linspace(0.0, end, 20001)
        above = np.flatnonzero(amplitude * np.vectorize(wave)(times) >= 1.0)
        if above.size == 0:
            return -1.0
        start = brentq(lambda t: amplitude * wave(t) - 1.0, times[max(above[0] - 1, 0)],
                       times[above[0]]) if above[0] else 0.0
        integral = quad(lambda s: amplitude * wave(s) * math.exp(-(s - start)), start, end,
                        limit=200, epsabs=1e-13, epsrel=1e-12)[0]
        return integral - 1.0

    high = 2.0
    while weighted_impulse(high) < 0.0:
        high *= 2.0
    return brentq(weighted_impulse, 1.0 + 1e-9, high, xtol=1e-12)


def exact_minimum_amplitude(block, shape: str, period_s: float, step: float = 0.001,
                            beyond: float = 1.5, tolerance: float = 1e-5,
                            free_motion_s: float = 10.0):
    """The exact solver's minimum overturning amplitude x = a_p/(g tan α) [-] of ``block`` under
    a one-cycle pulse, and the safe regions above it.

    Scans x upward from 1 (uplift) in relative steps of ``step``, refines the first overturning
    by bisection to ``tolerance``, then scans on to ``beyond`` × that amplitude and reports the
    amplitude windows in which the block survives again (Zhang & Makris 2001: overturning is not
    monotonic in the amplitude). A window is known to the scan's step only.

    Parameters
    ----------
    block : audit.physics.block.RigidBlock
    shape : str
        ``one-sine`` (type A) or ``one-cosine`` (type B), starting at t = 0.
    period_s : float
        T_p [s].
    step, beyond, tolerance :
        Relative scan step, end of the scan past the first overturning, bisection tolerance.
    free_motion_s : float
        Free motion after the pulse [s].

    Returns
    -------
    x_min : float
        First overturning amplitude.
    safe : list of (float, float)
        Amplitudes (first and last scanned) of each window above x_min in which it survives.
    """
    from audit.physics.rocking import simulate
    from records import one_pulse
    kind = {ONE_SINE: "sine", ONE_COSINE: "cosine"}[shape]
    unit_g = block.g * math.tan(block.alpha) / G  # x = 1 in g, as one_pulse takes it

    def overturns(x):
        return simulate(block, one_pulse(kind, x * unit_g, period_s), free_motion_s).overturned

    x = 1.0
    while not overturns(x * (1.0 + step)):
        x *= 1.0 + step
        if x > 100.0:
            raise ValueError("no overturning up to 100 g tan α")
    low, high = x, x * (1.0 + step)
    while high - low > tolerance * low:
        middle = 0.5 * (low + high)
        low, high = (low, middle) if overturns(middle) else (middle, high)
    safe, window = [], None
    x = high
    while x < beyond * high:
        x *= 1.0 + step
        if not overturns(x):
            window = (window[0], x) if window else (x, x)
        elif window:
            safe.append(window)
            window = None
    if window:
        safe.append(window)
    return high, safe


def required_alpha_pulse(amplitude_m_s2, period_s, radius_m, shape: str, g: float = G):
    """Design inversion of the published line: the smallest slenderness [rad] a block of
    half-diagonal R needs to survive a pulse of amplitude a_p and period T_p,
    α = a_p / (g (1 + β ω_p/p)) (p depends on R alone).

    Parameters
    ----------
    amplitude_m_s2 : float or array
        a_p [m/s²].
    period_s : float or array
        T_p [s].
    radius_m : float or array
        R [m].
    shape : str
        ``half-sine``, ``one-sine`` or ``one-cosine``.
    g : float
        Acceleration of gravity [m/s²].
    """
    p = np.sqrt(3.0 * g / (4.0 * np.asarray(radius_m, dtype=float)))
    ratio = 2.0 * np.pi / np.asarray(period_s, dtype=float) / p
    return np.asarray(amplitude_m_s2, dtype=float) / (g * linear_minimum_amplitude(ratio, shape))


def required_alpha_housner(spectral_velocity_m_s, p_rad_s, g: float = G):
    """Design inversion of Housner's eq. 17 for a rectangle: α = p S_v / g [rad]."""
    return np.asarray(p_rad_s, dtype=float) * np.asarray(spectral_velocity_m_s, dtype=float) / g


__all__ = ["PULSE_SHAPES", "HALF_SINE", "ONE_SINE", "ONE_COSINE", "LINEAR_BETA",
           "housner_critical_velocity", "housner_critical_velocity_slender",
           "linear_minimum_amplitude", "housner_half_sine_amplitude",
           "half_sine_minimum_amplitude", "one_sine_no_impact_amplitude",
           "impulse_minimum_amplitude", "exact_minimum_amplitude", "required_alpha_pulse", "required_alpha_housner"]
