"""The NTC 2018 horizontal elastic spectrum at a site (§3.2.3.2.1 and §3.2.3.2.3): its tables,
and its displacement spectrum, which follows Eq. 3.5 only up to T_E."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.design_spectra import DesignSpectrum, positive_g
from records.sites import NTC2018_SITE_KEYS, NTC2018_SOILS, NTC2018_TOPOGRAPHIES

#: NTC 2018 Tab. 3.2.IV: soil → (S_S lower bound, intercept, slope on F₀·a_g/g, upper bound,
#: C_C coefficient, C_C exponent on T_C*); S_S = clip(intercept − slope·F₀·a_g/g).
NTC2018_TABLE_3_2_IV = dict(zip(NTC2018_SOILS, (
    (1.00, 1.00, 0.00, 1.00, 1.00, 0.00),
    (1.00, 1.40, 0.40, 1.20, 1.10, -0.20),
    (1.00, 1.70, 0.60, 1.50, 1.05, -0.33),
    (0.90, 2.40, 1.50, 1.80, 1.25, -0.50),
    (1.00, 2.00, 1.10, 1.60, 1.15, -0.40),
)))
#: NTC 2018 Tab. 3.2.V: topographic category → S_T.
NTC2018_TABLE_3_2_V = dict(zip(NTC2018_TOPOGRAPHIES, (1.0, 1.2, 1.2, 1.4)))
#: NTC 2018 Tab. 3.2.VII: soil → T_E [s]; T_F = 10 s for every soil.
NTC2018_TABLE_3_2_VII_TE_S = dict(zip(NTC2018_SOILS, (4.5, 5.0, 6.0, 6.0, 6.0)))
NTC2018_TF_S = 10.0


@dataclass(frozen=True)
class NTC2018Spectrum(DesignSpectrum):
    """NTC 2018 horizontal elastic spectrum at a site (§3.2.3.2.1 and §3.2.3.2.3).

    Attributes
    ----------
    ag_g : float
        a_g, peak acceleration on rock for the limit state's return period [g].
    f0 : float
        F₀, maximum amplification of the spectrum [-].
    tc_star_s : float
        T_C*, start of the constant-velocity branch on rock [s].
    soil : str
        Soil category A–E (Tab. 3.2.IV).
    topography : str
        Topographic category T1–T4 (Tab. 3.2.V).
    """

    ag_g: float
    f0: float
    tc_star_s: float
    soil: str = "A"
    topography: str = "T1"
    name = "NTC 2018"

    def __post_init__(self):
        positive_g(self.ag_g, "NTC a_g")
        for value, field in ((self.f0, "NTC F0"), (self.tc_star_s, "NTC T_C* [s]")):
            if not (value is not None and math.isfinite(value) and value > 0):
                raise InputError(f"{field}: must be a positive number, got {value}")
        if self.soil not in NTC2018_TABLE_3_2_IV:
            raise InputError(f"NTC soil: must be one of {', '.join(NTC2018_TABLE_3_2_IV)}, "
                             f"got {self.soil!r}")
        if self.topography not in NTC2018_TABLE_3_2_V:
            raise InputError(f"NTC topography: must be one of {', '.join(NTC2018_TABLE_3_2_V)}, "
                             f"got {self.topography!r}")

    @classmethod
    def from_site(cls, site: dict) -> NTC2018Spectrum:
        """The spectrum of a record's site, read from its :data:`NTC2018_SITE_KEYS`."""
        return cls(*(site[key] for key in NTC2018_SITE_KEYS))

    def site(self) -> dict:
        """The site as :data:`NTC2018_SITE_KEYS` → value (the inverse of :meth:`from_site`)."""
        return dict(zip(NTC2018_SITE_KEYS, (self.ag_g, self.f0, self.tc_star_s, self.soil,
                                             self.topography)))

    @property
    def soil_factor(self) -> float:
        """S = S_S·S_T (Eq. 3.2.3), S_S of Tab. 3.2.IV within its bounds [-]."""
        low, intercept, slope, high, _, _ = NTC2018_TABLE_3_2_IV[self.soil]
        s_s = min(max(intercept - slope * self.f0 * self.ag_g, low), high)
        return s_s * NTC2018_TABLE_3_2_V[self.topography]

    def corner_periods(self):
        """(T_B, T_C, T_D) [s]: T_C = C_C·T_C* (Eq. 3.2.7, Tab. 3.2.IV), T_B = T_C/3 (Eq. 3.2.8),
        T_D = 4.0·a_g/g + 1.6 (Eq. 3.2.9)."""
        _, _, _, _, coefficient, exponent = NTC2018_TABLE_3_2_IV[self.soil]
        t_c = coefficient * self.tc_star_s ** exponent * self.tc_star_s
        return t_c / 3.0, t_c, 4.0 * self.ag_g + 1.6

    @staticmethod
    def damping_factor(damping):
        """η = √(10/(5 + ξ)) ≥ 0.55 with ξ in percent (Eq. 3.2.6), for β [-]."""
        return np.maximum(np.sqrt(10.0 / (5.0 + 100.0 * np.asarray(damping, dtype=float))), 0.55)

    def acceleration(self, period_s, damping):
        """S_e(T) [g] in the four branches of Eq. 3.2.2, for damping β [-]."""
        period = np.asarray(period_s, dtype=float)
        t_b, t_c, t_d = self.corner_periods()
        amplification = self.damping_factor(damping) * self.f0
        plateau = self.ag_g * self.soil_factor * amplification
        with np.errstate(divide="ignore"):
            return np.select(
                [period < t_b, period < t_c, period < t_d],
                [plateau * (period / t_b + (1.0 - period / t_b) / amplification),
                 plateau, plateau * t_c / period],
                default=plateau * t_c * t_d / period ** 2)

    def displacement(self, period_s, damping, g=G):
        """S_De(T) [m]: Eq. 3.2.10 up to T_E, then Eq. 3.2.11 to T_F and d_g (Eq. 3.2.12)."""
        period = np.asarray(period_s, dtype=float)
        _, t_c, t_d = self.corner_periods()
        t_e = NTC2018_TABLE_3_2_VII_TE_S[self.soil]
        amplification = self.f0 * self.damping_factor(damping)
        d_g = 0.025 * self.ag_g * g * self.soil_factor * t_c * t_d
        fraction = (period - t_e) / (NTC2018_TF_S - t_e)
        return np.select(
            [period <= t_e, period <= NTC2018_TF_S],
            [super().displacement(period, damping, g),
             d_g * (amplification + (1.0 - amplification) * fraction)],
            default=d_g)
