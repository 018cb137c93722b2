"""Where an object stands: the ground, or a floor of a linear building.

One settings object for every command that rocks blocks (``--floor``, ``--building``,
``--building-model``, ``--building-damping``; the API's ``floor=Floor(z_over_h,
Building(period_s, model, damping))``), checked once by :meth:`Floor.parse`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

from audit.errors import InputError, field_name as named

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


def _real(name, value, low, high, low_open=False, high_open=False) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) \
            or not math.isfinite(value) \
            or (value >= high if high_open else value > high) \
            or (value <= low if low_open else value < low):
        raise InputError(f"{name}: expected a number in {'(' if low_open else '['}{low:g}, "
                         f"{high:g}{')' if high_open else ']'}, got {value!r}", name)
    return float(value)


@dataclass(frozen=True)
class Building:
    """The linear building an object's floor is in.

    :meth:`parse` checks every field once.

    Attributes
    ----------
    period_s : float or None
        First-mode period T1 [s], in (0, 20]; None only where the floor is the ground.
    model : BuildingModel or str
        ``shear:N`` or ``continuum:α0`` (:class:`BuildingModel`); None: the default,
        :data:`DEFAULT_BUILDING_MODEL`.
    damping : float
        ζ in every mode [-], 0 < ζ < 1.
    """

    period_s: float | None
    model: BuildingModel | str | None = DEFAULT_BUILDING_MODEL
    damping: float = DEFAULT_BUILDING_DAMPING

    @classmethod
    def parse(cls, value, argument: str | None = "building") -> Building:
        """``value`` (a Building) with every field checked; InputError naming
        ``argument.field`` (``floor.building.damping``).

        Parameters
        ----------
        value : Building
            What was given.
        argument : str
            The argument the building was given as, for the messages.
        """
        if not isinstance(value, Building):
            raise InputError(f"{argument}: expected a Building(period_s, model, damping), got "
                             f"{value!r}", argument)
        # a ratio, under critical: the modes' exact recurrence is that of an underdamped
        # oscillator (no building is damped near critically)
        damping = _real(named(argument, "damping"), value.damping, 0.0, 1.0, low_open=True,
                        high_open=True)
        model = BuildingModel.parse(DEFAULT_BUILDING_MODEL if value.model is None
                                    else value.model, named(argument, "model"))
        period_s = value.period_s
        if period_s is not None:
            period_s = _real(named(argument, "period_s"), period_s, 0.0, 20.0, low_open=True)
        return cls(period_s, model, damping)


@dataclass(frozen=True)
class Floor:
    """The object's floor: relative height z/H in a building.

    :meth:`parse` checks every field once; it takes ``None`` or ``0`` for the ground.

    Attributes
    ----------
    z_over_h : float
        0 = the ground (the default: no building filter), 1 = the roof [-].
    building : Building or None
        The building the floor is in; None on the ground.
    """

    z_over_h: float = 0.0
    building: Building | None = None

    @property
    def on_ground(self) -> bool:
        return self.building is None

    @classmethod
    def parse(cls, value=None, argument: str = "floor") -> Floor:
        """The floor of ``value``, each field checked once; InputError naming
        ``argument.field`` (``floor.z_over_h``, ``floor.building.period_s``).

        Parameters
        ----------
        value : Floor, 0 or None
            A Floor; ``None`` or the number 0 for the ground (a floor above it needs its
            building: ``Floor(z_over_h, Building(period_s))``).
        argument : str
            The argument the floor was given as, for the messages.
        """
        if value is None:
            return cls()
        if isinstance(value, numbers.Real) and not isinstance(value, bool):
            if value == 0:
                return cls()
            raise InputError(f"{argument}: a number is the ground only (0); a floor above it "
                             f"is in a building: Floor({value!r}, Building(period_s=T1)), got "
                             f"{value!r}", argument)
        if not isinstance(value, Floor):
            raise InputError(f"{argument}: expected a Floor(z_over_h, Building(period_s)), 0 or "
                             f"None (the ground), got {value!r}", argument)
        z_over_h = _real(named(argument, "z_over_h"), value.z_over_h, 0.0, 1.0)
        # checked on the ground too: a malformed value is refused wherever it is given
        building = (None if value.building is None
                    else Building.parse(value.building, named(argument, "building")))
        if z_over_h == 0.0:
            # On the ground the building does not matter, whatever was said of it.
            return cls()
        if building is None:
            raise InputError(f"{named(argument, 'building')}: a floor above the ground needs "
                             "the building it is in, Building(period_s=T1 [s])",
                             named(argument, "building"))
        if building.period_s is None:
            name = named(named(argument, "building"), "period_s")
            raise InputError(f"{name}: a floor above the ground needs T1, the first-mode period "
                             "[s] of the structure it is in", name)
        return cls(z_over_h, building)

    def describe(self) -> str:
        """In words, for pages and printed summaries."""
        if self.on_ground:
            return "on the ground"
        return (f"at z/H = {self.z_over_h:g} of a building with T1 = "
                f"{self.building.period_s:g} s ({self.building.model}, "
                f"ζ = {self.building.damping:g})")


__all__ = ["Floor", "Building", "BuildingModel", "DEFAULT_BUILDING_MODEL", "DEFAULT_BUILDING_DAMPING"]
