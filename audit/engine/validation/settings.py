"""The settings of a campaign's validation (``audit validate``): its grid of equivalent blocks,
the band of the table motions, the folds and the lapse rate, checked once."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from audit.engine.shared import fields as check
from audit.errors import InputError


@dataclass(frozen=True)
class ValidationSettings:
    """How a campaign is validated (checked once).

    Attributes
    ----------
    alpha_deg : tuple
        Slenderness nodes of the grid [degrees], increasing (log-spaced by default).
    p_rad_s : tuple
        Frequency parameters of the grid [rad/s].
    restitution_factors : tuple
        Multiples of Eq. 4.8's r on the grid [-].
    highpass_hz, lowpass_hz : float
        Zero-phase 4th-order Butterworth band [Hz] of the motions PGA and PGV are read from
        (velocity needs the drift removed); the low-pass is skipped at or above the Nyquist
        frequency.
    band_pass : bool
        Also solve the blocks under the band-passed motions. Off by default: on the granite
        campaign the band flips as many outcomes at the fitted block as 1–3 % of α does
        (docs/validation.md); the exact response is to the motion as recorded.
    refined_solves : int
        Blocks per test of each fine grid solved around the region the previous grid allows,
        per specimen (:mod:`~audit.engine.validation.refine`); 0 fits on the coarse grid only.
    folds : int
        Cross-validation folds (tests of one ground motion always share a fold).
    lapse : float
        Probabilities are kept in [lapse, 1 − lapse] (mis-recorded outcomes), so one outcome
        cannot make a likelihood −∞ [-].
    free_motion_s : float
        Free rocking simulated after each motion [s].
    jobs : int
        Solver threads.
    """

    alpha_deg: tuple = tuple(np.round(np.geomspace(1.5, 20.0, 22), 4))
    p_rad_s: tuple = tuple(np.round(np.geomspace(3.0, 8.0, 7), 4))
    restitution_factors: tuple = (0.3, 0.45, 0.6, 0.8, 1.0)
    highpass_hz: float = 0.1
    lowpass_hz: float = 25.0
    band_pass: bool = False
    refined_solves: int = 800
    folds: int = 5
    lapse: float = 0.005
    free_motion_s: float = 10.0
    jobs: int = 1

    def __post_init__(self):
        # each field checked once, naming it; a frozen dataclass keeps the checked values
        alpha = check.numbers("alpha_deg", self.alpha_deg, "slendernesses in (0, 45) degrees",
                              0, 45, low_open=True, high_open=True)
        if len(alpha) < 2 or any(b <= a for a, b in zip(alpha, alpha[1:])):
            raise InputError("alpha_deg: needs ≥ 2 increasing slendernesses in (0, 45) degrees",
                             "alpha_deg")
        check.numbers("p_rad_s", self.p_rad_s, "positive frequency parameters in rad/s", 0,
                      low_open=True)
        check.numbers("restitution_factors", self.restitution_factors,
                      "multiples of Eq. 4.8's r in (0, 1]", 0, 1, low_open=True)
        high = check.number("highpass_hz", self.highpass_hz, "a positive frequency in Hz", 0,
                            low_open=True)
        low = check.number("lowpass_hz", self.lowpass_hz, "a positive frequency in Hz", 0,
                           low_open=True)
        if not high < low:
            raise InputError("highpass_hz: must be positive and below lowpass_hz",
                             "highpass_hz", "lowpass_hz")
        if not isinstance(self.band_pass, bool):
            raise InputError(f"band_pass: expected True or False, got {self.band_pass!r}",
                             "band_pass")
        object.__setattr__(self, "refined_solves",
                           check.whole("refined_solves", self.refined_solves, 0))
        object.__setattr__(self, "folds", check.whole("folds", self.folds, 2))
        check.number("lapse", self.lapse, "a probability in (0, 0.5)", 0, 0.5, low_open=True,
                     high_open=True)
        check.number("free_motion_s", self.free_motion_s, "a duration ≥ 0 s", 0)
        object.__setattr__(self, "jobs", check.whole("jobs", self.jobs, 1))

    @property
    def solves_per_test(self) -> int:
        return len(self.alpha_deg) * len(self.p_rad_s) * len(self.restitution_factors)


__all__ = ["ValidationSettings"]
