"""What ``audit margins`` prints: the design-level audit's bottom line in a few lines of text,
from its tables and summary (:mod:`audit.engine.design.margins`)."""

from __future__ import annotations

import math


def margins_summary_text(run, seconds: float) -> str:
    """The lines ``audit margins`` prints of a design-level audit ``run`` (its ``fragility``,
    ``capacity``, ``required_alpha``, ``risk`` tables and ``summary``) computed in
    ``seconds`` [s], each ending in a newline.

    Parameters
    ----------
    run : MarginsRun
        The design-level audit.
    seconds : float
        The time it took [s].
    """
    fragility, summary = run.fragility, run.summary
    sizes = summary["grid"]["size_s"]
    lines = [f"Fragility of {len(fragility)} blocks on {summary['records_source']} in "
             f"{summary['scheduler']} ({seconds:.1f} s)"
             + (f"; reused {len(summary['resumed'])} records of an interrupted run"
                if summary["resumed"] else "")]
    if summary["design_im"]:
        lines.append(f"  median CMR {fragility['cmr'].median():.2f} (over the MCE "
                     f"{summary['im']} = {summary['mce_im']:.3g} {summary['im_unit']}; "
                     f"{fragility['median_extrapolated'].sum()} medians beyond the stripes give "
                     "bounds)")
    source = summary.get("exact_source", {})
    if source.get("method") == "atlas":
        lines.append(f"  {source['text']} Direct: the guidelines, the required slenderness, "
                     "the acceptance; no islands or scan (whole outcomes)")
    else:
        lines.append(f"  blocks with islands of survival above overturning: "
                     f"{(fragility['records_with_islands'] > 0).mean():.0%}")
    for name, rows in run.capacity.groupby("procedure", sort=False):
        if rows["achieved_p_fit"].isna().all():
            lines.append(f"  {name}: draws no line (it can evaluate none of these records)")
            continue
        lines.append(f"  {name}: median exact P(overturn) where it draws its line "
                     f"{rows['achieved_p_fit'].median():.2f}, its line / exact median "
                     f"{rows['ratio_to_exact_median'].median():.2f}")
    exact = run.required_alpha.set_index(["procedure", "size_s"])["required_alpha_deg"]
    drawn = set(run.required_alpha["procedure"])
    for name in (p["name"] for p in summary["procedures"] if p["name"] in drawn):
        below = [size for size in sizes
                 if exact.get((name, size), math.nan) < exact.get(("exact@0.10", size), math.nan)]
        lines.append(f"  {name} accepts blocks more slender than the exact 10 % curve for "
                     + (f"2π/p = {min(below):g}–{max(below):g} s ({len(below)} of {len(sizes)} "
                        "sizes)" if below else "no size"))
    for verdict in summary.get("acceptance", ()):
        lines.append(f"  {verdict['procedure']} as a seismic system (FEMA P695): "
                     f"{verdict['share_meeting_acmr20']:.0%} of the {verdict['blocks']} blocks "
                     f"it sizes meet ACMR20 %; mean CMR {verdict['mean_cmr']:.2f} against "
                     f"ACMR10 % {verdict['acmr10']:.2f}: "
                     f"{'passes' if verdict['passes'] else 'fails'}")
    if run.risk is not None:
        lines += _risk_lines(run)
    return "".join(f"{line}\n" for line in lines)


def _risk_lines(run) -> list[str]:
    hazard = run.summary["hazard"]
    lines = [f"  at the site ({hazard['source']}), target P {hazard['target_p50']:g} in 50 years:"]
    named = run.risk[run.risk["width_m"].notna()]
    for row in named.itertuples():
        lines.append(f"  block {row.width_m:g}x{row.height_m:g} m: λ_ov "
                     f"{row.annual_rate_fit:.3g}/yr, P in 50 years {row.p50_fit:.3g} (stripe "
                     f"shares: {row.annual_rate_stripes:.3g}/yr); "
                     f"90 % of it from {row.im_low_90_g:.3g}–{row.im_high_90_g:.3g} g")
    return lines


__all__ = ["margins_summary_text"]
