"""The page of a campaign's validation, drawn from its saved files only (plotly.js inlined).

Per specimen: the outcome map in the dimensionless plane (PGA/(g tan α̂), p̂·PGV/PGA) with the
fitted model's 50 % line, the calibration of the cross-validated probabilities and the α–p
ridge of the profile likelihood; then the fitted blocks beside the geometry (the ridge's 95 %
region where α̂ or p is not identified), the predictions and their bands, the scores of model,
baselines and peer columns, and where
the model fails.
"""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np
import pandas as pd

from audit.engine.validation.baselines import VectorLogistic
from audit.engine.validation.cross_validation import MODEL, PGA, PGV, VECTOR
from audit.engine.validation.pipeline import (FITS_CSV, PREDICTIONS_CSV, RIDGE_CSV, SCORES_CSV,
                                              TESTS_CSV, methods_statement)
from reports.html_parts import PAGE_STYLE, html_table
from reports.plots import to_json

VALIDATION_HTML = "validation.html"
#: Edges of the probability bins of the calibration plot.
CALIBRATION_EDGES = np.linspace(0.0, 1.0, 11)
#: Edges of the PGA bins of the table of failures [g].
PGA_EDGES_G = (0.0, 0.1, 0.2, 0.3, 0.5, 0.8, 1.2, 10.0)
_SCORE_HEADINGS = {"log_loss": "log-loss", "true_positive": "TP", "false_positive": "FP",
                   "true_negative": "TN", "false_negative": "FN",
                   "brier_minus_model": "Brier − model's", "brier_minus_model_se": "± SE"}
_OUTCOME_STYLE = {1.0: ("overturned", "#d62728", "x"), 0.0: ("stood", "#1f77b4", "circle-open")}


def _fifty_percent_line(tests: pd.DataFrame, fit) -> dict | None:
    """The model's 50 % line in the plane: its full-fit probabilities on these tests smoothed
    by a logistic in ln PGA and ln(PGV/PGA) (the probability depends on the whole motion, so
    any line in a two-number plane is a projection). None where the model puts every test on
    one side of 50 % (e.g. a campaign where every test overturned): the smoothing logistic's
    coefficients then run off to infinity and no line crosses the tests."""
    p = tests["p_model"].to_numpy(dtype=float)
    if not ((p > 0.5).any() and (p < 0.5).any()):
        return None
    smooth = VectorLogistic.fit(tests["pga_g"], tests["pgv_pga_s"], tests["p_model"], 1e-9)
    b0, b1, b2 = smooth.coefficients
    if b2 == 0.0:  # the line does not depend on PGV/PGA: vertical, off this parametrisation
        return None
    tan_alpha = math.tan(math.radians(fit.alpha_deg))
    reach = tests["pga_g"] / tan_alpha
    x = np.geomspace(reach.min(), reach.max(), 120)
    y = fit.p_rad_s * np.exp(-(b0 + b1 * np.log(x * tan_alpha)) / b2)
    return {"type": "scatter", "mode": "lines", "name": "model, 50 % (smoothed)",
            "x": x, "y": y, "line": {"color": "black"}}


def _outcome_map(tests: pd.DataFrame, fit) -> dict:
    tan_alpha = math.tan(math.radians(fit.alpha_deg))
    x = tests["pga_g"] / tan_alpha
    y = fit.p_rad_s * tests["pgv_pga_s"]
    data = []
    for value, (name, colour, symbol) in _OUTCOME_STYLE.items():
        chosen = tests["observed"] == value
        data.append({"type": "scatter", "mode": "markers", "name": f"observed {name}",
                     "x": x[chosen], "y": y[chosen], "text": tests["test"][chosen].astype(str),
                     "marker": {"color": colour, "symbol": symbol, "size": 7}})
    unknown = tests["observed"].isna()
    data.append({"type": "scatter", "mode": "markers", "name": "no outcome (predicted)",
                 "x": x[unknown], "y": y[unknown], "text": tests["test"][unknown].astype(str),
                 "marker": {"color": "#999999", "size": 4}})
    line = _fifty_percent_line(tests, fit)
    if line is not None:
        data.append(line)
    return {"data": data, "layout": {
        "title": {"text": f"{fit.specimen}: outcomes (α̂ = {fit.alpha_deg:.1f}°, "
                          f"p̂ = {fit.p_rad_s:.2f} rad/s)"},
        "xaxis": {"title": {"text": "PGA / (g tan α̂) [-]"}, "type": "log"},
        "yaxis": {"title": {"text": "p̂ · PGV / PGA [-]"}, "type": "log"},
        "height": 460, "width": 620}}


def _calibration(tests: pd.DataFrame, name: str) -> dict:
    known = tests[tests["observed"].notna()]
    data = [{"type": "scatter", "mode": "lines", "name": "perfect", "x": [0.0, 1.0],
             "y": [0.0, 1.0], "line": {"color": "#999999", "dash": "dot"}}]
    for method in (MODEL, PGV):
        probability = known["cv_" + method].to_numpy()
        bins = np.clip(np.digitize(probability, CALIBRATION_EDGES) - 1, 0, 9)
        rows = pd.DataFrame({"bin": bins, "p": probability, "y": known["observed"]}).groupby(
            "bin").agg(p=("p", "mean"), y=("y", "mean"), n=("y", "size"))
        data.append({"type": "scatter", "mode": "lines+markers", "name": method,
                     "x": rows["p"], "y": rows["y"], "text": [f"{n} tests" for n in rows["n"]],
                     "marker": {"size": np.sqrt(rows["n"].to_numpy(float)) * 2.5}})
    return {"data": data, "layout": {
        "title": {"text": f"{name}: calibration (cross-validated)"},
        "xaxis": {"title": {"text": "predicted P(overturn)"}, "range": [0, 1]},
        "yaxis": {"title": {"text": "observed share overturned"}, "range": [0, 1]},
        "height": 460, "width": 520}}


def _verdict(scores: pd.DataFrame, name: str) -> str:
    """Whether the rocking model beats each baseline, from the paired Brier differences."""
    rows = scores[scores["specimen"] == name].set_index("method")
    model = rows.loc[MODEL]
    parts = []
    for method in (PGA, PGV, VECTOR):
        row = rows.loc[method]
        gap, se = row.brier_minus_model, row.brier_minus_model_se
        if gap > 2 * se:
            word = "worse than the rocking model"
        elif gap < -2 * se:
            word = "better than the rocking model"
        else:
            word = "as good as the rocking model (within two standard errors)"
        parts.append(f"the {method} (Brier {row.brier:.3f}, accuracy {row.accuracy:.0%}) is "
                     f"{word}")
    return (f"{name}: the rocking model's cross-validated Brier score is {model.brier:.3f} "
            f"(accuracy {model.accuracy:.0%}, log-loss {model.log_loss:.3f}); "
            + "; ".join(parts) + ".")


def _failures(tests: pd.DataFrame) -> str:
    known = tests[tests["observed"].notna()].copy()
    known["wrong"] = (known["cv_" + MODEL] >= 0.5) != (known["observed"] > 0.5)
    known["missed"] = known["wrong"] & (known["observed"] > 0.5)
    by_record = known.groupby(["specimen", "ground_motion"]).agg(
        tests=("wrong", "size"), wrong=("wrong", "sum"), missed_overturning=("missed", "sum"),
        pga_g_min=("pga_g", "min"), pga_g_max=("pga_g", "max"))
    worst = by_record[by_record["wrong"] > 0].sort_values(
        ["wrong", "tests"], ascending=[False, True]).head(12).reset_index()
    known["PGA [g]"] = pd.cut(known["pga_g"], PGA_EDGES_G)  # categories sort by PGA
    by_pga = known.groupby(["specimen", "PGA [g]"], observed=True).agg(
        tests=("wrong", "size"), wrong=("wrong", "sum"), missed_overturning=("missed", "sum"),
        observed_overturned=("observed", lambda v: int(v.sum()))).reset_index()
    by_pga["PGA [g]"] = by_pga["PGA [g]"].astype(str)
    return (f"<h3>By PGA (cross-validated classification at P ≥ 0.5)</h3>"
            f"{html_table(by_pga)}"
            f"<h3>Ground motions with the most wrong predictions</h3>"
            f"{html_table(worst)}")


def _fits_table(fits: pd.DataFrame) -> str:
    """Fitted values with their 95 % profile-likelihood intervals, beside the geometry."""
    def span(row, name, digits, bounds=None, identified=True):
        low, high = (getattr(row, (bounds or name) + end) for end in ("_low", "_high"))
        value = getattr(row, name)
        if pd.isna(value):
            return "—"
        text = f"{value:.{digits}f} ({low:.{digits}f}–{high:.{digits}f})"
        return text if identified else f"not identified: {text}, the ridge below"
    rows = [{"specimen": row.specimen, "tests fitted": row.n_tests,
             "α̂ [°] (95 %)": span(row, "alpha_deg", 2, identified=row.alpha_identified),
             "σ of ln α (95 %)": span(row, "sigma_ln_alpha", 3, "sigma"),
             "p [rad/s] (95 %)": span(row, "p_rad_s", 2, identified=row.p_identified),
             "restitution factor (95 %)": span(row, "restitution_factor", 2),
             "resolution: α̂, p, f": f"{row.alpha_step_pct:.1f} %, {row.p_step_pct:.1f} %, "
             f"{row.restitution_step:.3g}",
             "over the folds: α̂ [°], p, f": f"{row.alpha_deg_folds_min:.2f}–"
             f"{row.alpha_deg_folds_max:.2f}, {row.p_rad_s_folds_min:.2f}–"
             f"{row.p_rad_s_folds_max:.2f}, {row.restitution_factor_folds_min:g}–"
             f"{row.restitution_factor_folds_max:g}",
             "log-likelihood": f"{row.log_likelihood:.1f}",
             "geometry α [°]": "" if pd.isna(row.geometry_alpha_deg)
             else f"{row.geometry_alpha_deg:g}",
             "geometry p [rad/s]": "" if pd.isna(row.geometry_p_rad_s)
             else f"{row.geometry_p_rad_s:g}",
             "geometry note": "" if pd.isna(row.geometry_note) else row.geometry_note}
            for row in fits.itertuples()]
    return html_table(pd.DataFrame(rows))


def _ridge_figure(ridge: pd.DataFrame, name: str) -> dict:
    """The best α̂ at each p and the 95 % region's α̂ range: the ridge along which the
    outcomes trade p for α."""
    inside = ridge[ridge["inside_95"]]
    return {"data": [
        {"type": "scatter", "mode": "lines", "name": "best α̂ at p", "x": ridge["p_rad_s"],
         "y": ridge["alpha_deg"], "line": {"color": "#999999"}},
        {"type": "scatter", "mode": "markers", "name": "95 % region",
         "x": inside["p_rad_s"], "y": 0.5 * (inside["alpha_deg_low"] + inside["alpha_deg_high"]),
         "error_y": {"type": "data", "symmetric": False,
                     "array": 0.5 * (inside["alpha_deg_high"] - inside["alpha_deg_low"]),
                     "arrayminus": 0.5 * (inside["alpha_deg_high"] - inside["alpha_deg_low"])},
         "marker": {"color": "#d62728", "size": 5}}],
        "layout": {"title": {"text": f"{name}: α̂ along p (the profile's ridge)"},
                   "xaxis": {"title": {"text": "p [rad/s]"}},
                   "yaxis": {"title": {"text": "α̂ [°]"}}, "height": 460, "width": 520}}


def _ridge_text(fits: pd.DataFrame, ridge: pd.DataFrame) -> str:
    """Where α̂ or p is not identified, the ridge's 95 % region as a table."""
    parts = []
    for row in fits.itertuples():
        if row.alpha_identified and row.p_identified:
            continue
        inside = ridge[(ridge["specimen"] == row.specimen) & ridge["inside_95"]]
        which = " and ".join(n for n, ok in (("α̂", row.alpha_identified),
                                              ("p", row.p_identified)) if not ok)
        table = inside[["p_rad_s", "alpha_deg", "alpha_deg_low", "alpha_deg_high",
                        "log_likelihood"]].rename(columns={
                            "p_rad_s": "p [rad/s]", "alpha_deg": "best α̂ [°]",
                            "alpha_deg_low": "95 % α̂ from [°]", "alpha_deg_high": "to [°]"})
        parts.append(f"<p>{html.escape(row.specimen)}: the outcomes do not identify {which}: "
                     f"its 95 % set reaches the end of the searched range. They pin down the "
                     f"ridge below (every (p, α̂) in it explains the outcomes alike); a point "
                     f"on it is not a measurement of either.</p>{html_table(table.round(3))}")
    return "".join(parts)


def _predictions(predictions: pd.DataFrame) -> str:
    """How many tests without an outcome are predicted to overturn, and those whose band
    straddles 50 %."""
    if predictions.empty:
        return "<p>Every test has an outcome: nothing to predict.</p>"
    predictions = predictions.assign(
        uncertain=(predictions["p_overturn_low"] < 0.5) & (predictions["p_overturn_high"] >= 0.5))
    counts = predictions.groupby("specimen").agg(
        tests=("test", "size"), predicted_overturned=("predicted_overturned", "sum"),
        band_straddles_50_pct=("uncertain", "sum")).reset_index()
    shown = predictions[predictions["uncertain"]].drop(columns="uncertain")
    return (f"<p>P(overturn) of each test without an outcome is averaged over the parameters "
            f"the outcomes allow (weighted by the likelihood), with the 95 % band of that "
            f"average's spread (predictions.csv). Tests whose band straddles 50 % are those the "
            f"fit cannot call:</p>{html_table(counts)}"
            f"{html_table(shown.round(3)) if len(shown) else ''}")


def render_validation_page(folder, title: str, solves: int) -> str:
    """The HTML page of the validation saved in ``folder`` (its CSV files)."""
    from plotly.offline import get_plotlyjs
    folder = Path(folder)
    fits = pd.read_csv(folder / FITS_CSV, keep_default_na=False, na_values=[""])
    scores = pd.read_csv(folder / SCORES_CSV)
    tests = pd.read_csv(folder / TESTS_CSV, dtype={"test": str})
    ridge = pd.read_csv(folder / RIDGE_CSV)
    predictions = pd.read_csv(folder / PREDICTIONS_CSV, dtype={"test": str})
    figures, verdicts = [], []
    for row in fits.itertuples():
        chosen = tests[tests["specimen"] == row.specimen]
        for spec in (_outcome_map(chosen, row), _calibration(chosen, row.specimen),
                     _ridge_figure(ridge[ridge["specimen"] == row.specimen], row.specimen)):
            figures.append(f'<div id="f{len(figures)}" style="display:inline-block"></div>'
                           f'<script>(s => Plotly.newPlot("f{len(figures)}", s.data, '
                           f's.layout))({to_json(spec)});</script>')
        verdicts.append(f"<p>{html.escape(_verdict(scores, row.specimen))}</p>")
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}"
            f"</title><script>{get_plotlyjs()}</script><style>{PAGE_STYLE}</style></head><body>"
            f"<h1>{html.escape(title)}</h1>"
            f"<p>Each specimen's equivalent 2-D rigid block (median slenderness α̂ with a "
            f"test-to-test lognormal dispersion σ, frequency parameter p, restitution factor f "
            f"on Eq. 4.8) is fitted by maximum likelihood of the observed outcomes under the "
            f"exact solver ({solves:,} exact simulations). Scores are cross-validated by ground "
            f"motion: every test is predicted by a fit that saw no test of its record. The "
            f"baselines are fitted on the same folds; the peer columns are another group's "
            f"predictions, scored as given (not cross-validated: they may have been tuned on "
            f"these outcomes). Brier difference: the method's Brier score minus "
            f"the model's on the same tests (positive: the model is better), with its standard "
            f"error.</p>{''.join(verdicts)}"
            f"<h2>Fitted blocks and geometry</h2>"
            f"{_fits_table(fits)}<p>Every interval is a profile-likelihood interval: the set "
            f"where the log-likelihood, maximised over the other parameters, is within 1.92 "
            f"of the best, widened by one step of the fine grid (its resolution, given beside). "
            f"The folds' fits (each on ~80 % of the ground motions) show how far α̂, p and f "
            f"move between subsets.</p>{_ridge_text(fits, ridge)}"
            f"<h2>Predictions of the tests without an outcome</h2>{_predictions(predictions)}"
            f"<h2>Cross-validated scores</h2>"
            f"{html_table(scores.rename(columns=_SCORE_HEADINGS))}"
            f"<h2>Figures</h2>{''.join(figures)}"
            f"<h2>Where the model fails</h2>{_failures(tests)}"
            f"<h2>Limits</h2><p>{html.escape(methods_statement(fits, scores))}</p>"
            f"</body></html>")


__all__ = ["render_validation_page", "VALIDATION_HTML"]
