"""The compiled response spectra of a table of oscillators (Eq. 3.2): the recurrence over the
samples, four oscillators at a time (:func:`~audit.physics.oscillator.sampled_responses`), then
the search between samples (:mod:`audit.physics.peaks_between_samples`) where a bound lets an
extremum through; :func:`spectrum_peaks` for a table, :func:`fill_displacement` for one entry.
"""

from __future__ import annotations

import math

import numpy as np

from audit.physics.kernel_cache import kernel
from audit.physics.oscillator import (LANES, sampled_response, sampled_responses,
                                      step_coefficients)
from audit.physics.peaks_between_samples import step_may_peak, step_peaks


@kernel(inline="always")
def _displacement_through(u_at, k, margin_d, sd):
    """Whether the record's bound lets an extremum of u inside step k beat ``sd``."""
    return max(abs(u_at[k]), abs(u_at[k + 1])) + margin_d > sd


@kernel(inline="always")
def _motion_through(u_at, v_at, k, two_xi_omega, omega2, margin_v, margin_a, sv, sa):
    """Whether the record's bounds let an extremum of u' or ü + üg inside step k beat ``sv``
    or ``sa`` (both evaluated, no branch: the loop over every step compiles to vector
    instructions)."""
    return ((max(abs(v_at[k]), abs(v_at[k + 1])) + margin_v > sv)
            | (max(abs(two_xi_omega * v_at[k] + omega2 * u_at[k]),
                   abs(two_xi_omega * v_at[k + 1] + omega2 * u_at[k + 1])) + margin_a > sa))


@kernel()
def _searched_between_samples(acc, dt, u_at, v_at, acc_max, slope_max, omega, damping, sd, sv,
                              sa, displacement_only, candidates):
    """One oscillator's sampled peaks (sd, sv, sa) raised to its extrema between the samples
    (the second pass of :func:`spectrum_peaks`; ``candidates`` is scratch, one per step)."""
    xi_omega = damping * omega
    two_xi_omega = 2.0 * xi_omega
    omega2 = omega * omega
    omega_d = omega * math.sqrt(1.0 - damping * damping)
    # bounds on |u''|, …, |u⁽⁵⁾| at every sample by Eq. 3.2 (peaks_between_samples._derivatives)
    d2 = two_xi_omega * sv + omega2 * sd + acc_max
    d3 = two_xi_omega * d2 + omega2 * sv + slope_max
    d4 = two_xi_omega * d3 + omega2 * d2
    d5 = two_xi_omega * d4 + omega2 * d3
    reach = dt * dt / 8.0
    margin_d = (d2 + (d3 + xi_omega * d2) / omega_d) * reach
    margin_v = (d3 + (d4 + xi_omega * d3) / omega_d) * reach
    margin_a = (d4 + (d5 + xi_omega * d4) / omega_d) * reach
    n_segments = int(omega_d * dt / 3.0) + 1
    inv_omega_d = 1.0 / omega_d
    # the record's bounds against the sampled peaks at every step first, in loops without a
    # branch (compiled to vector instructions); the peaks only grow in the search below, so
    # a step these bounds stop would be stopped there too
    if displacement_only:
        for k in range(acc.size - 1):
            candidates[k] = _displacement_through(u_at, k, margin_d, sd)
    else:
        for k in range(acc.size - 1):
            candidates[k] = (_displacement_through(u_at, k, margin_d, sd)
                             | _motion_through(u_at, v_at, k, two_xi_omega, omega2, margin_v,
                                               margin_a, sv, sa))
    for k in range(acc.size - 1):
        if (candidates[k]
                and (_displacement_through(u_at, k, margin_d, sd)
                     or not displacement_only
                     and _motion_through(u_at, v_at, k, two_xi_omega, omega2, margin_v,
                                         margin_a, sv, sa))
                and step_may_peak(u_at[k], v_at[k], u_at[k + 1], v_at[k + 1], acc[k],
                                  (acc[k + 1] - acc[k]) / dt, n_segments, xi_omega, omega2,
                                  dt, inv_omega_d, sd, sv, sa, displacement_only)):
            sd, sv, sa = step_peaks(u_at[k], v_at[k], u_at[k + 1], v_at[k + 1], acc[k],
                                    (acc[k + 1] - acc[k]) / dt, n_segments, xi_omega, omega_d,
                                    omega2, dt, sd, sv, sa, displacement_only)
    return sd, sv, sa


@kernel()
def spectrum_peaks(acc, dt, coeffs, omega, damping, between_samples, displacement_only, out):
    """out[i] = (max|u|, max|u'|, max|u'' + üg|) of oscillator i (see
    :func:`~audit.physics.response_spectra.response_spectra`); with ``displacement_only`` the
    last two are NaN and only max|u| is searched between samples.

    Two passes per oscillator. The first runs the recurrence, keeps the states at the samples
    and their peaks (:func:`~audit.physics.oscillator.sampled_responses`, four oscillators at
    a time). The second looks inside a step only where an extremum there could beat those
    peaks. Inside a step each f of u, u', ü + üg has f'' = e^{−ξωτ}(P cos ω_dτ + Q sin ω_dτ)
    (``peaks_between_samples._closed_form``), so |f''| ≤ |P| + |Q| over the whole step, and
    an interior extremum exceeds max(|f|) at the step's ends by at most (|P| + |Q|)·dt²/8
    (``peaks_between_samples._may_peak_inside``). By Eq. 3.2, |P| and |Q| at every sample are
    bounded by the sampled peaks, max|üg| and max|üg'|: almost every step fails the test, and
    the few that pass get the exact search of
    :func:`~audit.physics.peaks_between_samples.step_peaks`.
    """
    n = acc.size
    last = coeffs.shape[0] - 1
    u_at = np.empty((LANES, n))
    v_at = np.empty((LANES, n))
    peaks = np.empty((LANES, 3))
    candidates = np.empty(n, dtype=np.bool_)
    two_xi_omega = 2.0 * (damping * omega)
    omega2 = omega * omega
    acc_max = 0.0
    slope_max = 0.0
    for k in range(n):
        acc_max = max(acc_max, abs(acc[k]))
        if k:
            slope_max = max(slope_max, abs(acc[k] - acc[k - 1]) / dt)
    for first in range(0, last + 1, LANES):
        if first == last:
            peaks[0] = sampled_response(acc, step_coefficients(coeffs[first]),
                                        two_xi_omega[first], omega2[first], u_at[0], v_at[0])
        else:  # the last lanes of a table not a multiple of four repeat its last oscillator
            lanes = (first, min(first + 1, last), min(first + 2, last), min(first + 3, last))
            sampled_responses(acc, coeffs, two_xi_omega, omega2, lanes, u_at, v_at, peaks)
        for lane in range(min(LANES, last + 1 - first)):
            i = first + lane
            sd, sv, sa = peaks[lane, 0], peaks[lane, 1], peaks[lane, 2]
            if between_samples:
                sd, sv, sa = _searched_between_samples(
                    acc, dt, u_at[lane], v_at[lane], acc_max, slope_max, omega[i], damping[i],
                    sd, sv, sa, displacement_only, candidates)
            out[i, 0] = sd
            out[i, 1] = math.nan if displacement_only else sv
            out[i, 2] = math.nan if displacement_only else sa


@kernel()
def fill_displacement(acc, dt, coeffs, omega, damping, sd, known, j):
    """sd[j] = max|u| of oscillator j (:func:`spectrum_peaks` with ``displacement_only``, on
    that oscillator alone: the same number as among all of them), unless ``known[j]``."""
    if not known[j]:
        out = np.empty((1, 3))
        spectrum_peaks(acc, dt, coeffs[j:j + 1], omega[j:j + 1], damping[j:j + 1], True, True,
                       out)
        sd[j] = out[0, 0]
        known[j] = True


__all__ = ["fill_displacement", "spectrum_peaks"]
