"""The absolute acceleration of a floor, from the ground's: modal superposition of a linear,
classically damped building (:mod:`.shear`, :mod:`.continuum`).

Each mode n obeys q̈_n + 2ζω_n q̇_n + ω_n² q_n = −üg and is solved exactly for üg linear between
samples with the recurrence of the spectra (:mod:`audit.physics.oscillator`); its absolute
acceleration at a sample is q̈_n + üg = −2ζω_n q̇_n − ω_n² q_n. The floor at z moves with

    ü_floor(z) = Σ_n Γ_n φ_n(z) (q̈_n + üg) + (1 − Σ_n Γ_n φ_n(z)) üg,

the last term the modes a model leaves out, rigid at the record's frequencies (zero for the
shear building, which keeps all of its modes). The building goes on vibrating after the ground
stops: the floor motion runs on until its first mode has decayed to 1 % (ln 100/(ζω_1) more),
at most the record's own length again. The filter is linear: the floor motion of a scaled
record is the scaled floor motion.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace

import numpy as np

from audit.physics.building.continuum import ContinuumBuilding
from audit.physics.building.floor import Floor
from audit.physics.building.shear import ShearBuilding
from audit.physics.kernel_cache import kernel
from audit.physics.oscillator import (INTERPRETED_STEP_S, oscillator_step,
                                      recurrence_coefficients, step_coefficients)
from audit.physics.tiers import tiered

#: What the first mode's free vibration has decayed to where the floor motion stops [-].
FREE_VIBRATION_LEFT = 0.01


def building_of(floor: Floor):
    """The model object of ``floor.building.model`` (``shear:N`` or ``continuum:α0``)."""
    model = floor.building.model
    return (ShearBuilding(int(model.value)) if model.kind == "shear"
            else ContinuumBuilding(model.value))


@functools.lru_cache(maxsize=64)
def floor_modes(floor: Floor, dt: float):
    """(T_n [s], Γ_n φ_n(z) [-]) of the modes the floor motion keeps at sampling step ``dt``
    (remembered: the records of a suite mostly share a few steps, and the continuum's roots
    and integrals cost far more than filtering a record), read-only."""
    periods, weights = building_of(floor).modes(floor.building.period_s, floor.z_over_h, 2.0 * dt)
    periods.flags.writeable = weights.flags.writeable = False
    return periods, weights


@kernel()
def _modal_sum(acc, coeffs, weights, two_xi_omega, omega2, out):
    """out[k] −= Σ_n w_n (2ζω_n q̇_n + ω_n² q_n) at every sample, each mode from rest."""
    for m in range(weights.size):
        c = step_coefficients(coeffs[m])
        w, damping_term, stiffness_term = weights[m], two_xi_omega[m], omega2[m]
        u = v = 0.0
        for k in range(acc.size - 1):
            u, v = oscillator_step(c, u, v, acc[k], acc[k + 1])
            out[k + 1] -= w * (damping_term * v + stiffness_term * u)


def _free_vibration_samples(samples: int, dt: float, floor: Floor) -> int:
    """Samples of the building's free vibration appended to a record of ``samples`` samples."""
    tail = min(math.log(1.0 / FREE_VIBRATION_LEFT) * floor.building.period_s
               / (2.0 * math.pi * floor.building.damping), (samples - 1) * dt)
    return int(math.ceil(tail / dt))


def interpreted_time_s(samples: int, dt: float, floor: Floor) -> float:
    """Estimated time [s] of the floor filter of a record of ``samples`` samples ``dt`` apart
    run by the interpreter (for :func:`audit.physics.tiers.tiered`): every kept mode at every
    sample, the building's free vibration included."""
    if floor.on_ground:
        return 0.0
    modes = floor_modes(floor, dt)[0].size
    return (samples + _free_vibration_samples(samples, dt, floor)) * modes * INTERPRETED_STEP_S


def floor_acceleration(acceleration, dt: float, floor: Floor) -> np.ndarray:
    """The absolute floor acceleration at the samples of ``acceleration`` (the ground's, any
    unit; the same unit out), zeros appended for the building's free vibration (see the
    module). On the ground: the ground's acceleration itself.

    Parameters
    ----------
    acceleration : numpy.ndarray
        üg at t = k·dt, linear between samples.
    dt : float
        Sampling step [s].
    floor : Floor
        Where the object stands.
    """
    acc = np.asarray(acceleration, dtype=float)
    if floor.on_ground:
        return acc.copy()
    periods, weights = floor_modes(floor, dt)
    run_s = interpreted_time_s(acc.size, dt, floor)
    acc = np.concatenate((acc, np.zeros(_free_vibration_samples(acc.size, dt, floor)
                                        if periods.size else 0)))
    out = (1.0 - weights.sum()) * acc
    if periods.size:
        damping = np.full(periods.size, floor.building.damping)
        omega = 2.0 * np.pi / periods
        coeffs = recurrence_coefficients(periods, damping, dt)
        tiered(_modal_sum, run_s)(
            acc, coeffs, np.ascontiguousarray(weights, dtype=float), 2.0 * damping * omega,
            omega ** 2, out)
    return out


def floor_motion(motion, floor: Floor):
    """The floor motion of a ground motion (:class:`records.GroundMotion`), which keeps its
    ground motion as ``ground`` (the intensity measures of the hazard read it) and its id; the
    ground motion itself on the ground. A motion that is already a floor's is refused."""
    if floor.on_ground:
        return motion
    if motion.ground is not None:
        from audit.errors import InputError
        raise InputError(f"floor: {motion.id} is already the motion of a floor", "floor")
    acc = floor_acceleration(motion.acceleration, motion.dt, floor)
    # the vertical component is the ground's: the building is modelled for horizontal motion
    vertical = None if motion.vertical is None else np.concatenate(
        (motion.vertical, np.zeros(acc.size - motion.vertical.size)))
    return replace(motion, acceleration=acc, pulse=None, vertical=vertical, ground=motion,
                   component=f"{motion.component}, {floor.describe()}".lstrip(", "))


__all__ = ["floor_acceleration", "floor_motion", "floor_modes", "building_of",
           "interpreted_time_s",
           "FREE_VIBRATION_LEFT"]
