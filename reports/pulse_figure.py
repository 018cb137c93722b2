"""The figure of ``python -m audit pulse --plot``: each record's velocity with its pulse."""

from __future__ import annotations

import numpy as np

from reports.figures import new_figure

#: Height of one record's panel [inch].
PANEL_HEIGHT_IN = 1.6


def draw_record_pulses(panels) -> "matplotlib.figure.Figure":
    """One panel per record: its velocity [cm/s], the extracted pulse along it and the fitted
    Mavroeidis & Papageorgiou pulse along it.

    Parameters
    ----------
    panels : list of dict
        ``title``, ``time_s``, ``velocity_cm_s``, ``pulse_cm_s`` (None when not pulse-like) and
        ``fit_cm_s`` (None without a fit).
    """
    height = PANEL_HEIGHT_IN * len(panels) + 0.8
    fig = new_figure(10.0, height)
    fig.subplots_adjust(top=1 - 0.3 / height, bottom=0.5 / height, left=0.08, right=0.98,
                        hspace=0.55)
    axes = np.atleast_1d(fig.subplots(len(panels), 1))
    for ax, panel in zip(axes, panels):
        ax.plot(panel["time_s"], panel["velocity_cm_s"], color="0.55", lw=0.7, label="record")
        if panel["pulse_cm_s"] is not None:
            ax.plot(panel["time_s"], panel["pulse_cm_s"], color="tab:red", lw=1.2,
                    label="extracted pulse (10 db4 wavelets)")
        if panel["fit_cm_s"] is not None:
            ax.plot(panel["time_s"], panel["fit_cm_s"], color="tab:blue", lw=1.0, ls="--",
                    label="Mavroeidis-Papageorgiou fit")
        ax.set_title(panel["title"], fontsize=8, loc="left")
        ax.set_ylabel("v [cm/s]", fontsize=8)
        ax.tick_params(labelsize=7)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("time [s]")
    return fig
