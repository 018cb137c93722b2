"""The site's intensity of a check: for the guidelines, the design spectrum (``--site``) at the
intensity measure; for the exact answer, the same, or the site's hazard curve at a return period
(``--return-period`` or ``--poe`` with ``--hazard``).

The guidelines are written for a design spectrum, so they keep reading ``--site`` whatever the
hazard says; the exact answer is a probability at one intensity, which the hazard curve gives at
the hazard level the engineer names ("2 % in 50 years"). When the two intensities disagree by
more than :data:`DISAGREEMENT` the check says so (a warning, and ``site_hazard.warning`` in
``check.json``): the guidelines' verdicts and the exact probability are then at different
levels.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from audit.engine.design.risk import YEARS
from audit.errors import InputError, InputWarning

#: Relative difference between the hazard curve's and the design spectrum's intensity above
#: which a check warns.
DISAGREEMENT = 0.10


@dataclass(frozen=True)
class SiteIntensity:
    """Where a check's records are scaled.

    Attributes
    ----------
    site_im : float
        The exact answer's intensity [unit of the intensity measure]: the centre of the
        stripes, where P(overturn) is read.
    design_im : float
        The design spectrum's intensity, where the guidelines judge the object.
    return_period_years : float or None
        The return period ``site_im`` is read at on the hazard curve; None when it is the
        design spectrum's.
    warning : str or None
        The disagreement between the two, when above :data:`DISAGREEMENT`.
    """

    site_im: float
    design_im: float
    return_period_years: float | None = None
    warning: str | None = None

    def as_dict(self, curve=None) -> dict:
        """``site_hazard`` of ``check.json`` (None when the site is the design spectrum's).

        Parameters
        ----------
        curve : records.hazard.HazardCurve, optional
            The hazard curve read, for its source.
        """
        if self.return_period_years is None:
            return None
        years = self.return_period_years
        return {"return_period_years": years,
                "poe_50_years": -math.expm1(-YEARS / years),
                "site_im_g": self.site_im, "design_im_g": self.design_im,
                "ratio_to_design": self.site_im / self.design_im,
                "source": curve.source if curve is not None else None,
                "warning": self.warning}


def site_intensity(im, design_site: dict | None, curve=None,
                   return_period_years: float | None = None) -> SiteIntensity:
    """The site's intensities of a check (see the module): ``design_site`` (S_XS, S_X1 [g]) at
    ``im``, and ``curve`` at ``return_period_years`` when both are given; a warning
    (:class:`~audit.errors.InputWarning`) when they disagree by more than
    :data:`DISAGREEMENT`.

    Parameters
    ----------
    im : IntensityMeasure
        The check's intensity measure.
    design_site : dict or None
        FEMA 356 design site, ``sxs_g`` and ``sx1_g`` [g].
    curve : records.hazard.HazardCurve, optional
        The site's hazard curve.
    return_period_years : float, optional
        The site's return period [years].
    """
    design_im = im.of_design_site(design_site)
    if not design_im:
        raise InputError("site: the check needs the site's S_XS,S_X1 [g]", "site")
    if curve is None or return_period_years is None:
        return SiteIntensity(design_im, design_im)
    site_im = curve.im_at_rate(1.0 / return_period_years)
    warning = None
    if abs(site_im / design_im - 1.0) > DISAGREEMENT:
        warning = (f"the hazard curve gives {im.name} = {site_im:.3g} g at "
                   f"{return_period_years:,.0f} years, the design spectrum {design_im:.3g} g "
                   f"({100 * (site_im / design_im - 1):+.0f} %): the exact answer is at the "
                   "curve's, the guidelines' verdicts at the design spectrum's")
        warnings.warn(f"site: {warning}", InputWarning, stacklevel=2)
    return SiteIntensity(site_im, design_im, return_period_years, warning)


__all__ = ["SiteIntensity", "site_intensity", "DISAGREEMENT"]
