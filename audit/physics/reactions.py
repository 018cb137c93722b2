"""Pivot reactions of a rocking block: where pure rocking stops being valid.

Newton's law for the centroid of a rectangular block (mass m, R, α) rocking about a corner on
ground moving with horizontal acceleration ü_g. With s = ±1 the side of the pivot (the sign of
θ) and φ = α − sθ, the centroid sits at x = −sR sin φ, y = R cos φ from the pivot, so

    H / m = ü_g + R (θ'' cos φ + s θ'² sin φ)
    V / m = g   + R (s θ'' sin φ − θ'² cos φ)

with θ'' from the equation of motion (Eq. 4.3 of Makris & Konstantinidis 2001). Pure rocking
needs V ≥ 0 (else the block jumps) and a friction coefficient μ ≥ |H| / V. At uplift
(θ = θ' = 0, |ü_g| = g tan α, θ'' = 0) this is the classic μ ≥ tan α; during rocking the
θ'² terms and θ'' change it (derivation in docs/ground-truth-assumptions.md).
"""

from __future__ import annotations

import numpy as np

from audit import G


def pivot_reactions(theta_rad, omega_rad_s, ground_acc, side, p, alpha_rad, g=G):
    """Horizontal and vertical pivot reactions H/(mg), V/(mg) [-] of a block rocking on one corner.

    Parameters
    ----------
    theta_rad, omega_rad_s : float or array
        θ [rad] and θ' [rad/s].
    ground_acc : float or array
        ü_g [m/s²].
    side : float or array
        +1 rocking on the corner of θ > 0, −1 on the other.
    p : float
        Frequency parameter [rad/s]; R = 3g / (4p²).
    alpha_rad : float
        Slenderness α [rad].
    g : float
        Acceleration of gravity [m/s²].
    """
    theta, omega = np.asarray(theta_rad, dtype=float), np.asarray(omega_rad_s, dtype=float)
    phi = side * alpha_rad - theta
    # Eq. 4.3 on the current pivot
    theta_acc = -p ** 2 * (np.sin(phi) + ground_acc / g * np.cos(phi))
    radius = 3.0 * g / (4.0 * p ** 2)
    # φ here is sα − θ = s(α − sθ): cos is even, s·sin(α − sθ) = sin(sα − θ)
    horizontal = ground_acc + radius * (theta_acc * np.cos(phi) + omega ** 2 * np.sin(phi))
    vertical = g + radius * (theta_acc * np.sin(phi) - omega ** 2 * np.cos(phi))
    return horizontal / g, vertical / g


def required_friction(horizontal, vertical):
    """Friction coefficient max |H| / V [-] pure rocking needs (inf where V ≤ 0: jumping)."""
    horizontal, vertical = np.asarray(horizontal, float), np.asarray(vertical, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(vertical > 0, np.abs(horizontal) / vertical, np.inf)
    return float(ratio.max()) if ratio.size else 0.0


def rocking_validity(response, motion):
    """Friction the pure-rocking response requires and whether it jumps, over the whole response.

    Evaluated at every solver output point of ``response.history()`` (sampling grid, turning
    points, both sides of each impact). At rest on the base H = m ü_g, V = m g; at an impact
    (θ = 0) both pivots are reached, so both are evaluated.

    Parameters
    ----------
    response : RockingResponse
    motion : records.GroundMotion

    Returns
    -------
    required_friction : float
        max |H| / V [-] (inf when the block would jump).
    jumps : bool
        V < 0 somewhere.
    """
    block = response.block
    time, theta, omega = response.history()
    ground = motion.acceleration_at(time)
    at_rest = (theta == 0) & (omega == 0)
    on_base = ~at_rest & (theta == 0)
    sides = [np.sign(theta[~at_rest & ~on_base])]
    points = [(theta[~at_rest & ~on_base], omega[~at_rest & ~on_base], ground[~at_rest & ~on_base])]
    for side in (1.0, -1.0):
        sides.append(side)
        points.append((theta[on_base], omega[on_base], ground[on_base]))
    horizontal, vertical = [ground[at_rest] / block.g], [np.ones(int(at_rest.sum()))]
    for side, (th, om, ug) in zip(sides, points):
        h, v = pivot_reactions(th, om, ug, side, block.p, block.alpha, block.g)
        horizontal.append(np.atleast_1d(h))
        vertical.append(np.atleast_1d(v))
    horizontal, vertical = np.concatenate(horizontal), np.concatenate(vertical)
    return required_friction(horizontal, vertical), bool(np.any(vertical < 0))


__all__ = ["pivot_reactions", "required_friction", "rocking_validity"]
