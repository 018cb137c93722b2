"""Design-site audits: a FEMA 356 design site for the records, and FEMA P695 scaling.

Both are pure transformations of a :class:`~records.RecordSuite`, applied before the
audit: :func:`with_design_site` gives FEMA 356 the user's site (S_XS, S_X1 of FEMA 356 §1.6)
for the records that have none; :func:`scale_to_site` makes the suite consistent with that
site's design spectrum, the FEMA P695 way (normalise each record, then scale the whole suite
so its median spectral acceleration equals the design spectrum at an anchor period).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.design_spectra import FEMA356Spectrum
from audit.physics.ntc2018_spectrum import NTC2018Spectrum
from records import RecordSuite

#: Damping of the spectra the suite is scaled on, 5 % as in FEMA P695 and FEMA 356 [-].
SCALING_DAMPING = 0.05


def with_design_site(suite: RecordSuite, sxs_g: float, sx1_g: float,
                     override: bool = False) -> RecordSuite:
    """The suite with a FEMA 356 design site for every record that has none.

    Parameters
    ----------
    suite : RecordSuite
    sxs_g, sx1_g : float
        S_XS and S_X1, design spectral accelerations at short periods and at 1 s [g]
        (FEMA 356 §1.6.1.5).
    override : bool
        Also replace the sites records carry (Table 3.1 for catalogue records, or a manifest's).

    Returns
    -------
    RecordSuite
        With ``site = {"sxs_g", "sx1_g"}`` on the records given the design site, and
        :attr:`RecordSuite.design_site` saying which.
    """
    spectrum = FEMA356Spectrum(sxs_g, sx1_g)  # refuses non-positive values
    design = {"sxs_g": spectrum.sxs_g, "sx1_g": spectrum.sx1_g}
    entries, given = [], []
    for entry in suite:
        if override or entry.site.get("sxs_g") is None:
            entry = replace(entry, site=dict(design))
            given.append(entry.id)
        entries.append(entry)
    kept = len(entries) - len(given)
    description = (f"{suite.description}; FEMA 356 design site S_XS = {spectrum.sxs_g:g} g, "
                   f"S_X1 = {spectrum.sx1_g:g} g for {len(given)} of {len(entries)} records"
                   + (f" ({kept} keep their own site)" if kept else ""))
    return replace(suite, entries=tuple(entries), description=description,
                   design_site={**design, "override": override, "records": given})


def with_ntc_site(suite: RecordSuite, ag_g: float, f0: float, tc_star_s: float, soil: str,
                  topography: str) -> RecordSuite:
    """The suite with an NTC 2018 site on every record (§3.2: a_g, F₀, T_C*, soil, topography).

    The NTC 2018 procedure then reads its demand off the code spectrum S_De of that site
    instead of the record's own spectrum (``procedures.ntc_2018.NTC2018.demand_variant``).

    Parameters
    ----------
    suite : records.RecordSuite
        The records.
    ag_g : float
        Peak ground acceleration on rock a_g [g].
    f0 : float
        Spectral amplification F₀ [-].
    tc_star_s : float
        T_C* [s].
    soil, topography : str
        Soil category (A–E, Tab. 3.2.II) and topographic category (T1–T4, Tab. 3.2.III).
    """
    spectrum = NTC2018Spectrum(ag_g, f0, tc_star_s, soil, topography)  # validates every field
    ntc = spectrum.site()
    entries = tuple(replace(entry, site={**entry.site, **ntc}) for entry in suite)
    description = (f"{suite.description}; NTC 2018 site a_g = {ag_g:g} g, F0 = {f0:g}, "
                   f"T_C* = {tc_star_s:g} s, soil {soil}, topography {topography}")
    return replace(suite, entries=entries, description=description,
                   design_site={**suite.design_site, "ntc": ntc})


def scale_to_site(suite: RecordSuite, sxs_g: float, sx1_g: float,
                  anchor_period_s: float = 1.0) -> RecordSuite:
    """The suite scaled to a FEMA 356 design spectrum the FEMA P695 way.

    Each record is multiplied by its P695 normalisation factor ``n_i``
    (``metadata["p695_normalisation_factor"]``; records without one, from files or manifests,
    take n_i = 1), then every record by one suite factor

        s = Sa_design(T_a) / median_i(n_i·Sa_i(T_a)),

    so the median 5 %-damped spectral acceleration of the normalised suite equals the design
    spectrum at the anchor period T_a. Sa_i is the true absolute acceleration spectrum
    max|ü + üg| of the record over its duration (:func:`audit.physics.response_spectra.response_spectra`);
    the median of an even count is the mean of the two middle values. Records without a motion
    are kept as they are.

    Parameters
    ----------
    suite : RecordSuite
        Records whose FEMA 356 site, where they have one, is this design site (see
        :func:`with_design_site`): a record is not scaled to one spectrum and audited at another.
    sxs_g, sx1_g : float
        S_XS and S_X1 of the design site [g].
    anchor_period_s : float
        T_a [s].

    Returns
    -------
    RecordSuite
        Scaled motions (``pulse`` amplitudes too), and :attr:`RecordSuite.scaling` holding the
        target, the median, the suite factor and per record ``normalisation_factor``,
        ``normalised_sa_g`` and ``scale_factor`` = n_i·s.
    """
    from audit.physics.response_spectra import response_spectra  # numba: only when scaling
    spectrum = FEMA356Spectrum(sxs_g, sx1_g)
    if not (math.isfinite(anchor_period_s) and anchor_period_s > 0):
        raise InputError(f"anchor period: must be a positive number of seconds, got {anchor_period_s}")
    records = [entry for entry in suite if not entry.missing]
    if not records:
        raise InputError(f"scale to site: {suite.description} holds no record with a motion")
    elsewhere = [entry.id for entry in records if entry.site.get("sxs_g") is not None
                 and (entry.site["sxs_g"], entry.site["sx1_g"]) != (spectrum.sxs_g, spectrum.sx1_g)]
    if elsewhere:
        raise InputError(f"scale to site: {', '.join(elsewhere)} keep another FEMA 356 site than "
                         "the one they would be scaled to; give them the design site "
                         "(site.override)", "site.override")
    normalisation = {entry.id: entry.metadata.get("p695_normalisation_factor", 1.0)
                     for entry in records}
    # the pseudo-spectral acceleration ω²·S_d, as the design spectrum and hazard curves define it
    normalised_sa_g = {entry.id: normalisation[entry.id] * float(response_spectra(
        entry.motion, anchor_period_s, SCALING_DAMPING,
        displacement_only=True).pseudo_acceleration[0, 0]) / G for entry in records}
    median_g = float(np.median(list(normalised_sa_g.values())))
    target_g = float(spectrum.acceleration(anchor_period_s, SCALING_DAMPING))
    suite_factor = target_g / median_g
    factors = {record_id: n * suite_factor for record_id, n in normalisation.items()}
    entries = []
    for entry in suite:
        if not entry.missing:
            factor = factors[entry.id]
            component = (f"{entry.component}; scaled × {factor:.4g} (P695 normalisation "
                         f"{normalisation[entry.id]:g} × suite factor {suite_factor:.4g})")
            entry = replace(entry, component=component,
                            motion=entry.motion.scaled(factor, component))
        entries.append(entry)
    scaling = {
        "method": "FEMA P695: each record × its P695 normalisation factor (1 where it has none), "
                  "then one suite factor so the median 5 %-damped pseudo-spectral acceleration "
                  "ω²·S_d at the anchor period equals "
                  "the FEMA 356 design spectrum",
        "sxs_g": spectrum.sxs_g, "sx1_g": spectrum.sx1_g, "anchor_period_s": anchor_period_s,
        "damping_pct": 100 * SCALING_DAMPING, "target_sa_g": target_g,
        "median_normalised_sa_g": median_g, "suite_factor": suite_factor,
        "records": {record_id: {"normalisation_factor": normalisation[record_id],
                                "normalised_sa_g": normalised_sa_g[record_id],
                                "scale_factor": factors[record_id]} for record_id in factors},
        "without_normalisation_factor": [entry.id for entry in records
                                         if "p695_normalisation_factor" not in entry.metadata],
    }
    description = (f"{suite.description}; scaled to the FEMA 356 design spectrum (S_XS = "
                   f"{spectrum.sxs_g:g} g, S_X1 = {spectrum.sx1_g:g} g) at T = {anchor_period_s:g} s "
                   f"the FEMA P695 way, suite factor {suite_factor:.4g}")
    return replace(suite, entries=tuple(entries), description=description, scaling=scaling)
