"""The exact P(overturn) at the site at the other standard intensity measure: S_a(1 s) beside
PGA, PGA beside any S_a(T).

P(overturn | site) depends on the IM the records are scaled on: scaled to one S_a(1 s) the
records spread in PGA, and the reverse, so the same site gives a different P (three-fold for
a slender block). The IM to use is that of the user's hazard (the hazard curve or the design
value the site's intensity comes from); the other is shown so the difference is seen, not
hidden. The records are scaled to the other IM's stripes (the same lattice with a stripe at the
design spectrum's value at it) and solved exactly, the fragility fitted on the lattice and P at
the site chosen between it and the count at the site's stripe, as for the chosen IM
(:mod:`audit.engine.design.site_probability`). With an atlas of the records at the other IM,
the objects inside its grid are read from it instead, with its error there.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from audit.engine.check.atlas_side import AtlasSide
from audit.engine.check.widths import Family
from audit.engine.shared.intensity import IntensityMeasure
from audit.engine.design.site_probability import lattice_fragility, site_probability

#: The other standard IM of each kind.
PGA_IM = IntensityMeasure("pga")
SA1_IM = IntensityMeasure("sa", 1.0)


def other_im(im: IntensityMeasure) -> IntensityMeasure:
    """PGA beside an S_a(T); S_a(1 s) beside PGA.

    Parameters
    ----------
    im : IntensityMeasure
        The check's intensity measure.
    """
    return SA1_IM if im.kind == "pga" else PGA_IM


def other_im_answers(family: Family, objects, design_site: dict, levels_of, fitted_of,
                     seed: int | None = None, atlas=None) -> list[dict]:
    """Per object, ``{im, site_im, p_overturn_at_site, median, beta, p_at_site, source,
    p_error}`` at the other IM (``p_at_site``:
    :meth:`~audit.engine.design.site_probability.SiteProbability.as_dict`; ``source``
    ``atlas`` or ``direct``, ``p_error`` the atlas's error of P there, None where solved).

    Parameters
    ----------
    family : audit.engine.check.widths.Family
        The check's records, ready to solve at any stripes.
    objects : sequence of audit.engine.check.objects.CheckObject
    design_site : dict
        S_XS, S_X1 [g]: the site's intensity at the other IM.
    levels_of : callable
        ``levels_of(site_im)`` → a check's stripes with a site's intensity.
    fitted_of : callable
        ``fitted_of(levels)`` → which of them the fragility is fitted on.
    seed : int, optional
        The bootstrap's seed (its default when None).
    atlas : (audit.engine.atlas.answers.Atlas, str), optional
        An atlas of the records at the other IM (on the check's floor, restitution, g and free
        motion) and its key: the objects inside its grid read from it as the check's own IM
        is (:mod:`audit.engine.check.atlas_side`), the others solved.
    """
    settings = family.settings
    im = other_im(settings.im)
    site_im = im.of_design_site(design_site)
    levels = levels_of(site_im)
    fitted, site = fitted_of(levels), int(np.argmin(np.abs(levels - site_im)))
    side = (AtlasSide.of(atlas[0], atlas[1], objects, levels, fitted, site_im, settings.g)
            if atlas is not None else None)
    read = np.flatnonzero(side.covered) if side is not None else np.array([], dtype=int)
    solve = np.setdiff1d(np.arange(len(objects)), read)
    overturned = np.empty((len(family.entries), levels.size, len(objects)))
    errors = np.full(len(objects), np.nan)
    if solve.size:
        intensity = {e.id: im.of_record(e.motion, settings.free_motion_s)
                     for e in family.entries}
        theirs = replace(family, levels=levels, intensity=intensity)
        overturned[:, :, solve] = theirs.overturned([objects[b].height_m for b in solve],
                                                    [objects[b].width_m for b in solve])
    if read.size:
        alpha_deg = [objects[b].alpha_deg for b in read]
        size_s = [objects[b].size_s for b in read]
        overturned[:, :, read] = side.outcomes(alpha_deg, size_s)
        errors[read] = side.p_error(alpha_deg, size_s)
    out = []
    for b in range(len(objects)):
        mine = overturned[:, :, b]
        fit, boot = lattice_fragility(levels[fitted], mine[:, fitted], seed)
        at_site = site_probability(
            float(fit.probability(site_im)) if fit else None,
            [float(v) for v in boot.probability_band(site_im)] if fit else None,
            int(np.rint(mine[:, site].sum())), mine.shape[0])
        from_atlas = bool(np.isfinite(errors[b]))
        out.append({"im": im.name, "im_unit": im.unit, "site_im": site_im,
                    "p_overturn_at_site": at_site.p, "median": fit.median if fit else None,
                    "beta": fit.beta if fit else None, "p_at_site": at_site.as_dict(),
                    "source": "atlas" if from_atlas else "direct",
                    "p_error": float(errors[b]) if from_atlas else None})
    return out


__all__ = ["other_im", "other_im_answers"]
