"""Code design spectra: FEMA 356 general horizontal spectrum and UBC 97 (the NTC 2018 elastic
spectrum, whose displacement follows its own equations beyond T_E, is
:mod:`audit.physics.ntc2018_spectrum`).

Each code is a small object with ``acceleration(T, β)`` [g]; the displacement follows from
Eq. 3.5 in the shared base class, so another code's spectrum (ASCE 7, Eurocode 8) is one more
subclass.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from audit import G
from audit.errors import InputError

#: FEMA 356 Table 1-6: effective damping β [-] → (B_S, B_1); linear between rows, held beyond.
FEMA356_TABLE_1_6 = np.array([
    (0.02, 0.8, 0.8),
    (0.05, 1.0, 1.0),
    (0.10, 1.3, 1.2),
    (0.20, 1.8, 1.5),
    (0.30, 2.3, 1.7),
    (0.40, 2.7, 1.9),
    (0.50, 3.0, 2.0),
])

#: UBC 97 Table A-16-C (damping coefficient B_D of the isolation appendix): β [-] → B.
UBC97_TABLE_A_16_C = np.array([
    (0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0),
])


def fema356_damping_coefficients(damping):
    """Damping coefficients (B_S, B_1) of FEMA 356 Table 1-6, linearly interpolated.

    Parameters
    ----------
    damping : float or array
        Effective damping β [-] (0.05 for 5 %).
    """
    return _table_1_6_at(float(damping)) if np.ndim(damping) == 0 else _table_1_6(damping)


def _table_1_6(damping):
    table = FEMA356_TABLE_1_6
    return (np.interp(damping, table[:, 0], table[:, 1]),
            np.interp(damping, table[:, 0], table[:, 2]))


# one damping's (B_S, B_1), kept: a guideline's iteration reads the spectrum at one damping
# thousands of times, and the two interpolations cost as much as the rest of the spectrum
_table_1_6_at = functools.lru_cache(maxsize=256)(_table_1_6)


def displacement_from_acceleration(sa_g, period_s, g=G):
    """Sd = Sa·g·T²/(4π²) [m] from a spectral acceleration in g (Eq. 3.5)."""
    return np.asarray(sa_g) * g * np.asarray(period_s, dtype=float) ** 2 / (4.0 * math.pi ** 2)


class DesignSpectrum:
    """A code design spectrum: ``acceleration`` [g] by code, displacement by Eq. 3.5."""

    name = ""
    #: Whether Sd(T) never falls as T grows, whatever the site and damping: the fixed-point scan
    #: (:func:`procedures.rotation_map.fixed_points`) then bounds Sd over a range of periods by
    #: its values at the range's ends.
    displacement_nondecreasing = False

    def acceleration(self, period_s, damping):
        """Spectral acceleration Sa [g] at periods T [s] and effective damping β [-]."""
        raise NotImplementedError

    def displacement(self, period_s, damping, g=G):
        """Spectral displacement Sd [m] (Eq. 3.5)."""
        return displacement_from_acceleration(self.acceleration(period_s, damping), period_s, g)


@dataclass(frozen=True, eq=False)
class DesignDisplacement:
    """Sd(T) [m] of a design spectrum at one effective damping β [-], as a function of the
    period T [s] (array in, array out, elementwise)."""

    spectrum: DesignSpectrum
    damping: float

    @property
    def nondecreasing(self) -> bool:
        """Whether Sd never falls as T grows (:attr:`DesignSpectrum.displacement_nondecreasing`)."""
        return self.spectrum.displacement_nondecreasing

    def __call__(self, period_s):
        return self.spectrum.displacement(period_s, self.damping)


def positive_g(value, field):
    """Refuse ``value`` (a number of g, or one per period) unless every element is > 0."""
    if not (value is not None and np.all(np.isfinite(value)) and np.all(np.asarray(value) > 0)):
        raise InputError(f"{field}: must be a positive number of g, got {value}")


def _where(value, mask):
    """``value`` at the elements ``mask`` picks, for a value given per element; a scalar as is."""
    return value[mask] if np.ndim(value) else value


@dataclass(frozen=True)
class FEMA356Spectrum(DesignSpectrum):
    """FEMA 356 general horizontal response spectrum (FEMA 356 §1.6.1.5).

    Attributes
    ----------
    sxs_g : float or numpy.ndarray
        S_XS, short-period design spectral acceleration at 5 % damping [g].
    sx1_g : float or numpy.ndarray
        S_X1, design spectral acceleration at 1 s and 5 % damping [g]. Given as arrays (one
        site per period asked for), each period is read on its own site's spectrum, with the
        operations of a site given alone.
    """

    sxs_g: float
    sx1_g: float
    name = "FEMA 356"
    # Sa·T² is continuous and grows on each branch: S_X1·T/B_1 beyond T_S, S_XS·T²/B_S on the
    # plateau, and below T_0 = 0.2·T_S d(Sa·T²)/dT = S_XS·T·[3(5/B_S − 2)·T/T_S + 0.8] > 0
    # whenever B_S < 7.5 (Table 1-6's largest is 3.0)
    displacement_nondecreasing = True

    def __post_init__(self):
        positive_g(self.sxs_g, "S_XS")
        positive_g(self.sx1_g, "S_X1")

    def corner_periods(self, damping):
        """(T_0, T_S) [s]: T_S = S_X1·B_S/(S_XS·B_1), T_0 = 0.2·T_S."""
        b_s, b_1 = fema356_damping_coefficients(damping)
        t_s = self.sx1_g * b_s / (self.sxs_g * b_1)
        return 0.2 * t_s, t_s

    def branch_constants(self, damping, blocks: int) -> np.ndarray:
        """(S_XS, S_X1, B_S, B_1, T_0, T_S) of the spectrum at β [-], a row for each of
        ``blocks`` blocks (the site's, or each block's own where the site is given per block):
        what :func:`procedures.design_spectrum_kernels.fema356_displacement` reads."""
        b_s, b_1 = fema356_damping_coefficients(damping)
        columns = np.broadcast_arrays(self.sxs_g, self.sx1_g, b_s, b_1,
                                      *self.corner_periods(damping))
        return np.ascontiguousarray(np.broadcast_to(np.stack(columns, axis=-1), (blocks, 6)),
                                    dtype=float)

    def acceleration(self, period_s, damping):
        """Sa [g] in its three branches, with B_S, B_1 of Table 1-6 for β [-].

        Sa = S_XS·[(5/B_S − 2)·T/T_S + 0.4] for T < T_0; S_XS/B_S for T_0 ≤ T ≤ T_S;
        S_X1/(B_1·T) for T > T_S.
        """
        period = np.asarray(period_s, dtype=float)
        b_s, b_1 = fema356_damping_coefficients(damping)
        t_0, t_s = self.corner_periods(damping)
        # each branch computed only where it holds (the same operations per element), not all
        # three over every period: the fixed-point scan asks for ~10⁶ periods at once
        short, plateau = period < t_0, period <= t_s
        sa = np.full(period.shape, self.sxs_g / b_s)
        sa[short] = _where(self.sxs_g, short) * ((5.0 / b_s - 2.0) * period[short]
                                                 / _where(t_s, short) + 0.4)
        long = ~plateau  # T > T_S, and a NaN period (whose Sa is NaN)
        with np.errstate(divide="ignore"):
            sa[long] = _where(self.sx1_g, long) / (b_1 * period[long])
        return sa


@dataclass(frozen=True)
class UBC97Spectrum(DesignSpectrum):
    """UBC 97 design response spectrum, seismic zone 4, soil profile S_D (UBC 97 Fig. 16-3).

    C_a = 0.44·N_a and C_v = 0.64·N_v (Tables 16-Q, 16-R); T_S = C_v/(2.5 C_a), T_0 = 0.2 T_S;
    Sa = C_a(1 + 1.5 T/T_0) below T_0, 2.5 C_a up to T_S, C_v/T beyond. Damping other than 5 %
    divides the spectrum by B of Table A-16-C.

    Attributes
    ----------
    near_source_na, near_source_nv : float
        Near-source factors N_a, N_v [-] (default 1.0).
    """

    near_source_na: float = 1.0
    near_source_nv: float = 1.0
    name = "UBC 97"

    def __post_init__(self):
        for value, field in ((self.near_source_na, "N_a"), (self.near_source_nv, "N_v")):
            if not (math.isfinite(value) and value > 0):
                raise InputError(f"{field}: must be a positive factor, got {value}")

    @property
    def ca(self) -> float:
        return 0.44 * self.near_source_na

    @property
    def cv(self) -> float:
        return 0.64 * self.near_source_nv

    def acceleration(self, period_s, damping=0.05):
        """Sa [g] at periods T [s] and damping β [-]."""
        period = np.asarray(period_s, dtype=float)
        t_s = self.cv / (2.5 * self.ca)
        t_0 = 0.2 * t_s
        with np.errstate(divide="ignore"):
            sa = np.where(period < t_0, self.ca * (1.0 + 1.5 * period / t_0),
                          np.where(period <= t_s, 2.5 * self.ca, self.cv / period))
        return sa / np.interp(damping, UBC97_TABLE_A_16_C[:, 0], UBC97_TABLE_A_16_C[:, 1])
