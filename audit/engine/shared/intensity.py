"""Intensity measures of the design-level audit: PGA, PGV, or a spectral acceleration S_a(T) as
hazard curves, ground-motion models (OpenQuake, USGS, NGA-West2) and design codes define it: the
5 %-damped *pseudo*-spectral acceleration ω²·S_d, not the true absolute acceleration
max|ü + üg| (0.3–0.8 % above it at 1 s on the FEMA P695 far-field set, median 0.55 %)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from audit import G
from audit.errors import InputError

PGA, PGV, SA = "pga", "pgv", "sa"
#: Damping of the spectral acceleration of ``sa:T`` [-].
IM_DAMPING = 0.05


@dataclass(frozen=True)
class IntensityMeasure:
    """An intensity measure: ``pga`` [g], ``pgv`` [m/s] or ``sa:T`` (the 5 %-damped
    pseudo-spectral acceleration ω²·S_d at period T, ω = 2π/T [g])."""

    kind: str
    period_s: float | None = None

    @classmethod
    def parse(cls, text: str) -> IntensityMeasure:
        """``pga``, ``pgv`` or ``sa:T``; InputError naming ``im`` otherwise.

        Parameters
        ----------
        text : str
            The intensity measure, ``sa:T`` with the period T [s].
        """
        if not isinstance(text, str):
            raise InputError(f"im: expected pga, pgv or sa:T with T a period in s, got {text!r}",
                             "im")
        text = text.strip().lower()
        if text in (PGA, PGV):
            return cls(text)
        if text.startswith(f"{SA}:"):
            try:
                period = float(text[3:])
            except ValueError:
                period = math.nan
            if math.isfinite(period) and period > 0:
                return cls(SA, period)
        raise InputError(f"im: expected pga, pgv or sa:T with T a period in s, got '{text}'",
                         "im")

    @property
    def name(self) -> str:
        return f"{SA}:{self.period_s:g}" if self.kind == SA else self.kind

    @property
    def unit(self) -> str:
        return "m/s" if self.kind == PGV else "g"

    def of_record(self, motion, free_motion_s: float) -> float:
        """The intensity of a record (in :attr:`unit`): of its ground motion where it is the
        motion of a floor (the hazard is at the ground).

        Parameters
        ----------
        motion : records.GroundMotion
            The record (or a floor motion, carrying its ground motion).
        free_motion_s : float
            Free-motion time after the record [s], for the oscillator of Sa(T).

        Returns
        -------
        float
            PGA [g], PGV [m/s] or Sa(T) at 5 % [g].
        """
        motion = motion.ground if motion.ground is not None else motion
        if self.kind == PGA:
            return motion.pga_g
        if self.kind == PGV:
            return motion.pgv
        import numpy as np

        from audit.physics.response_spectra import response_spectra
        spectra = response_spectra(motion, np.array([self.period_s]), [IM_DAMPING],
                                   free_motion_s, displacement_only=True)
        return float(spectra.pseudo_acceleration[0, 0]) / G

    def of_design_site(self, site: dict) -> float | None:
        """The intensity of a FEMA 356 design site (S_XS, S_X1 [g]), or None: PGA = 0.4 S_XS,
        Sa(T) of the design spectrum at 5 %; PGV has no design value.

        Parameters
        ----------
        site : dict or None
            The design site, ``sxs_g`` and ``sx1_g`` [g] (absent where only an NTC 2018 site
            was given).

        Returns
        -------
        float or None
            The intensity [g]; None without a FEMA 356 site.
        """
        if not site or site.get("sxs_g") is None or self.kind == PGV:
            return None
        from audit.physics.design_spectra import FEMA356Spectrum
        spectrum = FEMA356Spectrum(site["sxs_g"], site["sx1_g"])
        return float(spectrum.acceleration(0.0 if self.kind == PGA else self.period_s, 0.05))

    def of_ntc_site(self, site: dict) -> float | None:
        """The intensity of an NTC 2018 site (a_g, F0, T_C*, soil, topography): its elastic
        spectrum S_e (Eq. 3.2.2) at 5 % at T = 0 (PGA) or at the IM's period, or None: PGV has
        no design value, and a site without every NTC value has none.

        Parameters
        ----------
        site : dict or None
            A record's site (:data:`records.sites.NTC2018_SITE_KEYS` among its keys).

        Returns
        -------
        float or None
            The intensity [g].
        """
        from records.sites import NTC2018_SITE_KEYS
        if not site or self.kind == PGV or any(site.get(key) is None
                                               for key in NTC2018_SITE_KEYS):
            return None
        from audit.physics.ntc2018_spectrum import NTC2018Spectrum
        spectrum = NTC2018Spectrum.from_site(site)
        return float(spectrum.acceleration(0.0 if self.kind == PGA else self.period_s, 0.05))


__all__ = ["IntensityMeasure", "PGA", "PGV", "SA", "IM_DAMPING"]
