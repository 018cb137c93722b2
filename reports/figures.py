"""Static matplotlib images for the CLI's ``--plot FILE.png`` (``rock``, ``spectrum``).

The HTML report draws its figures in the browser (:mod:`reports.plots` and the ``*_figures``
modules); this module is imported only when a PNG is asked for. Every ``draw_*`` function fills a given
:class:`matplotlib.figure.Figure` from plain arrays or DataFrames; units on every axis.
"""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from reports.palette import alpha_colour, damping_colour  # noqa: E402

DPI = 80


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
        _draw_history(ax_theta, ax_omega, block)


def _draw_history(ax_theta, ax_omega, block: dict):
    """One item of :func:`draw_time_histories`' ``blocks`` on its two axes."""
    time, theta_ratio, omega = block["time"], block["theta_ratio"], block["omega"]
    title, rocking_span = block["title"], block.get("rocking_span")
    procedures, excitation_end = block.get("procedures"), block.get("excitation_end")
    cycle_starts = block.get("cycle_starts", ())
    cycle_durations = block.get("cycle_durations", ())
    unknown = set(block) - {"time", "theta_ratio", "omega", "title", "rocking_span",
                            "cycle_starts", "cycle_durations", "procedures", "excitation_end"}
    if unknown:  # as the keywords it was called with named them
        raise TypeError(f"draw_time_histories: unknown block key(s) {sorted(unknown)}")
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


