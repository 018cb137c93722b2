"""The section of ``margins.html`` on the risk at a site (``margins --hazard``), drawn from the
saved ``risk.csv``, ``risk_alpha.csv``, ``hazard.csv`` and ``summary.json``: the numbers to
quote per named block with its hazard × fragility figure, the slenderness each size needs for
the risk target beside each guideline's, and the annual rate of overturning over the grid.
"""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np
import pandas as pd

from audit.engine.design.risk import block_fragilities, risk_integral
from audit.engine.shared.schemas import block_labels, upgrade_columns
from records.hazard import HazardCurve
from reports.html_parts import html_table, plot_div
from reports.block_metres import METRES_ROOM_PX, add_metres_axis, block_hover, block_size_m
from reports.plots import alpha_size_map, padded_span, required_alpha_layout
from reports.risk_figure import risk_figure

_EXACT_RISK = "exact@risk"


def _curve(folder: Path, hazard: dict) -> HazardCurve:
    table = pd.read_csv(folder / "hazard.csv")
    return HazardCurve.checked(hazard["im"], table["im_g"], table["annual_rate"],
                               hazard["source"], tuple(hazard["site"] or ()) or None)


def _quote(row, label, target) -> str:
    years = 1.0 / row["annual_rate_fit"] if row["annual_rate_fit"] > 0 else math.inf
    meets = "meets" if row["p50_fit"] <= target else "does not meet"
    return (f"At this site the {label} m block (α = {row['alpha_deg']:.3g}°, 2π/p = "
            f"{row['size_s']:.3g} s) overturns on average once in {years:,.0f} years: λ_ov = "
            f"{row['annual_rate_fit']:.3g}/yr, P = {row['p50_fit']:.2%} in 50 years, which "
            f"{meets} the target {target:.2%}; 90 % of the risk comes from {row['im']} "
            f"{row['im_low_90_g']:.3g}–{row['im_high_90_g']:.3g} g. With the counted stripe "
            f"shares instead of the fit: {row['annual_rate_stripes']:.3g}/yr "
            f"(P {row['p50_stripes']:.2%}).")


def _alpha_figure(risk_alpha, titles, colour_of, target) -> dict:
    data = []
    for name, rows in risk_alpha.groupby("procedure", sort=False):
        exact = name == _EXACT_RISK
        label = (f"exact: P in 50 years ≤ {target:.2%}" if exact else titles.get(name, name))
        data.append({"type": "scatter", "mode": "lines+markers", "x": rows["size_s"],
                     "y": rows["required_alpha_deg"], "name": label, "customdata": rows["p50"],
                     "line": {"color": "#000" if exact else colour_of(name),
                              "width": 2.5 if exact else 1.5, "dash": "solid" if exact else "dash"},
                     "marker": {"size": 4},
                     "hovertemplate": f"{label}<br>2π/p = %{{x:.3g}} s: α ≥ %{{y:.3g}}°<br>"
                                      "P of overturning in 50 years there: %{customdata:.2%}"
                                      "<extra></extra>"})
    figure = {"data": data, "layout": required_alpha_layout()}
    add_metres_axis(figure, padded_span(risk_alpha["size_s"]), room_px=METRES_ROOM_PX)
    return figure


def _map_figure(risk: pd.DataFrame, target_rate: float) -> dict:
    grid = risk[risk["width_m"].isna()]
    pivot = grid.pivot_table(index="alpha_deg", columns="size_s", values="annual_rate_fit",
                             aggfunc="first")
    alphas = pivot.index.to_numpy(dtype=float)
    sizes = pivot.columns.to_numpy(dtype=float)
    rates = pivot.to_numpy(dtype=float)
    with np.errstate(divide="ignore"):
        z = np.log10(rates)
    ticks = np.arange(-7, 0)
    data = [{"type": "heatmap", "x": sizes, "y": alphas, "z": z,
             "customdata": [[[rate, *block_size_m(a, s)] for s, rate in zip(sizes, row)]
                            for a, row in zip(alphas, rates)],
             "zmid": math.log10(target_rate),
             "colorscale": [[0, "#2166ac"], [0.5, "#f7f7f7"], [1, "#b2182b"]], "ygap": 2,
             "colorbar": {"title": {"text": "λ_ov [1/yr]"}, "thickness": 12,
                          "tickvals": ticks, "ticktext": [f"1e{t}" for t in ticks]},
             "hovertemplate": f"α = %{{y:~g}}°, 2π/p = %{{x:~g}} s: {block_hover(1)}<br>"
                              "λ_ov = %{customdata[0]:.3g}/yr<extra></extra>"}]
    return alpha_size_map(data, alphas, sizes)


def risk_section(folder, summary, fragility, stripes, keys, titles, colour_of) -> list[str]:
    """The HTML of the section; empty when the audit had no hazard curve.

    ``keys`` gives which block each row of a table is about (``margins_page._keys``),
    ``colour_of(procedure)`` each guideline's colour on the page.
    """
    folder = Path(folder)
    hazard = summary.get("hazard")
    if not hazard or not (folder / "risk.csv").exists():
        return []
    risk = upgrade_columns(pd.read_csv(folder / "risk.csv"))
    risk_alpha = pd.read_csv(folder / "risk_alpha.csv")
    curve = _curve(folder, hazard)
    target = hazard["target_p50"]
    parts = [f"<h2>Risk at the site</h2><p>Hazard: {html.escape(hazard['source'])}. Each "
             "block's mean annual rate of overturning λ_ov = ∫ P(overturn | im) |dλ/d im| d im "
             "(the hazard curve interpolated log–log), and P = 1 − exp(−50 λ_ov) in 50 years, "
             f"against the risk target {target:.2%} in 50 years (λ = "
             f"{hazard['target_annual_rate']:.3g}/yr). The records' {html.escape(hazard['im'])} "
             "is the 5 %-damped pseudo-spectral acceleration ω²·S_d of the component as "
             "audited; a hazard curve's is the one its ground-motion models predict (often of "
             "RotD50, the orientation-independent median of two horizontal components).</p>"]
    named = risk[risk["width_m"].notna()]
    if len(named):
        parts.append("<p>Per named block: the site's hazard curve (top), the block's exact "
                     "fragility (middle: the fit, and the share of records overturning at each "
                     "stripe), and their product, the share of λ_ov per unit ln im (bottom; "
                     "its kinks are the hazard curve's levels, between which it is a power "
                     "law). Shaded: the intensities of the central 90 % of λ_ov.</p>")
    stripe_keys = keys(stripes)
    for i, (label, row) in enumerate(zip(block_labels(named), named.to_dict("records"))):
        parts.append(f'<p class="quote">{html.escape(_quote(row, label, target))}</p>')
        block = fragility[keys(fragility) == label].iloc[0]
        fitted, counted = block_fragilities(block, stripes[stripe_keys == label])
        if fitted is not None:
            parts.append(plot_div(f"risk{i}", risk_figure(
                curve, fitted, risk_integral(fitted, curve), counted,
                f"{label} m: λ_ov = {row['annual_rate_fit']:.3g}/yr, P in 50 years "
                f"{row['p50_fit']:.2%}; 90 % of it from {row['im_low_90_g']:.3g} to "
                f"{row['im_high_90_g']:.3g} g (shaded)")))
    grid = risk[risk["width_m"].isna()]
    if grid["alpha_deg"].nunique() > 1:
        parts.append("<h3>Slenderness for the risk target</h3><p>Per size, the smallest α "
                     "of the grid's (ln P interpolated between them) above which the exact "
                     "fragility's P of overturning in 50 years stays within the target (solid), "
                     "beside the α each guideline accepts (dashed; hover: its P in 50 years "
                     "at this site). Missing where no α of the grid meets the target, or a "
                     "guideline's α lies outside the grid's.</p>")
        parts.append(plot_div("riskalpha", _alpha_figure(risk_alpha, titles, colour_of,
                                                         target)))
        parts.append(html_table(risk_alpha.assign(procedure=risk_alpha["procedure"].map(
            lambda name: titles.get(name, name)))))
    if len(grid):
        parts.append("<h3>Annual rate of overturning over the grid</h3><p>λ_ov of the "
                     "lognormal fit of each grid block; red: above the risk target, blue: "
                     "below.</p>")
        parts.append(plot_div("riskmap", _map_figure(risk, hazard["target_annual_rate"])))
    if grid["truncated"].any() or named["truncated"].any():
        parts.append('<p class="note">The hazard curve stops below the fragility\'s median '
                     f"for {int(risk['truncated'].sum())} blocks: their λ_ov is a lower bound; "
                     "risk.csv annual_rate_fit_upper bounds it.</p>")
    if len(named):
        parts.append(html_table(named))
    return parts


__all__ = ["risk_section"]
