"""Blocks an audit covers: the (α, 2π/p) grid and blocks named by their dimensions.

``--block WIDTHxHEIGHT`` (full width × full height [m]) lets an engineer ask about *their*
cabinet beside the grid: α = atan(width/height) and 2π/p with p = √(3g/(4R)) (Eq. 4.2),
R = ½√(width² + height²). Outputs name such a block by its dimensions (``block_m``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.block import RigidBlock


@dataclass(frozen=True)
class NamedBlock:
    """A block given by its full width and height [m]."""

    width_m: float
    height_m: float
    g: float = G

    @property
    def label(self) -> str:
        """``WIDTHxHEIGHT`` in metres, as a block is typed."""
        return f"{self.width_m:g}x{self.height_m:g}"

    @property
    def rigid(self) -> RigidBlock:
        return RigidBlock.from_dimensions(self.width_m / 2.0, self.height_m / 2.0, g=self.g)

    @property
    def alpha_deg(self) -> float:
        """Slenderness α = atan(width/height) [degrees]."""
        return math.degrees(self.rigid.alpha)

    @property
    def size_s(self) -> float:
        """Size 2π/p [s]."""
        return self.rigid.size_s


def parse_blocks(texts, option: str = "blocks", g: float = G) -> list[NamedBlock]:
    """Blocks of ``option`` texts (repeated, each possibly comma-separated), e.g.
    ``0.4x2.0`` [m]; InputError naming the option and the value otherwise."""
    blocks = []
    for text in texts or ():
        for item in str(text).split(","):
            item = item.strip()
            if not item:
                continue
            parts = item.lower().replace("×", "x").split("x")
            try:
                width, height = (float(part) for part in parts)
            except ValueError:
                raise InputError(f"{option}: expected WIDTHxHEIGHT in metres (e.g. 0.4x2.0), "
                                 f"got '{item}'", option) from None
            if not (math.isfinite(width) and math.isfinite(height) and width > 0 and height > 0):
                raise InputError(f"{option}: width and height must be positive numbers of "
                                 f"metres, got '{item}'", option)
            if width >= height:
                raise InputError(f"{option}: a rocking block is taller than it is wide "
                                 f"(α < 45°), got width {width:g} m ≥ height {height:g} m", option)
            blocks.append(NamedBlock(width, height, g))
    return blocks


@dataclass(frozen=True)
class BlockList:
    """Every block of an audit in one order: the grid (α-major, then size), then the named
    blocks. Arrays are one entry per block.

    Attributes
    ----------
    alpha_deg, size_s : numpy.ndarray
        Slenderness [degrees] and size 2π/p [s].
    label : numpy.ndarray of str
        ``WIDTHxHEIGHT`` [m] of a named block, ``""`` for a grid block.
    """

    alpha_deg: np.ndarray
    size_s: np.ndarray
    label: np.ndarray

    @classmethod
    def of(cls, alpha_deg=(), size_s=(), named=()) -> BlockList:
        alpha_deg = np.asarray(alpha_deg, dtype=float)
        size_s = np.asarray(size_s, dtype=float)
        grid_alpha, grid_size = (a.ravel() for a in np.meshgrid(alpha_deg, size_s,
                                                                   indexing="ij"))
        return cls(np.concatenate([grid_alpha, [b.alpha_deg for b in named]]),
                   np.concatenate([grid_size, [b.size_s for b in named]]),
                   np.array([""] * grid_alpha.size + [b.label for b in named], dtype=object))

    def __len__(self) -> int:
        return self.alpha_deg.size

    @property
    def alpha_rad(self) -> np.ndarray:
        return np.radians(self.alpha_deg)

    def groups(self) -> list[tuple[float, np.ndarray]]:
        """Blocks of one slenderness together: ``(alpha_rad, indices)`` in order of first
        appearance; a procedure evaluates and the solver solves each group in one call."""
        groups: dict[float, list[int]] = {}
        for index, alpha in enumerate(self.alpha_deg):
            groups.setdefault(float(alpha), []).append(index)
        return [(math.radians(alpha), np.array(indices)) for alpha, indices in groups.items()]


__all__ = ["NamedBlock", "parse_blocks", "BlockList"]
