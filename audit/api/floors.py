"""``audit.floor_motion``: the motion of a floor of a linear building under a record, what
``python -m audit floor-motion`` writes.

    import audit
    floor = audit.floor_motion("rsn1111_nis000", records="p695-far-field", building=1.0,
                               building_model="shear:10", floor=1.0)
    floor.pfa_g, floor.pfv_m_s, floor.spectrum_peak_g
    floor.csv()            # time_s,acceleration_g
"""

from __future__ import annotations

from audit import G
from audit.engine.shared.defaults import DEFAULT_PERIODS
from audit.physics.building.floor import Floor

#: Damping of the floor spectrum whose peak is reported [-].
SPECTRUM_DAMPING = 0.05


class FloorMotion:
    """A floor's absolute acceleration and its peaks.

    Attributes
    ----------
    motion : records.GroundMotion
        The floor motion (its ``ground`` the record), [m/s²].
    floor : dict
        The floor and the building (:func:`audit.engine.shared.floors.floor_document`).
    pfa_g, pfv_m_s : float
        Peak floor acceleration [g] and velocity [m/s].
    spectrum_peak_g, spectrum_peak_period_s : float
        The peak of the floor motion's 5 %-damped absolute-acceleration spectrum [g] over the
        periods of ``audit spectrum`` (0.02–10 s), and where it is [s].
    """

    def __init__(self, motion, floor: dict):
        import numpy as np

        from audit.engine.shared.floors import floor_peaks
        from audit.engine.shared.grid import size_grid
        from audit.physics.response_spectra import response_spectra
        self.motion, self.floor = motion, floor
        peaks = floor_peaks(motion)
        self.pfa_g, self.pfv_m_s = peaks["pfa_g"], peaks["pfv_m_s"]
        periods = size_grid(*DEFAULT_PERIODS)
        sa = response_spectra(motion, periods, [SPECTRUM_DAMPING], 0.0).sa[0]
        peak = int(np.argmax(sa))
        self.spectrum_peak_g = float(sa[peak]) / G
        self.spectrum_peak_period_s = float(periods[peak])

    def csv(self) -> bytes:
        """``time_s,acceleration_g``, one row per sample."""
        import numpy as np
        rows = np.column_stack((self.motion.time, self.motion.acceleration / G))
        return ("time_s,acceleration_g\n" + "".join(f"{t:.8g},{a:.8g}\n" for t, a in rows)
                ).encode()

    def as_dict(self) -> dict:
        return {"record": self.motion.id, "floor": self.floor, "pfa_g": self.pfa_g,
                "pfv_m_s": self.pfv_m_s, "spectrum_peak_g": self.spectrum_peak_g,
                "spectrum_peak_period_s": self.spectrum_peak_period_s,
                "dt_s": self.motion.dt, "samples": int(self.motion.acceleration.size)}

    def __repr__(self) -> str:
        return (f"FloorMotion({self.motion.id} {self.floor['description']}: PFA = "
                f"{self.pfa_g:.3g} g, PFV = {self.pfv_m_s:.3g} m/s)")


def floor_motion(motion, floor: Floor, records=None) -> FloorMotion:
    """The absolute acceleration of ``floor`` (``Floor(z_over_h, Building(period_s, model,
    damping))``: z/H in a building of first-mode period T1 [s], ``shear:N`` or
    ``continuum:α0``, damping in every mode) under ``motion`` (as for :func:`audit.rock`: an id
    of ``records``, a file, a GroundMotion or (acceleration [m/s²], dt [s]))
    (:mod:`audit.physics.building.floor_motion`); ``records``: where an id is looked up and how
    the record is read, as for :func:`audit.rock`."""
    from audit.api.inputs import floor_group, on_floor_of
    motion, document = on_floor_of(motion, floor_group(floor), records)
    return FloorMotion(motion, document)


__all__ = ["floor_motion", "FloorMotion"]
