"""Pieces of the HTML pages drawn from saved files: their templates, a number, a plotly
figure's div and a table."""

from __future__ import annotations

import functools
import math

import pandas as pd
from jinja2 import Environment, FileSystemBytecodeCache, PackageLoader, select_autoescape

from reports.plots import to_json


def number(value, fmt: str = "{:.3g}") -> str:
    """``value`` formatted, "—" where it is missing (None or NaN)."""
    return "—" if value is None or (isinstance(value, float) and math.isnan(value)) \
        else fmt.format(value)


class _SparingBytecodeCache(FileSystemBytecodeCache):
    """jinja2's cache of compiled templates, which never fails a page: compiled code it cannot
    read or write is compiled again, as without a cache."""

    def load_bytecode(self, bucket) -> None:
        try:
            super().load_bytecode(bucket)
        except OSError:
            pass

    def dump_bytecode(self, bucket) -> None:
        try:
            super().dump_bytecode(bucket)
        except OSError:
            pass


@functools.cache
def _bytecode_cache() -> FileSystemBytecodeCache | None:
    """The cache in jinja2's folder of the user's temporary directory (``_jinja2-cache-UID``),
    None where that folder cannot be made or is not safely the user's own."""
    try:
        return _SparingBytecodeCache()
    except (OSError, RuntimeError):
        return None


def page_templates() -> Environment:
    """The pages' templates (``reports/templates``), with the ``num`` filter (:func:`number`).

    Compiling a template costs ~80 ms a process; jinja2 keeps the compiled code, keyed by the
    template's source, so later processes load it instead (:func:`_bytecode_cache`)."""
    env = Environment(loader=PackageLoader("reports", "templates"),
                      autoescape=select_autoescape(["html", "j2"]), trim_blocks=True,
                      lstrip_blocks=True, bytecode_cache=_bytecode_cache())
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
