"""Pieces of the HTML pages drawn from saved files: a plotly figure's div and a table."""

from __future__ import annotations

import pandas as pd

from reports.plots import to_json


def plot_div(figure_id: str, spec: dict) -> str:
    """A div drawn by plotly.js (inlined in the page's head) from ``spec``."""
    return (f'<div id="{figure_id}"></div><script>(s => Plotly.newPlot("{figure_id}", s.data, '
            f's.layout, {{displaylogo: false}}))({to_json(spec)});</script>')


def html_table(frame: pd.DataFrame) -> str:
    """A table, three significant digits, "—" for a missing value."""
    return frame.to_html(index=False, na_rep="—", border=0,
                         float_format=lambda v: f"{v:.3g}")


__all__ = ["plot_div", "html_table"]
