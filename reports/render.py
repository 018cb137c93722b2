"""The self-contained HTML audit report (SPEC §8), rendered from an :class:`~audit.engine.runner.AuditRun`.

Figures are drawn with matplotlib and embedded as base64 PNG; the page references nothing
outside itself, so it opens offline and can be attached to a design review.
"""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor
from datetime import datetime, timezone
from multiprocessing import get_context

import numpy as np
import pandas as pd
from jinja2 import Environment, PackageLoader, select_autoescape

from audit import G
from audit.physics.block import RigidBlock, coefficient_of_restitution
from audit.physics.damping import damping_fema356, damping_free_rocking, damping_priestley
from audit.physics.design_spectra import FEMA356Spectrum, UBC97Spectrum
from audit.physics.oscillator import oscillator_history
from audit.physics.rocking import simulate
from audit.engine.runner import VERDICTS
from records import one_pulse
from reports import figures

#: Figure 4.1 vs 7.2: block p = 2 rad/s, α = 15°, one-cosine pulses of T_p = 2 s (SPEC §2).
SENSITIVITY_PULSES_G = (0.310, 0.315, 0.316)
SENSITIVITY_BLOCK = {"p": 2.0, "alpha_deg": 15.0, "pulse_period_s": 2.0, "free_motion_s": 8.0}

VERDICT_MEANING = {
    "no-uplift": "PGA ≤ g tan α: neither the block nor the procedure rocks",
    "both-overturn": "both the exact response and the procedure overturn",
    "false-overturn": "the procedure predicts overturning; the block survives",
    "missed-overturn": "the block overturns; the procedure says it survives",
    "conservative": "the procedure's rotation exceeds the exact one beyond the agreement band",
    "unconservative": "the procedure's rotation is below the exact one beyond the agreement band",
    "not-converged": "the procedure's iteration has no fixed point (oscillates)",
    "agrees": "both survive and approx/exact lies within the agreement band",
}


def _environment() -> Environment:
    env = Environment(loader=PackageLoader("reports", "templates"),
                      autoescape=select_autoescape(["html", "j2"]), trim_blocks=True,
                      lstrip_blocks=True)
    env.filters["num"] = lambda v, fmt="{:.3g}": "—" if v is None or (
        isinstance(v, float) and math.isnan(v)) else fmt.format(v)
    return env


class _Figures:
    """Collects figure jobs (a module-level ``draw(fig, *args)`` and a size in inches) and
    draws them together, in worker processes when there are several cores to use."""

    def __init__(self):
        self.jobs = []

    def add(self, draw, args, width, height) -> int:
        self.jobs.append((draw, args, width, height))
        return len(self.jobs) - 1

    def render(self, processes: int) -> list[str]:
        if processes > 1 and len(self.jobs) > 1:
            with ProcessPoolExecutor(processes, mp_context=get_context("fork")) as pool:
                return list(pool.map(_draw_job, self.jobs))
        return [_draw_job(job) for job in self.jobs]


def _draw_job(job) -> str:
    draw, args, width, height = job
    fig = figures.new_figure(width, height)
    draw(fig, *args)
    return figures.data_uri(fig)


def _procedure_summary(procedure: dict, results: pd.DataFrame, names: dict) -> dict:
    """Plain-language verdict of one procedure, with the numbers behind it."""
    rows = results[results["procedure"] == procedure["name"]]
    total = len(rows)
    counts = rows["verdict"].value_counts()
    share = {v: (int(counts.get(v, 0)), 100.0 * counts.get(v, 0) / total if total else 0.0)
             for v in VERDICTS}
    ratios = rows.dropna(subset=["ratio"])
    ratios = ratios[np.isfinite(ratios["ratio"])]

    def where(row):
        return (f"{names.get(row['record'], row['record'])}, α = {row['alpha_deg']:g}°, "
                f"2π/p = {row['size_s']:.2f} s")

    worst_low = ratios.loc[ratios["ratio"].idxmin()] if len(ratios) else None
    worst_high = ratios.loc[ratios["ratio"].idxmax()] if len(ratios) else None
    return {
        **procedure, "blocks": total, "records": int(rows["record"].nunique()), "share": share,
        "median_ratio": float(ratios["ratio"].median()) if len(ratios) else None,
        "min_ratio": float(worst_low["ratio"]) if worst_low is not None else None,
        "min_where": where(worst_low) if worst_low is not None else "",
        "max_ratio": float(worst_high["ratio"]) if worst_high is not None else None,
        "max_where": where(worst_high) if worst_high is not None else "",
    }


def _conclusion(rows: pd.DataFrame) -> str:
    """What a procedure concluded for one block, in a few words."""
    row = rows.iloc[0]
    if row["approx_outcome"] == "converged":
        ratio = row["approx_theta_rad"] / np.radians(row["alpha_deg"])
        return f"T(θ) = {row['approx_period_s']:.2f} s, θ/α = {ratio:.3f}"
    return {"overturn": "predicts overturning", "no-uplift": "predicts no rocking",
            "not-converged": "no fixed point"}.get(row["approx_outcome"], row["approx_outcome"])


def _design_frame(site: dict, dampings, periods) -> pd.DataFrame:
    """Design spectra overlaid on Figure 5.x: FEMA 356 at each damping where the record has
    site parameters, and UBC 97 (zone 4, soil S_D, N_a = N_v = 1) at 5 % on every record."""
    frames = [pd.DataFrame({"code": "UBC 97 zone 4, S_D", "period_s": periods, "damping_pct": 5.0,
                            "sa_g": UBC97Spectrum().acceleration(periods, 0.05),
                            "sd_m": UBC97Spectrum().displacement(periods, 0.05)})]
    if site.get("sxs_g") and site.get("sx1_g"):
        spectrum = FEMA356Spectrum(site["sxs_g"], site["sx1_g"])
        frames += [pd.DataFrame({"code": "FEMA 356", "period_s": periods, "damping_pct": 100.0 * d,
                                 "sa_g": spectrum.acceleration(periods, d),
                                 "sd_m": spectrum.displacement(periods, d)}) for d in dampings]
    return pd.concat(frames, ignore_index=True)


def _record_sections(run, procedures, pending: _Figures) -> list[dict]:
    # records without a file still show the estimate of a procedure that needs none
    results = pd.concat([run.results, run.estimates_only], ignore_index=True)
    spectra, histories = run.spectra, run.histories
    summary = run.summary
    sections = []
    for number, record in enumerate(summary["records"], start=1):
        rid = record["id"]
        section = {"record": record, "number": number, "figures": [],
                   "unauditable": [u for u in summary["unauditable"] if u["record"] == rid]}
        rows = results[results["record"] == rid]
        if not record["missing"]:
            response = spectra[(spectra["record"] == rid) & (spectra["procedure"] == "")]
            rocking = run.rocking[run.rocking["record"] == rid]
            has_site = bool((record.get("site") or {}).get("sxs_g"))
            design = _design_frame(record.get("site") or {}, [d / 100.0 for d in summary["settings"]["figure_5_damping_pct"]],
                                   np.linspace(0.0, 8.0, 321))
            section["figures"].append({
                "id": f"fig-5-{number}", "caption": f"Figure 5.{number} — {record['name']}: true "
                f"response spectra Sd, Sv, Sa (relative displacement, relative velocity, absolute "
                f"acceleration; not pseudo-spectra) for ξ = 5/10/15 % with the design spectra "
                f"{'of FEMA 356 (dashed, site parameters of Table 3.1) and ' if has_site else ''}"
                f"of UBC 97 (dotted, zone 4, soil S_D, 5 %) "
                f"(left), and the exact rocking spectra for α = "
                f"{'/'.join(f'{a:g}' for a in summary['grid']['alpha_deg'])}° (right).",
                "src": pending.add(figures.draw_figure_5,
                                   (response, rocking, record["name"], design), 11, 7.5)})
        for procedure in procedures:
            prows = rows[rows["procedure"] == procedure["name"]]
            if prows.empty:
                continue
            pspec = spectra[(spectra["record"] == rid) & (spectra["procedure"] == procedure["name"])]
            series = procedure["figure_series"] or "P"
            section["figures"].append({
                "id": f"fig-{series}-{number}-{procedure['name']}",
                "caption": f"Figure {series}.{number} — {procedure['title']} on {record['name']}: "
                f"displacement spectrum the procedure reads at its β(α) (left), exact peak rotation "
                f"against the procedure's converged rotation (centre), converged T(θ) of Eq. 8.1 "
                f"(right); one row per α.",
                "src": pending.add(figures.draw_procedure_comparison,
                                   (prows, pspec, record["name"], procedure["title"]),
                                   11, 1.2 + 2.2 * prows["alpha_deg"].nunique())})
        blocks = [h for h in summary["histories"] if h["record"] == rid]
        if blocks:
            drawn = []
            for meta in blocks:
                h = histories[(histories["record"] == rid)
                              & np.isclose(histories["size_s"], meta["size_s"])
                              & np.isclose(histories["alpha_deg"], meta["alpha_deg"])]
                match = rows[np.isclose(rows["size_s"], meta["size_s"])
                             & np.isclose(rows["alpha_deg"], meta["alpha_deg"])]
                drawn.append({
                    "time": h["time_s"].to_numpy(), "theta_ratio": h["theta_ratio"].to_numpy(),
                    "omega": h["omega_rad_s"].to_numpy(),
                    "title": f"2π/p = {meta['size_s']:.2f} s, α = {meta['alpha_deg']:g}°: "
                             f"exact peak θ/α = {meta['peak_rotation_ratio']:.3f}",
                    "rocking_span": (None if meta["first_impact_s"] is None
                                     else (meta["first_impact_s"], meta["last_impact_s"])),
                    "cycle_starts": meta["cycle_starts_s"],
                    "cycle_durations": meta["cycle_durations_s"],
                    "procedures": {p["title"]: _conclusion(match[match["procedure"] == p["name"]])
                                   for p in procedures if (match["procedure"] == p["name"]).any()},
                    "excitation_end": meta["excitation_end_s"]})
            section["figures"].append({
                "id": f"fig-th-{number}", "caption": f"Time histories of representative blocks "
                f"under {record['name']} (as Figures 8.2, 8.5, 8.7, 8.9): θ/α and θ' against "
                f"time; shaded spans are full rocking cycles (every second impact) with their "
                f"durations, to compare with the converged T(θ) of each procedure in the title; "
                f"the dashed line marks the end of the record (time axis zoomed on the rocking).",
                "src": pending.add(figures.draw_time_histories, (drawn,), 11,
                                   0.7 + 3.2 * len(blocks))})
        sections.append(section)
    return sections


def _mechanics(pending: _Figures) -> list[dict]:
    r = np.linspace(0.5, 1.0, 101)[:-1]
    curves = {(ratio, n): damping_free_rocking(ratio, n, r)
              for ratio in (0.1, 0.3, 0.5, 0.7) for n in (2, 4, 6, 8)}
    fig_7_1 = pending.add(figures.draw_figure_7_1,
                          (r, curves, damping_priestley(r), damping_fema356(r)), 9, 5)
    spec = SENSITIVITY_BLOCK
    alpha = math.radians(spec["alpha_deg"])
    block = RigidBlock(spec["p"], alpha)
    beta = float(damping_priestley(coefficient_of_restitution(alpha)))
    rocking, oscillator = {}, {}
    for amplitude in SENSITIVITY_PULSES_G:
        motion = one_pulse("cosine", amplitude, spec["pulse_period_s"])
        response = simulate(block, motion, spec["free_motion_s"])
        label = f"a_p = {amplitude:.3f} g" + (" (overturns)" if response.overturned else "")
        rocking[label] = (response.time, response.theta / alpha)
        oscillator[f"a_p = {amplitude:.3f} g"] = oscillator_history(
            motion, 2.0 * math.pi / spec["p"], beta, spec["free_motion_s"])
    fig_sens = pending.add(figures.draw_sensitivity, (
        rocking, oscillator,
        f"Figure 4.1: rocking block p = {spec['p']:g} rad/s, α = {spec['alpha_deg']:g}°, "
        f"one-cosine pulse T_p = {spec['pulse_period_s']:g} s",
        f"Figure 7.2: 'equivalent' oscillator ω = p, ξ = β = {100 * beta:.2f} % (Eq. 7.10)"),
        11, 4)
    return [
        {"id": "fig-7-1", "src": fig_7_1, "caption": "Figure 7.1 — Equivalent damping β versus "
         "the coefficient of restitution r from the free-rocking decay (Eq. 7.9) for θ₀/α = "
         "0.1 … 0.7 and n = 2 … 8 impacts, with the Priestley et al. fit (Eq. 7.10) and the FEMA "
         "356 law (Eq. 9.1)."},
        {"id": "fig-sensitivity", "src": fig_sens, "caption": "Figure 4.1 vs 7.2 — A 1.6 % "
         "change of pulse amplitude takes the block from a modest rocking to overturning "
         "(left), while the 'equivalent' linear oscillator barely notices (right): the "
         "sensitivity that no equivalent-oscillator procedure can represent."},
    ]


def render_report(run, generated: datetime | None = None, processes: int = 2) -> str:
    """The HTML report of an audit run, as one self-contained string.

    Parameters
    ----------
    run : audit.engine.runner.AuditRun
        Results of ``run_audit`` or of ``audit.engine.results.load_run``.
    generated : datetime, optional
        Time stamp printed in the report (default: now, UTC).
    processes : int
        Worker processes drawing the figures.
    """
    pending = _Figures()
    summary = run.summary
    procedures = summary["procedures"]
    names = {r["id"]: r["name"] for r in summary["records"]}
    audited = [r["id"] for r in summary["records"]
               if (run.results["record"] == r["id"]).any()]
    verdict_maps = []
    for procedure in procedures:
        rows = run.results[run.results["procedure"] == procedure["name"]]
        records = [r for r in audited if (rows["record"] == r).any()]
        if records:
            verdict_maps.append({"procedure": procedure, "src": pending.add(
                figures.draw_verdict_map, (rows, records, names), 11, 1.3 + 1.0 * len(records))})
    statistics = [dict(s, record_name=names.get(s["record"], s["record"]))
                  for s in summary["statistics"]]
    sections = _record_sections(run, procedures, pending)
    mechanics = _mechanics(pending)
    images = pending.render(processes)
    for item in verdict_maps + mechanics + [f for s in sections for f in s["figures"]]:
        item["src"] = images[item["src"]]
    html = _environment().get_template("report.html.j2").render(
        summary=summary, procedures=procedures,
        procedure_summaries=[_procedure_summary(p, run.results, names) for p in procedures],
        verdict_maps=verdict_maps, sections=sections, mechanics=mechanics, statistics=statistics,
        verdicts=VERDICTS, verdict_meaning=VERDICT_MEANING, verdict_colours=figures.VERDICT_COLOURS,
        records=summary["records"], g=G,
        generated=(generated or datetime.now(timezone.utc)).strftime("%Y-%m-%d %H:%M UTC"))
    return html
