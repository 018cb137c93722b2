"""NTC 2018 + Circolare 21 Jan 2019 n. 7, §C8.7.1.2.1: local-mechanism checks of a free block.

Implemented from the Circolare's text (§C8.7.1.2.1 and formulas [C8.7.1.3]–[C8.7.1.11]) as the
project transcribed it. A free-standing rectangular block at ground level is one rigid body
rocking about its base corner: α₀ = b/h, e* = 1,
FC = 1, T₀ = 0, control point the centroid, so the spectral displacement is the centroid's,
d = R [sin α − sin(α − θ)], and instability is at d₀ = b. The procedure *verifies* the block:

* SLD (§C8.7.1.2.1.5, [C8.7.1.9]): S_e(T₀ = 0) = PGA ≤ a₀ = α₀ g/(e* FC); with e* = FC = 1
  this is exactly the rigid-block uplift criterion.
* SLV, linear (§C8.7.1.2.1.7): PGA/q ≤ a₀, q = 2.
* SLV and SLC in displacement (§C8.7.1.2.1.6, §C8.7.1.2.1.8): the demand read at the reduced
  period T_SLV = 1.68π√(d_SLV/a(d_SLV)) [C8.7.1.10] (T_SLC = 1.56π√(d_SLC/a(d_SLC))
  [C8.7.1.11]) at ξ = 8 % (10 %) must not exceed d_SLV = 0.4 d₀ (d_SLC = 0.6 d₀). a(d) is the
  capacity curve in spectral acceleration, a = α(d) g/(e* FC) [C8.7.1.3], with the exact
  multiplier α(d) = tan(α − θ(d)) or the linearised (b/h)(1 − d/b). Where the SLD check passes
  the SLV one does too: "if a_g,SLV < a_g,SLD, a_g,SLD is used for SLV" (§C8.7.1.2.1.8).

The demand comes in two variants, chosen per record (:meth:`NTC2018.demand_variant`):

* *code-spectrum* when the record's site carries NTC parameters (:data:`SITE_KEYS`, all five
  then required): S_De(T_LS, ξ) of NTC §3.2.3.2 (:class:`~audit.physics.ntc2018_spectrum.
  NTC2018Spectrum`), PGA = a_g S;
* *record-based* otherwise (the recorded motion is then required): the largest Sd of the
  record's true spectrum at ξ over [T₀, T_LS] (the Circolare's rule for accelerograms), PGA of
  the record.

On a floor (:attr:`NTC2018.floor` above the ground) the code-spectrum variant reads the
Circolare's floor spectrum for elements at height (§C7.2.3, [C7.2.11],
:class:`~audit.physics.ntc2018_floor_spectrum.NTC2018FloorSpectrum`) at the block's periods in
place of the site's, and the floor's peak acceleration α·S·(1 + z/H) in place of a_g·S; the
record-based variant reads the record given, which on a floor is the floor motion.

The rotation the audit compares with the exact peak is θ(d_dem(T_SLV)) at ξ_SLV: 0 where the
SLD check passes (the block does not rock), overturning where d_dem ≥ d₀.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from audit import G
from audit.errors import InputError
from audit.physics.block import radius_from_p, rotation_at_displacement
from audit.physics.building.floor import Floor
from audit.physics.ntc2018_floor_spectrum import NTC2018FloorSpectrum
from audit.physics.ntc2018_spectrum import NTC2018Spectrum
from records.sites import NTC2018_SITE_KEYS as SITE_KEYS
from procedures.parameters import Parameter
from procedures.base import (CONVERGED, EXACT_ROTATION, EXACT_UPLIFT, NO_UPLIFT, OVERTURN,
                             STORED_SPECTRUM_PERIODS_S, Check, Estimate, Evaluation, Procedure)

# Demand variants.
AUTO = "auto"
RECORD_BASED = "record"
CODE_SPECTRUM = "code-spectrum"
#: d_LS/d₀ (§C8.7.1.2.1.6).
THRESHOLD_RATIO = {"SLV": 0.4, "SLC": 0.6}
#: c of T_LS = c·π·√(d_LS/a(d_LS)), [C8.7.1.10] and [C8.7.1.11].
PERIOD_COEFFICIENT = {"SLV": 1.68, "SLC": 1.56}


def spectral_acceleration(displacement_m, alpha_rad, radius_m, e_star=1.0,
                          confidence_factor=1.0, linear=False, g=G):
    """Capacity curve a(d) = α(d)·g/(e*·FC) [m/s²] of the block (Eq. C8.7.1.3, one rigid body rocking about its base corner).

    Parameters
    ----------
    displacement_m : float or array
        Spectral (= centroid) displacement d [m], 0 ≤ d ≤ d₀ = b.
    alpha_rad : float
        Slenderness α [rad].
    radius_m : float or array
        R [m].
    e_star, confidence_factor : float
        Participating mass fraction e* [-] (Eq. C8.7.1.5; 1 for one block) and FC [-].
    linear : bool
        The linearised multiplier α(d) = (b/h)(1 − d/b) instead of the exact tan(α − θ(d)).
    g : float
        Acceleration of gravity [m/s²].
    """
    if linear:
        multiplier = np.tan(alpha_rad) * (1.0 - displacement_m / (radius_m * np.sin(alpha_rad)))
    else:
        multiplier = np.tan(alpha_rad - rotation_at_displacement(displacement_m, alpha_rad,
                                                                 radius_m))
    return multiplier * g / (e_star * confidence_factor)


def limit_state_period(displacement_m, acceleration_m_s2, coefficient):
    """Reduced secant period T_LS = c·π·√(d_LS/a(d_LS)) [s] (Eqs. C8.7.1.10, C8.7.1.11)."""
    return coefficient * np.pi * np.sqrt(displacement_m / acceleration_m_s2)


def running_maximum(period_s, values, upto_s):
    """max of a piecewise-linear spectrum over [period_s[0], upto_s], for many upper ends.

    Parameters
    ----------
    period_s : array
        Increasing periods of the tabulated spectrum [s].
    values : array
        Spectrum at those periods (e.g. Sd [m]), linear in between.
    upto_s : float or array
        Upper ends of the interval [s], ≥ period_s[0]; beyond the table the last value holds.
    """
    peaks = np.maximum.accumulate(values)
    last = np.searchsorted(period_s, upto_s, side="right") - 1  # last tabulated period ≤ upto
    return np.maximum(peaks[last], np.interp(upto_s, period_s, values))


@dataclass(frozen=True)
class NTC2018(Procedure):
    """NTC 2018 / Circolare 2019 local-mechanism checks of a free-standing block, with the
    choices the text leaves open as options.

    Attributes
    ----------
    e_star : float
        e* [-]: 1 as the Circolare's formula gives for one block; 0.75 for a block sliced into
        distributed masses. It scales the spectral acceleration a = α g/(e* FC) only.
    linear_curve : bool
        Linearised capacity curve instead of the exact one.
    demand : str
        ``auto`` (see the module docstring), ``record`` or ``code-spectrum``.
    damping_slv, damping_slc : float
        ξ of the mechanism for SLV and SLC [-] (8 % and 10 % per the text).
    confidence_factor : float
        FC [-] (1 for the audit).
    behaviour_factor : float
        q of the linear SLV check [-].
    floor : audit.physics.building.floor.Floor
        Where the block stands; above the ground the code spectrum is the floor spectrum.
    """

    e_star: float = 1.0
    linear_curve: bool = False
    demand: str = AUTO
    damping_slv: float = 0.08
    damping_slc: float = 0.10
    confidence_factor: float = 1.0
    behaviour_factor: float = 2.0
    floor: Floor = Floor()

    name = "ntc2018"
    rotation_limits = True  # SLV and SLC on d/d₀: θ short of α
    alpha_per_block = True
    title = "NTC 2018 / Circolare 2019"
    reference = ("NTC 2018, D.M. 17 gennaio 2018, §3.2.3.2; Circolare 21 gennaio 2019 n. 7 "
                 "C.S.LL.PP., §C8.7.1.2.1 (local mechanisms, kinematic analysis).")
    damping_law = "ξ = 8 % (SLV), 10 % (SLC) of the mechanism (§C8.7.1.2.1.8), whatever r"
    spectrum_source = ("NTC 2018 elastic displacement spectrum S_De (Eqs. 3.2.2–3.2.12) of the "
                       "site, or the record's largest Sd over [0, T_LS]; read at T_SLV "
                       "[C8.7.1.10] and T_SLC [C8.7.1.11]")

    parameters = (
        Parameter("q", "behaviour_factor", "-", "behaviour factor of the linear SLV check",
                  "§C8.7.1.2.1.7: q = 2.0", True, 1.0, 4.0),
        Parameter("e_star", "e_star", "-", "participating mass fraction e*",
                  "[C8.7.1.5] for one rigid block: 1.0", True, 0.0, 1.0, low_open=True),
        Parameter("FC", "confidence_factor", "-", "confidence factor",
                  "1.0, the audit's choice (the Circolare's knowledge levels LC1–LC3 give "
                  "1.35, 1.2, 1.0)", False, 1.0, 1.35),
        Parameter("xi_SLV", "damping_slv", "-", "damping ratio of the mechanism at SLV",
                  "§C8.7.1.2.1.8: 0.08", True, 0.0, 0.3),
        Parameter("xi_SLC", "damping_slc", "-", "damping ratio of the mechanism at SLC",
                  "§C8.7.1.2.1.8: 0.10", True, 0.0, 0.3),
    )

    def __post_init__(self):
        super().__post_init__()
        if self.demand not in (AUTO, RECORD_BASED, CODE_SPECTRUM):
            raise InputError(f"ntc2018 demand: must be {AUTO}, {RECORD_BASED} or "
                             f"{CODE_SPECTRUM}, got {self.demand!r}")

    def demand_variant(self, entry) -> str:
        """``code-spectrum`` when forced or the site has an NTC key, else ``record``."""
        if self.demand != AUTO:
            return self.demand
        return CODE_SPECTRUM if any(key in entry.site for key in SITE_KEYS) else RECORD_BASED

    def spectrum_read(self, entry) -> str:
        """The site's code spectrum (its parameters, S and on a floor the Circolare's floor
        spectrum) or the record's own, in words."""
        if self.demand_variant(entry) == RECORD_BASED:
            return "each record's own displacement spectrum (its largest Sd over [0, T_LS])"
        ground = NTC2018Spectrum.from_site(entry.site)
        words = (f"NTC 2018 elastic spectrum S_De (§3.2.3.2) of the site a_g = {ground.ag_g:g} g, "
                 f"F0 = {ground.f0:g}, T_C* = {ground.tc_star_s:g} s, soil {ground.soil}, "
                 f"topography {ground.topography} (S = S_S·S_T = {ground.soil_factor:.4g}), "
                 "the values of the limit state assessed")
        if self.floor.on_ground:
            return words
        return f"the Circolare's floor spectrum (§C7.2.3) at z/H = {self.floor.z_over_h:g} of the {words}"

    def reads_record(self, entry) -> bool:
        return self.demand_variant(entry) == RECORD_BASED

    def unmet_requirements(self, entry) -> str | None:
        if self.demand_variant(entry) == CODE_SPECTRUM:
            missing = [key for key in SITE_KEYS if entry.site.get(key) is None]
            return f"no {self.title} site parameters ({', '.join(missing)})" if missing else None
        if entry.motion is None:
            return (f"no record file ({entry.missing_reason}) and no {self.title} site "
                    f"({', '.join(SITE_KEYS)})")
        return None

    def damping(self, r):
        return self.damping_slv

    def site_spectrum(self, entry) -> NTC2018Spectrum | NTC2018FloorSpectrum:
        """The NTC 2018 elastic spectrum of the record's site; on a floor, the Circolare's floor
        spectrum (§C7.2.3) of it."""
        ground = NTC2018Spectrum.from_site(entry.site)
        if self.floor.on_ground:
            return ground
        return NTC2018FloorSpectrum(ground, self.floor.z_over_h, self.floor.building.period_s)

    def peak_ground_acceleration(self, entry, context):
        """S_e(T₀ = 0) [m/s²]: a_g·S of the site (α·S·(1 + z/H) on a floor), or the record's
        PGA."""
        if self.demand_variant(entry) == CODE_SPECTRUM:
            return float(self.site_spectrum(entry).acceleration(0.0, self.damping_slv)) * G
        return entry.motion.pga

    def displacement_spectrum(self, entry, damping, context):
        """Demand spectrum [m] at damping ξ: S_De(T), or max of the record's Sd over [0, T]."""
        if self.demand_variant(entry) == CODE_SPECTRUM:
            spectrum = self.site_spectrum(entry)
            return lambda period_s: spectrum.displacement(period_s, damping)
        spectra = context.true_spectra(damping, displacement_only=True)
        return lambda period_s: running_maximum(spectra.period_s, spectra.sd[0], period_s)

    def thresholds(self, p, alpha_rad: float, g: float = G) -> dict:
        """d_LS [m] and T_LS [s] of SLV and SLC: ``{"SLV": (d_m, period_s), "SLC": …}``."""
        radius = radius_from_p(np.asarray(p, dtype=float), g)
        out = {}
        for state, ratio in THRESHOLD_RATIO.items():
            d_m = ratio * radius * np.sin(alpha_rad)  # d₀ = R sin α = b
            a_m_s2 = spectral_acceleration(d_m, alpha_rad, radius, self.e_star,
                                           self.confidence_factor, self.linear_curve, g)
            out[state] = (d_m, limit_state_period(d_m, a_m_s2, PERIOD_COEFFICIENT[state]))
        return out

    def checks(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> list[Check]:
        """SLD, linear SLV, SLV and SLC checks of the blocks (see the module docstring)."""
        p = np.asarray(p, dtype=float)
        radius = radius_from_p(p, g)
        nan = np.full(p.shape, np.nan)
        pga = np.full(p.shape, self.peak_ground_acceleration(entry, context))
        a_0 = np.full(p.shape, spectral_acceleration(0.0, alpha_rad, radius, self.e_star,
                                                     self.confidence_factor, False, g))
        sld_passes = pga <= a_0
        thresholds = self.thresholds(p, alpha_rad, g)
        slv_limit = rotation_at_displacement(thresholds["SLV"][0], alpha_rad, radius)
        checks = [
            Check("SLD", EXACT_UPLIFT, sld_passes, nan, nan, pga, a_0, nan, nan, nan,
                  "S_e(T₀ = 0) ≤ α₀ g/(e* FC) [C8.7.1.9]: the uplift criterion when e* = FC = 1"),
            Check("SLV-linear", EXACT_ROTATION, pga / self.behaviour_factor <= a_0, nan, nan,
                  pga / self.behaviour_factor, a_0, nan, slv_limit, nan,
                  f"a_g S/q ≤ α₀ g/(e* FC), q = {self.behaviour_factor:g} (§C8.7.1.2.1.7)")]
        for state, damping in (("SLV", self.damping_slv), ("SLC", self.damping_slc)):
            capacity_m, period_s = thresholds[state]
            demand_m = self.displacement_spectrum(entry, damping, context)(period_s)
            passes = demand_m <= capacity_m
            rule = ""
            if state == "SLV":
                passes = passes | sld_passes
                rule = "; passes where SLD passes (a_g,SLV ≥ a_g,SLD)"
            stable = demand_m < radius * np.sin(alpha_rad)
            checks.append(Check(
                state, EXACT_ROTATION, passes, demand_m, capacity_m, nan, nan,
                np.where(stable, rotation_at_displacement(demand_m, alpha_rad, radius), np.nan),
                rotation_at_displacement(capacity_m, alpha_rad, radius), period_s,
                f"d_dem(T_{state}, ξ = {100 * damping:g} %) ≤ {THRESHOLD_RATIO[state]:g} d₀, "
                f"T_{state} = {PERIOD_COEFFICIENT[state]:g}π√(d/a(d)) "
                f"[C8.7.1.{10 if state == 'SLV' else 11}]{rule}"))
        return checks

    def evaluate(self, entry, p, alpha_rad: float, r: float, context, g: float = G) -> Evaluation:
        """The four checks, and the rotation θ(d_dem(T_SLV)) at ξ_SLV [rad] they imply: 0 where
        SLD passes, overturning where d_dem ≥ d₀; the demand spectrum read at ξ_SLV."""
        evaluation = self.evaluate_for_verdict(entry, p, alpha_rad, r, context, g)
        spectrum = self.displacement_spectrum(entry, self.damping_slv, context)
        return replace(evaluation, spectrum_sd_m=spectrum(STORED_SPECTRUM_PERIODS_S))

    def evaluate_for_verdict(self, entry, p, alpha_rad, r, context,
                             g: float = G) -> Evaluation:
        """:meth:`evaluate` without the stored spectrum; α and r may be arrays of p's shape
        (:attr:`~procedures.base.Procedure.alpha_per_block`)."""
        checks = self.checks(entry, p, alpha_rad, r, context, g)
        by_state = {check.limit_state: check for check in checks}
        sld, slv = by_state["SLD"], by_state["SLV"]
        over = ~sld.passes & np.isnan(slv.demand_theta_rad)
        outcome = np.select([sld.passes, over], [NO_UPLIFT, OVERTURN], CONVERGED).astype(object)
        theta = np.where(sld.passes, 0.0, slv.demand_theta_rad)
        period = np.where(sld.passes, 0.0, np.where(over, np.nan, slv.period_s))
        estimate = Estimate(theta=theta, period_s=period,
                            iterations=np.zeros(theta.shape, dtype=int), outcome=outcome,
                            detail=np.full(theta.shape, "", dtype=object),
                            damping=self.damping_slv,
                            # no iteration, so no fixed points or cycles to report
                            fixed_points=np.full(theta.shape, "", dtype=object),
                            cycle=np.full(theta.shape, "", dtype=object))
        return Evaluation(estimate, None, checks)
