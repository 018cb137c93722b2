"""The exact solver over a grid of equivalent blocks for every test of a campaign, solved once.

Every fit of the validation (each specimen, each cross-validation fold) reads this one table of
exact outcomes, so the solve count is that of the grid: tests × α × p × restitution factors.
The table motions are band-passed first (the campaign's records are unfiltered feedback signals
with a DC drift and content above 25 Hz; docs/validation.md).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.signal import butter, sosfiltfilt

from audit import G
from audit.engine.validation.settings import ValidationSettings
from audit.errors import InputError
from audit.physics.block import Restitution
from audit.physics.rocking import rocking_blocks


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
class OverturningGrid:
    """Exact overturning of every grid block under every test.

    Attributes
    ----------
    overturned : numpy.ndarray of bool
        Shaped (test, restitution factor, p, α) of the settings' grid.
    solves : int
        Exact simulations run.
    """

    overturned: np.ndarray
    solves: int


def overturning_grid(motions, settings: ValidationSettings, progress=None) -> OverturningGrid:
    """Solve every grid block (α, p, restitution factor) under every motion exactly.

    Parameters
    ----------
    motions : sequence of GroundMotion
        Band-passed table motions [m/s²].
    settings : ValidationSettings
    progress : callable, optional
        Called as ``progress(done, total, what)`` after each test.
    """
    alpha = np.radians(np.asarray(settings.alpha_deg, dtype=float))
    p = np.asarray(settings.p_rad_s, dtype=float)
    grid_p, grid_alpha = np.meshgrid(p, alpha, indexing="ij")
    size = 2.0 * np.pi / grid_p.ravel()
    shape = (len(settings.restitution_factors), p.size, alpha.size)
    out = np.empty((len(motions),) + shape, dtype=bool)
    for i, motion in enumerate(motions):
        for j, factor in enumerate(settings.restitution_factors):
            peaks = rocking_blocks(motion, size, grid_alpha.ravel(), Restitution(factor=factor),
                                   free_motion_s=settings.free_motion_s, jobs=settings.jobs)
            out[i, j] = peaks.overturned.reshape(shape[1:])
        if progress is not None:
            progress(i + 1, len(motions), motion.id)
    return OverturningGrid(out, len(motions) * settings.solves_per_test)


__all__ = ["ValidationSettings", "Intensities", "OverturningGrid", "band_passed", "intensities",
           "overturning_grid"]
