"""The exact solver's own assumptions as settings: impact model, vertical motion, the friction
of the base, and the alternative models a verdict's sensitivity is measured against.

The exact response is exact for Housner's model: pure rocking (no sliding, no jumping), energy
lost only at impact (Eq. 4.8 by default), horizontal ground motion. :class:`GroundTruth` says
which variant of that model a run solves; ``--sensitivity`` names alternatives, each solved
again so that a verdict which changes under one of them is flagged.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from audit.errors import InputError
from audit.physics.block import Restitution

#: The ``--sensitivity`` word of the vertical component as the alternative.
VERTICAL = "vertical"


@dataclass(frozen=True)
class GroundTruth:
    """One exact model: its impact model (text of :meth:`Restitution.parse`) and whether the
    vertical ground motion is included."""

    restitution: str = "housner"
    vertical: bool = False

    @property
    def impact(self) -> Restitution:
        return Restitution.parse(self.restitution)

    def __str__(self):
        return f"r = {self.restitution}" + (", with the vertical component" if self.vertical
                                            else "")


def parse_sensitivity(texts, option: str = "sensitivity") -> tuple[str, ...]:
    """``restitution=A,B,...`` (impact models: ``x0.9``, ``0.9x``, a fixed r, ``housner``)
    and/or ``vertical``, given once or repeated; the alternatives in a canonical spelling
    (``restitution=x0.9``, ``vertical``).

    Parameters
    ----------
    texts : iterable of str or None
        The option's values.
    option : str
        The option's name, for the message.
    """
    alternatives = []
    for text in texts or ():
        word = str(text).strip()
        if word.lower() == VERTICAL:
            alternatives.append(VERTICAL)
            continue
        name, _, values = word.partition("=")
        if name.strip().lower() != "restitution" or not values.strip():
            raise InputError(f"{option}: expected restitution=MODEL,... or vertical, got "
                             f"'{text}'", option)
        alternatives += [f"restitution={Restitution.parse(v, option)}"
                         for v in values.split(",") if v.strip()]
    return tuple(dict.fromkeys(alternatives))


def alternatives(model: GroundTruth, sensitivity) -> list[GroundTruth]:
    """The models of ``sensitivity`` (:func:`parse_sensitivity`) as variants of ``model``:
    another impact model, or the vertical component switched.

    Parameters
    ----------
    model : GroundTruth
        The reference model (impact model and vertical component).
    sensitivity : iterable of str
        Alternatives as :func:`parse_sensitivity` spells them.
    """
    out = []
    for word in sensitivity:
        if word == VERTICAL:
            out.append(GroundTruth(model.restitution, not model.vertical))
        else:
            out.append(GroundTruth(word.partition("=")[2], model.vertical))
    return out


def slides(required_friction, friction):
    """Blocks that would slide on a base of friction coefficient μ = ``friction`` [-]: their
    pure-rocking response needs more friction than μ (every block that uplifts needs at least
    tan α, so a block with tan α > μ slides before it can rock). NaN where μ is not given.

    Parameters
    ----------
    required_friction : array_like of float
        Friction coefficient each block's pure-rocking response needs [-].
    friction : float or None
        Friction coefficient μ of the base [-], None when not given.

    Returns
    -------
    numpy.ndarray
        True where the block slides (float NaN everywhere when μ is None).
    """
    required = np.asarray(required_friction, dtype=float)
    if friction is None:
        return np.full(required.shape, np.nan)
    return required > friction


__all__ = ["GroundTruth", "parse_sensitivity", "alternatives", "slides", "VERTICAL"]
