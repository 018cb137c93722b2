"""The contract of a probabilistic procedure: P(event | IM) for listed components, each standing
for a rocking block, not a rotation or a check (audited by calibration against exact solves).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from procedures.iteration import OVERTURN

#: Intensity measures a probabilistic procedure may declare: peak ground velocity [m/s] and peak
#: ground acceleration [m/s²] (a procedure written for floor motion is read at the ground floor).
INTENSITY_MEASURES = ("PGV", "PGA")


@dataclass(frozen=True)
class LognormalFragility:
    """P(event | IM) = Φ(ln(IM/θ)/β), the lognormal fragility.

    Attributes
    ----------
    median : float
        θ, the intensity at which the event has probability 1/2 [m/s for PGV, m/s² for PGA].
    beta : float
        β, the logarithmic standard deviation [-].
    """

    median: float
    beta: float

    def probability(self, intensity):
        """P(event | IM = ``intensity``) [-]; 0 at zero intensity."""
        from scipy.special import ndtr  # kept local: only probabilistic audits need scipy here
        intensity = np.asarray(intensity, dtype=float)
        with np.errstate(divide="ignore"):
            return ndtr(np.log(intensity / self.median) / self.beta)


@dataclass(frozen=True)
class FragilityComponent:
    """One component of a probabilistic procedure and the rocking block it stands for.

    Attributes
    ----------
    id : str
        The procedure's component id (e.g. ``E.20.22.104a``).
    description : str
        The procedure's description of the component.
    intensity_measure : str
        One of :data:`INTENSITY_MEASURES`.
    fragility : LognormalFragility
        The procedure's fragility for the event, in SI.
    depth_m, height_m : float
        Full depth (the dimension it rocks across) and full height of the block [m]; NaN where
        the procedure gives no geometry, and the component then has no block to audit.
    """

    id: str
    description: str
    intensity_measure: str
    fragility: LognormalFragility
    depth_m: float = float("nan")
    height_m: float = float("nan")

    @property
    def has_block(self) -> bool:
        """Whether the component has dimensions, hence a rocking block to audit."""
        return bool(np.isfinite(self.depth_m) and np.isfinite(self.height_m))


class ProbabilisticProcedure:
    """Base class of a procedure that gives P(event | IM) for listed components.

    A subclass declares its ``name``, the ``event`` its fragilities are for and its
    ``components``; the engine audits each component with a block against the frequency of the
    event in exact solves (calibration, Brier score, log-likelihood, exact fragility).
    """

    name: ClassVar[str] = ""
    title: ClassVar[str] = ""
    #: The event the fragilities give the probability of.
    event: ClassVar[str] = OVERTURN
    components: ClassVar[tuple[FragilityComponent, ...]] = ()

    def component(self, component_id: str) -> FragilityComponent:
        """The component ``component_id``."""
        for component in self.components:
            if component.id == component_id:
                return component
        raise KeyError(component_id)

    def probability(self, component_id: str, intensity):
        """P(event | IM = ``intensity``) of the component ``component_id`` [-] (SI intensity)."""
        return self.component(component_id).fragility.probability(intensity)


__all__ = ["INTENSITY_MEASURES", "FragilityComponent", "LognormalFragility", "ProbabilisticProcedure"]
