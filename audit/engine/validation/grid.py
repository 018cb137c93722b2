"""The exact solver over a grid of equivalent blocks for every test of a campaign, solved once.

Every fit of the validation (each specimen, each cross-validation fold) reads this one table of
exact outcomes, so the solve count is that of the grids: tests × blocks (the coarse grid, then
the fine grids of :mod:`~audit.engine.validation.refine`). The blocks rock under the motions as
recorded unless ``band_pass`` is set; PGA and PGV are read from the band-passed motions (the
campaign's records are unfiltered feedback signals with a DC drift; docs/validation.md).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.signal import butter, sosfiltfilt

from audit import G
from audit.engine.validation.settings import ValidationSettings
from audit.errors import InputError
from audit.physics.block import Restitution
from audit.physics.rocking import RockingOptions, rocking_blocks


def band_passed(motion, settings: ValidationSettings):
    """The motion band-passed (zero phase) as ``settings`` says; SI in and out. InputError
    naming the motion's file where its step leaves the high-pass at or above the Nyquist
    frequency, or where it is too short for the zero-phase filter's padding.

    Parameters
    ----------
    motion : records.GroundMotion
        The table's motion.
    settings : ValidationSettings
        The band (``highpass_hz``, ``lowpass_hz`` [Hz]).
    """
    nyquist = 0.5 / motion.dt
    if settings.highpass_hz >= nyquist:
        raise InputError(f"{motion.source}: time step {motion.dt:g} s: the Nyquist frequency "
                         f"{nyquist:g} Hz is not above the {settings.highpass_hz:g} Hz "
                         "high-pass; is the time column in seconds?")
    if settings.lowpass_hz < nyquist:
        sos = butter(4, [settings.highpass_hz, settings.lowpass_hz], "bandpass",
                     fs=1.0 / motion.dt, output="sos")
    else:
        sos = butter(4, settings.highpass_hz, "highpass", fs=1.0 / motion.dt, output="sos")
    # sosfiltfilt pads each end by 3 samples per pole (scipy's default padlen) and needs more
    pad = 3 * (2 * len(sos) + 1 - min((sos[:, 2] == 0).sum(), (sos[:, 5] == 0).sum()))
    if motion.acceleration.size <= pad:
        raise InputError(f"{motion.source}: {motion.acceleration.size} samples "
                         f"({motion.duration:g} s), too short for the zero-phase band-pass "
                         f"filter: needs more than {pad}")
    return replace(motion, acceleration=sosfiltfilt(sos, motion.acceleration),
                   component=f"{motion.component}, band-passed "
                             f"{settings.highpass_hz:g}–{settings.lowpass_hz:g} Hz")


@dataclass(frozen=True)
class Intensities:
    """Per test: PGA [m/s²] and PGV [m/s] of the band-passed motion."""

    pga: np.ndarray
    pgv: np.ndarray

    @property
    def pga_g(self) -> np.ndarray:
        return self.pga / G

    @property
    def pgv_pga_s(self) -> np.ndarray:
        return self.pgv / self.pga


def intensities(motions) -> Intensities:
    """PGA and PGV (trapezoid integral from rest) of each (band-passed) motion.

    Parameters
    ----------
    motions : iterable of records.GroundMotion
        The motions, accelerations [m/s²].

    Returns
    -------
    Intensities
        PGA [m/s²] and PGV [m/s] of each.
    """
    pga, pgv = [], []
    for motion in motions:
        acc = motion.acceleration
        velocity = np.concatenate(([0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * motion.dt)))
        pga.append(np.max(np.abs(acc)))
        pgv.append(np.max(np.abs(velocity)))
    return Intensities(np.asarray(pga), np.asarray(pgv))


@dataclass(frozen=True)
class BlockGrid:
    """The blocks solved under every test: each (restitution factor, p) has its own α nodes.

    Attributes
    ----------
    restitution_factors : numpy.ndarray
        Multiples of Eq. 4.8's r [-], shape (F,).
    p_rad_s : numpy.ndarray
        Frequency parameters [rad/s], shape (P,).
    alpha_deg : numpy.ndarray
        Slenderness nodes [degrees], shape (F, P, N), increasing along the last axis.
    search_alpha_deg, search_p_rad_s : tuple
        The range searched (the coarse grid's, which a fine grid inherits): a 95 % set that
        reaches its end does not identify the parameter; one that reaches only a fine grid's
        end is bounded there by the coarser grid's likelihood.
    """

    restitution_factors: np.ndarray
    p_rad_s: np.ndarray
    alpha_deg: np.ndarray
    search_alpha_deg: tuple
    search_p_rad_s: tuple

    @classmethod
    def from_settings(cls, settings: ValidationSettings) -> BlockGrid:
        """The settings' grid: the same α nodes at every (f, p).

        Parameters
        ----------
        settings : ValidationSettings
            ``restitution_factors`` [-], ``p_rad_s`` [rad/s] and ``alpha_deg`` [degrees].
        """
        f = np.asarray(settings.restitution_factors, dtype=float)
        p = np.asarray(settings.p_rad_s, dtype=float)
        alpha = np.broadcast_to(np.asarray(settings.alpha_deg, dtype=float),
                                (f.size, p.size, len(settings.alpha_deg))).copy()
        return cls(f, p, alpha, (float(alpha.min()), float(alpha.max())),
                   (float(p.min()), float(p.max())))

    @property
    def solves_per_test(self) -> int:
        return int(self.alpha_deg.size)


@dataclass(frozen=True)
class OverturningGrid:
    """Exact overturning of every grid block under every test.

    Attributes
    ----------
    overturned : numpy.ndarray of bool
        Shaped (test, restitution factor, p, α node) of ``blocks``.
    blocks : BlockGrid
    solves : int
        Exact simulations run.
    """

    overturned: np.ndarray
    blocks: BlockGrid
    solves: int


def overturning_grid(motions, settings: ValidationSettings, progress=None,
                     blocks: BlockGrid | None = None) -> OverturningGrid:
    """Solve every grid block (α, p, restitution factor) under every motion exactly.

    Parameters
    ----------
    motions : sequence of GroundMotion
        Table motions [m/s²].
    settings : ValidationSettings
    progress : callable, optional
        Called as ``progress(done, total, what)`` after each test.
    blocks : BlockGrid, optional
        The blocks; the settings' grid when not given.
    """
    blocks = BlockGrid.from_settings(settings) if blocks is None else blocks
    shape = blocks.alpha_deg.shape
    size = np.broadcast_to(2.0 * np.pi / blocks.p_rad_s[:, None], shape[1:]).ravel()
    out = np.empty((len(motions),) + shape, dtype=bool)
    for i, motion in enumerate(motions):
        for j, factor in enumerate(blocks.restitution_factors):
            peaks = rocking_blocks(motion, size, np.radians(blocks.alpha_deg[j]).ravel(),
                                   Restitution(factor=float(factor)),
                                   RockingOptions(free_motion_s=settings.free_motion_s),
                                   jobs=settings.jobs)
            out[i, j] = peaks.overturned.reshape(shape[1:])
        if progress is not None:
            progress(i + 1, len(motions), motion.id)
    return OverturningGrid(out, blocks, len(motions) * blocks.solves_per_test)


__all__ = ["ValidationSettings", "Intensities", "BlockGrid", "OverturningGrid", "band_passed",
           "intensities", "overturning_grid"]
