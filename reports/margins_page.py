"""The page of a design-level audit (``margins.html``), rendered from its saved files only.

What it shows, in the order an engineer reads it: one sentence per procedure to quote (how
often blocks it accepts overturn in site-consistent records), the required-slenderness chart,
the margins per procedure, the collapse margin ratio over the grid, fragility curves of chosen
blocks with each guideline's line, the fine amplitude scan (why the first overturning intensity
is no number to build on), and the worst blocks.
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd

from audit.engine.shared.schemas import block_labels, upgrade_columns
from records.suite import counted_records
from reports.html_parts import html_table as _table
from reports.html_parts import plot_div as _plot
from reports.block_metres import describe_block
from reports.margins_figures import (cmr_figure, fragility_figure, procedure_colour,
                                     required_figure, scan_figure)
from reports.margins_risk_section import risk_section

MARGINS_HTML = "margins.html"
#: Grid blocks whose fragility curves are drawn when no block is named: per α, these sizes [s].
CURVE_SIZES_S = (1.0, 2.0, 4.0)
#: Rows of the worst-blocks table per procedure.
WORST_ROWS = 5
_CSS = ("body{font-family:DejaVu Sans,Helvetica,Arial,sans-serif;max-width:1100px;margin:2em auto;"
        "padding:0 1em;color:#222}table{border-collapse:collapse;font-size:13px;margin:1em 0}"
        "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#f2f2f2}"
        ".quote{background:#f7f7f0;border-left:4px solid #b58900;padding:.6em 1em;margin:.6em 0}"
        ".note{color:#555;font-size:13px}")



def _keys(frame: pd.DataFrame) -> pd.Series:
    """Which block each row is about: its dimensions, else its grid α and size (the files round
    α and size to different digits, so a named block is matched by name)."""
    grid = frame["alpha_deg"].map("{:.6g}".format) + "|" + frame["size_s"].map("{:.6g}".format)
    labels = block_labels(frame)
    return labels.where(labels != "", grid)



def _site_words(summary) -> str:
    site = summary.get("design_site") or {}
    if not site.get("sxs_g"):
        return "the records as audited"
    scaled = " scaled to the site (FEMA P695)" if summary.get("scaling") else ""
    level = "design-level" if summary.get("site_level") == "design" else "MCE-level"
    return f"S_XS = {site['sxs_g']:g} g, S_X1 = {site['sx1_g']:g} g ({level}){scaled}"


def _sentences(required: pd.DataFrame, summary, titles) -> list[str]:
    """One sentence per procedure: how often the blocks it accepts overturn."""
    records = len(summary["records"])
    out = []
    for name, rows in required.groupby("procedure", sort=False):
        if name.startswith("exact@"):
            continue
        share = rows["exact_overturning_share"].dropna()
        if share.empty:
            out.append(f"{titles.get(name, name)} accepts no block up to α = 40° at any size.")
            continue
        out.append(
            f"Blocks sized by {titles.get(name, name)} for {_site_words(summary)} (the most "
            f"slender block it accepts at each size 2π/p = {rows['size_s'].min():g}–"
            f"{rows['size_s'].max():g} s) overturn in a median {share.median():.0%} "
            f"(range {share.min():.0%}–{share.max():.0%}) of the {records} records audited.")
    return out





def _margins_table(fragility, capacity, required, titles) -> pd.DataFrame:
    exact10 = required[required["procedure"] == "exact@0.10"].set_index("size_s")
    rows = []
    for name, rows_p in capacity.groupby("procedure", sort=False):
        mine = required[required["procedure"] == name].set_index("size_s")
        below = [s for s in mine.index if mine.loc[s, "required_alpha_deg"]
                 < exact10["required_alpha_deg"].get(s, math.nan)]
        rows.append({"procedure": titles.get(name, name),
                     "median line / exact median": rows_p["ratio_to_exact_median"].median(),
                     "median exact P(overturn) at its line (fit)": rows_p["achieved_p_fit"].median(),
                     "same, nearest stripe": rows_p["achieved_p_stripe"].median(),
                     "sizes where it accepts more slender blocks than the exact 10 % curve":
                         f"{min(below):g}–{max(below):g} s ({len(below)} of {len(mine)})"
                         if below else "none"})
    return pd.DataFrame(rows)


def _read(path: Path) -> pd.DataFrame | None:
    """A saved table (an earlier version's columns read too), ``cmr_bound`` as text: empty for
    a CMR that is the fit's (pandas 3 reads an empty field as NaN even through a ``str``
    converter)."""
    if not path.exists():
        return None
    frame = upgrade_columns(pd.read_csv(path))
    if "cmr_bound" in frame:
        frame["cmr_bound"] = frame["cmr_bound"].astype(object).fillna("").astype(str)
    return frame


def render_margins_page(folder) -> str:
    """The HTML page of the design-level audit saved in ``folder``, plotly.js inlined."""
    from plotly.offline import get_plotlyjs
    folder = Path(folder)
    summary = json.loads((folder / "summary.json").read_text())
    read = {name: _read(folder / f"{name}.csv")
            for name in ("stripes", "fragility", "capacity", "required_alpha", "scan")}
    stripes, fragility, capacity = read["stripes"], read["fragility"], read["capacity"]
    required, scan = read["required_alpha"], read["scan"]
    titles = {p["name"]: p["title"] for p in summary["procedures"]}
    names = [p["name"] for p in summary["procedures"]]
    suite = counted_records(len(summary["records"]), summary["records_source"])
    parts = [f"<h1>How safe is a block sized by each guideline?</h1>"
             f"<p>{html.escape(suite)}"
             f", design site {html.escape(_site_words(summary))}; intensity measure "
             f"{html.escape(summary['im'])} [{summary['im_unit']}], {len(summary['levels'])} "
             f"stripes from {min(summary['levels']):.3g} to {max(summary['levels']):.3g}; "
             f"impact model r = {html.escape(summary.get('restitution', 'housner'))} "
             f"(housner: Eq. 4.8).</p>"]
    source = summary.get("exact_source", {})
    atlas = source.get("method") == "atlas"
    if atlas:  # from the atlas, ±x; and what is not (summary.json's exact_source lists it)
        parts.append(f'<p class="quote">{html.escape(source["text"])} The guidelines, the '
                     f'required slenderness and the FEMA P695 acceptance are solved directly; '
                     f'no islands, peak rotations or amplitude scan (they need whole '
                     f'outcomes).</p>')
    if required is not None:
        parts.append("<h2>The numbers to quote</h2>")
        parts += [f'<p class="quote">{html.escape(s)}</p>'
                  for s in _sentences(required, summary, titles)]
        parts.append("<h2>Required slenderness</h2><p>For each size, the most slender block "
                     "(smallest α) each guideline accepts for these records (it predicts "
                     "overturning for at most half of them), against the smallest α above which "
                     "the exact share of records overturning the block stays within 10 % (solid "
                     "black) and 50 % (dotted). Where a guideline's curve lies below the exact "
                     "10 % curve, blocks it accepts overturn in more than 10 % of the records. "
                     "The share is not monotonic in α, so each exact curve is the smallest α "
                     "above which it stays within the target on a 2° search, the last crossing "
                     "bisected to 0.125°.</p>")
        parts.append(_plot("required", required_figure(required, names, titles)))
        parts.append("<h2>Margins per procedure</h2><p>Each guideline's line is where the share "
                     "of records for which it predicts overturning first reaches one half; the "
                     "achieved probability is the exact P(overturn) there. Medians over the "
                     "blocks.</p>")
        parts.append(_table(_margins_table(fragility, capacity, required, titles)))
    if summary.get("acceptance"):
        parts.append("<h2>Would each guideline pass FEMA P695 as a seismic system?</h2><p>The "
                     "blocks each guideline sizes (its required slenderness at every size) get "
                     "their exact fragility; P695 accepts when every one has CMR ≥ ACMR20 % and "
                     "their mean CMR ≥ ACMR10 %, the ACMRs at β_TOT = √(β_RTR² + β_MDL²), "
                     "β_RTR the fitted record-to-record β, β_MDL the ground truth's modelling "
                     "uncertainty measured with the impact model × 0.9 and × 0.8 (spectral "
                     "shape factor 1). Per block in acceptance.csv.</p>")
        parts.append(_table(pd.DataFrame(summary["acceptance"]).assign(
            procedure=lambda f: f["procedure"].map(lambda n: titles.get(n, n)))))
    parts.append("<h3>How each procedure meets the stripes</h3><ul>" + "".join(
        f"<li><b>{html.escape(p['title'])}</b>: {html.escape(p['reads'])}</li>"
        for p in summary["procedures"]) + "</ul>")
    parts += risk_section(folder, summary, fragility, stripes, _keys, titles,
                          lambda name: procedure_colour(names, name))
    if summary.get("design_im") and fragility["width_m"].isna().any():
        extrapolated = int(fragility["median_extrapolated"].sum())
        parts.append("<h2>Collapse margin ratio over the grid</h2><p>CMR = median of the exact "
                     f"fragility / the site's MCE intensity ({summary['mce_im']:.3g} "
                     f"{summary['im_unit']}; FEMA P695 takes the MCE, S_MT: the site's values "
                     + ("are design-level, so the MCE is 1.5 × them" if summary.get("site_level")
                        == "design" else "are taken as MCE-level; were they design-level, "
                        "every CMR here would be 1.5 × too high (site_level design)")
                     + "). Red: below 1, the block is more likely than not to overturn at the "
                     f"MCE. {extrapolated} of {len(fragility)} medians lie beyond the stripes: "
                     "the fit extrapolates there, and the CMR shown is only a bound (the "
                     "outermost stripe / the MCE intensity, flagged in fragility.csv).</p>")
        parts.append(_plot("cmr", cmr_figure(fragility)))
    parts.append("<h2>Fragility curves</h2><p>Dots: the share of records that overturn the "
                 "block at each stripe (not monotonic: islands); line: the lognormal of "
                 "greatest binomial likelihood; dashed verticals: where each guideline draws its "
                 "line (diamond: the exact P there); dotted: the design intensity.</p>")
    stripe_keys, capacity_keys = _keys(stripes), _keys(capacity)
    chosen = _chosen_blocks(fragility)
    for i, (key, (_, block)) in enumerate(zip(_keys(chosen), chosen.iterrows())):
        parts.append(_plot(f"fragility{i}", fragility_figure(
            block, stripes[stripe_keys == key], capacity[capacity_keys == key], names, titles,
            summary)))
    if scan is not None and len(scan):
        parts.append("<h2>Why the first overturning intensity is not a number</h2><p>One record "
                     "scaled in 0.2 % steps around the stripes where it first overturns the "
                     "block: overturning comes and goes in ever narrower windows, so the smallest "
                     "overturning intensity depends on the step of the scan. The share of records "
                     "that overturn at an intensity is the number to build on.</p>")
        for i, (_, rows) in enumerate(scan.groupby([scan["alpha_deg"], scan["size_s"],
                                                    block_labels(scan)], sort=False)):
            parts.append(_plot(f"scan{i}", scan_figure(rows.reset_index(drop=True), summary)))
    parts.append("<h2>Worst blocks</h2><p>Per procedure, the blocks with the largest exact "
                 "probability of overturning where the guideline draws its line.</p>")
    worst = (capacity.dropna(subset=["achieved_p_fit"])
             .sort_values("achieved_p_fit", ascending=False, kind="stable")
             .groupby("procedure", sort=False).head(WORST_ROWS))
    worst = worst.assign(procedure=worst["procedure"].map(lambda n: titles.get(n, n)))
    worst.insert(3, "object", [describe_block(a, s)[2:] for a, s
                               in zip(worst["alpha_deg"], worst["size_s"])])
    parts.append(_table(worst))
    if not atlas:
        parts.append(f"<h2>Islands</h2><p>{(fragility['records_with_islands'] > 0).mean():.0%}"
                     f" of the blocks have at least one record under which the block survives a "
                     f"stripe above its first overturning one; on average "
                     f"{fragility['island_share'].mean():.0%} of the records per block do (at "
                     f"this stripe spacing).</p>")
    title = "Design-level audit: fragility and collapse margins"
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{title}</title>"
            f"<style>{_CSS}</style><script>{get_plotlyjs()}</script></head><body>"
            + "".join(parts) + "</body></html>")


def _chosen_blocks(fragility: pd.DataFrame) -> pd.DataFrame:
    """Blocks whose fragility curves are drawn: the named ones and, per α, the grid blocks of
    :data:`CURVE_SIZES_S` (the nearest sizes of the grid)."""
    named = fragility[fragility["width_m"].notna()]
    grid = fragility[fragility["width_m"].isna()]
    picked = []
    for _, rows in grid.groupby("alpha_deg"):
        sizes = rows["size_s"].to_numpy()
        for size in CURVE_SIZES_S:
            picked.append(rows.index[int(np.argmin(np.abs(sizes - size)))])
    return pd.concat([named, grid.loc[list(dict.fromkeys(picked))]])


__all__ = ["render_margins_page", "MARGINS_HTML"]