"""The floor spectrum of Circolare 21 Jan 2019 n. 7 §C7.2.3 for elements at height in a building.

Clause followed, known second-hand: the Circolare's text could not be read here; the formula
and Table C7.2.I are as third-party practitioners' notes and a public calculator script give
them, which agree. For an element of period T_a at relative height z/H of a building of
first-mode period T_1, with α = a_g/g and S = S_S·S_T of the site (NTC 2018 §3.2.3.2.1):

    S_a(T_a) = α·S·(1 + z/H)·a_p/[1 + (a_p − 1)·(1 − T_a/(a·T_1))²]   T_a < a·T_1
    S_a(T_a) = α·S·(1 + z/H)·a_p                                        a·T_1 ≤ T_a < b·T_1
    S_a(T_a) = α·S·(1 + z/H)·a_p/[1 + (a_p − 1)·(1 − T_a/(b·T_1))²]   T_a ≥ b·T_1

each at least α·S, with (a, b, a_p) of Table C7.2.I: (0.8, 1.4, 5.0) for T_1 ≤ 0.5 s,
(0.3, 1.2, 4.0) for 0.5 < T_1 ≤ 1 s, (0.3, 1.0, 2.5) beyond. At T_a = 0 it is the floor's
peak acceleration α·S·(1 + z/H); on the ground (z/H = 0) its plateau is a_p·α·S.

The Circolare gives it at 5 % damping. At another damping ξ it is scaled here by NTC 2018's
η = √(10/(5 + ξ%)) ≥ 0.55 (Eq. 3.2.6) as the ground spectrum is, but on the rising branch
(T_a < a·T_1) never below the floor's peak acceleration, which a rigid element feels whatever its
damping (as Eq. 3.2.2 leaves a_g·S undamped at T = 0): an assumption of this module, not the
Circolare's text.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from audit.physics.design_spectra import DesignSpectrum
from audit.physics.ntc2018_spectrum import NTC2018Spectrum

#: Table C7.2.I: (upper T_1 of the row [s], a, b, a_p).
TABLE_C7_2_I = ((0.5, 0.8, 1.4, 5.0), (1.0, 0.3, 1.2, 4.0), (float("inf"), 0.3, 1.0, 2.5))


def floor_spectrum_parameters(building_period_s: float) -> tuple[float, float, float]:
    """(a, b, a_p) of Table C7.2.I for a building of first-mode period T_1 [s]."""
    for upper_s, a, b, a_p in TABLE_C7_2_I:
        if building_period_s <= upper_s:
            return a, b, a_p
    raise ValueError(building_period_s)  # NaN


@dataclass(frozen=True)
class NTC2018FloorSpectrum(DesignSpectrum):
    """The Circolare 2019 §C7.2.3 floor spectrum [C7.2.11] at z/H of a building at a site.

    Attributes
    ----------
    ground : NTC2018Spectrum
        The site's spectrum (α = a_g/g and S of it).
    z_over_h : float
        Relative height of the element's floor [-].
    building_period_s : float
        T_1 of the building [s].
    """

    ground: NTC2018Spectrum
    z_over_h: float
    building_period_s: float
    name = "NTC 2018 floor (Circolare §C7.2.3)"

    @property
    def peak_floor_acceleration_g(self) -> float:
        """α·S·(1 + z/H) [g], the spectrum at T_a = 0."""
        return self.ground.ag_g * self.ground.soil_factor * (1.0 + self.z_over_h)

    def acceleration(self, period_s, damping):
        """S_a(T_a) [g] at the element's periods T_a [s] and damping ξ [-] (module docstring)."""
        period = np.asarray(period_s, dtype=float)
        a, b, a_p = floor_spectrum_parameters(self.building_period_s)
        t_1 = self.building_period_s
        corner = np.where(period < a * t_1, a * t_1, np.where(period >= b * t_1, b * t_1, period))
        amplification = a_p / (1.0 + (a_p - 1.0) * (1.0 - period / corner) ** 2)
        at_five = np.maximum(self.peak_floor_acceleration_g * amplification,
                             self.ground.ag_g * self.ground.soil_factor)
        damped = NTC2018Spectrum.damping_factor(damping) * at_five
        # an element stiffer than the floor's peak (the rising branch) feels at least the floor
        return np.where(period < a * t_1, np.maximum(damped, self.peak_floor_acceleration_g),
                        damped)


__all__ = ["NTC2018FloorSpectrum", "floor_spectrum_parameters", "TABLE_C7_2_I"]
