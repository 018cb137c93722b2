"""Priestley, Evison & Carr (1978): the rocking block as an oscillator on the record's spectrum.

Section 8 of the reference report (Makris & Konstantinidis 2001): β = −0.34 ln r (Eq. 7.10) and the true
displacement spectrum of the record itself at that damping.
"""

from __future__ import annotations

from audit.physics.damping import damping_priestley
from procedures.base import Procedure


class PriestleyEvisonCarr1978(Procedure):
    """Priestley, Evison & Carr (1978) procedure (Eqs. 7.10, 8.1, 8.2)."""

    name = "priestley1978"
    title = "Priestley, Evison & Carr (1978)"
    reference = ("Priestley, M. J. N., Evison, R. J. and Carr, A. J. (1978). Seismic response of "
                 "structures free to rock on their foundations. Bulletin of the New Zealand "
                 "National Society for Earthquake Engineering 11(3), 141–150.")
    damping_law = "β = −0.34 ln r (Eq. 7.10)"
    spectrum_source = "true displacement spectrum of the record at damping β (Eq. 3.2)"
    figure_series = "8"
    requires_motion = True

    def damping(self, r):
        return damping_priestley(r)

    def peak_ground_acceleration(self, entry, context):
        return entry.motion.pga

    def displacement_spectrum(self, entry, damping, context):
        return context.true_displacement(damping)
