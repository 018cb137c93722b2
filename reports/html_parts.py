"""Pieces of the HTML pages drawn from saved files: their templates, a number, a plotly
figure's div and a table."""

from __future__ import annotations

import math

import pandas as pd
from jinja2 import Environment, FileSystemBytecodeCache, PackageLoader, select_autoescape

from reports.plots import to_json


def number(value, fmt: str = "{:.3g}") -> str:
    """``value`` formatted, "—" where it is missing (None or NaN)."""
    return "—" if value is None or (isinstance(value, float) and math.isnan(value)) \
        else fmt.format(value)


def page_templates() -> Environment:
    """The pages' templates (``reports/templates``), with the ``num`` filter (:func:`number`).

    Compiling a template costs ~80 ms a process; jinja2 keeps the compiled code in its own
    folder of the user's temporary directory, keyed by the template's source, so later
    processes load it instead."""
    env = Environment(loader=PackageLoader("reports", "templates"),
                      autoescape=select_autoescape(["html", "j2"]), trim_blocks=True,
                      lstrip_blocks=True, bytecode_cache=FileSystemBytecodeCache())
    env.filters["num"] = number
    return env


def plot_div(figure_id: str, spec: dict) -> str:
    """A div drawn by plotly.js (inlined in the page's head) from ``spec``."""
    return (f'<div id="{figure_id}"></div><script>(s => Plotly.newPlot("{figure_id}", s.data, '
            f's.layout, {{displaylogo: false}}))({to_json(spec)});</script>')


def html_table(frame: pd.DataFrame) -> str:
    """A table, three significant digits, "—" for a missing value."""
    return frame.to_html(index=False, na_rep="—", border=0,
                         float_format=lambda v: f"{v:.3g}")


__all__ = ["page_templates", "number", "plot_div", "html_table"]
