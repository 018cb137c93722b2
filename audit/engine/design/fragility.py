"""Multiple-stripe overturning fragility of a block: the records of a suite scaled to a set of
intensity levels (stripes; by default the fixed lattice, :mod:`audit.engine.shared.lattice`), the exact response at every record × stripe, and a lognormal
fragility fitted to the stripe counts by maximum likelihood on the binomial likelihood (the
standard method for multiple-stripe analysis, Baker 2015, Earthquake Spectra 31(1) 579–599).

Overturning is not monotonic in intensity: a block that overturns at one scale factor may
survive a larger one (islands). The fraction that overturns at a level, over a suite, is a
number to build on; "the smallest factor that overturns the block" is not, since it depends on
the spacing of the stripes. :func:`overturning_pattern` says both per record. The fit is in
:mod:`audit.engine.design.lognormal_fit`, its bootstrap band in :mod:`audit.engine.design.bootstrap`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from audit.physics.rocking import RockingOptions, rocking_spectrum


@dataclass(frozen=True)
class OverturningPattern:
    """Per record, where along ascending stripes the block first overturns, and whether it
    survives again above (an island of survival). Both depend on the stripe spacing.

    Attributes
    ----------
    first_stripe : numpy.ndarray of int
        Index of the first stripe that overturns the block; −1 where none does.
    islands : numpy.ndarray of bool
        The block survives at some stripe above its first overturning one.
    """

    first_stripe: np.ndarray
    islands: np.ndarray


def overturning_pattern(overturned) -> OverturningPattern:
    """The pattern of each row of ``overturned`` (records × ascending stripes, bool).

    Parameters
    ----------
    overturned : array_like of bool
        Exact outcomes, shaped (record, stripe), stripes ascending.
    """
    overturned = np.asarray(overturned, dtype=bool)
    any_over = overturned.any(axis=1)
    first = np.where(any_over, np.argmax(overturned, axis=1), -1)
    after = np.arange(overturned.shape[1])[None, :] > first[:, None]
    islands = any_over & np.any(after & ~overturned, axis=1)
    return OverturningPattern(first, islands)


def stripe_outcomes(motion, factors, size_s, alpha_rad, g: float, free_motion_s: float,
                    jobs: int = 1, r=None) -> tuple[np.ndarray, np.ndarray]:
    """Exact overturning and peak rotation of blocks under ``motion`` scaled by each factor.

    Parameters
    ----------
    motion : records.GroundMotion
    factors : array
        Scale factors of the stripes [-], ascending.
    size_s : array
        Block sizes 2π/p [s].
    alpha_rad : array
        Slendernesses [rad].
    g, free_motion_s, jobs :
        Gravity [m/s²], free motion after the record [s], solver threads.
    r : float or audit.physics.block.Restitution, optional
        The impact model; Eq. 4.8 when not given.

    Returns
    -------
    overturned, theta_peak_rad : numpy.ndarray
        Shaped (stripe, α, size).
    """
    spectra = [rocking_spectrum(motion.scaled(float(f)), size_s, alpha_rad, r=r,
                                options=RockingOptions(g, free_motion_s), jobs=jobs,
                                reactions=False)
               for f in factors]
    return (np.stack([s.overturned for s in spectra]),
            np.stack([s.theta_peak for s in spectra]))


__all__ = ["overturning_pattern", "OverturningPattern", "stripe_outcomes"]
