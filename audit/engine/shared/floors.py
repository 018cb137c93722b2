"""Objects on floors: every record of a suite turned once into the motion of the object's floor.

The site scales the *ground* motion (the hazard is at the ground), then :func:`on_floor` filters
each record through the building (:mod:`audit.physics.building.floor_motion`) — the one place
the records are prepared for solving, once per record. The building is linear, so a stripe's
scale factor carries over to the floor motion, and the stripes stay in the ground's intensity
measure (a floor motion keeps its ground motion, which :class:`~audit.engine.shared.intensity.
IntensityMeasure` reads). Procedures that read the record read the floor motion.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import numpy as np

from audit import G
from audit.physics.building.floor import (DEFAULT_BUILDING_DAMPING, DEFAULT_BUILDING_MODEL,
                                          Floor)

#: The keywords (and command-line flags) of the object's floor, and their defaults.
FLOOR_DEFAULTS = {"floor": 0.0, "building": None, "building_model": None,
                  "building_damping": DEFAULT_BUILDING_DAMPING}
FLOOR_FIELDS = tuple(FLOOR_DEFAULTS)


def floor_document(floor: Floor) -> dict:
    """The floor and the building, JSON-ready (``z_over_h`` 0 on the ground).

    Parameters
    ----------
    floor : audit.physics.building.Floor
        Where the objects stand.
    """
    building = floor.building
    return {"z_over_h": floor.z_over_h, "building_period_s": building and building.period_s,
            "building_model": building and str(building.model),
            "building_damping": building and building.damping,
            "description": floor.describe()}


def floor_peaks(motion) -> dict:
    """Peak floor acceleration [g] and velocity [m/s] of a floor motion (the ground's peaks on
    the ground): PFA = max|ü_floor|, PFV by the same integration as the records' PGV.

    Parameters
    ----------
    motion : records.GroundMotion
        The floor's (or the ground's) motion.

    Returns
    -------
    dict
        ``pfa_g`` [g] and ``pfv_m_s`` [m/s].
    """
    return {"pfa_g": motion.pga / G, "pfv_m_s": motion.pgv}


def suite_floor(suite) -> dict:
    """``suite.floor`` (the floor, the building, each record's PFA and PFV), or the ground's:
    what every output file says of where the objects stand.

    Parameters
    ----------
    suite : records.RecordSuite
        The records, on a floor (:func:`on_floor`) or on the ground.
    """
    return suite.floor or {**floor_document(Floor()), "records": {}}


#: Periods of the floor and ground spectra of a check's page [s]: 0.05–5 s, log-spaced.
SPECTRUM_PERIODS_S = tuple(np.geomspace(0.05, 5.0, 49).tolist())
#: Their damping [-].
SPECTRUM_DAMPING = 0.05


def floor_at_site(suite, entries, intensity: dict, site_im: float) -> dict:
    """:func:`suite_floor` with each record's PFA and PFV at the site (the record scaled so that
    its ground intensity is ``site_im``; ``intensity`` holds each record's as it stands), and on
    a floor the median 5 %-damped spectra [g] of the floor motions and of the ground motions at
    the site, ``spectra``.

    Parameters
    ----------
    suite : records.RecordSuite
        The records, on a floor or on the ground.
    entries : iterable of records.RecordEntry
        The records used, each with its motion.
    intensity : dict
        Each record's ground intensity as it stands, by record id, in the unit of the IM.
    site_im : float
        The site's intensity, in the same unit.
    """
    document = suite_floor(suite)
    factors = {entry.id: site_im / intensity[entry.id] for entry in entries}
    records = {record: {name: value * factors[record] for name, value in peaks.items()}
               for record, peaks in document["records"].items() if record in factors}
    if not records:
        return {**document, "records": records}
    from audit.physics.response_spectra import response_spectra
    periods = np.array(SPECTRUM_PERIODS_S)

    def median_sa(motions) -> list:
        return (np.median([response_spectra(m, periods, [SPECTRUM_DAMPING], 0.0).sa[0] * factor
                           for m, factor in motions], axis=0) / G).tolist()

    spectra = {"period_s": list(SPECTRUM_PERIODS_S), "damping": SPECTRUM_DAMPING,
               "floor_median_sa_g": median_sa([(e.motion, factors[e.id]) for e in entries]),
               "ground_median_sa_g": median_sa([(e.motion.ground, factors[e.id])
                                                for e in entries])}
    return {**document, "records": records, "spectra": spectra}


def on_floor(suite, floor: Floor):
    """``suite`` with every motion replaced by that of ``floor`` (see the module); on the ground
    the suite itself. ``suite.floor`` names the floor and the building and holds each record's
    PFA and PFV.

    Parameters
    ----------
    suite : records.RecordSuite
        The ground motions.
    floor : audit.physics.building.Floor
        The floor and the building filtering them.

    Returns
    -------
    records.RecordSuite
    """
    if floor.on_ground:
        return suite
    # the filter's kernels load only here: reading results back (audit report) needs none
    from audit.physics.building.floor_motion import floor_motion, interpreted_time_s
    from audit.physics.tiers import expect
    motions = [entry.motion for entry in suite if entry.motion is not None]
    expect(sum(interpreted_time_s(m.acceleration.size, m.dt, floor) for m in motions))
    # the records filtered two at a time: the compiled filter releases the GIL
    with ThreadPoolExecutor(2) as pool:
        filtered = iter(pool.map(lambda motion: floor_motion(motion, floor), motions))
        entries = tuple(entry if entry.motion is None else replace(entry, motion=next(filtered))
                        for entry in suite)
    peaks = {entry.id: floor_peaks(entry.motion) for entry in entries if entry.motion is not None}
    return replace(suite, entries=entries, description=f"{suite.description}; {floor.describe()}",
                   floor={**floor_document(floor), "records": peaks})


__all__ = ["on_floor", "suite_floor", "floor_at_site", "floor_document", "floor_peaks", "FLOOR_FIELDS", "FLOOR_DEFAULTS",
           "DEFAULT_BUILDING_MODEL"]
