"""What an atlas depends on, checked once, and the key that names it in the cache."""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass

import numpy as np

from audit import __version__
from audit.engine.check.pipeline import LATTICE_EVERY
from audit.engine.shared.intensity import IntensityMeasure
from audit.engine.shared.lattice import stripe_lattice
from audit.physics.block import Restitution

#: The atlas's slenderness grid [degrees]: 4–44.5° every 1.5° (the spacing whose interpolation
#: error docs/atlas.md measures): to 44.5° so that the check's width search, which scans up to
#: 0.95 of the height (α 43.5°), finds the 10 % width of a small object too.
ALPHA_DEG = tuple(float(a) for a in np.arange(4.0, 44.5 + 1e-9, 1.5))
#: The atlas's size grid 2π/p [s]: 0.4–8 s, 2^(1/4) apart (ln-uniform: interpolation is in ln p).
SIZE_S = tuple(float(s) for s in 0.4 * 2.0 ** (np.arange(0, 18) / 4.0)) + (8.0,)


@dataclass(frozen=True)
class AtlasSettings:
    """What an atlas's outcomes depend on.

    Attributes
    ----------
    records : str
        The record set as named (its content is hashed into :meth:`key`).
    records_digest : str
        SHA-256 of every record's identity and samples (:func:`records_digest`).
    im : IntensityMeasure
    floor : str
        The floor in words (``ground``, or the building and z/H).
    restitution : Restitution
    g, free_motion_s : float
        Gravity [m/s²], free motion after each record [s].
    alpha_deg, size_s : tuple of float
        The grid, ascending [degrees], [s].
    jobs : int
        Solver threads of a task (not part of the key).
    """

    records: str
    records_digest: str
    im: IntensityMeasure
    floor: str
    restitution: Restitution
    g: float
    free_motion_s: float
    alpha_deg: tuple = ALPHA_DEG
    size_s: tuple = SIZE_S
    jobs: int = 1

    @property
    def levels(self) -> np.ndarray:
        """The stripes: the check's lattice (k even) [unit of ``im``]."""
        return stripe_lattice(LATTICE_EVERY)

    def as_dict(self) -> dict:
        """The provenance (everything but ``jobs``), as stored beside the atlas."""
        return {"kind": "atlas", "solver_version": __version__, "records": self.records,
                "records_digest": self.records_digest, "im": self.im.name,
                "floor": self.floor, "restitution": str(self.restitution), "g": self.g,
                "free_motion_s": self.free_motion_s, "levels": self.levels.tolist(),
                "alpha_deg": list(self.alpha_deg), "size_s": list(self.size_s)}

    def key(self) -> str:
        """SHA-256 of :meth:`as_dict` but the record set's name (its content, the digest,
        decides: a suite named by two paths is one atlas): the atlas's name in the cache."""
        content = {k: v for k, v in self.as_dict().items() if k != "records"}
        return hashlib.sha256(json.dumps(content, sort_keys=True).encode()).hexdigest()


def records_digest(entries) -> str:
    """SHA-256 over the records' own keys (id, site, file and samples:
    :func:`audit.engine.shared.partial.record_key`), in order.

    Parameters
    ----------
    entries : sequence of records.RecordEntry
    """
    from audit.engine.shared.partial import record_key
    digest = hashlib.sha256()
    for entry in entries:
        digest.update(record_key(entry).encode())
    return digest.hexdigest()


def floor_words(floor) -> str:
    """``ground``, or the floor's z/H and its building (what the floor motion depends on).

    Parameters
    ----------
    floor : audit.physics.building.floor.Floor
    """
    if floor.on_ground:
        return "ground"
    return (f"z/H = {floor.z_over_h:g} of T1 = {floor.building.period_s:g} s, "
            f"{floor.building.model}, ζ = {floor.building.damping:g}")


__all__ = ["AtlasSettings", "records_digest", "floor_words", "ALPHA_DEG", "SIZE_S"]
