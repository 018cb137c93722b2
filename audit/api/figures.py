"""The figures the command line saves as PNG: matplotlib (:mod:`reports.figures`) is loaded
when one is drawn, not by the front door."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

def png_bytes(fig: Figure) -> bytes:
    """The PNG of a matplotlib figure (``RockingResponse.plot()``, :func:`spectra_figure`, the
    figure of :func:`audit.record_pulses`)."""
    from reports.figures import png_bytes as png
    return png(fig)


def spectra_figure(frame: pd.DataFrame, kind: str, title: str = "", *,
                   height_in: float = 6.0) -> Figure:
    """The spectra of one motion drawn on a new figure 10 inch wide.

    Parameters
    ----------
    frame : pandas.DataFrame
        The table of :func:`audit.rocking_spectrum` (``kind="rocking"``) or of
        :func:`audit.response_spectra` (``kind="response"``).
    kind : {"rocking", "response"}
        Rotation θ/α and angular velocity against 2π/p, or Sd, Sv, Sa against T.
    title : str
        The figure's title (the record's id).
    height_in : float
        Height of the figure [inch].
    """
    from reports.figures import draw_response_spectra, draw_rocking_spectra, new_figure
    draw = {"rocking": draw_rocking_spectra, "response": draw_response_spectra}[kind]
    fig = new_figure(10.0, height_in)
    draw(fig, frame, title)
    return fig


__all__ = ["png_bytes", "spectra_figure"]
