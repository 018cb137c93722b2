"""Housner (1963): the energy criterion on the velocity spectrum, a check of overturning.

A block of slenderness α overturns with about 50 % probability when the record's spectral
velocity reaches S_v,cr (eq. 17, α = S_v √(MR/(I₀g)); for a rectangle MR²/I₀ = 3/4, so
S_v,cr = gα/p). The check passes a block when S_v < S_v,cr, and is audited against exact
overturning.

Which S_v of a real record the paper leaves open: its derivation takes the energy an
idealised motion with a flat, undamped velocity spectrum feeds the block, and notes that the
block's "damping" vanishes near instability. The default is therefore the peak of the record's
lightly damped (ξ = 2 %) true relative-velocity spectrum over periods up to 10 s: the largest
kinetic energy the record gives a system with little damping, the least favourable reading of
the criterion. ``damping``, ``max_period_s`` and ``slender`` (Housner's eq. 17a, α√(gR),
13 % lower) are options. The equations were transcribed from the paper by the project and
tested against numbers worked by hand.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from audit import G
from audit.physics.block import radius_from_p
from audit.physics.overturning_criteria import (housner_critical_velocity,
                                                housner_critical_velocity_slender)
from procedures.base import EXACT_OVERTURNING, Check, Procedure


@dataclass(frozen=True)
class Housner1963(Procedure):
    """Housner's (1963) overturning criterion on the velocity spectrum (eqs. 17, 17a).

    Attributes
    ----------
    damping : float
        ξ of the velocity spectrum read [-].
    max_period_s : float
        S_v is the spectrum's peak over periods up to this one [s].
    slender : bool
        Eq. 17a (MR²/I₀ ≈ 1, S_v,cr = α√(gR)) instead of eq. 17 for a rectangle (gα/p).
    """

    damping: float = 0.02
    max_period_s: float = 10.0
    slender: bool = False

    name = "housner1963"
    title = "Housner (1963), energy criterion"
    reference = ("Housner, G. W. (1963). The behavior of inverted pendulum structures during "
                 "earthquakes. Bulletin of the Seismological Society of America 53(2), 403–417.")
    damping_law = "no equivalent damping: a limit state on the record's velocity spectrum"
    spectrum_source = ("peak of the record's true relative-velocity spectrum at ξ = 2 % over "
                       "T ≤ 10 s, against S_v,cr = gα/p (eq. 17, rectangle)")
    requires_motion = True
    estimates_rotation = False
    alpha_per_block = True

    def checks(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> list[Check]:
        p = np.asarray(p, dtype=float)
        spectra = context.true_spectra(self.damping)
        demand = float(np.max(spectra.sv[0][spectra.period_s <= self.max_period_s]))
        capacity = (housner_critical_velocity_slender(alpha_rad, radius_from_p(p, g), g)
                    if self.slender else housner_critical_velocity(alpha_rad, p, g))
        nan = np.full(p.shape, np.nan)
        return [Check("overturning", EXACT_OVERTURNING, demand < capacity, nan, nan, nan, nan,
                      nan, nan, nan,
                      f"max S_v(T ≤ {self.max_period_s:g} s, ξ = {100 * self.damping:g} %) < "
                      + ("α√(gR) (eq. 17a)" if self.slender else "gα/p (eq. 17, rectangle)"),
                      demand_m_s=np.full(p.shape, demand), capacity_m_s=capacity)]
