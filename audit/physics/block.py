"""The free-standing rigid block (Eqs. 4.1–4.8 of Makris & Konstantinidis 2001)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit import G
from audit.errors import InputError


def slenderness(b, h):
    """Slenderness α = atan(b/h) [rad] of a block of half-width ``b`` and half-height ``h`` [m]."""
    return np.arctan2(b, h)


def frequency_parameter(radius, g=G):
    """Frequency parameter p = sqrt(3g / (4R)) [rad/s] of a rectangular block.

    Parameters
    ----------
    radius : float or array
        R, distance from the centre of mass to a pivot point [m].
    g : float
        Acceleration of gravity [m/s²].
    """
    return np.sqrt(3.0 * g / (4.0 * np.asarray(radius, dtype=float)))


def radius_from_p(p, g=G):
    """R = 3g / (4p²) [m] from the frequency parameter p [rad/s]."""
    return 3.0 * g / (4.0 * np.asarray(p, dtype=float) ** 2)


def coefficient_of_restitution(alpha_rad):
    """Largest coefficient of restitution for pure rocking, r = (1 − 1.5 sin²α)² (Eq. 4.8).

    r is the ratio of kinetic energies after and before an impact; the angular velocity
    is multiplied by sqrt(r) (Eq. 4.6–4.7).

    Parameters
    ----------
    alpha_rad : float or array
        Slenderness α [rad].
    """
    return (1.0 - 1.5 * np.sin(alpha_rad) ** 2) ** 2


@dataclass(frozen=True)
class RigidBlock:
    """A rectangular rigid block rocking on a rigid base.

    Attributes
    ----------
    p : float
        Frequency parameter [rad/s]; the block's "size" on spectra is 2π/p [s].
    alpha : float
        Slenderness α [rad], 0 < α < π/4.
    r : float
        Coefficient of restitution (energy ratio per impact); Eq. 4.8 when not given.
    g : float
        Acceleration of gravity [m/s²].
    """

    p: float
    alpha: float
    r: float | None = None
    g: float = G

    def __post_init__(self):
        if not (math.isfinite(self.p) and self.p > 0):
            raise InputError(f"block p: must be a positive number of rad/s, got {self.p}")
        if not (math.isfinite(self.alpha) and 0 < self.alpha < math.pi / 4):
            raise InputError(f"block alpha: must lie between 0 and 45 degrees, got "
                             f"{math.degrees(self.alpha):g} degrees")
        if self.r is None:
            object.__setattr__(self, "r", float(coefficient_of_restitution(self.alpha)))
        if not (math.isfinite(self.r) and 0 < self.r <= 1):
            raise InputError(f"block r: coefficient of restitution must lie in (0, 1], got {self.r}")
        if not (math.isfinite(self.g) and self.g > 0):
            raise InputError(f"block g: must be a positive acceleration in m/s², got {self.g}")

    @classmethod
    def from_dimensions(cls, b: float, h: float, r: float | None = None, g: float = G) -> RigidBlock:
        """Block of half-width ``b`` [m] and half-height ``h`` [m]."""
        if not (b > 0 and h > 0):
            raise InputError(f"block dimensions: half-width and half-height must be positive, "
                             f"got b = {b}, h = {h}")
        return cls(float(frequency_parameter(math.hypot(b, h), g)), float(slenderness(b, h)), r, g)

    @classmethod
    def from_size(cls, size_s: float, alpha_rad: float, r: float | None = None, g: float = G) -> RigidBlock:
        """Block of "size" 2π/p [s] and slenderness α [rad]."""
        if not (math.isfinite(size_s) and size_s > 0):
            raise InputError(f"block size: 2π/p must be a positive number of seconds, got {size_s}")
        return cls(2.0 * math.pi / size_s, alpha_rad, r, g)

    @property
    def size_s(self) -> float:
        """2π/p [s]."""
        return 2.0 * math.pi / self.p

    @property
    def radius(self) -> float:
        """R [m]."""
        return float(radius_from_p(self.p, self.g))

    @property
    def half_width(self) -> float:
        """b = R sin α [m]."""
        return self.radius * math.sin(self.alpha)

    @property
    def half_height(self) -> float:
        """h = R cos α [m]."""
        return self.radius * math.cos(self.alpha)

    @property
    def uplift_acceleration(self) -> float:
        """Ground acceleration g·tan α above which the block uplifts [m/s²]."""
        return self.g * math.tan(self.alpha)
