"""Equivalent-damping laws and the Housner rocking "period" (Section 7 and Eq. 8.1 of Makris & Konstantinidis 2001)."""

from __future__ import annotations

import numpy as np


def housner_peak_ratio(theta0_ratio, n_impacts, r):
    """Peak rotation θn/α after n impacts of linearised free rocking (Eq. 7.5, Housner 1963).

    θn/α = 1 − sqrt(1 − rⁿ [1 − (1 − θ₀/α)²])

    Parameters
    ----------
    theta0_ratio : float or array
        Initial rotation θ₀/α [-], released at rest.
    n_impacts : int or array
        Number of impacts n.
    r : float or array
        Coefficient of restitution [-].
    """
    x0 = np.asarray(theta0_ratio, dtype=float)
    return 1.0 - np.sqrt(1.0 - np.power(r, n_impacts) * (1.0 - (1.0 - x0) ** 2))


def damping_free_rocking(theta0_ratio, n_impacts, r):
    """Damping ratio that forces the free-rocking decay into a log decrement (Eq. 7.8–7.9).

    β = (1/(nπ)) · ln[(θ₀/α) / (θn/α)], with θn/α from Eq. 7.5.

    Parameters
    ----------
    theta0_ratio : float or array
        θ₀/α [-].
    n_impacts : int or array
        n, the number of impacts (half-cycles) the decay is measured over.
    r : float or array
        Coefficient of restitution [-].

    Returns
    -------
    float or array
        β [-] (fraction of critical).
    """
    return np.log(np.asarray(theta0_ratio, dtype=float)
                  / housner_peak_ratio(theta0_ratio, n_impacts, r)) / (np.asarray(n_impacts) * np.pi)


def damping_priestley(r):
    """Equivalent damping of Priestley, Evison & Carr (1978), β = −0.34 ln r (Eq. 7.10) [-]."""
    return -0.34 * np.log(r)


def damping_fema356(r):
    """Equivalent damping of FEMA 356 for rocking, β = 0.4 (1 − sqrt r) (Eq. 9.1) [-]."""
    return 0.4 * (1.0 - np.sqrt(r))


def housner_period(theta_ratio, p):
    """Amplitude-dependent rocking period T = (4/p) acosh(1 / (1 − θ/α)) (Eq. 8.1) [s].

    Parameters
    ----------
    theta_ratio : float or array
        Rotation amplitude θ/α [-], 0 ≤ θ/α < 1 (infinite at θ/α = 1).
    p : float or array
        Frequency parameter [rad/s].
    """
    x = np.asarray(theta_ratio, dtype=float)
    with np.errstate(divide="ignore"):
        return 4.0 / np.asarray(p, dtype=float) * np.arccosh(1.0 / (1.0 - x))


def housner_rotation_ratio(period_s, p):
    """Inverse of Eq. 8.1: θ/α = 1 − 1/cosh(pT/4) for a rocking period T [s] [-]."""
    return 1.0 - 1.0 / np.cosh(np.asarray(p, dtype=float) * np.asarray(period_s, dtype=float) / 4.0)
