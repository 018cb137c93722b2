"""The uniform shear building: N storeys of equal mass m and equal storey stiffness k.

M = m·I and K tridiagonal (2k on the diagonal, k in its last entry, −k beside it), floors at
z/H = j/N, j = 1 … N. Its modes are known in closed form (e.g. Chopra, *Dynamics of Structures*,
the uniform shear frame): φ_n(j) = sin(j·θ_n), θ_n = (2n − 1)π/(2N + 1), ω_n = 2√(k/m)·sin(θ_n/2),
so k/m is set by ω_1 = 2π/T1 and T_n/T1 = sin(θ_1/2)/sin(θ_n/2). With equal masses,
Γ_n = Σ_j φ_n(j) / Σ_j φ_n(j)². All N modes are kept: the floor motion is that of the MDOF
system exactly.

An object between floors (z/H not a multiple of 1/N) is given the mode shapes interpolated
linearly between the floors below and above (the ground, z = 0, has φ = 0): it moves with the
straight line joining the two floors' motions, as on a stiff stair or mezzanine hung between
them. Σ_n Γ_n φ_n(z) = 1 still holds there, as it does at every floor.
"""

from __future__ import annotations

import numpy as np


class ShearBuilding:
    """``shear:N``: a uniform shear building of N storeys.

    Parameters
    ----------
    storeys : int
        N ≥ 1.
    """

    def __init__(self, storeys: int):
        self.storeys = int(storeys)
        n = np.arange(1, self.storeys + 1)
        self.theta = (2 * n - 1) * np.pi / (2 * self.storeys + 1)

    def period_ratios(self) -> np.ndarray:
        """T_n/T1 of every mode [-]."""
        half = np.sin(self.theta / 2.0)
        return half[0] / half

    def shapes_at(self, z_over_h: float) -> np.ndarray:
        """φ_n at relative height z/H (linear between floors; φ_n(floor j) = sin(jθ_n)) [-]."""
        j = z_over_h * self.storeys
        below = min(int(np.floor(j)), self.storeys - 1)
        weight = j - below
        return ((1.0 - weight) * np.sin(below * self.theta)
                + weight * np.sin((below + 1) * self.theta))

    def participation(self) -> np.ndarray:
        """Γ_n = Σ_j φ_n(j) / Σ_j φ_n(j)² (equal masses) [-]."""
        j = np.arange(1, self.storeys + 1)[:, None]
        shapes = np.sin(j * self.theta)
        return shapes.sum(axis=0) / (shapes ** 2).sum(axis=0)

    def modes(self, period_s: float, z_over_h: float, shortest_period_s: float):
        """(T_n [s], Γ_n φ_n(z) [-]) of every mode: the shear building keeps all N modes
        (``shortest_period_s`` is not needed)."""
        return period_s * self.period_ratios(), self.participation() * self.shapes_at(z_over_h)


__all__ = ["ShearBuilding"]
