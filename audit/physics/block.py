"""The free-standing rigid block (Eqs. 4.1–4.8 of Makris & Konstantinidis 2001)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from audit import G
from audit.errors import InputError


def slenderness(b, h):
    """Slenderness α = atan(b/h) [rad] of a block of half-width ``b`` and half-height ``h`` [m]."""
    import numpy as np  # here, not at the top: the API's front door imports this module
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
    import numpy as np
    return np.sqrt(3.0 * g / (4.0 * np.asarray(radius, dtype=float)))


def radius_from_p(p, g=G):
    """R = 3g / (4p²) [m] from the frequency parameter p [rad/s]."""
    import numpy as np
    return 3.0 * g / (4.0 * np.asarray(p, dtype=float) ** 2)


def rotation_at_displacement(displacement_m, alpha_rad, radius_m):
    """θ(d) = α − asin(sin α − d/R) [rad]: the rotation at which the centroid has moved
    d = R [sin α − sin(α − θ)] (rotation about the base corner).

    NaN for d outside [0, R(1 + sin α)]; d ≥ R sin α = b is at or beyond instability (θ ≥ α).
    """
    import numpy as np
    with np.errstate(invalid="ignore"):
        return alpha_rad - np.arcsin(np.sin(alpha_rad)
                                     - np.asarray(displacement_m, dtype=float) / radius_m)


def coefficient_of_restitution(alpha_rad):
    """Largest coefficient of restitution for pure rocking, r = (1 − 1.5 sin²α)² (Eq. 4.8).

    r is the ratio of kinetic energies after and before an impact; the angular velocity
    is multiplied by sqrt(r) (Eq. 4.6–4.7).

    Parameters
    ----------
    alpha_rad : float or array
        Slenderness α [rad].
    """
    import numpy as np
    return (1.0 - 1.5 * np.sin(alpha_rad) ** 2) ** 2


@dataclass(frozen=True)
class Restitution:
    """The impact model: which coefficient of restitution r each block gets.

    r is the ratio of kinetic energies after and before an impact, so the angular velocity
    is multiplied by sqrt(r) (Eq. 4.6–4.7). ``factor`` scales Eq. 4.8 (the upper bound for
    pure rocking; shake-table studies often measure less); ``value`` fixes r for every block.

    Attributes
    ----------
    factor : float
        Multiple of Eq. 4.8 [-] (1 for Housner's model); ignored when ``value`` is set.
    value : float, optional
        A fixed r [-] for every block.
    """

    factor: float = 1.0
    value: float | None = None

    @classmethod
    def parse(cls, text: str, option: str = "restitution") -> Restitution:
        """``housner`` (Eq. 4.8), a fixed r ``VALUE`` in (0, 1], or ``xFACTOR`` times Eq. 4.8."""
        word = str(text).strip().lower()
        if word == "housner":
            return cls()
        scaled = word.startswith("x") or word.endswith("x")
        try:
            number = float(word.strip("x"))
        except ValueError:
            number = math.nan
        if not (math.isfinite(number) and 0 < number <= 1):
            raise InputError(f"{option}: expected housner, a coefficient of restitution in (0, 1] "
                             f"or xFACTOR with a factor in (0, 1], got {text!r}", option)
        return cls(factor=number) if scaled else cls(value=number)

    def r(self, alpha_rad):
        """Coefficient of restitution r [-] of a block of slenderness ``alpha_rad`` [rad]."""
        import numpy as np
        if self.value is not None:
            return np.full_like(np.asarray(alpha_rad, dtype=float), self.value)[()]
        return self.factor * coefficient_of_restitution(alpha_rad)

    def __str__(self):
        if self.value is not None:
            return f"{self.value:g}"
        return "housner" if self.factor == 1.0 else f"x{self.factor:g}"


@dataclass(frozen=True)
class RigidBlock:
    """A rectangular rigid block rocking on a rigid base.

    Attributes
    ----------
    p : float
        Frequency parameter [rad/s]; the block's "size" on spectra is 2π/p [s].
    alpha : float
        Slenderness α [rad], 0 < α < π/4.
    r : float or Restitution
        Coefficient of restitution (energy ratio per impact), or the impact model giving it;
        Eq. 4.8 when not given.
    g : float
        Acceleration of gravity [m/s²].
    """

    p: float
    alpha: float
    r: float | Restitution | None = None
    g: float = G

    def __post_init__(self):
        if not (math.isfinite(self.p) and self.p > 0):
            raise InputError(f"block p: must be a positive number of rad/s, got {self.p}")
        if not (math.isfinite(self.alpha) and 0 < self.alpha < math.pi / 4):
            raise InputError(f"block alpha: must lie between 0 and 45 degrees, got "
                             f"{math.degrees(self.alpha):g} degrees")
        model = Restitution() if self.r is None else self.r
        if isinstance(model, Restitution):
            object.__setattr__(self, "r", float(model.r(self.alpha)))
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
