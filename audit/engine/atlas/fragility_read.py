"""Fragilities read from an atlas (``margins --method atlas``, ``fragility --method atlas``): the
blocks' per-record outcomes at the atlas's stripes in place of their direct solve, and the
atlas's stated error along each block's curve.

What the atlas can answer, and what it cannot:

* the exact multiple-stripe fragility of a block, *at the atlas's stripes*: the 14 levels of
  the lattice with k even (√2 apart, :data:`audit.engine.check.pipeline.LATTICE_EVERY`), not
  the 27 levels of ``margins``' default nor ``fragility``'s 19 PGV levels (0.05–3.2 m/s,
  2^(1/3) apart). The fit on those 14 is what is answered, and said so; stripes other than the
  atlas's, asked for explicitly, are refused (:func:`atlas_for`). At a grid node the outcomes
  are the stored ones, so the fit equals the direct fit on the same 14 stripes;
* not a record's peak rotation (the atlas keeps θ/α only at its nodes), nor where along the
  stripes a record first overturns or survives again (islands: read from whole outcomes, which
  between nodes the atlas interpolates to a fraction);
* not the required slenderness of ``margins``: its exact share is of the records at their own
  (site-scaled) intensity, which lies between the atlas's stripes (√2 apart), so it stays
  direct; nor the FEMA P695 acceptance (its impact model × 0.9 and × 0.8 is another atlas).
"""

from __future__ import annotations

import numpy as np

from audit.engine.atlas.answers import Atlas
from audit.errors import InputError, NoAtlas

#: The values of ``method``: None is the atlas where one answers, else the direct solve.
METHODS = ("atlas", "direct")
class AtlasReading:
    """An atlas as a fragility reads it: its stripes, the blocks' outcomes there and the
    atlas's error along their curves, with its key for the outputs to name.

    Parameters
    ----------
    atlas : Atlas
    key : str
        Its key (its folder's name in the cache).
    """

    def __init__(self, atlas: Atlas, key: str):
        self.atlas, self.key = atlas, key
        self.levels = np.asarray(atlas.levels, dtype=float)

    def outcomes(self, alpha_deg, size_s, levels=None) -> np.ndarray:
        """Each record's outcome at the atlas's stripes (or those of them in ``levels``), per
        block, interpolated bilinearly in (α, ln 2π/p) (:meth:`Atlas.outcomes`): shaped
        (record, stripe, block) [-], the stored 0 or 1 at a node.

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The blocks [degrees], [s].
        levels : sequence of float, optional
            Some of the atlas's stripes [unit of its IM]; default all.
        """
        outcomes = np.moveaxis(self.atlas.outcomes(alpha_deg, size_s), 0, 2)
        if levels is None:
            return outcomes
        return outcomes[:, _among(self.levels, levels), :]

    def errors(self, alpha_deg, size_s) -> np.ndarray:
        """Per block, the atlas's stated error of P (:meth:`Atlas.local_error`, whose adequacy
        docs/atlas.md measures against direct solves) at each of its stripes, the largest along
        the curve [-]. At a node the outcomes are the stored ones, but the stated error keeps
        its term of the grid's curvature there.

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            The blocks [degrees], [s].
        """
        return np.max([self.atlas.local_error(alpha_deg, size_s, float(level))
                       for level in self.levels], axis=0)

    def words(self, errors) -> str:
        """One sentence for a page: the source and its error over the blocks read.

        Parameters
        ----------
        errors : array_like of float
            The blocks' :meth:`errors` [-].
        """
        errors = np.asarray(errors, dtype=float)
        return (f"The exact fragilities are from the atlas {self.key[:12]} (its "
                f"{self.levels.size} stripes, {self.levels[0]:.4g}–{self.levels[-1]:.4g}), "
                f"±{100 * np.max(errors):.1f} % in P"
                + (f" at most over the blocks (median ±{100 * np.median(errors):.1f} %)"
                   if errors.size > 1 else "") + ".")


def checked_method(method):
    """``method`` itself, checked: None, ``atlas`` or ``direct`` (InputError naming it).

    Parameters
    ----------
    method : str or None
    """
    if method is not None and method not in METHODS:
        raise InputError(f"method: expected {' or '.join(METHODS)}, got {method!r}", "method")
    return method


def atlas_for(method, atlas: Atlas | None, key: str, alpha_deg, size_s, build: dict,
              stripes=None) -> AtlasReading | None:
    """The atlas the answer reads (None: the direct solve) by ``method``: ``direct`` never,
    ``atlas`` always (:class:`~audit.errors.NoAtlas` naming ``method`` where it cannot
    answer), None where it can answer every block.

    It cannot where there is none for these records, intensity measure, floor, restitution,
    g and free motion, where a block lies outside its grid, or where ``stripes`` are asked that
    are not all the atlas's.

    Parameters
    ----------
    method : {None, "atlas", "direct"}
    atlas : Atlas or None
        The atlas of these records and settings, if built.
    key : str
        Its key.
    alpha_deg, size_s : array_like of float
        The blocks [degrees], [s].
    build : dict
        What builds the atlas asked for (:class:`~audit.errors.NoAtlas`).
    stripes : sequence of float, optional
        Stripes asked for explicitly.
    """
    if checked_method(method) == "direct":
        return None
    reason = None
    if atlas is None:
        reason = ("no atlas of these records, intensity measure, floor, restitution, g and "
                  "free motion")
    elif not np.all(inside := atlas.covers(alpha_deg, size_s)):
        outside = int(np.sum(~inside))
        reason = (f"{outside} block(s) outside the atlas's grid (α {atlas.alpha_deg[0]:g}–"
                  f"{atlas.alpha_deg[-1]:g}°, 2π/p {atlas.size_s[0]:g}–{atlas.size_s[-1]:g} s)")
    elif stripes is not None and not np.all(_among(stripes, atlas.levels)):
        reason = ("stripes other than the atlas's (the lattice's 14 levels "
                  f"{atlas.levels[0]:.4g}–{atlas.levels[-1]:.4g}, √2 apart)")
    if reason is None:
        return AtlasReading(atlas, key)
    if method == "atlas":
        raise NoAtlas(reason, build if atlas is None else None)
    return None


def _among(levels, others) -> np.ndarray:
    """Whether each of ``levels`` is one of ``others`` (to a relative 1e-9: lattice levels
    typed by hand or read back from a file)."""
    levels, others = np.asarray(levels, dtype=float), np.asarray(others, dtype=float)
    return np.any(np.abs(levels[:, None] / others[None, :] - 1.0) < 1e-9, axis=1)


__all__ = ["METHODS", "AtlasReading", "atlas_for", "checked_method"]
