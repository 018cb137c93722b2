"""The page of a probabilistic procedure's audit, rendered from its saved files only.

Per component, the procedure's fragility curve beside the exact one: the fraction of records
that overturn at each PGV stripe, the lognormal fitted to those counts and the procedure's
lognormal; then the table of medians, β, Brier scores and log-likelihoods.
"""

from __future__ import annotations

import html
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.special import ndtr

from audit.engine.fragility.pipeline import COMPONENTS_CSV, STRIPES_CSV
from reports.plots import to_json

#: The caveat every page states: what a ground-level audit of a floor-motion fragility tests.
FLOOR_MOTION_CAVEAT = (
    "FEMA P-58 writes these fragilities for peak floor velocity; at the ground floor, it says, "
    "the fragility is based on the ground motion only. This audit scales ground-motion records, "
    "so it tests only that ground-floor clause, not the fragilities of upper floors. Each "
    "component is the block b = depth/2, h = height/2 (uniform contents assumed).")
_CURVE_POINTS = np.geomspace(0.02, 5.0, 200)


def _figure(component: pd.Series, stripes: pd.DataFrame) -> dict:
    def lognormal(median, beta):
        return ndtr(np.log(_CURVE_POINTS / median) / beta)
    return {"data": [
        {"type": "scatter", "mode": "markers", "name": "exact, fraction of records",
         "x": stripes["pgv_m_s"].to_numpy(),
         "y": (stripes["overturned"] / stripes["records"]).to_numpy()},
        {"type": "scatter", "mode": "lines", "name": "exact, lognormal fit",
         "x": _CURVE_POINTS, "y": lognormal(component.exact_median_m_s, component.exact_beta)},
        {"type": "scatter", "mode": "lines", "name": "FEMA P-58", "line": {"dash": "dash"},
         "x": _CURVE_POINTS,
         "y": lognormal(component.procedure_median_m_s, component.procedure_beta)}],
        "layout": {"title": {"text": f"{component.component}: {component.description}"},
                   "xaxis": {"title": {"text": "PGV [m/s]"}, "type": "log"},
                   "yaxis": {"title": {"text": "P(overturn)"}, "range": [0, 1]},
                   "height": 360, "width": 480}}


def render_fragility_page(folder, title: str) -> str:
    """The HTML page of the audit saved in ``folder`` (its CSV files), plotly.js inlined."""
    from plotly.offline import get_plotlyjs
    components = pd.read_csv(Path(folder) / COMPONENTS_CSV)
    stripes = pd.read_csv(Path(folder) / STRIPES_CSV)
    figures = []
    for i, component in components.iterrows():
        spec = _figure(component, stripes[stripes["component"] == component.component])
        figures.append(f'<div id="f{i}" style="display:inline-block"></div><script>'
                       f'(s => Plotly.newPlot("f{i}", s.data, s.layout))({to_json(spec)});'
                       f'</script>')
    columns = ["component", "alpha_deg", "p_rad_s", "exact_median_m_s", "exact_beta",
               "procedure_median_m_s", "procedure_beta", "median_ratio",
               "conservative_at_median", "brier", "log_likelihood", "exact_fit_brier",
               "exact_fit_log_likelihood", "outcomes"]
    source = ""
    if "exact_source" in components and (components["exact_source"] == "atlas").any():
        errors = components["atlas_error"]
        columns.append("atlas_error")
        source = (f"<p>The exact fragilities are from the atlas "
                  f"{html.escape(str(components['atlas_key'].iloc[0])[:12])} (its "
                  f"{stripes['pgv_m_s'].nunique()} PGV stripes, {stripes['pgv_m_s'].min():.4g}–"
                  f"{stripes['pgv_m_s'].max():.4g} m/s), ±{100 * errors.max():.1f} % in P at "
                  f"most over the components (median ±{100 * errors.median():.1f} %); each "
                  f"record's outcome between the atlas's nodes is a probability, and the scores "
                  f"are their expectations.</p>")
    table = components[columns].to_html(index=False, float_format=lambda v: f"{v:.3g}")
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}"
            f"</title><script>{get_plotlyjs()}</script></head><body>"
            f"<h1>{html.escape(title)}</h1>{source}<p>{html.escape(FLOOR_MOTION_CAVEAT)}</p>"
            f"<p>Exact fragility: records scaled to each PGV stripe, lognormal of greatest "
            f"binomial likelihood. median_ratio is the procedure's median over the exact one "
            f"(below 1: the procedure expects overturning at a lower PGV). Brier score and "
            f"log-likelihood score the procedure's probability at every record's scaled PGV "
            f"against the exact outcome; the exact fit's scores, in-sample (fitted to these "
            f"outcomes), are given for comparison.</p>"
            f"{table}{''.join(figures)}</body></html>")
