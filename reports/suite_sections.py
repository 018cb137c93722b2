"""The whole-suite sections of the run report (:mod:`reports.render`): the block mechanics
behind the verdicts, the suite statistics with the ratio bands, the limit-state checks, and
the reproduction checklist; each returns what the template shows, its figures added to the
page's figure list."""

from __future__ import annotations

from collections import Counter, defaultdict

import numpy as np

from audit.engine.shared.verdicts import CHECK_VERDICTS, CLAIM_STATUSES, meanings, names
from reports.grid_figures import MapColours, grid_map_figure, ratio_band_figure
from reports.history_figures import lines_figure, sensitivity_figure
from reports.palette import CHECK_COLOURS

CHECK_MEANING = meanings(CHECK_VERDICTS)
CLAIM_STATUS_NAMES = names(CLAIM_STATUSES)


def mechanics_section(run, pending) -> list[dict]:
    """Figures 7.1 and 4.1 vs 7.2, from the run's ``mechanics.csv``."""
    curves = run.mechanics
    dashes = {2: "solid", 4: "dash", 6: "dashdot", 8: "dot"}
    shades = {0.1: "#440154", 0.3: "#31688e", 0.5: "#35b779", 0.7: "#b5de2b"}
    laws = {"Eq. 7.10": "#d62728", "Eq. 9.1": "#000000"}
    series = []
    for name, rows in curves[curves["figure"] == "7.1"].groupby("series", sort=False):
        ratio, impacts = rows["theta0_ratio"].iloc[0], rows["impacts"].iloc[0]
        if np.isfinite(ratio):
            style = {"colour": shades[round(ratio, 6)], "dash": dashes[int(impacts)], "width": 1}
        else:
            style = {"colour": laws[name.split(":")[0]], "width": 3}
        series.append({"x": rows["x"].to_numpy(), "y": rows["y"].to_numpy(), "name": name,
                       **style})
    fig_7_1 = pending.add("fig-7-1", lines_figure(
        series, "coefficient of restitution r [-]", "equivalent damping β [%]", height=460,
        legend_below=True))
    fig_7_1["caption"] = (
        "Figure 7.1 — Equivalent damping β versus the coefficient of restitution r from the "
        "free-rocking decay (Eq. 7.9) for θ₀/α = 0.1 … 0.7 (colour) and n = 2 … 8 impacts "
        "(dash), with the Priestley et al. fit (Eq. 7.10) and the FEMA 356 law (Eq. 9.1). "
        "Click a legend entry to hide a curve.")
    spec = run.summary["mechanics"]

    def histories(figure):
        rows = curves[curves["figure"] == figure]
        return {name: (group["x"].to_numpy(), group["y"].to_numpy())
                for name, group in rows.groupby("series", sort=False)}
    fig_sens = pending.add("fig-sensitivity", sensitivity_figure(
        histories("4.1"), histories("7.2"),
        f"Figure 4.1: rocking block p = {spec['p']:g} rad/s, α = {spec['alpha_deg']:g}°, "
        f"one-cosine pulse T_p = {spec['pulse_period_s']:g} s",
        f"Figure 7.2: 'equivalent' oscillator ω = p, ξ = β = {100 * spec['beta']:.2f} % "
        "(Eq. 7.10)"))
    fig_sens["caption"] = (
        "Figure 4.1 vs 7.2 — A 1.6 % change of pulse amplitude takes the block from a modest "
        "rocking to overturning (left), while the 'equivalent' linear oscillator barely notices "
        "(right): the sensitivity that no equivalent-oscillator procedure can represent.")
    return [fig_7_1, fig_sens]


def suite_section(run, procedures, pending) -> dict | None:
    suite = run.suite
    if suite is None or suite.empty:
        return None
    maps, sentences = [], []
    present = [p for p in procedures if (suite["procedure"] == p["name"]).any()]
    reds = [[0, "#ffffff"], [0.25, "#fcbba1"], [0.5, "#fb6a4a"], [1, "#67000d"]]
    if present:
        figure = pending.add("suite-unsafe", grid_map_figure(
            suite, "frac_unsafe", [(p["title"], suite["procedure"] == p["name"]) for p in present],
            lambda title: title, "{title}<br>α = %{y:~g}°, 2π/p = %{x:.2f} s: {block}<br>"
            "unsafe for %{z:.1%} of the records<extra></extra>",
            MapColours(reds, 0, 1, "unsafe")))
        figure["caption"] = ("Share of the records for which each guideline is unsafe "
                             "(missed overturning or underestimate beyond the band), per block.")
        maps.append(figure)
    # the quotable sentences of summary.json (audit.engine.run.suite.suite_summary), at α = 15°
    # where the grid has it
    quoted = run.summary.get("suite") or []
    for p in present:
        rows = suite[suite["procedure"] == p["name"]]
        mine = [item for item in quoted if item["procedure"] == p["name"]]
        pick = next((item for item in mine if item["alpha_deg"] == 15.0), mine[0] if mine else None)
        if pick is not None:
            sentences.append(pick["sentence"][0].upper() + pick["sentence"][1:] + ".")
        if rows[["ratio_p16", "ratio_p50", "ratio_p84"]].notna().any().any():
            figure = pending.add(f"suite-ratio-{p['name']}", ratio_band_figure(rows))
            figure["caption"] = (f"{p['title']}: median approx/exact over the records where "
                                 f"both survive, with the 16–84 % band, per α.")
            maps.append(figure)
    return {"figures": maps, "sentences": sentences}


def checks_section(run, names, pending, detail_ids) -> dict | None:
    # the columns drawn and counted only: every selection below copies fewer
    checks = run.checks.loc[run.checks["record"].isin(detail_ids),
                            ["procedure", "limit_state", "record", "verdict", "alpha_deg",
                             "size_s"]]
    if checks.empty:
        return None
    titles = {p["name"]: p["title"] for p in run.summary["procedures"]}
    classes = list(CHECK_MEANING)
    tallies = defaultdict(Counter)  # per procedure, limit state and record, in order of rows
    keyed = checks[checks[["procedure", "limit_state", "record"]].notna().all(axis=1)]
    for procedure, state, record, verdict in zip(*(keyed[c].tolist() for c in (
            "procedure", "limit_state", "record", "verdict"))):
        tallies[procedure, state, record][verdict] += 1
    confusion = [{"procedure": titles.get(procedure, procedure), "limit_state": state,
                  "record": names.get(record, record),
                  "counts": {c: counts[c] for c in classes}}
                 for (procedure, state, record), counts in tallies.items()]
    codes = checks.assign(code=checks["verdict"].map({c: i for i, c in enumerate(classes)}))
    scale = []
    for i, c in enumerate(classes):
        scale += [[i / len(classes), CHECK_COLOURS[c]],
                  [(i + 1) / len(classes), CHECK_COLOURS[c]]]
    figures = []
    for (procedure, state), rows in codes.groupby(["procedure", "limit_state"], sort=False):
        records = rows["record"].unique().tolist()
        figure = pending.add(f"checks-{procedure}-{state}", grid_map_figure(
            rows, "code", [(r, rows["record"] == r) for r in records],
            lambda r: names.get(r, r),
            "{title}<br>α = %{y:~g}°, 2π/p = %{x:.2f} s: {block}<br>"
            f"{state}: " + "%{text}<extra></extra>",
            MapColours(scale, -0.5, len(classes) - 0.5, labels=classes)))
        figure["caption"] = (f"Limit-state check {state} of {titles.get(procedure, procedure)} "
                             "against the exact response, one panel per record.")
        figures.append(figure)
    return {"confusion": confusion, "classes": classes, "figures": figures}


def claims_section(run) -> dict | None:
    claims = run.claims
    if claims is None or claims.empty:
        return None
    counts = claims["status"].value_counts()
    return {"rows": claims.to_dict("records"),
            "tally": {s: int(counts.get(s, 0)) for s in CLAIM_STATUS_NAMES}}


__all__ = ["mechanics_section", "suite_section", "checks_section", "claims_section",
           "CHECK_MEANING", "CLAIM_STATUS_NAMES"]
