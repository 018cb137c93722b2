"""FEMA 356 (2000) rocking procedure: Priestley's iteration on the site's design spectrum.

Section 9 of the reference report (Makris & Konstantinidis 2001): β = 0.4 (1 − sqrt r) (Eq. 9.1) and the FEMA 356
general horizontal design spectrum of the site (S_XS, S_X1 of Table 3.1), modified for damping
with Table 1-6, converted to displacement by Eq. 3.5. The estimate depends on the site and the
block only, not on the recorded motion.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from audit import G
from audit.physics.damping import damping_fema356
from audit.physics.design_spectra import DesignDisplacement, FEMA356Spectrum
from procedures.base import Procedure


class FEMA356(Procedure):
    """FEMA 356 rocking procedure (Eqs. 9.1, 3.5, 8.1, 8.2)."""

    name = "fema356"
    title = "FEMA 356 (2000)"
    reference = ("FEMA 356 (2000). Prestandard and Commentary for the Seismic Rehabilitation of "
                 "Buildings, Chapter 4 (rocking) and §1.6 (design spectrum). Federal Emergency "
                 "Management Agency, Washington DC.")
    damping_law = "β = 0.4 (1 − √r) (Eq. 9.1)"
    spectrum_source = ("FEMA 356 general horizontal design spectrum from S_XS, S_X1, with B_S, B_1 "
                       "of Table 1-6, Sd = Sa·g·T²/(4π²) (Eq. 3.5)")
    figure_series = "9"
    requires_site = ("sxs_g", "sx1_g")

    def damping(self, r):
        return damping_fema356(r)

    @staticmethod
    def design_spectrum(entry) -> FEMA356Spectrum:
        return FEMA356Spectrum(entry.site["sxs_g"], entry.site["sx1_g"])

    def peak_ground_acceleration(self, entry, context):
        # the design spectrum's zero-period acceleration, 0.4·S_XS: the site, not the record
        return float(self.design_spectrum(entry).acceleration(0.0, 0.05)) * G

    def displacement_spectrum(self, entry, damping, context):
        spectrum = self.design_spectrum(entry)
        return DesignDisplacement(spectrum, damping)

    def site_displacements(self, entries, damping):
        spectra = FEMA356Spectrum(np.array([e.site["sxs_g"] for e in entries], dtype=float),
                                  np.array([e.site["sx1_g"] for e in entries], dtype=float))

        def of(index):
            mine = replace(spectra, sxs_g=spectra.sxs_g[index], sx1_g=spectra.sx1_g[index])
            return DesignDisplacement(mine, damping)
        return of
