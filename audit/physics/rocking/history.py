"""One block under one ground motion: :func:`simulate` and the :class:`RockingHistory` it
returns."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit.errors import InputError
from audit.physics.block import RigidBlock
from audit.physics.defaults import (DEFAULT_FREE_MOTION_S, DEFAULT_REST_TOLERANCE,
                                    DEFAULT_STEPS_PER_RADIAN)
from audit.physics.rocking.kernel import (_IMPACT_EPISODE, _IMPACT_TIME, _OMEGA_AFTER_IMPACT,
                                          _OMEGA_BEFORE_IMPACT, _TURN_THETA, _TURN_TIME,
                                          _free_samples, _motion_arguments, _simulate)
from audit.physics.rocking.rest import MIN_REST_TOLERANCE
from audit.physics.tiers import tiered

#: Impacts whose times are kept by :func:`simulate`.
IMPACT_CAPACITY = 100_000
#: Most samples of θ(t) and θ'(t) kept by :func:`simulate` (longer histories are decimated, so
#: one block's history stays within ~10 MB; peaks and impacts are located exactly regardless).
HISTORY_CAPACITY = 400_000
#: Time of one Runge–Kutta step of the kernel run interpreted (see audit.physics.tiers) [s].
INTERPRETED_STEP_S = 5e-6


@dataclass(frozen=True)
class RockingHistory:
    """Result of one simulation (all angles in rad, times in s).

    Attributes
    ----------
    time, theta, omega : numpy.ndarray
        θ(t) [rad] and θ'(t) [rad/s] on the motion's sampling grid, extended over the free
        motion (every k-th sample where that would exceed :data:`HISTORY_CAPACITY`); NaN
        after overturning.
    impact_times : numpy.ndarray
        Times of the impacts [s] (the first :data:`IMPACT_CAPACITY`).
    impact_episode : numpy.ndarray
        Rocking episode (1, 2, …; a return to rest ends one) of each impact.
    omega_before_impact, omega_after_impact : numpy.ndarray
        θ' just before and just after each impact [rad/s] (Eq. 4.6–4.8; 0 after an impact
        that ends in rest).
    turning_times, turning_rotations : numpy.ndarray
        Time [s] and θ [rad] of every turning point θ' = 0 (the first
        :data:`IMPACT_CAPACITY`), located inside the solver's steps.
    overturned : bool
    overturn_time : float
        NaN when the block survives.
    peak_rotation : float
        max |θ| [rad] (α when overturned).
    peak_rotation_signed : float
        θ at the peak [rad].
    peak_angular_velocity : float
        max |θ'| [rad/s].
    peak_rotation_after_excitation : float
        max |θ| after the excitation ends [rad].
    n_impacts : int
    uplifted : bool
    block : RigidBlock
    excitation_end : float
        End of the excitation [s].
    required_friction : float
        Friction coefficient max |H|/V [-] the pure-rocking response needs at its pivot
        (:func:`pivot_reactions`; inf where it would jump).
    min_vertical_reaction : float
        Smallest vertical reaction V/(mg) [-]; below zero the block would jump.
    """

    time: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    impact_times: np.ndarray
    impact_episode: np.ndarray
    omega_before_impact: np.ndarray
    omega_after_impact: np.ndarray
    turning_times: np.ndarray
    turning_rotations: np.ndarray
    overturned: bool
    overturn_time: float
    peak_rotation: float
    peak_rotation_signed: float
    peak_angular_velocity: float
    peak_rotation_after_excitation: float
    n_impacts: int
    uplifted: bool
    block: RigidBlock
    excitation_end: float
    required_friction: float = math.nan
    min_vertical_reaction: float = math.nan

    @property
    def jumps(self) -> bool:
        """Whether the vertical pivot reaction becomes negative: the block would leave the
        ground, which pure rocking does not model."""
        return bool(self.min_vertical_reaction < 0)

    @property
    def peak_rotation_ratio(self) -> float:
        """max |θ| / α [-]."""
        return self.peak_rotation / self.block.alpha

    @property
    def peak_rotation_free_vibration(self) -> float:
        """Largest |θ| at a turning point (θ' = 0) strictly after the excitation ends [rad].

        The peak of the free vibration of Figures 4.1–4.2 (0.38α in Figure 4.2); NaN when the
        block overturns or has no turning point after the excitation.
        """
        after = self.turning_times > self.excitation_end
        if self.overturned or not after.any():
            return math.nan
        return float(np.max(np.abs(self.turning_rotations[after])))

    def history(self):
        """The response at every solver output point, in time order.

        The motion's sampling grid (up to overturning) merged with every turning point
        (θ' = 0) and every impact, which appears twice at its time: θ' just before, then just
        after.

        Returns
        -------
        time, theta, omega : numpy.ndarray
            t [s], θ [rad], θ' [rad/s].
        """
        defined = np.isfinite(self.theta)
        n_impacts, n_turns = self.impact_times.size, self.turning_times.size
        time = np.concatenate((self.time[defined], self.turning_times, self.impact_times,
                               self.impact_times))
        theta = np.concatenate((self.theta[defined], self.turning_rotations,
                                np.zeros(2 * n_impacts)))
        omega = np.concatenate((self.omega[defined], np.zeros(n_turns),
                                self.omega_before_impact, self.omega_after_impact))
        # ties at one time: grid point and turning point, then before, then after an impact
        rank = np.repeat([0, 0, 1, 2], [int(defined.sum()), n_turns, n_impacts, n_impacts])
        order = np.lexsort((rank, time))
        return time[order], theta[order], omega[order]

    @property
    def cycle_starts(self) -> np.ndarray:
        """Start times of the full rocking cycles of :attr:`cycle_durations` [s]."""
        return self._cycles()[0]

    @property
    def cycle_durations(self) -> np.ndarray:
        """Durations of full rocking cycles [s]: time between every second impact.

        Cycles are counted from the first impact of each rocking episode; a return to rest
        ends the episode, so no cycle spans a rest.
        """
        return self._cycles()[1]

    def _cycles(self):
        starts, durations = [], []
        for episode in np.unique(self.impact_episode):
            times = self.impact_times[self.impact_episode == episode]
            starts.extend(times[:-2:2])
            durations.extend(times[2::2] - times[:-2:2])
        return np.asarray(starts), np.asarray(durations)


def simulate(block: RigidBlock, motion, free_motion_s: float = DEFAULT_FREE_MOTION_S,
             steps_per_radian: float = DEFAULT_STEPS_PER_RADIAN,
             rest_tolerance: float = DEFAULT_REST_TOLERANCE, initial_rotation: float = 0.0,
             initial_velocity: float = 0.0, vertical: bool = False) -> RockingHistory:
    """Exact rocking response of one block to one ground motion (Eq. 4.3).

    Parameters
    ----------
    block : RigidBlock
        The block (p [rad/s], α [rad], r [-], g [m/s²]).
    motion : records.GroundMotion
        Ground acceleration [m/s²], linear between samples or an analytic pulse.
    free_motion_s : float
        Free motion simulated after the excitation ends [s].
    steps_per_radian : float
        Accuracy setting: Runge–Kutta step h ≤ 1/(steps_per_radian·p) [-].
    rest_tolerance : float
        Largest rebound, as a fraction of α, of a chatter that may end in rest [-].
    initial_rotation, initial_velocity : float
        θ(0) [rad] and θ'(0) [rad/s]; the block starts at rest when both are zero.
    vertical : bool
        Include the motion's vertical component (gravity g + üv), where it has one.

    Returns
    -------
    RockingHistory
    """
    if not MIN_REST_TOLERANCE <= rest_tolerance < 1.0:
        raise InputError(f"rest tolerance: must be at least {MIN_REST_TOLERANCE:g} and below 1, "
                         f"got {rest_tolerance:g}")
    if abs(initial_rotation) >= block.alpha:
        raise InputError(f"initial rotation: |θ0| must be below α = {block.alpha:g} rad, "
                         f"got {initial_rotation:g}")
    args = _motion_arguments(motion, free_motion_s, vertical)
    n_samples = motion.acceleration.size + _free_samples(motion, free_motion_s)
    stride = -(-n_samples // HISTORY_CAPACITY)
    n_out = (n_samples - 1) // stride + 1
    theta = np.empty(n_out)
    omega = np.empty(n_out)
    impacts = np.empty((IMPACT_CAPACITY, 4))
    turns = np.empty((IMPACT_CAPACITY, 2))
    n_steps = (n_samples - 1) * math.ceil(motion.dt * block.p * steps_per_radian)
    kernel = tiered(_simulate, n_steps * INTERPRETED_STEP_S)
    summary = kernel(*args, block.p, block.alpha, math.sqrt(block.r), block.g, steps_per_radian,
                     rest_tolerance, initial_rotation, initial_velocity, theta, omega, impacts,
                     turns, stride, True)
    n_kept = min(int(summary.n_impacts), IMPACT_CAPACITY)
    n_turns = min(int(summary.n_turns), IMPACT_CAPACITY)
    return RockingHistory(
        time=np.arange(n_out) * (stride * motion.dt), theta=theta, omega=omega,
        impact_times=impacts[:n_kept, _IMPACT_TIME].copy(),
        impact_episode=impacts[:n_kept, _IMPACT_EPISODE].astype(int),
        omega_before_impact=impacts[:n_kept, _OMEGA_BEFORE_IMPACT].copy(),
        omega_after_impact=impacts[:n_kept, _OMEGA_AFTER_IMPACT].copy(),
        turning_times=turns[:n_turns, _TURN_TIME].copy(),
        turning_rotations=turns[:n_turns, _TURN_THETA].copy(),
        overturned=bool(summary.overturned), overturn_time=float(summary.overturn_time),
        peak_rotation=float(summary.peak_rotation),
        peak_rotation_signed=float(summary.peak_rotation_signed),
        peak_angular_velocity=float(summary.peak_angular_velocity),
        peak_rotation_after_excitation=float(summary.peak_rotation_after_excitation),
        n_impacts=int(summary.n_impacts), uplifted=bool(summary.uplifted), block=block,
        excitation_end=motion.duration, required_friction=float(summary.required_friction),
        min_vertical_reaction=float(summary.min_vertical_reaction),
    )

