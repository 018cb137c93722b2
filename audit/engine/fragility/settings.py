"""The settings of the audit of a probabilistic procedure (``audit fragility``): the PGV stripes
the records are scaled to and the free motion after each, checked once."""

from __future__ import annotations

from dataclasses import dataclass

from audit.engine.fragility.calibration import PGV_LEVELS_M_S
from audit.engine.shared import fields as check
from audit.physics.defaults import DEFAULT_FREE_MOTION_S


@dataclass(frozen=True)
class FragilitySettings:
    """How a probabilistic procedure is audited (checked once).

    Attributes
    ----------
    levels_m_s : tuple of float
        The PGV stripes [m/s] (default :data:`~audit.engine.fragility.calibration.PGV_LEVELS_M_S`).
    free_motion_s : float
        Free rocking simulated after each scaled record [s].
    """

    levels_m_s: tuple = tuple(PGV_LEVELS_M_S.tolist())
    free_motion_s: float = DEFAULT_FREE_MOTION_S

    def __post_init__(self):
        # each field checked once, naming it; a frozen dataclass keeps the checked values
        object.__setattr__(self, "levels_m_s", check.numbers(
            "levels_m_s", self.levels_m_s, "positive peak ground velocities in m/s", 0,
            low_open=True))
        object.__setattr__(self, "free_motion_s", check.number(
            "free_motion_s", self.free_motion_s, "a duration ≥ 0 s", 0))


__all__ = ["FragilitySettings"]
