"""Spectra of one motion and of the codes: rocking spectra, oscillator response spectra, and
the design spectra of FEMA 356, UBC 97 and NTC 2018; what ``python -m audit spectrum`` and
``design-spectrum`` print."""

from __future__ import annotations

from typing import TYPE_CHECKING

from audit.engine.shared import fields as check
from audit.engine.shared.defaults import (DEFAULT_DAMPING_PCT, DEFAULT_DESIGN_DAMPING_PCT,
                                   DEFAULT_PERIODS, DEFAULT_RESPONSE_FREE_MOTION_S)
from audit.errors import InputError

if TYPE_CHECKING:
    from audit.engine.shared.design_site import Site
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.solver import Solver
    from audit.physics.building.floor import Floor

CODES = ("fema356", "ubc97", "ntc2018")


def rocking_spectrum(motion, *, size_s, alpha_deg, records=None, solver: Solver | None = None,
                     floor: Floor | None = None, runtime: Runtime | None = None):
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
    records : Records, str, path or records.RecordSuite, optional
        Where a record id is looked up and how a record is read, as for :func:`audit.rock`.
    solver : Solver, optional
        ``restitution`` (``housner``, Eq. 4.8; a fixed r in (0, 1] [-]; ``xFACTOR`` times
        Eq. 4.8), ``free_motion_s`` after the excitation [s], ``g`` [m/s²], ``vertical`` (the
        motion's vertical component in the equation).
    floor : Floor, optional
        Where the block stands, as for :func:`audit.rock`.
    runtime : Runtime, optional
        ``jobs``, the solver threads; ``force``, start even when the estimated work is beyond
        the limits.
    """
    import numpy as np

    from audit.api.inputs import floor_group, on_floor_of, runtime_of, solver_of
    from audit.engine.shared import guards
    from audit.engine.shared.defaults import DEFAULT_ALPHA_DEG, DEFAULT_SIZES
    from audit.engine.shared.grid import size_grid
    from audit.physics.rocking import RockingOptions, rocking_spectrum as spectrum
    solver = solver_of(solver, "rocking_spectrum",
                       ("restitution", "free_motion_s", "g", "vertical"))
    runtime = runtime_of(runtime, "rocking_spectrum", ("jobs", "force"))
    motion, floor_document = on_floor_of(motion, floor_group(floor), records)
    sizes = check.numbers("size_s", size_s, "positive block sizes 2π/p in s", 0, low_open=True)
    alphas = check.numbers("alpha_deg", alpha_deg, "slendernesses between 0 and 45 degrees", 0,
                           45, low_open=True, high_open=True)
    if solver.vertical and motion.vertical is None:
        raise InputError(f"solver.vertical: {motion.id} has no vertical component (give it in "
                         "the manifest as vertical_file, or a PEER UP/DWN file beside the "
                         "record)", "solver.vertical")
    guards.check(guards.estimate(
        [motion], solver.free_motion_s, blocks=len(sizes) * len(alphas), jobs=runtime.jobs,
        settings=(guards.Setting("size_s", len(sizes), size_grid(*DEFAULT_SIZES).size),
                  guards.Setting("alpha_deg", len(alphas), len(DEFAULT_ALPHA_DEG)))),
        runtime.force)
    frame = spectrum(motion, np.asarray(sizes), np.radians(alphas), solver.restitution,
                     RockingOptions(solver.g, solver.free_motion_s, vertical=solver.vertical),
                     jobs=runtime.jobs).to_frame()
    frame.attrs["record"] = motion.id
    frame.attrs["floor"] = floor_document
    return frame


def response_spectra(motion, *, periods_s, damping_pct=DEFAULT_DAMPING_PCT,
                     free_motion_s: float = DEFAULT_RESPONSE_FREE_MOTION_S, records=None,
                     floor: Floor | None = None, runtime: Runtime | None = None):
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
    records : Records, str, path or records.RecordSuite, optional
        Where a record id is looked up and how a record is read, as for :func:`audit.rock`.
    floor : Floor, optional
        Where the block stands, as for :func:`audit.rock`.
    runtime : Runtime, optional
        ``force``: start even when the estimated work is beyond the limits.
    """
    import numpy as np

    from audit.api.inputs import floor_group, on_floor_of, runtime_of
    from audit.engine.shared import guards
    from audit.engine.shared.grid import size_grid
    from audit.physics.response_spectra import response_spectra as spectra
    force = runtime_of(runtime, "response_spectra", ("force",)).force
    motion, floor_document = on_floor_of(motion, floor_group(floor), records)
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
                    site: Site | None = None, near_source=(1.0, 1.0)):
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
    site : Site, (float, float) or str
        FEMA 356: the design spectral accelerations S_XS, S_X1 [g] (``Site(sxs_g, sx1_g)`` or
        its shorthand); NTC 2018: ``Site(None, None, ntc=(a_g [g], F0 [-], T_C* [s], soil
        A–E, topography T1–T4))``. Not read by UBC 97.
    near_source : (float, float)
        UBC 97: the near-source factors N_a, N_v [-].
    """
    import numpy as np

    from audit.engine.shared.design_site import Site
    from audit.physics.design_spectra import FEMA356Spectrum, UBC97Spectrum
    from audit.physics.ntc2018_spectrum import NTC2018Spectrum
    periods = np.asarray(check.numbers("periods_s", periods_s, "periods ≥ 0 s", 0))
    damping = np.asarray(check.numbers("damping_pct", damping_pct,
                                       "damping ratios in [0, 100) %", 0, 100,
                                       high_open=True)) / 100.0
    if not isinstance(code, str) or code not in CODES:
        raise InputError(f"code: expected one of {', '.join(CODES)}, got {code!r}", "code")
    if code == "ubc97":
        if site is not None:
            raise InputError("site: ubc97 reads near_source, not a site", "site")
        na, nv = check.pair("near_source", near_source, "N_a, N_v (positive)", 0, low_open=True)
        spectrum = UBC97Spectrum(na, nv)
    else:
        site = Site.parse(site)
        if code == "fema356":
            if site is None or site.values_g is None:
                raise InputError("site: fema356 needs S_XS, S_X1", "site")
            spectrum = FEMA356Spectrum(site.sxs_g, site.sx1_g)
        else:
            if site is None or site.ntc is None:
                raise InputError("site.ntc: ntc2018 needs a_g, F0, T_C*, soil, topography",
                                 "site.ntc")
            spectrum = NTC2018Spectrum(*site.ntc)
    return spectrum, {
        "period_s": np.tile(periods, damping.size),
        "damping_pct": np.repeat(100.0 * damping, periods.size),
        "sa_g": np.concatenate([spectrum.acceleration(periods, d) for d in damping]),
        "sd_m": np.concatenate([spectrum.displacement(periods, d) for d in damping])}


__all__ = ["rocking_spectrum", "response_spectra", "design_spectrum", "CODES"]
