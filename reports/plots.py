"""Interactive figures of the report as plotly.js specifications (``{"data", "layout"}`` dicts).

The browser draws them from the embedded data (plotly.js is inlined once in the page), so
hovering a block shows its values and spectra can be zoomed; nothing is drawn on the server.
Every ``*_figure`` function takes plain frames and returns a JSON-ready dict; floats are rounded
to :data:`SIGNIFICANT_DIGITS` when the page is written (:func:`to_json`). Units on every axis;
the same colour for the same slenderness α, damping ratio and verdict everywhere.
"""

from __future__ import annotations

import math

import numpy as np
import orjson
import pandas as pd

from audit import G
from audit.engine.verdicts import ROCKING_FLOOR
from audit.physics.block import RigidBlock
from reports.palette import VERDICT_COLOURS, alpha_colour, damping_colour

#: Significant digits of the numbers embedded in the page.
SIGNIFICANT_DIGITS = 4
#: Every how many tabulated periods a spectrum curve is drawn: the table's 1.2 % steps in T
#: are finer than a figure resolves (the CSV keeps them all).
SPECTRUM_STRIDE = 2
#: Samples of a time history drawn in the page (decimated by a stride).
HISTORY_SAMPLES = 900
_FONT = {"family": "DejaVu Sans, Helvetica, Arial, sans-serif", "size": 12}


def rounded(values) -> np.ndarray:
    """Floats rounded to :data:`SIGNIFICANT_DIGITS` [same unit], all at once; NaN stays NaN,
    ±inf (and a value next to the largest double that rounds past it) becomes NaN: JSON has
    neither, both are written as null.

    Each value is the integer n = rint(x·10^k), with k making n hold the significant digits,
    over 10^k: n and 10^k are exact doubles, so the quotient is the double nearest the decimal
    n·10^(−k), the one the shortest representation writes back as those digits. 10^k is exact
    for |k| ≤ 22 only, so magnitudes outside 1e-18 … 1e24 (none in a figure of this tool) take
    the formatted digits one by one.
    """
    values = np.array(values, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        magnitude = np.abs(values)
        ordinary = (magnitude >= 1e-18) & (magnitude < 1e24)
        x = values[ordinary]
        k = SIGNIFICANT_DIGITS - 1 - np.floor(np.log10(np.abs(x))).astype(int)
        n = np.rint(x * 10.0 ** k)
        values[ordinary] = np.where(k >= 0, n / 10.0 ** np.maximum(k, 0),
                                    n * 10.0 ** np.maximum(-k, 0))
        extreme = np.isfinite(values) & ~ordinary & (values != 0.0)
        values[extreme] = [float(f"{v:.{SIGNIFICANT_DIGITS}g}") for v in values[extreme]]
        values[~np.isfinite(values)] = np.nan
    return values


def _rounded_scalar(value: float):
    """One float as :func:`rounded` and :func:`_json_numbers` give it inside an array (the same
    rint(x·10^k)/10^k in IEEE doubles), without numpy's per-call cost: figures carry thousands
    of lone floats in their hover data."""
    magnitude = abs(value)
    if not 1e-18 <= magnitude < 1e24:
        return _json_numbers(rounded([value]))[0]
    k = SIGNIFICANT_DIGITS - 1 - math.floor(math.log10(magnitude))
    n = float(round(value * 10.0 ** k))
    x = n / 10.0 ** k if k >= 0 else n * 10.0 ** -k
    if x != x or x in (math.inf, -math.inf):
        return None
    return int(x) if x.is_integer() and abs(x) < 1e15 else x


def _json_numbers(values: np.ndarray):
    """Rounded floats as JSON-ready nested lists: an int where integral (a lighter page), None
    for NaN."""
    if values.ndim > 1:
        return [_json_numbers(row) for row in values]
    return [None if v != v else int(v) if v.is_integer() and abs(v) < 1e15 else v
            for v in values.tolist()]


def to_json(spec) -> str:
    """The spec as compact JSON, numbers rounded, NaN/inf as null, safe inside ``<script>``.

    Arrays and lists of numbers (the bulk of every figure) are rounded in one vectorised step
    and serialised by orjson.
    """
    def clean(value):
        kind = type(value)
        if kind is dict:
            return {k: clean(v) for k, v in value.items()}
        if kind in (list, tuple):
            if value and all(type(v) is float for v in value):
                return _json_numbers(rounded(value))
            return [clean(v) for v in value]
        if kind in (str, int, bool) or value is None:
            return value
        if isinstance(value, (np.ndarray, pd.Series, pd.Index)):
            value = np.asarray(value)
            if value.dtype.kind == "f":
                return _json_numbers(rounded(value))
            return value if value.dtype.kind in "biu" else clean(value.tolist())
        if isinstance(value, (float, np.floating)):
            return _rounded_scalar(float(value))
        return value
    text = orjson.dumps(clean(spec), option=orjson.OPT_SERIALIZE_NUMPY).decode()
    return text.replace("</", "<\\/")


def _layout(height, **extra):
    layout = {"height": height, "margin": {"l": 70, "r": 20, "t": 40, "b": 50}, "font": _FONT,
              "plot_bgcolor": "#ffffff", "hovermode": "closest",
              "legend": {"orientation": "v", "x": 1.02, "xanchor": "left", "y": 1.0,
                         "font": {"size": 11}}}
    layout.update(extra)
    return layout


def _axis(title, domain=None, anchor=None, **extra):
    axis = {"title": {"text": title, "font": {"size": 12}}, "gridcolor": "#e5e5e5",
            "zeroline": False, "linecolor": "#888888", "mirror": True, "ticks": "outside"}
    if domain is not None:
        axis["domain"] = domain
    if anchor is not None:
        axis["anchor"] = anchor
    axis.update(extra)
    return axis


def required_alpha_layout() -> dict:
    """The layout of a required-slenderness chart: α against the block size 2π/p, the legend
    below."""
    layout = _layout(440)
    layout["xaxis"] = _axis("block size 2π/p [s]")
    layout["yaxis"] = _axis("required α [°]")
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.18, "yanchor": "top"}
    layout["margin"]["b"] = 120
    return layout


def _domains(count, gap):
    """``count`` equal [bottom, top] paper domains from the top down, ``gap`` apart."""
    height = (1.0 - gap * (count - 1)) / count
    return [[1.0 - (i + 1) * height - i * gap, 1.0 - i * height - i * gap] for i in range(count)]


def _stacked(count, panel_px=78, gap_px=26, margins_px=70):
    """Height [px] of a figure of ``count`` stacked map panels and the gap between them as a
    fraction of the plot area (room for each panel's title)."""
    height = margins_px + count * panel_px + (count - 1) * gap_px
    return height, gap_px / (height - margins_px)


def _ref(n):
    return "" if n == 1 else str(n)


def _note(text, xref, yref, y=0.5):
    return {"text": text, "xref": f"{xref} domain", "yref": f"{yref} domain", "x": 0.5, "y": y,
            "showarrow": False, "font": {"size": 12, "color": "#555555"}}


def _literal(text: str) -> str:
    """``text`` shown as it is inside a plotly hover template (no ``%{...}`` substitution)."""
    return str(text).replace("%{", "%\u200b{")




def describe_block(alpha_deg: float, size_s: float) -> str:
    """The object a grid cell is, in metres: ``a 0.38 m × 1.15 m block`` (full width × full
    height, 2R sin α × 2R cos α with R = 3g/(4p²), p = 2π/size)."""
    block = RigidBlock.from_size(float(size_s), math.radians(float(alpha_deg)))
    return f"a {2 * block.half_width:.2f} m × {2 * block.half_height:.2f} m block"


def describe_exact(row) -> str:
    """The exact response of a result row in words (θ/α or 'overturns')."""
    if row["exact_overturned"] is True:
        return "overturns" + (" (fragile)" if row["exact_fragile"] is True else "")
    if not np.isfinite(row["exact_theta_rad"]):
        return "no record file"
    theta_ratio = row["exact_theta_rad"] / math.radians(row["alpha_deg"])
    if theta_ratio < ROCKING_FLOOR:
        return f"no rocking (θ/α = {theta_ratio:.2g})"
    return f"θ/α = {theta_ratio:.4g}"


def describe_guideline(row) -> str:
    """The procedure's outcome of a result row in words."""
    outcome = row["approx_outcome"]
    if outcome == "converged":
        return (f"θ/α = {row['approx_theta_rad'] / math.radians(row['alpha_deg']):.4g}, "
                f"T(θ) = {row['approx_period_s']:.3g} s")
    if outcome == "not-converged":
        cycle = row.get("approx_cycle") or ""
        return f"no fixed point reached (cycle θ/α {cycle.replace(';', ' ↔ ')})" if cycle \
            else "no fixed point reached"
    return {"overturn": "predicts overturning", "no-uplift": "predicts no rocking"}.get(
        outcome, str(outcome))


def verdict_map_figure(results: pd.DataFrame, records: list, names: dict, verdicts) -> dict:
    """Verdict of every block of one procedure: 2π/p across, α up, one panel per record.

    Hovering a cell shows record, α, 2π/p, the exact and the guideline's values and the verdict
    (``customdata``); blocks whose exact overturning is fragile are marked ×.
    """
    codes = {v: i for i, v in enumerate(verdicts)}
    colourscale = []
    for i, verdict in enumerate(verdicts):
        colour = VERDICT_COLOURS[verdict]
        colourscale += [[i / len(verdicts), colour], [(i + 1) / len(verdicts), colour]]
    height, gap = _stacked(len(records))
    domains = _domains(len(records), gap)
    data, layout = [], _layout(height, margin={"l": 60, "r": 20, "t": 20, "b": 50})
    present = set()
    for n, record in enumerate(records, start=1):
        rows = results[results["record"] == record].sort_values(["alpha_deg", "size_s"])
        alphas = sorted(rows["alpha_deg"].unique())
        sizes = np.sort(rows["size_s"].unique())
        z = np.full((len(alphas), sizes.size), np.nan)
        custom = [[None] * sizes.size for _ in alphas]
        fragile_x, fragile_y = [], []
        for row in rows.to_dict("records"):
            i = alphas.index(row["alpha_deg"])
            j = int(np.searchsorted(sizes, row["size_s"]))
            z[i, j] = codes[row["verdict"]]
            present.add(row["verdict"])
            custom[i][j] = [describe_exact(row), describe_guideline(row), row["verdict"]]
            if row["exact_fragile"] is True:
                fragile_x.append(row["size_s"])
                fragile_y.append(row["alpha_deg"])
        data.append({
            "type": "heatmap", "x": sizes, "y": alphas, "z": z, "customdata": custom,
            "zmin": -0.5, "zmax": len(verdicts) - 0.5, "colorscale": colourscale,
            "showscale": False, "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}",
            "xgap": 0, "ygap": 1,
            # the record's name once per panel, not once per cell: it keeps the page light
            "hovertemplate": f"{_literal(names.get(record, record))}<br>"
                             "α = %{y}°, 2π/p = %{x:.2f} s<br>"
                             "exact: %{customdata[0]}<br>guideline: %{customdata[1]}<br>"
                             "<b>%{customdata[2]}</b><extra></extra>"})
        if fragile_x:
            data.append({"type": "scatter", "mode": "markers", "x": fragile_x, "y": fragile_y,
                         "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}", "hoverinfo": "skip",
                         "marker": {"symbol": "x", "size": 7, "color": "#ffffff",
                                    "line": {"width": 1, "color": "#000000"}},
                         "name": "fragile overturning (×)", "showlegend": False,
                         "legendgroup": "fragile"})
        layout[f"xaxis{_ref(n)}"] = _axis("2π/p [s]" if n == len(records) else "",
                                          anchor=f"y{_ref(n)}", matches="x" if n > 1 else None,
                                          showticklabels=n == len(records))
        layout[f"yaxis{_ref(n)}"] = _axis("α [°]", domain=domains[n - 1], anchor=f"x{_ref(n)}",
                                          tickvals=alphas, ticktext=[f"{a:g}°" for a in alphas],
                                          fixedrange=True)
        layout.setdefault("annotations", []).append({
            "text": f"<b>{names.get(record, record)}</b>", "xref": "paper",
            "yref": "paper", "x": 0, "y": domains[n - 1][1], "yanchor": "bottom",
            "xanchor": "left", "showarrow": False, "font": {"size": 11}})
    for key in list(layout):
        if key.startswith("xaxis") and layout[key].get("matches") is None:
            layout[key].pop("matches", None)
    layout["showlegend"] = False
    return {"data": data, "layout": layout, "present": [v for v in verdicts if v in present]}


def response_and_rocking_figure(response: pd.DataFrame, rocking: pd.DataFrame, design,
                                max_period: float = 8.0) -> dict:
    """Figure 5.x: true Sd, Sv, Sa for each damping with design spectra (left) and the exact
    rocking spectra θ/α and θ' per α (right); overturning marked per α above θ/α = 1."""
    data = []
    left, right = _domains(3, 0.06), _domains(2, 0.08)
    response = response[response["period_s"] <= max_period]
    for damping, group in response.groupby("damping_pct"):
        group = group.iloc[::SPECTRUM_STRIDE]
        colour = damping_colour(damping / 100.0)
        for n, column in enumerate(("sd_m", "sv_m_s", "sa_g"), start=1):
            data.append({"type": "scatter", "mode": "lines", "x": group["period_s"],
                         "y": group[column], "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}",
                         "line": {"color": colour, "width": 1.3}, "name": f"record, ξ = {damping:g} %",
                         "legendgroup": f"d{damping}", "showlegend": n == 1,
                         "hovertemplate": f"ξ = {damping:g} %<br>T = %{{x:.3f}} s<br>"
                                          f"{column.split('_')[0].capitalize()} = %{{y:.4g}}"
                                          "<extra></extra>"})
    if design is not None:
        design = design[design["period_s"] <= max_period]
        for (code, damping), group in design.groupby(["code", "damping_pct"], sort=False):
            fema = code.startswith("FEMA")
            line = {"color": damping_colour(damping / 100.0) if fema else "#000000", "width": 1.2,
                    "dash": "dash" if fema else "dot"}
            name = f"{code}, β = {damping:g} %"
            for n, column in ((1, "sd_m"), (3, "sa_g")):
                data.append({"type": "scatter", "mode": "lines", "x": group["period_s"],
                             "y": group[column], "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}",
                             "line": line, "name": name, "legendgroup": name,
                             "showlegend": n == 1,
                             "hovertemplate": f"{name}<br>T = %{{x:.3f}} s<br>%{{y:.4g}}"
                                              "<extra></extra>"})
    alphas = sorted(rocking["alpha_deg"].unique())
    for k, alpha in enumerate(alphas):
        group = rocking[rocking["alpha_deg"] == alpha].sort_values("size_s")
        colour = alpha_colour(alpha)
        over = group["overturned"].eq(True).to_numpy()
        size = group["size_s"].to_numpy()
        ratio = np.where(over, np.nan, group["theta_ratio"].to_numpy(dtype=float))
        omega = np.where(over, np.nan, group["omega_peak_rad_s"].to_numpy(dtype=float))
        data.append({"type": "scatter", "mode": "lines", "x": size, "y": ratio, "xaxis": "x4",
                     "yaxis": "y4", "line": {"color": colour, "width": 1.4},
                     "name": f"α = {alpha:g}°", "legendgroup": f"a{alpha}",
                     "hovertemplate": f"α = {alpha:g}°<br>2π/p = %{{x:.2f}} s<br>"
                                      "θ/α = %{y:.4f}<extra></extra>"})
        data.append({"type": "scatter", "mode": "lines", "x": size, "y": omega, "xaxis": "x5",
                     "yaxis": "y5", "line": {"color": colour, "width": 1.4},
                     "name": f"α = {alpha:g}°", "legendgroup": f"a{alpha}", "showlegend": False,
                     "hovertemplate": f"α = {alpha:g}°<br>2π/p = %{{x:.2f}} s<br>"
                                      "θ' = %{y:.4g} rad/s<extra></extra>"})
        if over.any():
            data.append({"type": "scatter", "mode": "markers", "x": size[over],
                         "y": np.full(int(over.sum()), 1.04 + 0.05 * k), "xaxis": "x4",
                         "yaxis": "y4", "marker": {"symbol": "x-thin", "size": 7,
                                                   "line": {"width": 1.5, "color": colour}},
                         "name": f"α = {alpha:g}° overturns", "legendgroup": f"a{alpha}",
                         "hovertemplate": f"α = {alpha:g}°, 2π/p = %{{x:.2f}} s: overturns"
                                          "<extra></extra>"})
    top = 1.04 + 0.05 * len(alphas)
    layout = _layout(640, margin={"l": 70, "r": 20, "t": 30, "b": 50})
    titles = ("Sd = max|u| [m]", "Sv = max|u'| [m/s]", "Sa = max|ü+üg| [g]")
    for n in (1, 2, 3):
        layout[f"xaxis{_ref(n)}"] = _axis("T [s]" if n == 3 else "", domain=[0, 0.44],
                                          anchor=f"y{_ref(n)}", matches="x" if n > 1 else None,
                                          range=[0, max_period], showticklabels=n == 3)
        layout[f"yaxis{_ref(n)}"] = _axis(titles[n - 1], domain=left[n - 1],
                                          anchor=f"x{_ref(n)}", rangemode="tozero")
    layout["xaxis"].pop("matches")
    span = [rocking["size_s"].min() - 0.1, rocking["size_s"].max() + 0.1] if len(rocking) else None
    layout["xaxis4"] = _axis("", domain=[0.56, 1], anchor="y4", showticklabels=False,
                             **({"range": span} if span else {}))
    layout["xaxis5"] = _axis("2π/p [s]", domain=[0.56, 1], anchor="y5", matches="x4")
    layout["yaxis4"] = _axis("max|θ|/α [-] (× overturns)", domain=right[0], anchor="x4",
                             range=[0, top])
    layout["yaxis5"] = _axis("max|θ'| [rad/s]", domain=right[1], anchor="x5",
                             rangemode="tozero")
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.1, "yanchor": "top",
                        "font": {"size": 11}}
    layout["margin"]["b"] = 110
    layout["height"] = 700
    return {"data": data, "layout": layout}


def _placeholder(size, axes) -> dict:
    """An invisible point that makes plotly create a panel which only carries words (a panel
    without any trace is not laid out; an empty trace leaves its grid undefined)."""
    return {"type": "scatter", "mode": "markers", "x": [float(np.mean(size))], "y": [0.5],
            **axes, "marker": {"opacity": 0}, "showlegend": False, "hoverinfo": "skip"}


def _split(text):
    """``'0.24s;0.25u'`` → [(0.24, 's'), (0.25, 'u')]; ``'0.57;0.88'`` → [(0.57, ''), …]."""
    items = []
    for part in str(text or "").split(";"):
        part = part.strip()
        if part:
            kind = part[-1] if part[-1] in "su" else ""
            items.append((float(part.rstrip("su")), kind))
    return items


def procedure_figure(results: pd.DataFrame, spectra: pd.DataFrame, procedure_title: str) -> dict:
    """Figures 8.x / 9.x for one record and procedure, one row per α: the Sd the procedure read
    at β(α) | exact vs guideline θ/α (cycles as vertical bands between their branches, repelling
    fixed points ○, overturning marked) | the converged T(θ) of Eq. 8.1."""
    alphas = sorted(results["alpha_deg"].unique())
    rows_dom = _domains(len(alphas), 0.22 / max(1, len(alphas)))
    data, annotations = [], []
    layout = _layout(120 + 230 * len(alphas), margin={"l": 70, "r": 20, "t": 30, "b": 120})
    shown = set()

    def legend(name):
        first = name not in shown
        shown.add(name)
        return {"name": name, "legendgroup": name, "showlegend": first}

    for r, alpha in enumerate(alphas):
        colour = alpha_colour(alpha)
        a, b, c = 3 * r + 1, 3 * r + 2, 3 * r + 3
        rows = results[results["alpha_deg"] == alpha].sort_values("size_s")
        beta = rows["beta_pct"].iloc[0]
        spec = spectra[spectra["alpha_deg"] == alpha].iloc[::SPECTRUM_STRIDE]
        data.append({"type": "scatter", "mode": "lines", "x": spec["period_s"], "y": spec["sd_m"],
                     "xaxis": f"x{_ref(a)}", "yaxis": f"y{_ref(a)}",
                     "line": {"color": colour, "width": 1.3}, **legend(f"α = {alpha:g}°"),
                     "hovertemplate": f"Sd at β = {beta:.2f} %<br>T = %{{x:.3f}} s<br>"
                                      "Sd = %{y:.4g} m<extra></extra>"})
        size = rows["size_s"].to_numpy()
        alpha_rad = math.radians(alpha)
        exact_over = rows["exact_overturned"].eq(True).to_numpy()
        approx_over = rows["approx_overturned"].eq(True).to_numpy()
        exact = np.where(exact_over, np.nan, rows["exact_theta_rad"].to_numpy(dtype=float)
                         / alpha_rad)
        approx = rows["approx_theta_rad"].to_numpy(dtype=float) / alpha_rad
        no_file = rows["exact_theta_rad"].isna().all()
        axes = {"xaxis": f"x{_ref(b)}", "yaxis": f"y{_ref(b)}"}
        if no_file and not np.isfinite(approx).any():
            data.append(_placeholder(size, axes))
        if no_file:
            annotations.append(_note("no record file: no exact response", f"x{_ref(b)}",
                                     f"y{_ref(b)}", y=0.92))
        else:
            data.append({"type": "scatter", "mode": "lines", "x": size, "y": exact, **axes,
                         "line": {"color": "#333333", "width": 1.5}, **legend("exact"),
                         "hovertemplate": "exact<br>2π/p = %{x:.2f} s<br>θ/α = %{y:.4f}"
                                          "<extra></extra>"})
        if np.isfinite(approx).any():
            data.append({"type": "scatter", "mode": "lines", "x": size, "y": approx, **axes,
                         "line": {"color": colour, "width": 1.3, "dash": "dash"},
                         **legend(f"{procedure_title} (dashed, colour of α)"),
                         "hovertemplate": "guideline<br>2π/p = %{x:.2f} s<br>θ/α = %{y:.4f}"
                                          "<extra></extra>"})
        if exact_over.any():
            data.append({"type": "scatter", "mode": "markers", "x": size[exact_over],
                         "y": np.full(int(exact_over.sum()), 1.04), **axes,
                         "marker": {"symbol": "x-thin", "size": 7,
                                    "line": {"width": 1.5, "color": "#333333"}},
                         **legend("exact overturns (×)"),
                         "hovertemplate": "exact: overturns at 2π/p = %{x:.2f} s<extra></extra>"})
        if approx_over.any():
            data.append({"type": "scatter", "mode": "markers", "x": size[approx_over],
                         "y": np.full(int(approx_over.sum()), 1.1), **axes,
                         "marker": {"symbol": "triangle-up", "size": 6, "color": colour},
                         **legend("guideline predicts overturning (▲)"),
                         "hovertemplate": "guideline: overturns at 2π/p = %{x:.2f} s"
                                          "<extra></extra>"})
        band_x, band_y, branch_x, branch_y, rep_x, rep_y = [], [], [], [], [], []
        for s, cycle, points in zip(size, rows["approx_cycle"], rows["approx_fixed_points"]):
            values = [v for v, _ in _split(cycle)]
            if len(values) > 1:
                band_x += [s, s, None]
                band_y += [min(values), max(values), None]
                branch_x += [s] * len(values)
                branch_y += values
            for v, kind in _split(points):
                if kind == "u":
                    rep_x.append(s)
                    rep_y.append(v)
        if band_x:
            data.append({"type": "scatter", "mode": "lines", "x": band_x, "y": band_y, **axes,
                         "line": {"color": "#7b3294", "width": 4}, "opacity": 0.35,
                         "hoverinfo": "skip", **legend("cycle: band between its branches")})
            data.append({"type": "scatter", "mode": "markers", "x": branch_x, "y": branch_y,
                         **axes, "marker": {"color": "#7b3294", "size": 3},
                         **legend("cycle branches"),
                         "hovertemplate": "cycle branch θ/α = %{y:.4f}<br>2π/p = %{x:.2f} s"
                                          "<extra></extra>"})
        if rep_x:
            data.append({"type": "scatter", "mode": "markers", "x": rep_x, "y": rep_y, **axes,
                         "marker": {"symbol": "circle-open", "color": "#7b3294", "size": 6},
                         **legend("repelling fixed point (○)"),
                         "hovertemplate": "repelling fixed point θ/α = %{y:.4f}<br>"
                                          "2π/p = %{x:.2f} s<extra></extra>"})
        period = rows["approx_period_s"].to_numpy(dtype=float)
        if np.isfinite(period).any():
            data.append({"type": "scatter", "mode": "lines", "x": size, "y": period,
                         "xaxis": f"x{_ref(c)}", "yaxis": f"y{_ref(c)}",
                         "line": {"color": colour, "width": 1.3}, "showlegend": False,
                         "hovertemplate": "2π/p = %{x:.2f} s<br>T(θ) = %{y:.3f} s"
                                          "<extra></extra>"})
        else:
            data.append(_placeholder(size, {"xaxis": f"x{_ref(c)}", "yaxis": f"y{_ref(c)}"}))
            annotations.append(_note("no converged T(θ): no block settles below α",
                                     f"x{_ref(c)}", f"y{_ref(c)}"))
        domain = rows_dom[r]
        last = r == len(alphas) - 1
        span = [size.min() - 0.1, size.max() + 0.1]
        for n, dom, title, extent in ((a, [0, 0.28], "T [s]", [0, spec["period_s"].max()]),
                                      (b, [0.36, 0.66], "2π/p [s]", span),
                                      (c, [0.74, 1.0], "2π/p [s]", span)):
            layout[f"xaxis{_ref(n)}"] = _axis(title if last else "", domain=dom,
                                              anchor=f"y{_ref(n)}", range=extent)
            if r:
                layout[f"xaxis{_ref(n)}"]["matches"] = f"x{_ref(n - 3 * r)}"
        layout[f"yaxis{_ref(a)}"] = _axis(f"α = {alpha:g}°<br>Sd [m] at β = {beta:.2f} %",
                                          domain=domain, anchor=f"x{_ref(a)}", rangemode="tozero")
        layout[f"yaxis{_ref(b)}"] = _axis("max|θ|/α [-]", domain=domain, anchor=f"x{_ref(b)}",
                                          range=[0, 1.16])
        layout[f"yaxis{_ref(c)}"] = _axis("converged T(θ) [s]", domain=domain,
                                          anchor=f"x{_ref(c)}",
                                          **({} if np.isfinite(period).any() else
                                             {"showticklabels": False, "showgrid": False,
                                              "range": [0, 1]}))
        for k, n in enumerate((b, c)):  # the height of the block of each size at α, on top
            m = 3 * len(alphas) + 2 * r + k + 1
            layout[f"xaxis{m}"] = metres_axis(alpha, span, f"x{_ref(n)}", f"y{_ref(n)}")
            data.append({"type": "scatter", "x": span, "y": [None, None], "xaxis": f"x{m}",
                         "yaxis": f"y{_ref(n)}", "showlegend": False, "hoverinfo": "skip"})
    layout["annotations"] = annotations
    layout["legend"] = {"orientation": "h", "x": 0, "y": -60 / layout["height"] - 0.02,
                        "yanchor": "top", "font": {"size": 11}}
    return {"data": data, "layout": layout}


#: Heights of the ticks of a metres axis [m].
METRE_TICKS = (0.1, 0.2, 0.3, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0, 30.0, 50.0)


def metres_axis(alpha_deg: float, span, overlaying: str, anchor: str) -> dict:
    """A secondary x axis, on top of a 2π/p axis spanning ``span`` [s], labelled with the
    height [m] of the block of each size at slenderness α: h = 2R cos α, R = 3g/(4p²),
    p = 2π/size, so size = 2π √(2R/(3g)) with R = h/(2 cos α)."""
    radius = np.array(METRE_TICKS) / (2.0 * math.cos(math.radians(alpha_deg)))
    sizes = 2.0 * np.pi * np.sqrt(4.0 * radius / (3.0 * G))
    kept, last = [], -math.inf
    for height, size in zip(METRE_TICKS, sizes):  # a tick an eighth of the span from the last
        if span[0] <= size <= span[1] and size - last >= (span[1] - span[0]) / 8.0:
            kept.append((height, size))
            last = size
    return {"overlaying": overlaying, "anchor": anchor, "side": "top", "range": list(span),
            "tickvals": [size for _, size in kept],
            "ticktext": [f"{height:g} m" for height, _ in kept], "tickangle": 0,
            "tickfont": {"size": 9, "color": "#666"}, "showgrid": False, "ticks": "outside",
            "zeroline": False}


def history_figure(history: pd.DataFrame, meta: dict, estimates: list) -> dict:
    """θ/α and θ' of one block against time: full rocking cycles shaded (duration on hover and
    as a label where wide enough), each guideline's estimate ±θ/α dashed, its T(θ) in the legend.

    ``estimates`` are ``(label, theta_ratio or None, period_s or None, colour)``.
    """
    time = history["time_s"].to_numpy()
    start, stop = time[0], time[-1]
    if meta.get("first_impact_s") is not None:
        start = max(start, meta["first_impact_s"] - 2.0)
        stop = min(stop, meta["last_impact_s"] + 3.0)
    if meta.get("overturn_time_s") is not None:
        stop = min(time[-1], meta["overturn_time_s"] + 1.0)
    window = history[(history["time_s"] >= start) & (history["time_s"] <= stop)]
    stride = max(1, len(window) // HISTORY_SAMPLES)
    window = window.iloc[::stride]
    theta = window["theta_ratio"].to_numpy(dtype=float)
    peak = np.nanmax(np.abs(theta)) if np.isfinite(theta).any() else 1.0
    drawn = [abs(ratio) for _, ratio, _, _ in estimates if ratio is not None]
    limit = 1.1 if meta.get("overturned") else min(1.1, max(0.25, 1.3 * peak,
                                                             1.15 * max(drawn, default=0)))
    data = [{"type": "scatter", "mode": "lines", "x": window["time_s"], "y": theta,
             "line": {"color": "#333333", "width": 1.2}, "name": "exact θ/α",
             "hovertemplate": "t = %{x:.3f} s<br>θ/α = %{y:.4f}<extra></extra>"},
            {"type": "scatter", "mode": "lines", "x": window["time_s"],
             "y": window["omega_rad_s"], "xaxis": "x2", "yaxis": "y2",
             "line": {"color": "#666666", "width": 1}, "name": "exact θ'", "showlegend": False,
             "hovertemplate": "t = %{x:.3f} s<br>θ' = %{y:.4g} rad/s<extra></extra>"}]
    shapes, mid_x, mid_text = [], [], []
    for k, (begin, duration) in enumerate(zip(meta["cycle_starts_s"], meta["cycle_durations_s"])):
        if begin + duration < start or begin > stop:
            continue
        shapes.append({"type": "rect", "xref": "x", "yref": "y domain", "x0": begin,
                       "x1": begin + duration, "y0": 0, "y1": 1, "line": {"width": 0},
                       "fillcolor": "#1f77b4" if k % 2 else "#9ecae1", "opacity": 0.18,
                       "layer": "below"})
        mid_x.append(begin + duration / 2)
        mid_text.append(f"{duration:.2f} s" if duration > 0.07 * (stop - start) else "")
    if mid_x:
        data.append({"type": "scatter", "mode": "markers+text", "x": mid_x,
                     "y": [0.93 * limit] * len(mid_x), "text": mid_text,
                     "textposition": "middle right", "textfont": {"size": 10, "color": "#1f4e79"},
                     "marker": {"symbol": "square", "size": 9, "color": "#9ecae1"},
                     "name": "full rocking cycle (shaded; hover for its duration)",
                     "customdata": [d for b, d in zip(meta["cycle_starts_s"],
                                                       meta["cycle_durations_s"])
                                    if not (b + d < start or b > stop)],
                     "hovertemplate": "full rocking cycle: %{customdata:.3f} s<extra></extra>"})
    if meta.get("excitation_end_s") is not None and start < meta["excitation_end_s"] < stop:
        for yref in ("y domain", "y2 domain"):
            shapes.append({"type": "line", "xref": "x" if yref[1] == " " else "x2",
                           "yref": yref, "x0": meta["excitation_end_s"],
                           "x1": meta["excitation_end_s"], "y0": 0, "y1": 1,
                           "line": {"color": "#999999", "width": 1, "dash": "dash"}})
    for label, ratio, period, colour in estimates:
        if ratio is None:
            continue
        name = f"{label}: θ/α = {ratio:.3f}" + (f", T(θ) = {period:.2f} s" if period else "")
        data.append({"type": "scatter", "mode": "lines", "x": [start, stop, None, start, stop],
                     "y": [ratio, ratio, None, -ratio, -ratio],
                     "line": {"color": colour, "width": 1.2, "dash": "dash"}, "name": name,
                     "hovertemplate": name + "<extra></extra>"})
    if limit >= 1.0:
        data.append({"type": "scatter", "mode": "lines", "x": [start, stop, None, start, stop],
                     "y": [1, 1, None, -1, -1], "line": {"color": "#b2182b", "width": 1,
                                                         "dash": "dot"},
                     "name": "θ = ±α (overturning)", "hoverinfo": "skip"})
    layout = _layout(430, shapes=shapes, margin={"l": 70, "r": 20, "t": 10, "b": 45})
    layout["xaxis"] = _axis("", anchor="y", range=[start, stop], showticklabels=False)
    layout["xaxis2"] = _axis("t [s]", anchor="y2", matches="x")
    layout["yaxis"] = _axis("θ/α [-]", domain=[0.42, 1], range=[-limit, limit])
    layout["yaxis2"] = _axis("θ' [rad/s]", domain=[0, 0.36])
    layout["legend"] = {"orientation": "h", "x": 0, "y": 1.02, "yanchor": "bottom",
                        "font": {"size": 11}}
    layout["margin"]["t"] = 60
    return {"data": data, "layout": layout}


def lines_figure(series, x_title, y_title, height=420, y_range=None, legend_below=False):
    """Plain line plot: ``series`` are dicts with ``x, y, name`` and optional ``colour``,
    ``dash``, ``width``, ``showlegend``."""
    data = [{"type": "scatter", "mode": "lines", "x": s["x"], "y": s["y"], "name": s["name"],
             "line": {"color": s.get("colour"), "width": s.get("width", 1.3),
                      "dash": s.get("dash", "solid")},
             "showlegend": s.get("showlegend", True), "legendgroup": s.get("group", s["name"]),
             "hovertemplate": f"{s['name']}<br>%{{x:.4g}}, %{{y:.4g}}<extra></extra>"}
            for s in series]
    layout = _layout(height)
    layout["xaxis"] = _axis(x_title)
    layout["yaxis"] = _axis(y_title, **({"range": y_range} if y_range else {}))
    if legend_below:
        layout["margin"]["b"] = 190
        layout["height"] = height + 140
        layout["legend"] = {"orientation": "h", "x": 0, "yanchor": "top", "font": {"size": 11},
                            "y": -60 / (layout["height"] - 230)}
    return {"data": data, "layout": layout}


def sensitivity_figure(rocking: dict, oscillator: dict, title_rocking, title_oscillator) -> dict:
    """Figure 4.1 vs 7.2: block θ/α (left) and the 'equivalent' oscillator u (right)."""
    colours = ("#1f77b4", "#ff7f0e", "#d62728")
    data = []
    for colour, (label, (t, value)) in zip(colours, rocking.items()):
        data.append({"type": "scatter", "mode": "lines", "x": t, "y": value, "name": label,
                     "line": {"color": colour, "width": 1.3}, "legendgroup": label.split(" (")[0],
                     "hovertemplate": f"{label}<br>t = %{{x:.3f}} s<br>θ/α = %{{y:.4f}}"
                                      "<extra></extra>"})
    for colour, (label, (t, value)) in zip(colours, oscillator.items()):
        data.append({"type": "scatter", "mode": "lines", "x": t, "y": 100 * np.asarray(value),
                     "name": label, "xaxis": "x2", "yaxis": "y2", "showlegend": False,
                     "line": {"color": colour, "width": 1.3}, "legendgroup": label.split(" (")[0],
                     "hovertemplate": f"{label}<br>t = %{{x:.3f}} s<br>u = %{{y:.4g}} cm"
                                      "<extra></extra>"})
    layout = _layout(430, margin={"l": 70, "r": 20, "t": 50, "b": 100})
    layout["xaxis"] = _axis("t [s]", domain=[0, 0.45])
    layout["xaxis2"] = _axis("t [s]", domain=[0.55, 1], anchor="y2")
    layout["yaxis"] = _axis("θ/α [-]", range=[-1.1, 1.1])
    layout["yaxis2"] = _axis("u [cm]", anchor="x2")
    layout["annotations"] = [
        {"text": title_rocking, "xref": "x domain", "yref": "paper", "x": 0, "y": 1.02,
         "xanchor": "left", "yanchor": "bottom", "showarrow": False, "font": {"size": 11}},
        {"text": title_oscillator, "xref": "x2 domain", "yref": "paper", "x": 0, "y": 1.02,
         "xanchor": "left", "yanchor": "bottom", "showarrow": False, "font": {"size": 11}}]
    layout["legend"] = {"orientation": "h", "x": 0, "y": -0.2, "yanchor": "top"}
    return {"data": data, "layout": layout}


def _pivot(rows: pd.DataFrame, value: str):
    """``value`` over (α, size): the α and sizes that have a value, and the first value of each
    cell (NaN where none), as ``pivot_table(aggfunc="first")`` gives it, without its cost."""
    values = rows[value].to_numpy(dtype=float)
    keep = ~np.isnan(values)
    alphas, i = np.unique(rows["alpha_deg"].to_numpy(dtype=float)[keep], return_inverse=True)
    sizes, j = np.unique(rows["size_s"].to_numpy(dtype=float)[keep], return_inverse=True)
    z = np.full((alphas.size, sizes.size), np.nan)
    _, first = np.unique(i * sizes.size + j, return_index=True)  # each cell's first row
    z[i[first], j[first]] = values[keep][first]
    return alphas, sizes, z


def grid_map_figure(frame: pd.DataFrame, value: str, panels: list, title_of, hover: str,
                    colourscale, zmin, zmax, colourbar: str | None = None,
                    labels: list | None = None) -> dict:
    """A map of ``value`` over (2π/p across, α up), one panel per key of ``panels``
    (``frame`` rows selected by ``panels[i][1]``, a boolean mask); for suite statistics and
    limit-state checks. ``hover`` is the hover template, where ``{title}`` stands for the
    panel's title and ``%{text}`` for ``labels[z]`` when ``labels`` name the integer codes of
    ``value``."""
    height, gap = _stacked(len(panels))
    domains = _domains(len(panels), gap)
    data, annotations = [], []
    layout = _layout(height, margin={"l": 60, "r": 90 if colourbar else 20, "t": 20, "b": 50})
    for n, (key, mask) in enumerate(panels, start=1):
        alphas, sizes, z = _pivot(frame[mask], value)
        title = title_of(key)
        data.append({"type": "heatmap", "x": sizes, "y": alphas, "z": z,
                     "colorscale": colourscale, "zmin": zmin, "zmax": zmax,
                     "showscale": bool(colourbar) and n == 1, "ygap": 1,
                     "colorbar": {"title": {"text": colourbar or ""}, "len": 1, "x": 1.01,
                                  "thickness": 12, "tickformat": ".0%"},
                     "xaxis": f"x{_ref(n)}", "yaxis": f"y{_ref(n)}",
                     "hovertemplate": hover.replace("{title}", _literal(title))})
        if labels is not None:
            data[-1]["text"] = [[labels[int(v)] if np.isfinite(v) else "" for v in row]
                                for row in z]
        layout[f"xaxis{_ref(n)}"] = _axis("2π/p [s]" if n == len(panels) else "",
                                          anchor=f"y{_ref(n)}", showticklabels=n == len(panels))
        if n > 1:
            layout[f"xaxis{_ref(n)}"]["matches"] = "x"
        layout[f"yaxis{_ref(n)}"] = _axis("α [°]", domain=domains[n - 1], anchor=f"x{_ref(n)}",
                                          tickvals=alphas, ticktext=[f"{a:g}°" for a in alphas],
                                          fixedrange=True)
        annotations.append({"text": f"<b>{title}</b>", "xref": "paper", "yref": "paper", "x": 0,
                            "y": domains[n - 1][1], "yanchor": "bottom", "xanchor": "left",
                            "showarrow": False, "font": {"size": 11}})
    layout["annotations"] = annotations
    layout["showlegend"] = False
    return {"data": data, "layout": layout}


def ratio_band_figure(suite: pd.DataFrame) -> dict:
    """Suite statistics: median approx/exact against 2π/p per α with the 16–84 % band."""
    data = []
    for alpha, group in suite.groupby("alpha_deg"):
        group = group.sort_values("size_s")
        colour = alpha_colour(alpha)
        x = group["size_s"].to_numpy(dtype=float)
        data.append({"type": "scatter", "mode": "lines", "x": np.concatenate([x, x[::-1]]),
                     "y": np.concatenate([group["ratio_p84"].to_numpy(dtype=float),
                                          group["ratio_p16"].to_numpy(dtype=float)[::-1]]),
                     "fill": "toself", "fillcolor": colour, "opacity": 0.2,
                     "line": {"width": 0}, "hoverinfo": "skip", "legendgroup": f"a{alpha}",
                     "name": f"α = {alpha:g}°: 16–84 %"})
        data.append({"type": "scatter", "mode": "lines", "x": x, "y": group["ratio_p50"],
                     "line": {"color": colour, "width": 1.5}, "legendgroup": f"a{alpha}",
                     "name": f"α = {alpha:g}°: median",
                     "hovertemplate": f"α = {alpha:g}°, 2π/p = %{{x:.2f}} s<br>"
                                      "median approx/exact = %{y:.3f}<extra></extra>"})
    layout = _layout(380)
    layout["xaxis"] = _axis("2π/p [s]")
    # whole numbers on the log axis: plotly's default minor labels read "3" for 30
    ticks = [0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100]
    layout["yaxis"] = _axis("approx/exact [-] where both survive", type="log", tickvals=ticks,
                            ticktext=[f"{t:g}" for t in ticks])
    layout["shapes"] = [{"type": "line", "xref": "x domain", "x0": 0, "x1": 1, "yref": "y",
                         "y0": 1, "y1": 1, "line": {"color": "#888888", "dash": "dot"}}]
    return {"data": data, "layout": layout}
