"""Near-fault velocity pulses of a record suite: what ``python -m audit pulse`` prints."""

from __future__ import annotations

import math


def record_pulses(records=None, *, plot: bool = False):
    """The pulse of each record of a suite (Shahi & Baker 2014 and the Mavroeidis &
    Papageorgiou fit, :mod:`audit.physics.pulses.record_pulse`).

    Parameters
    ----------
    records : Records, str, path or records.RecordSuite, optional
        The suite, and how its files are read, as for :func:`audit.api.inputs.record_suite`.
    plot : bool
        Also return the figure of each record's velocity with its pulse.

    Returns
    -------
    pandas.DataFrame, and matplotlib Figure or None
        One row per record with a motion: ``record``, ``pulse_like``, ``tp_s`` (Shahi &
        Baker's, of the first pulse-like candidate), ``pulse_indicator``, ``candidate``,
        ``direction_deg`` (from the first component classified towards the second),
        ``component_factor`` (the pulse's share along this record's component), ``pgv_cm_s``
        (of the record rotated to the pulse's direction), ``pulse_pgv_cm_s``, the fit
        ``mp_tp_s``, ``mp_amplitude_m_s``, ``mp_gamma``, ``mp_nu_deg``, ``mp_t0_s``,
        ``mp_peak_acceleration_g`` (along the pulse), ``mp_rms_cm_s``, and ``classified``.
    """
    import numpy as np
    import pandas as pd

    from audit import G
    from audit.api.inputs import record_suite
    from audit.engine.shared.fields import flag
    from audit.physics.pulses.record_pulse import classify_entry, record_pulse
    from audit.physics.pulses.shahi_baker_2014 import velocity_cm_s

    plot = flag("plot", plot)
    suite = record_suite(records)
    rows, panels = [], []
    for entry in suite:
        found = record_pulse(entry)
        if found is None:
            continue
        fit = found.fit
        nan = math.nan
        rows.append({
            "record": entry.id, "pulse_like": found.pulse_like, "tp_s": found.tp_s,
            "pulse_indicator": found.pulse_indicator, "candidate": found.candidate,
            "direction_deg": found.direction_deg, "component_factor": found.component_factor,
            "pgv_cm_s": found.pgv_cm_s, "pulse_pgv_cm_s": found.pulse_pgv_cm_s,
            "mp_tp_s": fit.period_s if fit else nan,
            "mp_amplitude_m_s": fit.amplitude_m_s if fit else nan,
            "mp_gamma": fit.gamma if fit else nan,
            "mp_nu_deg": math.degrees(fit.nu_rad) if fit else nan,
            "mp_t0_s": fit.t0_s if fit else nan,
            "mp_peak_acceleration_g": fit.peak_acceleration_m_s2 / G if fit else nan,
            "mp_rms_cm_s": 100.0 * fit.rms_m_s if fit else nan,
            "classified": found.classified})
        if plot:
            motion = entry.motion
            time = motion.time
            velocity = velocity_cm_s(motion.acceleration, motion.dt)
            pulse = fitted = None
            if found.pulse_like:
                classification, _, scale = classify_entry(entry)
                along = found.component_factor * scale
                extracted = classification.candidates[found.candidate - 1].pulse_cm_s
                pulse = np.zeros(time.size)
                pulse[:min(time.size, extracted.size)] = along * extracted[:time.size]
                fitted = along * 100.0 * fit.velocity(time)
            words = (f"pulse-like: T_p {found.tp_s:.2f} s (fit 1/f_p {fit.period_s:.2f} s), "
                     f"PI {found.pulse_indicator:.1f}, θ {found.direction_deg:.0f}°, × "
                     f"{found.component_factor:.2f} on this component" if found.pulse_like
                     else found.classified if math.isnan(found.pulse_indicator)
                     else f"not pulse-like (PI {found.pulse_indicator:.2f})")
            panels.append({"title": f"{entry.id}: {words}", "time_s": time,
                           "velocity_cm_s": velocity, "pulse_cm_s": pulse,
                           "fit_cm_s": fitted})
    frame = pd.DataFrame(rows)
    frame.attrs["records"] = suite.description
    if not plot:
        return frame, None
    from reports.pulse_figure import draw_record_pulses
    return frame, draw_record_pulses(panels) if panels else None


def pulse_words(entry, *, cached_only: bool = True) -> str:
    """The pulse of a suite's record in one line, for ``list``: from the cache only by default
    (``python -m audit pulse`` fills it), "" when there is no motion or nothing cached.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    cached_only : bool
        Compute nothing (about a second a record otherwise).
    """
    from audit import G
    from audit.physics.pulses.record_pulse import record_pulse
    found = record_pulse(entry, cached_only=cached_only)
    if found is None:
        return ""
    if math.isnan(found.pulse_indicator):
        return f"pulse {found.classified}"
    if not found.pulse_like:
        return f"not pulse-like (Shahi & Baker 2014: PI {found.pulse_indicator:.2f})"
    return (f"pulse-like (Shahi & Baker 2014): T_p {found.tp_s:.2f} s, PI "
            f"{found.pulse_indicator:.1f}, θ {found.direction_deg:.0f}° (× "
            f"{found.component_factor:.2f} on this component); Mavroeidis-Papageorgiou fit "
            f"1/f_p {found.fit.period_s:.2f} s, γ {found.fit.gamma:.2f}, peak "
            f"{found.fit.peak_acceleration_m_s2 / G:.3f} g along the pulse")
