"""Many blocks under one ground motion: their peaks (:func:`rocking_blocks`) and rocking
spectra over a grid of blocks (:func:`rocking_spectrum`, Section 5)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from audit.errors import InputError
from audit.physics.block import RigidBlock
from audit.physics.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_REST_TOLERANCE,
                                    DEFAULT_STEPS_PER_RADIAN)
from audit.physics.kernel_threads import run_chunks
from audit.physics.rocking.kernel import _motion_arguments, _spectrum
from audit.physics.rocking.motion_equation import _SAMPLED


@dataclass(frozen=True)
class RockingOptions:
    """How blocks are solved beyond what they are: gravity, the free motion after the
    excitation, the solver's step and rest rule, the vertical component.

    Attributes
    ----------
    g : float, optional
        Acceleration of gravity [m/s²]; the block's default when not given.
    free_motion_s : float
        Free motion simulated after the excitation [s].
    steps_per_radian : float
        Runge–Kutta steps per radian of pτ: h ≤ 1/(steps_per_radian·p).
    rest_tolerance : float
        Rebounds below ``rest_tolerance``·α end the chatter at rest [-].
    vertical : bool
        Include the motion's vertical component (gravity g + üv), where it has one.
    """

    g: float | None = None
    free_motion_s: float = DEFAULT_FREE_MOTION_S
    steps_per_radian: float = DEFAULT_STEPS_PER_RADIAN
    rest_tolerance: float = DEFAULT_REST_TOLERANCE
    vertical: bool = False


class BlockPeaks(NamedTuple):
    """Peaks of blocks given one by one (:func:`rocking_blocks`), one value per block in each
    field (a NamedTuple, so that the compiled kernel fills its arrays in place)."""

    theta_peak: np.ndarray  # max |θ| [rad] (α where the block overturns)
    omega_peak: np.ndarray  # max |θ'| [rad/s]
    theta_after: np.ndarray  # max |θ| after the excitation [rad]
    overturned: np.ndarray  # bool
    uplifted: np.ndarray  # bool
    required_friction: np.ndarray  # max |H|/V [-] (NaN without reactions)
    min_vertical_reaction: np.ndarray  # min V/(mg) [-] (NaN without reactions)

    @classmethod
    def empty(cls, n: int) -> "BlockPeaks":
        """Room for the peaks of ``n`` blocks."""
        return cls(*(np.empty(n, dtype=bool if name in ("overturned", "uplifted") else float)
                     for name in cls._fields))


@dataclass(frozen=True)
class RockingSpectrum:
    """Rocking spectra of one record over a grid of blocks (Section 5).

    Arrays are shaped (len(alpha_rad), len(size_s)).

    Attributes
    ----------
    size_s : numpy.ndarray
        Block "sizes" 2π/p [s].
    alpha_rad : numpy.ndarray
        Slendernesses α [rad].
    theta_peak : numpy.ndarray
        max |θ| [rad] (α where the block overturns).
    omega_peak : numpy.ndarray
        max |θ'| [rad/s].
    theta_after : numpy.ndarray
        max |θ| after the excitation [rad].
    overturned, uplifted : numpy.ndarray of bool
    required_friction : numpy.ndarray
        Friction coefficient max |H|/V [-] pure rocking needs (inf where the block would jump).
    min_vertical_reaction : numpy.ndarray
        Smallest vertical pivot reaction V/(mg) [-]; below zero the block would jump.
    """

    size_s: np.ndarray
    alpha_rad: np.ndarray
    theta_peak: np.ndarray
    omega_peak: np.ndarray
    theta_after: np.ndarray
    overturned: np.ndarray
    uplifted: np.ndarray
    required_friction: np.ndarray
    min_vertical_reaction: np.ndarray

    @property
    def jumps(self) -> np.ndarray:
        """Blocks whose vertical pivot reaction becomes negative (they would leave the ground)."""
        return self.min_vertical_reaction < 0

    @property
    def p(self) -> np.ndarray:
        """Frequency parameters 2π/size [rad/s]."""
        return 2.0 * np.pi / self.size_s

    @property
    def theta_ratio(self) -> np.ndarray:
        """max |θ| / α [-]."""
        return self.theta_peak / self.alpha_rad[:, None]

    def to_frame(self):
        """One row per block: ``alpha_deg, size_s, p_rad_s, theta_peak_rad, theta_ratio,
        overturned, omega_peak_rad_s, theta_after_rad, uplifted, required_friction, jumps`` (the
        CSV of ``spectrum`` and ``rocking.csv``)."""
        import pandas as pd  # here, so that one simulation (``rock``) does not load pandas
        alpha_deg = np.round(np.degrees(self.alpha_rad), 10)  # 15, not 14.999999999999998
        return pd.concat([pd.DataFrame({
            "alpha_deg": alpha_deg[i], "size_s": self.size_s, "p_rad_s": self.p,
            "theta_peak_rad": self.theta_peak[i], "theta_ratio": self.theta_ratio[i],
            "overturned": self.overturned[i], "omega_peak_rad_s": self.omega_peak[i],
            "theta_after_rad": self.theta_after[i], "uplifted": self.uplifted[i],
            "required_friction": self.required_friction[i], "jumps": self.jumps[i]})
            for i in range(self.alpha_rad.size)], ignore_index=True)


def rocking_blocks(motion, size_s, alpha_rad, r=None, options: RockingOptions = RockingOptions(),
                   *, jobs: int = 1, reactions: bool = False, scale=None) -> BlockPeaks:
    """Peaks of blocks given one by one, ``size_s[i]`` with ``alpha_rad[i]``, under one motion
    (block i under the motion × ``scale[i]``, when given).

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²].
    size_s, alpha_rad : array
        Size 2π/p [s] and slenderness α [rad] of each block (same length).
    r : float or Restitution, optional
        Coefficient of restitution for every block, or the impact model giving each α its r;
        Eq. 4.8 of each α when not given.
    options : RockingOptions
        Gravity, free motion, the solver's step and rest rule, the vertical component.
    jobs : int
        Threads sharing the blocks (the kernel releases the GIL).
    reactions : bool
        Also evaluate the pivot reactions over the response (about 25 % more work).
    scale : array, optional
        Each block's scale factor of the motion [-]: its peaks are those under
        ``motion.scaled(scale[i])``, bit for bit, so one call solves a record at many levels
        (stripes) without a copy of it per level. 1 for every block when not given.

    Returns
    -------
    BlockPeaks
        One value per block; the reactions are NaN without ``reactions``.
    """
    size_s = np.atleast_1d(np.asarray(size_s, dtype=float))
    alpha = np.atleast_1d(np.asarray(alpha_rad, dtype=float))
    if not (size_s.size and np.all(np.isfinite(size_s) & (size_s > 0))):
        raise InputError("sizes: every 2π/p must be a positive number of seconds")
    # RigidBlock validates α, r and g once per slenderness, with the same messages as elsewhere
    unique, inverse = np.unique(alpha, return_inverse=True)
    g = options.g
    blocks = [RigidBlock(2 * np.pi / size_s.max(), a, r, **({} if g is None else {"g": g}))
              for a in unique]
    p = 2.0 * np.pi / size_s
    factor = (np.ones(p.size) if scale is None
              else np.ascontiguousarray(np.broadcast_to(np.asarray(scale, dtype=float), p.shape)))
    if not np.all(np.isfinite(factor)):
        raise InputError("scale: every scale factor of the motion must be a finite number")
    ratio = np.sqrt(np.array([b.r for b in blocks]))[inverse.ravel()]
    args = _motion_arguments(motion, options.free_motion_s, options.vertical)
    out = BlockPeaks.empty(p.size)
    rest = _at_rest(args, alpha, factor, blocks[0].g) if not reactions else np.zeros(p.size, bool)
    # the kernel's own answer for a block the motion never lifts (it stops at once there)
    out.theta_peak[rest] = out.omega_peak[rest] = out.theta_after[rest] = 0.0
    out.overturned[rest] = out.uplifted[rest] = False
    out.required_friction[rest] = out.min_vertical_reaction[rest] = np.nan
    # longest runs (small blocks: many steps) first, spread round-robin over the threads
    order = np.argsort(p, kind="stable")[::-1]
    order = order[~rest[order]]
    chunks = [order[i::max(1, jobs)] for i in range(max(1, jobs))]

    def run(chunk):
        part = BlockPeaks.empty(chunk.size)
        _spectrum(*args, p[chunk], alpha[chunk], ratio[chunk], factor[chunk], blocks[0].g,
                  options.steps_per_radian, options.rest_tolerance, reactions, part)
        for values, computed in zip(out, part):
            values[chunk] = computed

    # even one chunk runs in a worker thread, so that Ctrl-C reaches the main thread at once
    # instead of after the compiled kernel returns; on an interrupt nothing waits for the rest
    run_chunks(run, chunks)
    return out


#: Relative margin below g tan α within which a block is left to the kernel, not taken as at
#: rest by :func:`_at_rest` (so a last-ulp difference in tan α cannot change an answer).
_REST_MARGIN = 1e-12


def _at_rest(args, alpha, factor, g: float) -> np.ndarray:
    """Which blocks a sampled horizontal motion (no vertical) cannot lift: the largest |üg| ×
    the block's scale stays at or below g tan α (the uplift condition of
    :func:`~audit.physics.rocking.motion_equation._lifts`), so the block stays at rest, θ = 0,
    and the kernel would stop before its first step. Every block is left to the kernel for a
    pulse or with a vertical component."""
    acc, up, kind = args[0], args[1], args[4]
    if kind != _SAMPLED or up.size or not acc.size:
        return np.zeros(alpha.size, dtype=bool)
    peak = float(np.max(np.abs(acc)))
    return peak * np.abs(factor) <= g * np.tan(alpha) * (1.0 - _REST_MARGIN)


def rocking_spectrum(motion, size_s, alpha_rad, r=None,
                     options: RockingOptions = RockingOptions(), *, jobs: int = 1,
                     reactions: bool = True) -> RockingSpectrum:
    """Peak rotation and angular velocity of every block of a (α, 2π/p) grid under one motion
    (:func:`rocking_blocks` over the grid).

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²].
    size_s : array
        Block sizes 2π/p [s].
    alpha_rad : array
        Slendernesses α [rad].
    r : float or Restitution, optional
        Coefficient of restitution for every block, or the impact model giving each α its r;
        Eq. 4.8 of each α when not given.
    options : RockingOptions
        Gravity, free motion, the solver's step and rest rule, the vertical component.
    jobs : int
        Threads sharing the blocks (the kernel releases the GIL).
    reactions : bool
        As for :func:`rocking_blocks`.

    Returns
    -------
    RockingSpectrum
    """
    size_s = np.atleast_1d(np.asarray(size_s, dtype=float))
    alpha_rad = np.atleast_1d(np.asarray(alpha_rad, dtype=float))
    grid_alpha, grid_size = np.meshgrid(alpha_rad, size_s, indexing="ij")
    peaks = rocking_blocks(motion, grid_size.ravel(), grid_alpha.ravel(), r, options, jobs=jobs,
                           reactions=reactions)
    shape = grid_size.shape
    return RockingSpectrum(size_s, alpha_rad, peaks.theta_peak.reshape(shape),
                           peaks.omega_peak.reshape(shape), peaks.theta_after.reshape(shape),
                           peaks.overturned.reshape(shape), peaks.uplifted.reshape(shape),
                           peaks.required_friction.reshape(shape),
                           peaks.min_vertical_reaction.reshape(shape))
