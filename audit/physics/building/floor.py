"""Where an object stands: the ground, or a floor of a linear building.

One settings object for every command that rocks blocks (``--floor``, ``--building``,
``--building-model``, ``--building-damping`` and the API keywords of the same names), checked
once by :meth:`Floor.parse`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

from audit.errors import InputError

#: Miranda & Taghavi (2005) put moment-resisting frames at α0 ≈ 5–20; 10 is the middle of that
#: range on a log scale, and frames are where most cabinets, racks and vitrines stand.
DEFAULT_BUILDING_MODEL = "continuum:10"
#: Classical damping in every mode [-], the 5 % of the codes' spectra.
DEFAULT_BUILDING_DAMPING = 0.05


@dataclass(frozen=True)
class BuildingModel:
    """A named building model: ``shear:N`` (N storeys) or ``continuum:α0`` (Miranda & Taghavi
    2005, lateral stiffness ratio α0 ≥ 0)."""

    kind: str
    value: float

    @classmethod
    def parse(cls, text, field: str = "building_model") -> BuildingModel:
        if isinstance(text, BuildingModel):
            return text
        kind, _, value = text.strip().partition(":") if isinstance(text, str) else ("", "", "")
        try:
            number = float(value)
        except ValueError:
            number = math.nan
        if kind == "shear" and number in range(1, 201):
            return cls("shear", number)
        if kind == "continuum" and 0.0 <= number <= 1000.0:  # NaN fails the comparison
            return cls("continuum", number)
        raise InputError(f"{field}: expected shear:N (N storeys, 1-200) or continuum:ALPHA0 "
                         f"(0-1000), got {text!r}", field)

    def __str__(self) -> str:
        return f"shear:{int(self.value)}" if self.kind == "shear" else f"continuum:{self.value:g}"


@dataclass(frozen=True)
class Floor:
    """The object's floor: relative height z/H in a building of first-mode period T1.

    Attributes
    ----------
    z_over_h : float
        0 = the ground (the default: no building filter), 1 = the roof [-].
    building_period_s : float or None
        T1 [s]; None on the ground.
    building_model : BuildingModel or None
        None on the ground.
    building_damping : float
        ζ in every mode [-].
    """

    z_over_h: float = 0.0
    building_period_s: float | None = None
    building_model: BuildingModel | None = None
    building_damping: float = DEFAULT_BUILDING_DAMPING

    @property
    def on_ground(self) -> bool:
        return self.building_period_s is None

    @classmethod
    def parse(cls, *, floor=0.0, building=None, building_model=None,
              building_damping=DEFAULT_BUILDING_DAMPING) -> Floor:
        """The floor of the given keywords (``floor`` is z/H, ``building`` is T1 [s]), each
        checked once; InputError naming the keyword."""
        def real(name, value, low, high, low_open=False, high_open=False):
            if isinstance(value, bool) or not isinstance(value, numbers.Real) \
                    or not math.isfinite(value) \
                    or (value >= high if high_open else value > high) \
                    or (value <= low if low_open else value < low):
                raise InputError(f"{name}: expected a number in {'(' if low_open else '['}{low:g}, "
                                 f"{high:g}{')' if high_open else ']'}, got {value!r}", name)
            return float(value)

        z_over_h = real("floor", floor, 0.0, 1.0)
        # a ratio, under critical: the modes' exact recurrence is that of an underdamped
        # oscillator (no building is damped near critically)
        damping = real("building_damping", building_damping, 0.0, 1.0, low_open=True,
                       high_open=True)
        # checked on the ground too: a malformed value is refused wherever it is given
        model = None if building_model is None else BuildingModel.parse(building_model)
        if building is not None:
            building = real("building", building, 0.0, 20.0, low_open=True)
        if z_over_h == 0.0:
            # On the ground the building does not matter, whatever was said of it.
            return cls()
        if building is None:
            raise InputError("building: a floor above the ground needs T1, the first-mode period "
                             "[s] of the structure it is in", "building")
        model = BuildingModel.parse(DEFAULT_BUILDING_MODEL) if model is None else model
        return cls(z_over_h, building, model, damping)

    def describe(self) -> str:
        """In words, for pages and printed summaries."""
        if self.on_ground:
            return "on the ground"
        return (f"at z/H = {self.z_over_h:g} of a building with T1 = {self.building_period_s:g} s "
                f"({self.building_model}, ζ = {self.building_damping:g})")


__all__ = ["Floor", "BuildingModel", "DEFAULT_BUILDING_MODEL", "DEFAULT_BUILDING_DAMPING"]
