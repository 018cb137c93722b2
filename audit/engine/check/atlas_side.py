"""The exact side of a check read from an atlas (:mod:`audit.engine.atlas`) instead of solved.

For an object inside the atlas's grid, each record's outcome at each stripe of the check is
the atlas's, interpolated bilinearly in (α, ln 2π/p) (:meth:`Atlas.outcomes
<audit.engine.atlas.answers.Atlas.outcomes>`), and at the site's own stripe linearly in ln IM
between the lattice's stripes around it (:meth:`Atlas.site_outcomes
<audit.engine.atlas.answers.Atlas.site_outcomes>`): per-record probabilities, whole at a node.
On them the check's own rules run unchanged (the fragility on the lattice's stripes, its
bootstrap, the count at the site and the headline, the risk), and the exact width search
(:func:`~audit.engine.check.widths.required_width`) measures each width it tries on the atlas's
outcomes there. At a node of the grid the outcomes are the direct solve's, bit for bit.

Each answer carries the atlas's error at that point: P's from :meth:`Atlas.local_error
<audit.engine.atlas.answers.Atlas.local_error>`; a width's is P's error at that width divided
through P(w): the widths where P is the target ± that error, as a fraction of the width.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from audit.engine.atlas.answers import size_of
from audit.engine.check.widths import required_width

#: Blocks whose outcomes are interpolated at a time in the width search (each holds records ×
#: stripes of floats: an inventory's scan would hold hundreds of MB at once).
CHUNK_BLOCKS = 2000


@dataclass(frozen=True)
class CheckAtlases:
    """The atlases a check reads, each (atlas, key) or None where it solves.

    Attributes
    ----------
    own : (audit.engine.atlas.answers.Atlas, str) or None
        Of the check's intensity measure: its exact side.
    other : (audit.engine.atlas.answers.Atlas, str) or None
        Of the other standard intensity measure (:mod:`audit.engine.check.other_im`).
    """

    own: tuple | None = None
    other: tuple | None = None


@dataclass(frozen=True)
class AtlasSide:
    """The atlas a check reads its exact side from, and which of its objects it covers.

    Attributes
    ----------
    atlas : audit.engine.atlas.answers.Atlas
    key : str
        The atlas's key (its folder in the cache).
    covered : numpy.ndarray of bool
        Per object, whether it lies inside the atlas's grid (the others are solved directly).
    levels : numpy.ndarray
        The check's stripes (the lattice's and the site's) [unit of the IM].
    fitted : numpy.ndarray of bool
        Which of them are the lattice's (the atlas's stripes).
    site_im : float
        The site's intensity [unit of the IM].
    g : float
        Gravity [m/s²] (the atlas's).
    """

    atlas: object
    key: str
    covered: np.ndarray
    levels: np.ndarray
    fitted: np.ndarray
    site_im: float
    g: float

    @classmethod
    def of(cls, atlas, key: str, objects, levels, fitted, site_im: float, g: float):
        """The side of ``atlas`` for a check of ``objects`` on its stripes ``levels``.

        Parameters
        ----------
        atlas : audit.engine.atlas.answers.Atlas
        key : str
        objects : sequence of audit.engine.shared.blocks.Block
        levels : numpy.ndarray
            The check's stripes [unit of the IM].
        fitted : numpy.ndarray of bool
            Which of them are the lattice's.
        site_im : float
            The site's intensity [unit of the IM].
        g : float
            Gravity [m/s²].
        """
        if not np.allclose(levels[fitted], atlas.levels, rtol=1e-12):
            raise ValueError("the atlas's stripes are not the check's lattice")
        covered = atlas.covers([o.alpha_deg for o in objects], [o.size_s for o in objects])
        return cls(atlas, key, np.asarray(covered, dtype=bool), np.asarray(levels),
                   np.asarray(fitted), float(site_im), float(g))

    def outcomes(self, alpha_deg, size_s) -> np.ndarray:
        """Each record's outcome at every stripe of the check (the site's included), shaped
        (record, stripe, object) as the direct solve's [-].

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            Objects inside the grid [degrees], [s].
        """
        alpha_deg, size_s = np.asarray(alpha_deg, dtype=float), np.asarray(size_s, dtype=float)
        out = np.empty((self.atlas.records, self.levels.size, alpha_deg.size))
        for start in range(0, alpha_deg.size, CHUNK_BLOCKS):  # memory: an inventory's objects
            chunk = slice(start, start + CHUNK_BLOCKS)
            # (object, record, lattice stripe)
            lattice = self.atlas.outcomes(alpha_deg[chunk], size_s[chunk])
            out[:, self.fitted, chunk] = np.moveaxis(lattice, 0, 2)
            if not self.fitted.all():  # the site's stripe, between the lattice's
                out[:, ~self.fitted, chunk] = self.atlas.site_outcomes(
                    lattice, self.site_im).T[:, None, :]
        return out

    def p_error(self, alpha_deg, size_s) -> np.ndarray:
        """The atlas's error of P at the site at each object (absolute) [-].

        Parameters
        ----------
        alpha_deg, size_s : array_like of float
            Objects inside the grid [degrees], [s].
        """
        return self.atlas.local_error(alpha_deg, size_s, self.site_im)

    def _inside(self, widths_m, heights_m):
        """(α, 2π/p) of blocks clipped to the grid, and whether each lay inside it."""
        alpha_deg, size_s = size_of(widths_m, heights_m, self.g)
        a, s = self.atlas.alpha_deg, self.atlas.size_s
        inside = self.atlas.covers(alpha_deg, size_s)
        return (np.clip(alpha_deg, a[0], a[-1]), np.clip(size_s, s[0], s[-1])), inside

    def required_widths(self, heights_m, targets, measure) -> np.ndarray:
        """The check's exact width search on the atlas: ``measure(overturned, levels)`` (the
        check's own, of outcomes (record, lattice stripe, block)) at each width tried; widths
        [m] shaped (height, target), NaN where a width's block lies beyond the grid (measured
        at the grid's edge while searched, refused after).

        Parameters
        ----------
        heights_m : array_like of float
            Full heights [m].
        targets : sequence of float
            The limits of the measure.
        measure : callable
            ``measure(overturned, levels)`` → the measure per block.
        """
        def measured(heights, widths):
            (alpha_deg, size_s), _ = self._inside(widths, heights)
            parts = []
            for start in range(0, alpha_deg.size, CHUNK_BLOCKS):  # memory: an inventory's scan
                chunk = slice(start, start + CHUNK_BLOCKS)
                lattice = np.moveaxis(self.atlas.outcomes(alpha_deg[chunk], size_s[chunk]), 0, 2)
                parts.append(np.asarray(measure(lattice, self.atlas.levels)))
            return np.concatenate(parts)

        heights = np.asarray(heights_m, dtype=float)
        widths = required_width(measured, heights, list(targets))
        finite = np.isfinite(widths)
        _, inside = self._inside(np.where(finite, widths, 1.0),
                                 np.broadcast_to(heights[:, None], widths.shape))
        return np.where(finite & inside, widths, np.nan)

    def width_errors(self, heights_m, widths_m, targets) -> np.ndarray:
        """Each width's error from the atlas, as a fraction of the width [-]: P's error e at
        the width (:meth:`p_error`) carried through P(w), the widths where the atlas's P is
        the target ± e (the same search), the farther of the two from the width; NaN where the
        width is not finite, inf where P − e or P + e reaches no width up to the widest.

        Parameters
        ----------
        heights_m : array_like of float
            Full heights [m], ascending and distinct.
        widths_m : numpy.ndarray
            The widths found at them for each target, shaped (height, target) [m].
        targets : sequence of float
            P(overturn) at the site [-].
        """
        heights = np.asarray(heights_m, dtype=float)
        widths = np.asarray(widths_m, dtype=float)
        error = np.zeros(widths.shape)
        for t in range(len(targets)):
            ok = np.isfinite(widths[:, t])
            if ok.any():
                (alpha_deg, size_s), _ = self._inside(widths[ok, t], heights[ok])
                error[ok, t] = self.p_error(alpha_deg, size_s)
        row = {float(h): k for k, h in enumerate(heights)}

        def shifted(sign):  # the search for P = target + sign·e at each height
            def measure(h, w):
                (alpha_deg, size_s), _ = self._inside(w, h)
                p = self.atlas.probability_at_site(alpha_deg, size_s, self.site_im)
                e = error[[row[float(v)] for v in h]]
                return p[:, None] - sign * e
            return required_width(measure, heights, list(targets))

        far = np.zeros(widths.shape)
        for sign in (1.0, -1.0):
            other = shifted(sign)
            far = np.maximum(far, np.where(np.isfinite(other), np.abs(other - widths), np.inf))
        return np.where(np.isfinite(widths), far / widths, np.nan)

    def source(self, p_error: float, width_errors, rotations: bool = True,
               other_im: str = "direct") -> dict:
        """``exact.atlas`` of an object's entry in ``check.json``.

        Parameters
        ----------
        p_error : float
            P's error at the object [-].
        width_errors : sequence of float
            The relative errors of its exact widths for P ≤ 10 % and ≤ 50 % [-].
        rotations : bool
            Whether the object's exact response was solved at the stripes besides (for a
            guideline's limit short of overturning); if not, its limits' P(exceed) are
            P(overturn) and the records overturning at the site are not given.
        other_im : {"direct", "atlas"}
            Whether P at the other standard IM was solved or read from its own atlas.
        """
        def number(value):  # JSON: null where not finite (no width reaches P ± error)
            return float(value) if value is not None and math.isfinite(value) else None

        return {"key": self.key, "p_error": number(p_error),
                "required_width_m_10pct_error": number(width_errors[0]),
                "required_width_m_50pct_error": number(width_errors[1]),
                "text": f"from the atlas, ±{100 * p_error:.1f} %",
                "method": "each record's outcome interpolated bilinearly in (α, ln 2π/p) "
                          "between the atlas's nodes (at the site's stripe, linearly in "
                          "ln IM between the lattice's), then check's rules; the errors are "
                          "the atlas's at this point (docs/atlas.md)",
                "direct": self._solved(rotations, other_im)}

    @staticmethod
    def _solved(rotations: bool, other_im: str) -> str:
        """What a check from this atlas solved directly, in words."""
        solved = ["the guidelines"]
        if rotations:
            solved += ["the limits' P(exceed) other than overturning",
                       "the records overturning at the site"]
        solved += ["the friction"] + (["the other IM"] if other_im == "direct" else [])
        words = (", ".join(solved) + " and the guidelines' P in 50 years: solved directly"
                 + ("; the other IM read from its own atlas" if other_im == "atlas" else ""))
        if rotations:
            return words
        return (words + "; no chosen guideline has a limit short of overturning, so the object "
                "is not solved record by record and the records overturning at the site are "
                "not given")


__all__ = ["AtlasSide", "CheckAtlases", "CHUNK_BLOCKS"]
