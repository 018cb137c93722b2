"""What a record's design site may carry (``RecordEntry.site``, manifest fields): the keys and
the categories, defined here once; the spectra built from them live in
:mod:`audit.physics.design_spectra`."""

#: FEMA 356 site: class (Table 3.1) and the design parameters S_XS, S_X1 [g] (§1.6).
FEMA356_SITE_KEYS = ("site_class", "sxs_g", "sx1_g")
#: NTC 2018 site, in the order of :class:`audit.physics.ntc2018_spectrum.NTC2018Spectrum`'s
#: fields: a_g [g], F₀ [-], T_C* [s], soil category, topographic category.
NTC2018_SITE_KEYS = ("ntc_ag_g", "ntc_f0", "ntc_tc_star_s", "ntc_soil", "ntc_topography")
#: NTC 2018 soil categories (§3.2.2, Tab. 3.2.II).
NTC2018_SOILS = ("A", "B", "C", "D", "E")
#: NTC 2018 topographic categories (§3.2.2, Tab. 3.2.III).
NTC2018_TOPOGRAPHIES = ("T1", "T2", "T3", "T4")
#: Site parameters that are accelerations [g]: a design site scaled by a factor scales these.
ACCELERATION_SITE_KEYS = ("sxs_g", "sx1_g", "ntc_ag_g")


def scaled_site(site: dict, factor: float) -> dict:
    """A record's site with every design acceleration × ``factor`` (the design spectrum scaled)."""
    return {key: value * factor if key in ACCELERATION_SITE_KEYS and value is not None else value
            for key, value in site.items()}
