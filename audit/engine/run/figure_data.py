"""Figure data the report draws but no record audit produces, computed with the run and saved
with it (``design-spectra.csv``, ``mechanics.csv``), so the report renders from files alone.

* the design spectra overlaid on Figures 5.x: UBC 97 (zone 4, soil S_D, N_a = N_v = 1) at 5 %
  for every record, and FEMA 356 at each Figure 5 damping where a record has a FEMA 356 site;
* Figure 7.1, equivalent damping β against r: the free-rocking decay (Eq. 7.9) for θ₀/α =
  0.1 … 0.7 and n = 2 … 8 impacts, with Priestley's fit (Eq. 7.10) and FEMA 356 (Eq. 9.1);
* Figures 4.1 and 7.2: the block p = 2 rad/s, α = 15° under one-cosine pulses of T_p = 2 s of
  0.310, 0.315 and 0.316 g, and its "equivalent" oscillator ω = p, ξ = β(r) of Eq. 7.10.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from audit.engine.shared.schemas import DESIGN_SPECTRA_COLUMNS, MECHANICS_COLUMNS
from audit.engine.run.settings import FIGURE_5_DAMPING, HISTORY_POINTS
from audit.engine.shared.blocks import Block
from audit.physics.block import coefficient_of_restitution
from audit.physics.damping import damping_fema356, damping_free_rocking, damping_priestley
from audit.physics.design_spectra import FEMA356Spectrum, UBC97Spectrum
from audit.physics.oscillator import oscillator_history
from audit.physics.rocking import simulate
from records import one_pulse

#: Periods of the stored design spectra [s].
DESIGN_PERIODS_S = np.linspace(0.0, 8.0, 161)
#: Figure 4.1 vs 7.2: block p = 2 rad/s, α = 15°, one-cosine pulses of T_p = 2 s.
SENSITIVITY_PULSES_G = (0.310, 0.315, 0.316)
SENSITIVITY_BLOCK = {"p": 2.0, "alpha_deg": 15.0, "pulse_period_s": 2.0, "free_motion_s": 8.0}
#: θ₀/α and impacts n of the free-rocking decay curves of Figure 7.1.
FIGURE_7_1_RATIOS = (0.1, 0.3, 0.5, 0.7)
FIGURE_7_1_IMPACTS = (2, 4, 6, 8)


def ubc97_design_spectrum() -> pd.DataFrame:
    """The rows of ``design-spectra.csv`` common to every record: UBC 97 at 5 %."""
    periods = DESIGN_PERIODS_S
    ubc = UBC97Spectrum()
    return pd.DataFrame({"record": "", "code": "UBC 97 zone 4, S_D", "damping_pct": 5.0,
                         "period_s": periods, "sa_g": ubc.acceleration(periods, 0.05),
                         "sd_m": ubc.displacement(periods, 0.05)})[DESIGN_SPECTRA_COLUMNS]


def site_design_spectra(entry) -> pd.DataFrame:
    """The rows of ``design-spectra.csv`` of one record: FEMA 356 at each Figure 5 damping where
    it has a file and a site (none otherwise).

    Parameters
    ----------
    entry : records.RecordEntry
        The record, with its site (``sxs_g``, ``sx1_g`` [g]).
    """
    site = entry.site or {}
    if entry.motion is None or not (site.get("sxs_g") and site.get("sx1_g")):
        return pd.DataFrame(columns=DESIGN_SPECTRA_COLUMNS)
    periods = DESIGN_PERIODS_S
    spectrum = FEMA356Spectrum(site["sxs_g"], site["sx1_g"])
    return pd.concat([pd.DataFrame({"record": entry.id, "code": "FEMA 356",
                                    "damping_pct": 100.0 * d, "period_s": periods,
                                    "sa_g": spectrum.acceleration(periods, d),
                                    "sd_m": spectrum.displacement(periods, d)})
                      for d in FIGURE_5_DAMPING], ignore_index=True)[DESIGN_SPECTRA_COLUMNS]


def mechanics() -> pd.DataFrame:
    """``mechanics.csv``: the curves of Figures 7.1, 4.1 and 7.2."""
    nan = math.nan
    r = np.linspace(0.5, 1.0, 101)[:-1]
    frames = [pd.DataFrame({"figure": "7.1", "series": f"Eq. 7.9, θ₀/α = {ratio:g}, n = {n}",
                            "theta0_ratio": ratio, "impacts": n, "x": r,
                            "y": 100 * damping_free_rocking(ratio, n, r)})
              for ratio in FIGURE_7_1_RATIOS for n in FIGURE_7_1_IMPACTS]
    frames += [pd.DataFrame({"figure": "7.1", "series": name, "theta0_ratio": nan,
                             "impacts": nan, "x": r, "y": 100 * law(r)})
               for name, law in (("Eq. 7.10: β = −0.34 ln r", damping_priestley),
                                 ("Eq. 9.1: β = 0.4 (1 − √r)", damping_fema356))]
    spec = sensitivity_facts()
    alpha = math.radians(spec["alpha_deg"])
    # 2π/(2π/p) is p again for p = 2 rad/s, so the block is the figure's to the last bit
    block = Block(alpha_deg=spec["alpha_deg"], size_s=2.0 * math.pi / spec["p"]).rigid
    for amplitude in SENSITIVITY_PULSES_G:
        motion = one_pulse("cosine", amplitude, spec["pulse_period_s"])
        response = simulate(block, motion, spec["free_motion_s"])
        label = f"a_p = {amplitude:.3f} g"
        stride = max(1, response.time.size // HISTORY_POINTS)
        frames.append(pd.DataFrame({
            "figure": "4.1", "series": label + (" (overturns)" if response.overturned else ""),
            "theta0_ratio": nan, "impacts": nan, "x": response.time[::stride],
            "y": response.theta[::stride] / alpha}))
        time, displacement = oscillator_history(motion, 2.0 * math.pi / spec["p"], spec["beta"],
                                                spec["free_motion_s"])[:2]
        frames.append(pd.DataFrame({"figure": "7.2", "series": label, "theta0_ratio": nan,
                                    "impacts": nan, "x": time[::stride],
                                    "y": displacement[::stride]}))
    return pd.concat(frames, ignore_index=True)[MECHANICS_COLUMNS]


def sensitivity_facts() -> dict:
    """The block of Figures 4.1/7.2 and β [-] of its 'equivalent' oscillator (Eq. 7.10 at r of
    Eq. 4.8), for ``summary.json`` and the figure's titles."""
    alpha = math.radians(SENSITIVITY_BLOCK["alpha_deg"])
    return {**SENSITIVITY_BLOCK, "beta": float(damping_priestley(coefficient_of_restitution(alpha)))}


__all__ = ["ubc97_design_spectrum", "site_design_spectra", "mechanics", "sensitivity_facts",
           "SENSITIVITY_BLOCK", "SENSITIVITY_PULSES_G"]
