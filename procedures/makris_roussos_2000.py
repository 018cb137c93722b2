"""Makris & Roussos (2000), Zhang & Makris (2001): the minimum overturning acceleration of a
block under a near-fault pulse, a check of overturning.

The block survives a pulse of amplitude a_p and period T_p (ω_p = 2π/T_p) when a_p is below
the minimum overturning amplitude a_p0. Variants:

* ``published`` (default, what designers use): the linear approximations a_p0/(αg) =
  1 + β ω_p/p, β = 1/2 half-sine (eq. 28), 1/6 one-sine (eq. 41), 1/4 one-cosine (eq. 43);
* ``exact-linear``: the linearised block's exact condition, eq. 27 (half-sine) and eq. 47
  (one-sine, no impact), the no-impact impulse criterion for the one-cosine pulse;
* ``housner``: Housner's (1963) half-sine eq. 12, a_p0/(αg) = √(1 + (ω_p/p)²), whatever the
  pulse (the historical check).

Small-angle αg as published; ``tan_alpha`` uses g tan α instead. The pulse comes from the
record itself when it is an analytic pulse (its shape, amplitude and period), else from the
record's catalogue: Table 5.1's main-pulse period with the record's PGA as a_p, and a
one-cosine (type B, forward-and-back) pulse assumed, the shape of the built-in pulse suite.
Any other real record is classified by Shahi & Baker (2014) (:mod:`audit.physics.pulses`): a
pulse-like record is judged with T_p = 1/f_p and a_p = the peak acceleration of the
Mavroeidis & Papageorgiou pulse fitted to the extracted pulse (the extracted pulse is a sum of
db4 wavelets whose own acceleration is rough), along the record's component, one-cosine
assumed; the basis names Shahi & Baker's T_p and candidate too, since the two periods differ by
up to ~20 %. A record that is not pulse-like is not audited ("not pulse-like (PI …)"). The
equations were transcribed from the papers by the project and tested against numbers worked
by hand.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.overturning_criteria import (HALF_SINE, ONE_COSINE, ONE_SINE,
                                                half_sine_minimum_amplitude,
                                                housner_half_sine_amplitude,
                                                impulse_minimum_amplitude,
                                                linear_minimum_amplitude,
                                                one_sine_no_impact_amplitude)
from procedures.base import EXACT_OVERTURNING, Check, Procedure

PUBLISHED, EXACT_LINEAR, HOUSNER = "published", "exact-linear", "housner"
#: Shape of the pulse module records.pulses makes, in the criteria's names.
_SHAPES = {"cosine": ONE_COSINE, "sine": ONE_SINE}


def pulse_of(entry):
    """(shape, a_p [m/s²], T_p [s], where from) of a record's pulse, or (why not) a string."""
    motion = entry.motion
    if motion is None:
        return "no record"
    if motion.pulse is not None:
        pulse = motion.pulse
        return _SHAPES[pulse.shape], pulse.amplitude, pulse.period_s, "the analytic pulse"
    facts = entry.facts
    if facts is not None and facts.pulse_period_s:
        return (ONE_COSINE, motion.pga, facts.pulse_period_s,
                "Table 5.1's T_p with the record's PGA, one-cosine assumed")
    # imported here: the identification's wavelets and fit (scipy.signal, scipy.optimize) cost
    # every command that loads the registry 1.5 s, and only a real record's pulse needs them
    from audit.physics.pulses.record_pulse import record_pulse
    found = record_pulse(entry)
    if math.isnan(found.pulse_indicator):
        return f"no pulse identified: {found.classified}"
    if not found.pulse_like:
        return (f"not pulse-like (PI {found.pulse_indicator:.2f} ≤ 0, Shahi & Baker 2014 on "
                f"{found.classified})")
    fit = found.fit
    return (ONE_COSINE, found.amplitude_m_s2, fit.period_s,
            f"T_p = 1/f_p of the Mavroeidis-Papageorgiou pulse fitted to the Shahi & Baker "
            f"(2014) pulse (their T_p = {found.tp_s:.3g} s, candidate {found.candidate}, "
            f"PI {found.pulse_indicator:.1f}, θ = {found.direction_deg:.0f}° on "
            f"{found.classified}); a_p its peak acceleration × {abs(found.component_factor):.2f} "
            f"along this component; one-cosine assumed")


def minimum_amplitude_ratio(frequency_ratio, shape: str, variant: str):
    """a_p0/(αg) [-] of a variant (see the module docstring) at ω_p/p."""
    if variant == PUBLISHED:
        return linear_minimum_amplitude(frequency_ratio, shape)
    if variant == HOUSNER:
        return housner_half_sine_amplitude(frequency_ratio)
    if shape == HALF_SINE:
        return half_sine_minimum_amplitude(frequency_ratio)
    if shape == ONE_SINE:
        return one_sine_no_impact_amplitude(frequency_ratio)
    return np.vectorize(lambda ratio: impulse_minimum_amplitude(ratio, shape))(frequency_ratio)


@dataclass(frozen=True)
class MakrisRoussos2000(Procedure):
    """Pulse overturning criteria of Makris & Roussos (2000) and Zhang & Makris (2001).

    Attributes
    ----------
    variant : str
        ``published``, ``exact-linear`` or ``housner``.
    tan_alpha : bool
        g tan α instead of the published small-angle αg.
    """

    variant: str = PUBLISHED
    tan_alpha: bool = False

    name = "makrisroussos2000"
    title = "Makris & Roussos (2000), pulse criterion"
    reference = ("Makris, N. and Roussos, Y. S. (2000). Rocking response of rigid blocks under "
                 "near-source ground motions. Géotechnique 50(3), 243–262; Zhang, J. and Makris, "
                 "N. (2001). Rocking response of free-standing blocks under cycloidal pulses. "
                 "Journal of Engineering Mechanics 127(5), 473–483.")
    damping_law = "no equivalent damping: a limit state on the pulse's amplitude and period"
    spectrum_source = ("a_p0/(αg) = 1 + β ω_p/p (β = 1/2 half-sine, 1/6 one-sine, 1/4 "
                       "one-cosine); pulse from the analytic pulse, or Table 5.1's T_p with the "
                       "record's PGA (one-cosine assumed), else the Mavroeidis-Papageorgiou "
                       "pulse fitted to the Shahi & Baker (2014) pulse of a pulse-like record")
    basis_note = ("T_p and a_p of each record: the analytic pulse's; for a seed record, Table "
                  "5.1's T_p with its PGA; else T_p = 1/f_p and a_p = the peak acceleration "
                  "along the component of the Mavroeidis-Papageorgiou pulse fitted to the Shahi "
                  "& Baker (2014) pulse (not their wavelet T_p); one-cosine assumed; a record "
                  "that is not pulse-like is not judged")
    requires_motion = True
    estimates_rotation = False
    alpha_per_block = True

    def __post_init__(self):
        if self.variant not in (PUBLISHED, EXACT_LINEAR, HOUSNER):
            raise InputError(f"makrisroussos2000 variant: must be {PUBLISHED}, {EXACT_LINEAR} "
                             f"or {HOUSNER}, got {self.variant!r}")

    def unmet_requirements(self, entry) -> str | None:
        reason = super().unmet_requirements(entry)
        if reason is None:
            pulse = pulse_of(entry)
            if isinstance(pulse, str):
                return pulse
        return reason

    def checks(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> list[Check]:
        p = np.asarray(p, dtype=float)
        shape, amplitude, period_s, source = pulse_of(entry)
        ratio = 2.0 * np.pi / period_s / p
        unit = g * (np.tan(alpha_rad) if self.tan_alpha else alpha_rad)
        capacity = minimum_amplitude_ratio(ratio, shape, self.variant) * unit
        nan = np.full(p.shape, np.nan)
        return [Check("overturning", EXACT_OVERTURNING, amplitude < capacity, nan, nan,
                      np.full(p.shape, amplitude), capacity, nan, nan, nan,
                      f"a_p < a_p0, {self.variant} a_p0 of a {shape} pulse of T_p = "
                      f"{period_s:g} s ({source})")]
