"""Spectra of one motion and of the codes: rocking spectra, oscillator response spectra, and
the design spectra of FEMA 356, UBC 97 and NTC 2018; what ``python -m audit spectrum`` and
``design-spectrum`` print."""

from __future__ import annotations

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import (DEFAULT_DAMPING_PCT, DEFAULT_DESIGN_DAMPING_PCT,
                                   DEFAULT_FREE_MOTION_S, DEFAULT_JOBS, DEFAULT_PERIODS,
                                   DEFAULT_RESPONSE_FREE_MOTION_S, DEFAULT_RESTITUTION)
from audit.errors import InputError
from audit.physics.building.floor import DEFAULT_BUILDING_DAMPING

CODES = ("fema356", "ubc97", "ntc2018")


def rocking_spectrum(motion, *, size_s, alpha_deg, restitution=DEFAULT_RESTITUTION,
                     free_motion_s: float = DEFAULT_FREE_MOTION_S, vertical: bool = False,
                     jobs: int = DEFAULT_JOBS, force: bool = False, records=None,
                     dt_s: float | None = None, units: str | None = None,
                     skip_bad_records: bool = False, floor: float = 0.0,
                     building: float | None = None,
                     building_model: str | None = None,
                     building_damping: float = DEFAULT_BUILDING_DAMPING):
    """The rocking spectrum of ``motion`` (ids, paths, GroundMotions, (array, dt): see
    :func:`audit.rock`) over sizes 2π/p [s] × slendernesses [degrees]: a DataFrame (one row per
    block; ``audit.physics.rocking.RockingSpectrum.to_frame``), the record's id in
    ``.attrs["record"]``, the floor in ``.attrs["floor"]``.

    Parameters
    ----------
    motion : str, path, records.GroundMotion or (array, float)
        As for :func:`audit.rock` (acceleration [m/s²], dt [s]).
    size_s : float or sequence of float
        Block sizes 2π/p [s], positive.
    alpha_deg : float or sequence of float
        Slendernesses [degrees], in (0, 45).
    restitution : str or float
        ``housner`` (Eq. 4.8), a fixed r in (0, 1] [-] or ``xFACTOR`` times Eq. 4.8.
    free_motion_s : float
        Free motion after the excitation [s].
    vertical : bool
        Include the motion's vertical component.
    jobs : int
        Solver threads.
    force : bool
        Start even when the estimated work is beyond the limits.
    records : str, path or records.RecordSuite, optional
        Where a record id is looked up, as for :func:`audit.rock`.
    dt_s, units, skip_bad_records :
        How a record is read: the time step [s] and the units (``g``, ``m/s2``, ``cm/s2``) of
        a text record file that states none; the unreadable records of the suite an id is
        looked up in left out (:func:`audit.api.inputs.record_suite`).
    floor, building, building_model, building_damping :
        Where the block stands, as for :func:`audit.rock`.
    """
    import numpy as np

    from audit.api.inputs import floor_of, on_floor_of
    from audit.engine.shared.record_request import Records
    from audit.engine.shared import guards
    from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_SIZES
    from audit.engine.shared.grid import size_grid
    from audit.physics.block import Restitution
    from audit.physics.rocking import rocking_spectrum as spectrum
    force = check.flag("force", force)
    motion, floor_document = on_floor_of(
        motion, floor_of(floor, building, building_model, building_damping),
        Records(records, dt_s, units, skip_bad_records))
    sizes = check.numbers("size_s", size_s, "positive block sizes 2π/p in s", 0, low_open=True)
    alphas = check.numbers("alpha_deg", alpha_deg, "slendernesses between 0 and 45 degrees", 0,
                           45, low_open=True, high_open=True)
    free_motion_s = check.number("free_motion_s", free_motion_s, "a duration ≥ 0 s", 0)
    impact = restitution if isinstance(restitution, Restitution) else Restitution.parse(
        restitution, "restitution")
    if check.flag("vertical", vertical) and motion.vertical is None:
        raise InputError(f"vertical: {motion.id} has no vertical component (give it in the "
                         "manifest as vertical_file, or a PEER UP/DWN file beside the record)",
                         "vertical")
    jobs = check.whole("jobs", jobs, 1)
    guards.check(guards.estimate(
        [motion], free_motion_s, blocks=len(sizes) * len(alphas), jobs=jobs,
        settings=(guards.Setting("size_s", len(sizes), size_grid(*DEFAULT_SIZES).size),
                  guards.Setting("alpha_deg", len(alphas), len(DEFAULT_ALPHA_DEG)))), force)
    frame = spectrum(motion, np.asarray(sizes), np.radians(alphas), impact,
                     free_motion_s=free_motion_s, jobs=jobs, vertical=vertical).to_frame()
    frame.attrs["record"] = motion.id
    frame.attrs["floor"] = floor_document
    return frame


def response_spectra(motion, *, periods_s, damping_pct=DEFAULT_DAMPING_PCT,
                     free_motion_s: float = DEFAULT_RESPONSE_FREE_MOTION_S, force: bool = False,
                     records=None, dt_s: float | None = None, units: str | None = None,
                     skip_bad_records: bool = False,
                     floor: float = 0.0, building: float | None = None,
                     building_model: str | None = None,
                     building_damping: float = DEFAULT_BUILDING_DAMPING):
    """True response spectra of ``motion`` at periods [s] and damping ratios [%]: a DataFrame
    (``audit.physics.response_spectra.ResponseSpectra.to_frame``); on a floor, the floor
    spectra, the floor in ``.attrs["floor"]``.

    Parameters
    ----------
    motion : str, path, records.GroundMotion or (array, float)
        As for :func:`audit.rock`.
    periods_s : float or sequence of float
        Oscillator periods [s], ≥ 0.
    damping_pct : float or sequence of float
        Damping ratios [%], in [0, 100).
    free_motion_s : float
        Free vibration after the excitation [s].
    force : bool
        Start even when the estimated work is beyond the limits.
    records : str, path or records.RecordSuite, optional
        Where a record id is looked up, as for :func:`audit.rock`.
    dt_s, units, skip_bad_records :
        How a record is read: the time step [s] and the units (``g``, ``m/s2``, ``cm/s2``) of
        a text record file that states none; the unreadable records of the suite an id is
        looked up in left out (:func:`audit.api.inputs.record_suite`).
    floor, building, building_model, building_damping :
        Where the block stands, as for :func:`audit.rock`.
    """
    import numpy as np

    from audit.api.inputs import floor_of, on_floor_of
    from audit.engine.shared.record_request import Records
    from audit.engine.shared import guards
    from audit.engine.shared.grid import size_grid
    from audit.physics.response_spectra import response_spectra as spectra
    force = check.flag("force", force)
    motion, floor_document = on_floor_of(
        motion, floor_of(floor, building, building_model, building_damping),
        Records(records, dt_s, units, skip_bad_records))
    periods = check.numbers("periods_s", periods_s, "periods ≥ 0 s", 0)
    damping = check.numbers("damping_pct", damping_pct, "damping ratios in [0, 100) %", 0, 100,
                            high_open=True)
    free_motion_s = check.number("free_motion_s", free_motion_s, "a duration ≥ 0 s", 0)
    guards.check(guards.estimate(
        [motion], free_motion_s, oscillators=len(periods) * len(damping),
        settings=(guards.Setting("periods_s", len(periods), size_grid(*DEFAULT_PERIODS).size),
                  guards.Setting("damping_pct", len(damping), len(DEFAULT_DAMPING_PCT)))), force)
    frame = spectra(motion, np.asarray(periods), np.asarray(damping) / 100.0,
                    free_motion_s).to_frame()
    frame.attrs["record"] = motion.id
    frame.attrs["floor"] = floor_document
    return frame


def design_spectrum(code: str, periods_s, damping_pct=DEFAULT_DESIGN_DAMPING_PCT, *,
                    sxs_g: float | None = None, sx1_g: float | None = None,
                    na: float | None = None, nv: float | None = None,
                    ag_g: float | None = None, f0: float | None = None,
                    tc_star_s: float | None = None, soil: str = "A", topography: str = "T1"):
    """A code's design spectrum at periods [s] and damping ratios [%]: ``(spectrum, columns)``,
    the spectrum object and a dict of equal-length columns ``period_s, damping_pct, sa_g,
    sd_m`` (no pandas).

    Parameters
    ----------
    code : {"fema356", "ubc97", "ntc2018"}
    periods_s : float or sequence of float
        Periods [s], ≥ 0.
    damping_pct : float or sequence of float
        Damping ratios [%], in [0, 100).
    sxs_g, sx1_g : float
        FEMA 356: design spectral accelerations S_XS, S_X1 [g] (required).
    na, nv : float, optional
        UBC 97: near-source factors N_a, N_v [-] (1 when not given).
    ag_g, f0, tc_star_s : float
        NTC 2018: a_g [g], F0 [-], T_C* [s] (required).
    soil, topography : str
        NTC 2018: soil category A–E, topography T1–T4.
    """
    import numpy as np

    from audit.physics.design_spectra import FEMA356Spectrum, UBC97Spectrum
    from audit.physics.ntc2018_spectrum import NTC2018Spectrum
    periods = np.asarray(check.numbers("periods_s", periods_s, "periods ≥ 0 s", 0))
    damping = np.asarray(check.numbers("damping_pct", damping_pct,
                                       "damping ratios in [0, 100) %", 0, 100,
                                       high_open=True)) / 100.0
    needs = {"fema356": ("sxs_g", "sx1_g"), "ntc2018": ("ag_g", "f0", "tc_star_s"),
             "ubc97": ()}
    if not isinstance(code, str) or code not in needs:
        raise InputError(f"code: expected one of {', '.join(CODES)}, got {code!r}", "code")
    site = {"sxs_g": sxs_g, "sx1_g": sx1_g, "na": na, "nv": nv, "ag_g": ag_g, "f0": f0,
            "tc_star_s": tc_star_s}
    absent = [name for name in needs[code] if site[name] is None]
    if absent:
        raise InputError(f"{', '.join(absent)}: {code} needs {', '.join(needs[code])}",
                         *needs[code])
    site = {name: value if value is None else check.number(name, value, "a number")
            for name, value in site.items()}
    for name, value in (("soil", soil), ("topography", topography)):
        if not isinstance(value, str):
            raise InputError(f"{name}: expected a category's name, got {value!r}", name)
    if code == "fema356":
        spectrum = FEMA356Spectrum(site["sxs_g"], site["sx1_g"])
    elif code == "ntc2018":
        spectrum = NTC2018Spectrum(site["ag_g"], site["f0"], site["tc_star_s"], soil,
                                   topography)
    else:
        spectrum = UBC97Spectrum(site["na"] or 1.0, site["nv"] or 1.0)
    return spectrum, {
        "period_s": np.tile(periods, damping.size),
        "damping_pct": np.repeat(100.0 * damping, periods.size),
        "sa_g": np.concatenate([spectrum.acceleration(periods, d) for d in damping]),
        "sd_m": np.concatenate([spectrum.displacement(periods, d) for d in damping])}


__all__ = ["rocking_spectrum", "response_spectra", "design_spectrum", "CODES"]
