"""Exact rocking response of a rigid block (Eqs. 4.3–4.8 of Makris & Konstantinidis 2001) and rocking spectra (Section 5).

The equation of motion (Eq. 4.3)

    θ'' = −p² { sin[α sgn(θ) − θ] + (üg/g) cos[α sgn(θ) − θ] }

is integrated with a classical fixed-step Runge–Kutta scheme inside each interval on which the
ground acceleration is smooth (between two samples of a record, where it is linear, or inside an
analytic pulse, evaluated in closed form). A step takes one libm sin and cos: its later stages
turn the moment of Eq. 4.3 by angle addition, exact to rounding. Every event is located inside
its step rather than stepped across:

- uplift, when |üg| first exceeds g·tan α (a positive üg starts a negative rotation);
- impact, when θ returns to zero: the crossing time is found by safeguarded Newton iteration on
  the Runge–Kutta step length, then θ' is multiplied by sqrt(r) (Eq. 4.6–4.8) and the pivot
  switches;
- peaks of |θ|, where θ' vanishes, located the same way;
- overturning, when |θ| reaches α;
- return to rest, after an impact whose chatter (the Zeno sequence of ever smaller rebounds,
  summed in closed form by :func:`chatter_time_bound`) converges, with rebounds below
  ``rest_tolerance``·α, before the ground could lift the block on either corner.

The step is h ≤ 1/(``steps_per_radian``·p) and no longer than the record's sampling step, so a
run is accurate to ~1e-7 relative away from the overturning boundary (see the convergence test).

Modules: :mod:`~audit.physics.rocking.motion_equation` (Eq. 4.3, its Runge–Kutta step, events,
pivot reactions), :mod:`~audit.physics.rocking.rest` (the rest rule),
:mod:`~audit.physics.rocking.kernel` (the compiled solver), :mod:`~audit.physics.rocking.history`
(one block: :func:`simulate`), :mod:`~audit.physics.rocking.spectrum` (many blocks).
"""

from audit.physics.block import coefficient_of_restitution
from audit.physics.defaults import DEFAULT_FREE_MOTION_S
from audit.physics.rocking.history import (HISTORY_CAPACITY, IMPACT_CAPACITY, RockingHistory,
                                           simulate)
from audit.physics.rocking.motion_equation import pivot_reactions
from audit.physics.rocking.rest import MIN_REST_TOLERANCE, chatter_time_bound
from audit.physics.rocking.spectrum import (BlockPeaks, RockingOptions, RockingSpectrum,
                                            rocking_blocks, rocking_spectrum)

__all__ = ["simulate", "rocking_spectrum", "rocking_blocks", "pivot_reactions", "RockingHistory",
           "RockingSpectrum", "BlockPeaks", "RockingOptions", "chatter_time_bound", "coefficient_of_restitution",
           "DEFAULT_FREE_MOTION_S", "HISTORY_CAPACITY", "IMPACT_CAPACITY", "MIN_REST_TOLERANCE"]
