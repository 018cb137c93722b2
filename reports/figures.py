"""Matplotlib figures of the audit (the reference report's Figures 4.1, 5.x, 7.1, 7.2, 8.x, 9.x).

Every ``draw_*`` function fills a given :class:`matplotlib.figure.Figure` from plain arrays or
DataFrames, so the same drawing serves the command line (PNG files) and the HTML report
(embedded PNG), and a report can be re-drawn from saved results. Units on every axis; the same
colour for the same slenderness α and damping ratio everywhere.
"""

from __future__ import annotations

import base64
import io
import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from audit import G  # noqa: E402

ALPHA_COLOURS = {10.0: "#1f77b4", 15.0: "#d62728", 20.0: "#2ca02c"}
DAMPING_COLOURS = {0.05: "#1f77b4", 0.10: "#ff7f0e", 0.15: "#9467bd"}
_EXTRA_COLOURS = ("#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
# unsafe errors in reds, over-safe ones in orange and blue, the rest in greys and lavender
VERDICT_COLOURS = {
    "no-uplift": "#eeeeee", "both-overturn": "#4d4d4d", "false-overturn": "#fdbf6f",
    "missed-overturn": "#b2182b", "conservative": "#a6cee3", "unconservative": "#fb9a99",
    "not-converged": "#cab2d6", "agrees": "#b2df8a",
}
DPI = 80


def alpha_colour(alpha_deg: float) -> str:
    """Colour of a slenderness [degrees], the same in every figure."""
    key = round(float(alpha_deg), 6)
    return ALPHA_COLOURS.get(key, _EXTRA_COLOURS[int(key * 7) % len(_EXTRA_COLOURS)])


def damping_colour(damping: float) -> str:
    """Colour of a damping ratio [-]."""
    key = round(float(damping), 6)
    return DAMPING_COLOURS.get(key, _EXTRA_COLOURS[int(key * 1000) % len(_EXTRA_COLOURS)])


def new_figure(width: float, height: float) -> Figure:
    """A figure of the given size [inch], not tied to any GUI backend."""
    return Figure(figsize=(width, height), dpi=DPI)


def _margins(fig, height_inch, top_inch=0.45, bottom_inch=0.55, **spacing):
    """Fixed margins in inches (constrained layout would double the drawing time)."""
    fig.subplots_adjust(top=1 - top_inch / height_inch, bottom=bottom_inch / height_inch,
                        **{"left": 0.08, "right": 0.98, **spacing})


def png_bytes(fig: Figure) -> bytes:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=DPI)
    return buffer.getvalue()


def data_uri(fig: Figure) -> str:
    """The figure as a base64 PNG ``data:`` URI, for a self-contained HTML page."""
    return "data:image/png;base64," + base64.b64encode(png_bytes(fig)).decode("ascii")


def save_figure(draw, path, width: float = 10.0, height: float = 6.0) -> None:
    """Draw with ``draw(fig)`` and write a PNG to ``path`` atomically."""
    fig = new_figure(width, height)
    draw(fig)
    path = Path(path)
    handle, staging = tempfile.mkstemp(prefix=f".{path.name}-", dir=path.parent or ".")
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(png_bytes(fig))
        os.replace(staging, path)
    finally:
        if os.path.exists(staging):
            os.remove(staging)


def _mark_overturned(ax, size, value, overturned, colour):
    if np.any(overturned):
        ax.plot(size[overturned], value[overturned], "x", color=colour, ms=4, mew=1)


def draw_time_histories(fig, blocks):
    """θ/α and θ' against time for one or more blocks (Figures 4.1, 8.2, 8.5, 8.7, 8.9).

    Each item of ``blocks`` is a dict with ``time`` [s], ``theta_ratio`` [-], ``omega``
    [rad/s], ``title``, and optionally ``rocking_span`` (first and last impact [s]),
    ``cycle_starts`` and ``cycle_durations`` [s],
    ``procedures`` (label → what the procedure concluded, e.g. "T(θ) = 2.9 s") and
    ``excitation_end`` [s]. Full rocking cycles are shaded alternately with their durations,
    for comparison with the converged T(θ).
    """
    # room above each block for its title: two lines when procedures are named
    ratios = [r for b in blocks for r in (0.5 if b.get("procedures") else 0.15, 1.0, 1.0)]
    grid = fig.add_gridspec(3 * len(blocks), 1, hspace=0.3, height_ratios=ratios)
    _margins(fig, fig.get_figheight(), top_inch=0.1, bottom_inch=0.5)
    for i, block in enumerate(blocks):
        ax_theta = fig.add_subplot(grid[3 * i + 1, 0])
        ax_omega = fig.add_subplot(grid[3 * i + 2, 0], sharex=ax_theta)
        ax_theta.tick_params(labelbottom=False)
        _draw_history(ax_theta, ax_omega, **block)


def _draw_history(ax_theta, ax_omega, time, theta_ratio, omega, title, rocking_span=None,
                  cycle_starts=(), cycle_durations=(), procedures=None, excitation_end=None):
    ax_theta.plot(time, theta_ratio, color="#333333", lw=0.9)
    limit = min(1.1, max(0.25, 1.3 * np.nanmax(np.abs(theta_ratio))))
    if limit >= 1.0:
        for level in (-1.0, 1.0):
            ax_theta.axhline(level, color="#b2182b", lw=0.6, ls=":")
    # show the rocking, not the quiet record before and after it
    start, stop = time[0], time[-1]
    if rocking_span is not None:
        start = max(start, rocking_span[0] - 2.0)
        stop = min(stop, rocking_span[1] + 3.0)
    ax_theta.set_xlim(start, stop)
    for k, (begin, duration) in enumerate(zip(cycle_starts, cycle_durations)):
        ax_theta.axvspan(begin, begin + duration, color="#1f77b4" if k % 2 else "#9ecae1",
                         alpha=0.2, lw=0)
        if duration > 0.06 * (stop - start):  # label only the cycles wide enough to read
            ax_theta.text(begin + duration / 2, 0.95, f"{duration:.2f} s", ha="center", va="top",
                          fontsize=7, transform=ax_theta.get_xaxis_transform())
    if excitation_end is not None and start < excitation_end < stop:
        for ax in (ax_theta, ax_omega):
            ax.axvline(excitation_end, color="#999999", lw=0.6, ls="--")
    if procedures:
        title = (f"{title}\nshaded: full rocking cycles; "
                 + "; ".join(f"{label}: {text}" for label, text in procedures.items()))
    ax_theta.set_title(title, fontsize=9)
    ax_theta.set_ylabel("θ/α [-]")
    ax_theta.set_ylim(-limit, limit)
    ax_omega.plot(time, omega, color="#555555", lw=0.8)
    ax_omega.set_ylabel("θ' [rad/s]")
    ax_omega.set_xlabel("t [s]")
    for ax in (ax_theta, ax_omega):
        ax.grid(alpha=0.3)


def draw_response_spectra(fig, frame, title, design=None, axes=None, max_period=8.0):
    """True Sd [m], Sv [m/s], Sa [g] against T, one curve per damping (left of Figures 5.x).

    ``frame`` has columns ``period_s, damping_pct, sd_m, sv_m_s, sa_g``; ``design`` is an
    optional DataFrame ``code, period_s, damping_pct, sd_m, sa_g`` of code spectra: FEMA 356 dashed in the
    damping's colour, others dotted black.
    """
    if axes is None:
        axes = fig.subplots(3, 1, sharex=True)
        _margins(fig, fig.get_figheight(), hspace=0.1)
    frame = frame[frame["period_s"] <= max_period]
    for damping, group in frame.groupby("damping_pct"):
        colour = damping_colour(damping / 100.0)
        label = f"ξ = {damping:g} %"
        axes[0].plot(group["period_s"], group["sd_m"], color=colour, lw=1, label=label)
        axes[1].plot(group["period_s"], group["sv_m_s"], color=colour, lw=1, label=label)
        axes[2].plot(group["period_s"], group["sa_g"], color=colour, lw=1, label=label)
    if design is not None:
        design = design[design["period_s"] <= max_period]
        for (code, damping), group in design.groupby(["code", "damping_pct"], sort=False):
            fema = code.startswith("FEMA")
            style = {"color": damping_colour(damping / 100.0) if fema else "#000000", "lw": 1,
                     "ls": "--" if fema else ":", "label": f"{code}, β = {damping:g} %"}
            axes[0].plot(group["period_s"], group["sd_m"], **style)
            axes[2].plot(group["period_s"], group["sa_g"], **style)
    axes[0].set_title(title, fontsize=9)
    axes[0].set_ylabel("Sd = max|u| [m]")
    axes[1].set_ylabel("Sv = max|u'| [m/s]")
    axes[2].set_ylabel("Sa = max|ü+üg| [g]")
    axes[2].set_xlabel("T [s]")
    axes[0].legend(fontsize=7, ncol=2)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.set_xlim(0, max_period)


def draw_rocking_spectra(fig, frame, title, axes=None):
    """Rotation θ/α and angular-velocity spectra against 2π/p, one curve per α (Figures 5.x).

    ``frame`` has columns ``alpha_deg, size_s, theta_ratio, overturned, omega_peak_rad_s``;
    overturning is marked with × at θ/α = 1.
    """
    if axes is None:
        axes = fig.subplots(2, 1, sharex=True)
        _margins(fig, fig.get_figheight(), hspace=0.1)
    for alpha, group in frame.groupby("alpha_deg"):
        colour = alpha_colour(alpha)
        over = group["overturned"].eq(True).to_numpy()
        size = group["size_s"].to_numpy()
        ratio = np.where(over, np.nan, group["theta_ratio"].to_numpy())
        axes[0].plot(size, ratio, color=colour, lw=1, label=f"α = {alpha:g}°")
        _mark_overturned(axes[0], size, np.ones_like(size), over, colour)
        axes[1].plot(size, np.where(over, np.nan, group["omega_peak_rad_s"]), color=colour, lw=1)
    axes[0].set_title(f"{title}: rocking spectra (× overturns)", fontsize=9)
    axes[0].set_ylabel("max|θ|/α [-]")
    axes[0].set_ylim(0, 1.08)
    axes[1].set_ylabel("max|θ'| [rad/s]")
    axes[1].set_xlabel("2π/p [s]")
    axes[0].legend(fontsize=7)
    for ax in axes:
        ax.grid(alpha=0.3)


def draw_figure_5(fig, response, rocking, title, design=None):
    """Figure 5.x: response spectra (left) next to rocking spectra (right)."""
    grid = fig.add_gridspec(6, 2, hspace=0.9, wspace=0.22)
    _margins(fig, fig.get_figheight())
    left = [fig.add_subplot(grid[2 * i:2 * i + 2, 0]) for i in range(3)]
    right = [fig.add_subplot(grid[3 * i:3 * i + 3, 1]) for i in range(2)]
    draw_response_spectra(fig, response, f"{title}: true response spectra", design, axes=left)
    draw_rocking_spectra(fig, rocking, title, axes=right)


def draw_procedure_comparison(fig, results, spectra, title, procedure_title):
    """Figures 8.x / 9.x: Sd at β(α) | exact vs approximate θ/α | converged T(θ); a row per α.

    ``results`` are the result rows of one record and procedure; ``spectra`` a DataFrame
    ``alpha_deg, period_s, sd_m`` of the displacement spectrum the procedure read.
    """
    alphas = sorted(results["alpha_deg"].unique())
    axes = fig.subplots(len(alphas), 3, squeeze=False, sharex="col")
    _margins(fig, fig.get_figheight(), top_inch=0.75, hspace=0.35, wspace=0.25)
    for row, alpha in enumerate(alphas):
        colour = alpha_colour(alpha)
        rows = results[results["alpha_deg"] == alpha].sort_values("size_s")
        beta = rows["beta_pct"].iloc[0]
        spec = spectra[(spectra["alpha_deg"] == alpha) & (spectra["period_s"] <= 20)]
        ax = axes[row, 0]
        ax.plot(spec["period_s"], spec["sd_m"], color=colour, lw=1)
        ax.set_ylabel(f"α = {alpha:g}°\nSd [m]")
        ax.set_title(f"Sd at β = {beta:.2f} %", fontsize=8)
        size = rows["size_s"].to_numpy()
        alpha_rad = np.radians(alpha)
        exact_over = rows["exact_overturned"].eq(True).to_numpy()  # NaN: no record file
        approx_over = rows["approx_overturned"].eq(True).to_numpy()
        exact = np.where(exact_over, np.nan, rows["exact_theta_rad"].to_numpy() / alpha_rad)
        approx = rows["approx_theta_rad"].to_numpy(dtype=float) / alpha_rad
        ax = axes[row, 1]
        no_file = rows["exact_theta_rad"].isna().all()
        ax.plot(size, exact, color="#333333", lw=1.2,
                label="exact: no record file" if no_file else "exact")
        ax.plot(size, approx, color=colour, lw=1, ls="--", label=procedure_title)
        _mark_overturned(ax, size, np.full(size.shape, 1.0), exact_over, "#333333")
        if approx_over.any():
            ax.plot(size[approx_over], np.full(approx_over.sum(), 1.04), "^", color=colour, ms=3)
        not_conv = (rows["approx_outcome"] == "not-converged").to_numpy()
        if not_conv.any():
            ax.plot(size[not_conv], np.full(not_conv.sum(), 0.02), "|", color="#7b3294", ms=6)
        ax.set_ylim(0, 1.1)
        ax.set_ylabel("max|θ|/α [-]")
        ax.set_title("exact (× overturns) vs procedure (▲ predicts overturning, | no convergence)",
                     fontsize=8)
        ax = axes[row, 2]
        period = rows["approx_period_s"].to_numpy(dtype=float)
        ax.plot(size, period, color=colour, lw=1)
        if not np.isfinite(period).any():
            ax.set_yticks([])
            ax.text(0.5, 0.5, "no converged T(θ):\nno block has a fixed point below α",
                    ha="center", va="center", fontsize=8, transform=ax.transAxes)
        ax.set_ylabel("T(θ) [s]")
        ax.set_title("converged T(θ), Eq. 8.1", fontsize=8)
        if row == 0:
            axes[row, 1].legend(fontsize=7, loc="center left")
        for ax in axes[row]:
            ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("T [s]")
    axes[-1, 1].set_xlabel("2π/p [s]")
    axes[-1, 2].set_xlabel("2π/p [s]")
    fig.suptitle(f"{title}: {procedure_title}", fontsize=10)


def draw_verdict_map(fig, results, records, record_names):
    """Verdict per block: 2π/p across, α rows, one panel per record."""
    axes = fig.subplots(len(records), 1, squeeze=False)[:, 0]
    _margins(fig, fig.get_figheight(), top_inch=0.3, bottom_inch=0.95, left=0.06, hspace=0.6)
    names = list(VERDICT_COLOURS)
    cmap = ListedColormap([VERDICT_COLOURS[n] for n in names])
    for ax, record in zip(axes, records):
        rows = results[results["record"] == record]
        pivot = rows.pivot_table(index="alpha_deg", columns="size_s", values="verdict",
                                 aggfunc="first")
        codes = pivot.map(names.index).to_numpy(dtype=float)
        sizes = pivot.columns.to_numpy(dtype=float)
        step = sizes[1] - sizes[0] if sizes.size > 1 else 1.0
        ax.imshow(codes, aspect="auto", cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5,
                  interpolation="nearest", origin="lower",
                  extent=(sizes[0] - step / 2, sizes[-1] + step / 2, -0.5, len(pivot.index) - 0.5))
        ax.set_yticks(range(len(pivot.index)), [f"{a:g}°" for a in pivot.index])
        ax.set_ylabel("α")
        ax.set_title(record_names.get(record, record), fontsize=8, loc="left")
    axes[-1].set_xlabel("2π/p [s]")
    present = set(results.loc[results["record"].isin(records), "verdict"])
    fig.legend(handles=[Patch(facecolor=VERDICT_COLOURS[n], edgecolor="#888888", label=n)
                        for n in names if n in present],
               loc="lower center", ncol=4, fontsize=7)


def draw_figure_7_1(fig, r, beta_curves, priestley, fema):
    """Figure 7.1: β versus r from Eq. 7.9, with Eq. 7.10 and Eq. 9.1.

    ``beta_curves`` maps (θ₀/α, n) → β(r) arrays.
    """
    ax = fig.subplots()
    _margins(fig, fig.get_figheight())
    styles = {2: "-", 4: "--", 6: "-.", 8: ":"}
    cmap = matplotlib.colormaps["viridis"]
    ratios = sorted({key[0] for key in beta_curves})
    for (ratio, n), beta in beta_curves.items():
        ax.plot(r, 100 * beta, color=cmap(ratios.index(ratio) / max(1, len(ratios) - 1)),
                ls=styles.get(n, "-"), lw=0.8)
    ax.plot(r, 100 * priestley, color="#d62728", lw=2.2, label="Eq. 7.10: β = −0.34 ln r")
    ax.plot(r, 100 * fema, color="#000000", lw=2.2, label="Eq. 9.1: β = 0.4 (1 − √r)")
    for n, style in styles.items():
        ax.plot([], [], color="#555555", ls=style, label=f"Eq. 7.9, n = {n}")
    for ratio in ratios:
        ax.plot([], [], color=cmap(ratios.index(ratio) / max(1, len(ratios) - 1)), lw=3,
                label=f"θ₀/α = {ratio:g}")
    ax.set_xlabel("coefficient of restitution r [-]")
    ax.set_ylabel("equivalent damping β [%]")
    ax.set_title("Figure 7.1: equivalent damping of free rocking", fontsize=9)
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)


def draw_sensitivity(fig, rocking, oscillator, title_rocking, title_oscillator):
    """Figure 4.1 vs 7.2: block θ/α (left) and 'equivalent' oscillator u (right) under pulses.

    ``rocking`` and ``oscillator`` map a label to (time [s], value) pairs.
    """
    left, right = fig.subplots(1, 2)
    _margins(fig, fig.get_figheight(), wspace=0.2)
    colours = ("#1f77b4", "#ff7f0e", "#d62728")
    for colour, (label, (t, value)) in zip(colours, rocking.items()):
        left.plot(t, value, color=colour, lw=1, label=label)
    for colour, (label, (t, value)) in zip(colours, oscillator.items()):
        right.plot(t, 100 * value, color=colour, lw=1, label=label)
    left.set_ylim(-1.1, 1.1)
    left.set_ylabel("θ/α [-]")
    right.set_ylabel("u [cm]")
    left.set_title(title_rocking, fontsize=9)
    right.set_title(title_oscillator, fontsize=9)
    for ax in (left, right):
        ax.set_xlabel("t [s]")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
