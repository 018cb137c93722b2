"""Spectra of a record against block size and period: the record's response spectra with the
exact rocking spectra (Figure 5.x), and a procedure's reading of them against the exact response,
one row per α (Figures 8.x / 9.x)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from reports.block_metres import METRES_ROOM_PX, add_metres_axis
from reports.palette import alpha_colour, damping_colour
from reports.plots import _axis, _domains, _layout, _note, _ref

#: Every how many tabulated periods a spectrum curve is drawn: the table's 1.2 % steps in T
#: are finer than a figure resolves (the CSV keeps them all).
SPECTRUM_STRIDE = 2


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
    # the columns drawn, as arrays once; each α takes its rows by position (one per size)
    rocking_alpha = rocking["alpha_deg"].to_numpy()
    rocking_size = rocking["size_s"].to_numpy()
    rocking_over = rocking["overturned"].eq(True).to_numpy()
    rocking_ratio = rocking["theta_ratio"].to_numpy(dtype=float)
    rocking_omega = rocking["omega_peak_rad_s"].to_numpy(dtype=float)
    for k, alpha in enumerate(alphas):
        at = np.flatnonzero(rocking_alpha == alpha)
        at = at[np.argsort(rocking_size[at], kind="stable")]
        colour = alpha_colour(alpha)
        over = rocking_over[at]
        size = rocking_size[at]
        ratio = np.where(over, np.nan, rocking_ratio[at])
        omega = np.where(over, np.nan, rocking_omega[at])
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
    figure = {"data": data, "layout": layout}
    if span:  # over every α: the block's diagonal, titled, above the rocking spectra
        add_metres_axis(figure, span, "xaxis4", room_px=METRES_ROOM_PX)
    return figure


def _placeholder(size, axes) -> dict:
    """An invisible point that makes plotly create a panel which only carries words (a panel
    without any trace is not laid out; an empty trace leaves its grid undefined)."""
    return {"type": "scatter", "mode": "markers", "x": [float(np.mean(size))], "y": [0.5],
            **axes, "marker": {"opacity": 0}, "showlegend": False, "hoverinfo": "skip"}


def _split(text):
    """``'0.24s;0.25u'`` → [(0.24, 's'), (0.25, 'u')]; ``'0.57;0.88'`` → [(0.57, ''), …]."""
    items = []
    if not text:  # most rows: no cycle, no fixed point
        return items
    for part in str(text).split(";"):
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
    # the columns drawn, as arrays once: each α takes its rows by position, not by a pandas
    # selection (the rows of a record and procedure have one size each per α)
    row_alpha = results["alpha_deg"].to_numpy()
    row_size = results["size_s"].to_numpy(dtype=float)
    row_beta = results["beta_pct"].to_numpy()
    row_exact = results["exact_theta_rad"].to_numpy(dtype=float)
    row_approx = results["approx_theta_rad"].to_numpy(dtype=float)
    row_period = results["approx_period_s"].to_numpy(dtype=float)
    row_exact_over = results["exact_overturned"].eq(True).to_numpy()
    row_approx_over = results["approx_overturned"].eq(True).to_numpy()
    row_cycle = results["approx_cycle"].to_numpy(dtype=object)
    row_points = results["approx_fixed_points"].to_numpy(dtype=object)
    spectra = spectra[["alpha_deg", "period_s", "sd_m"]]
    spectrum_alpha = spectra["alpha_deg"].to_numpy()
    data, annotations = [], []
    layout = _layout(120 + 230 * len(alphas), margin={"l": 70, "r": 20, "t": 30, "b": 120})
    shown, metres = set(), []

    def legend(name):
        first = name not in shown
        shown.add(name)
        return {"name": name, "legendgroup": name, "showlegend": first}

    for r, alpha in enumerate(alphas):
        colour = alpha_colour(alpha)
        a, b, c = 3 * r + 1, 3 * r + 2, 3 * r + 3
        at = np.flatnonzero(row_alpha == alpha)
        at = at[np.argsort(row_size[at], kind="stable")]
        beta = row_beta[at[0]]
        spec = spectra.iloc[np.flatnonzero(spectrum_alpha == alpha)[::SPECTRUM_STRIDE]]
        data.append({"type": "scatter", "mode": "lines", "x": spec["period_s"], "y": spec["sd_m"],
                     "xaxis": f"x{_ref(a)}", "yaxis": f"y{_ref(a)}",
                     "line": {"color": colour, "width": 1.3}, **legend(f"α = {alpha:g}°"),
                     "hovertemplate": f"Sd at β = {beta:.2f} %<br>T = %{{x:.3f}} s<br>"
                                      "Sd = %{y:.4g} m<extra></extra>"})
        size = row_size[at]
        alpha_rad = math.radians(alpha)
        exact_over, approx_over = row_exact_over[at], row_approx_over[at]
        exact = np.where(exact_over, np.nan, row_exact[at] / alpha_rad)
        approx = row_approx[at] / alpha_rad
        no_file = np.isnan(row_exact[at]).all()
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
        for s, cycle, points in zip(size, row_cycle[at], row_points[at]):
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
        period = row_period[at]
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
        metres += [(span, f"xaxis{_ref(n)}", alpha) for n in (b, c)]
    layout["annotations"] = annotations
    layout["legend"] = {"orientation": "h", "x": 0, "y": -60 / layout["height"] - 0.02,
                        "yanchor": "top", "font": {"size": 11}}
    figure = {"data": data, "layout": layout}
    for span, axis, alpha in metres:  # one α per row: the height of the block of each size
        add_metres_axis(figure, span, axis, alpha)
    return figure
