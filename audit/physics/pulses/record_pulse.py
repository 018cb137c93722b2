"""The pulse of a suite's record: Shahi & Baker (2014) on the record's two horizontal
components, and the Mavroeidis & Papageorgiou pulse fitted to it, cached.

A FEMA P695 component is classified with its partner (the package's two components, component
a first, as the package gives them, not scaled); the direction θ is measured from component a
towards component b, and the component sees the pulse × cos θ (a) or sin θ (b). A record of
one component (a manifest's file) is classified alone (the second component zero, θ = 0), as
given. The identification costs about a second per record (up to ~3 s for long ones); its
summary is cached in the process and in the user cache folder, keyed by the samples.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

import numpy as np

from audit import G
from audit.errors import InputError
from audit.files import write_file_atomically
from audit.physics.pulses.mp_fit import MPFit, fit_mp_pulse
from records.p695 import cache_dir, station_components

if TYPE_CHECKING:
    from audit.physics.pulses.shahi_baker_2014 import PulseClassification

#: Part of the cache key: bump when the identification or the fit changes.
CACHE_VERSION = "shahi-baker-2014-matlab-2000226/mp-fit-2"
#: The MATLAB's limit on the difference of the components' lengths [samples] (the longer is cut).
MAX_LENGTH_DIFFERENCE = 20

_MEMORY: dict[str, dict] = {}


@dataclass(frozen=True)
class RecordPulse:
    """What the identification says of one record (component).

    Attributes
    ----------
    record_id : str
        The suite's id of the component.
    classified : str
        What was classified, in words (the two components, or this one alone).
    pulse_like : bool
        A candidate is pulse-like.
    pulse_indicator : float
        PI of the pulse, else the largest PI of the candidates [-].
    tp_s : float
        Shahi & Baker's T_p of the first pulse-like candidate [s] (NaN if none).
    candidate : int
        Which candidate (1–5) that is, 0 if none.
    candidate_tp_s : tuple of float
        T_p of the five candidates [s], in order.
    direction_deg : float
        θ of the pulse from the first component towards the second [degrees] (NaN if none).
    component_factor : float
        cos θ or sin θ: the share of the pulse along this component [-] (NaN if none).
    pgv_cm_s : float
        PGV of the record rotated to θ [cm/s] (of the first candidate if none is a pulse).
    pulse_pgv_cm_s : float
        Peak |v| of the extracted pulse [cm/s] (NaN if none).
    fit : MPFit or None
        The Mavroeidis & Papageorgiou pulse fitted to the extracted pulse, in the pulse's
        direction, of the record as classified (not scaled).
    scale_factor : float
        The component as audited / as classified [-] (a scaled record's factor, else 1).
    """

    record_id: str
    classified: str
    pulse_like: bool
    pulse_indicator: float
    tp_s: float
    candidate: int
    candidate_tp_s: tuple
    direction_deg: float
    component_factor: float
    pgv_cm_s: float
    pulse_pgv_cm_s: float
    fit: MPFit | None
    scale_factor: float = 1.0

    @property
    def amplitude_m_s2(self) -> float:
        """Peak acceleration of the fitted pulse along this component, as audited [m/s²]."""
        return (self.fit.peak_acceleration_m_s2 * abs(self.component_factor)
                * self.scale_factor)


def _summary(classification: PulseClassification) -> dict:
    pulse = classification.pulse
    summary = {"pulse_indicator": classification.pulse_indicator,
               "candidate_tp_s": [c.tp_s for c in classification.candidates],
               "pgv_cm_s": (pulse or classification.candidates[0]).pgv_cm_s}
    if pulse is None:
        return {**summary, "candidate": 0, "fit": None}
    fit = fit_mp_pulse(pulse.pulse_cm_s / 100.0, pulse.dt, pulse.tp_s)
    return {**summary, "candidate": classification.candidates.index(pulse) + 1,
            "tp_s": pulse.tp_s, "direction_rad": pulse.direction_rad,
            "pulse_pgv_cm_s": pulse.pulse_pgv_cm_s, "fit": asdict(fit)}


def _key(accelerations: list[np.ndarray], dt: float) -> str:
    digest = hashlib.sha256(f"{CACHE_VERSION} {dt!r} {len(accelerations)}".encode())
    for acceleration in accelerations:
        digest.update(np.ascontiguousarray(acceleration, dtype=float).tobytes())
    return digest.hexdigest()


def pair_velocities(accelerations_m_s2: list[np.ndarray], dt: float):
    """The two velocities [cm/s] the classification takes: one length (the longer cut, as the
    MATLAB does), zeros as the second of a record of one component."""
    # imported where a pulse is identified: its wavelets (scipy.signal) cost ~0.5 s of a
    # check whose records' pulses are all in the cache
    from audit.physics.pulses.shahi_baker_2014 import velocity_cm_s
    if len(accelerations_m_s2) == 1:
        first = velocity_cm_s(accelerations_m_s2[0], dt)
        return first, np.zeros_like(first)
    first, second = accelerations_m_s2
    if abs(first.size - second.size) > MAX_LENGTH_DIFFERENCE:
        raise InputError(f"pulse identification: the two components differ by "
                         f"{abs(first.size - second.size)} samples (at most "
                         f"{MAX_LENGTH_DIFFERENCE})")
    n = min(first.size, second.size)
    return velocity_cm_s(first[:n], dt), velocity_cm_s(second[:n], dt)


def _cache_file(key: str):
    return cache_dir() / "pulses" / f"{key}.json"


def is_cached(accelerations_m_s2: list[np.ndarray], dt: float) -> bool:
    """Whether the summary is in the process or the user cache already."""
    key = _key(accelerations_m_s2, dt)
    return key in _MEMORY or _cache_file(key).is_file()


def classification_summary(accelerations_m_s2: list[np.ndarray], dt: float) -> dict:
    """The cached summary of one or two components (keys as :func:`_summary` writes them)."""
    key = _key(accelerations_m_s2, dt)
    if key in _MEMORY:
        return _MEMORY[key]
    path = _cache_file(key)
    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        from audit.physics.pulses.shahi_baker_2014 import shahi_baker_2014
        summary = _summary(shahi_baker_2014(*pair_velocities(accelerations_m_s2, dt), dt))
        try:
            write_file_atomically(path, json.dumps(summary).encode())
        except InputError:  # the cache is an optimisation: never a reason to stop
            pass
    _MEMORY[key] = summary
    return summary


_STATIONS: dict[tuple, tuple] = {}


def _station(metadata: dict):
    """(component ids, accelerations [m/s²], words) of a P695 station, read once a process (a
    check asks for every record at every stripe)."""
    key = (metadata["p695_record_set"], metadata["p695_record_id"])
    if key not in _STATIONS:
        metas, accelerations = station_components(metadata)
        words = " and ".join(meta["component_name"] for meta in metas)
        _STATIONS[key] = ([meta["id"] for meta in metas], [a * G for a in accelerations],
                          f"{words} (as the package gives them)")
    return _STATIONS[key]


def _components(entry):
    """(accelerations as classified [m/s²], which one is this entry's, words, scale factor)."""
    motion = entry.motion
    if entry.metadata.get("p695_record_set") is None:
        return [motion.acceleration], 0, f"{entry.id} alone (one component)", 1.0
    ids, accelerations, words = _station(entry.metadata)
    index = ids.index(entry.metadata["id"])
    own = accelerations[index]
    peak = int(np.argmax(np.abs(own)))
    scale = float(motion.acceleration[peak] / own[peak]) if own[peak] else 1.0
    if (motion.acceleration.shape != own.shape or scale <= 0.0
            or not np.allclose(motion.acceleration, scale * own, rtol=1e-9,
                               atol=1e-9 * abs(scale * own[peak]))):
        # the motion audited is not the station's component scaled (a floor's motion): the
        # station's pulse is not its pulse
        return accelerations, index, None, scale
    return accelerations, index, words, scale


def classify_entry(entry) -> tuple[PulseClassification, int, float]:
    """The full classification of an entry's record (arrays included, not cached), which of
    the components classified the entry is (0 or 1), and its scale factor (as audited / as
    classified)."""
    from audit.physics.pulses.shahi_baker_2014 import shahi_baker_2014
    accelerations, index, _, scale = _components(entry)
    return (shahi_baker_2014(*pair_velocities(accelerations, entry.motion.dt), entry.motion.dt),
            index, scale)


def record_pulse(entry, cached_only: bool = False) -> RecordPulse | None:
    """The pulse of a suite's entry (see the module docstring); None without a motion, or
    with ``cached_only`` when it has not been identified yet (nothing is computed).

    A record whose two components differ in length by more than 20 samples is not classified,
    as the MATLAB skips it (its components may not start together): ``pulse_like`` False,
    ``pulse_indicator`` NaN and ``classified`` saying why.
    """
    if entry.motion is None:
        return None
    accelerations, index, words, scale = _components(entry)
    nan = math.nan
    if words is None:
        return RecordPulse(entry.id, "not classified: the motion audited is not the station's "
                                     "record scaled (a floor's motion), and the pulse of a floor "
                                     "motion is not identified", False, nan, nan, 0, (), nan,
                           nan, nan, nan, None, 1.0)
    lengths = {a.size for a in accelerations}
    if max(lengths) - min(lengths) > MAX_LENGTH_DIFFERENCE:
        return RecordPulse(entry.id, f"not classified: its components {words} differ by "
                                     f"{max(lengths) - min(lengths)} samples (Shahi & Baker's "
                                     f"MATLAB classifies a pair that differs by at most "
                                     f"{MAX_LENGTH_DIFFERENCE})", False, nan, nan, 0, (), nan,
                           nan, nan, nan, None, scale)
    if cached_only and not is_cached(accelerations, entry.motion.dt):
        return None
    summary = classification_summary(accelerations, entry.motion.dt)
    if not summary["candidate"]:
        return RecordPulse(entry.id, words, False, summary["pulse_indicator"], nan, 0,
                           tuple(summary["candidate_tp_s"]), nan, nan, summary["pgv_cm_s"],
                           nan, None, scale)
    theta = summary["direction_rad"]
    return RecordPulse(entry.id, words, True, summary["pulse_indicator"], summary["tp_s"],
                       summary["candidate"], tuple(summary["candidate_tp_s"]),
                       math.degrees(theta), math.sin(theta) if index else math.cos(theta),
                       summary["pgv_cm_s"], summary["pulse_pgv_cm_s"], MPFit(**summary["fit"]),
                       scale)
