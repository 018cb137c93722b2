"""The fixed stripe lattice: the intensities every fragility of the tool is computed at.

A fragility fitted on stripes placed around the site (a multiple of the site's intensity) is a
property of the site as much as of the object: two sites give two fragilities, and P at the
site need not rise with the site's intensity. On one fixed lattice per intensity measure the
fragility is a property of the object, the record set and the floor alone, so it can be reused
(a risk integral, an inventory, an atlas of objects).

The lattice is L_k = 2^(k/4) in the IM's own unit (g for S_a and PGA; the IM's unit for any
other), k = :data:`LATTICE_K` (0.0625–5.66 g): wide enough for the risk integral over a hazard
curve. ``check`` solves every other level (k even, √2 apart) and adds one stripe at the site's
own intensity (:func:`with_site`), which the fragility is not fitted on; ``margins`` solves every
level.
"""

from __future__ import annotations

import numpy as np

#: Levels per doubling of the intensity.
LEVELS_PER_OCTAVE = 4
#: The lattice's exponents k of L_k = 2^(k/4), first and last: 2^-4 = 0.0625 … 2^2.5 ≈ 5.66.
LATTICE_K = (-16, 10)
#: How close (relative) a site's intensity must be to a lattice level to be that level.
ON_LATTICE_TOLERANCE = 1e-9


def stripe_lattice(every: int = 1) -> np.ndarray:
    """The lattice's levels, ascending: 2^(k/4) for k from ``LATTICE_K[0]`` to ``LATTICE_K[1]``,
    every ``every``-th k (``every=2``: the levels √2 apart, k even).

    Parameters
    ----------
    every : int
        Step in k (1: the full 2^(1/4) lattice; 2: every other level).

    Returns
    -------
    numpy.ndarray
        The levels [unit of the intensity measure, e.g. g].
    """
    k = np.arange(LATTICE_K[0], LATTICE_K[1] + 1, every)
    return 2.0 ** (k / LEVELS_PER_OCTAVE)


def on_lattice(levels, every: int = 1) -> np.ndarray:
    """Whether each level is one of :func:`stripe_lattice` (``every``): a mask, so the fit can
    leave out a stripe added at a site.

    Parameters
    ----------
    levels : array_like of float
        Intensities [unit of the intensity measure].
    every : int
        Step in k of the lattice asked about.
    """
    k = LEVELS_PER_OCTAVE * np.log2(np.asarray(levels, dtype=float))
    nearest = np.round(k)
    return ((np.abs(k - nearest) < ON_LATTICE_TOLERANCE * LEVELS_PER_OCTAVE)
            & (nearest % every == 0) & (nearest >= LATTICE_K[0]) & (nearest <= LATTICE_K[1]))


def with_site(site_im: float, every: int = 2) -> np.ndarray:
    """The lattice (``every``) with one stripe added at the site's intensity, ascending; the
    site's level is not added where it is a lattice level already.

    Parameters
    ----------
    site_im : float
        The site's intensity [unit of the intensity measure].
    every : int
        Step in k of the lattice.
    """
    lattice = stripe_lattice(every)
    if on_lattice([site_im], every)[0]:
        return lattice
    return np.sort(np.append(lattice, float(site_im)))


__all__ = ["stripe_lattice", "on_lattice", "with_site", "LATTICE_K", "LEVELS_PER_OCTAVE",
           "ON_LATTICE_TOLERANCE"]
