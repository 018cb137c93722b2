"""Pieces of the HTML pages drawn from saved files: their templates, a number, a plotly
figure's div and a table."""

from __future__ import annotations

import functools
import math

import pandas as pd
from jinja2 import Environment, FileSystemBytecodeCache, PackageLoader, select_autoescape

from reports.plots import to_json


#: The look every page shares (check.html, validation.html).
PAGE_STYLE = """
  body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; color: #222; max-width: 1100px;
         margin: 0 auto; padding: 0 1.2em 3em; line-height: 1.45; font-size: 15px; }
  h2 { border-bottom: 2px solid #444; padding-bottom: 0.15em; margin-top: 2em; }
  .meta { color: #555; font-size: 0.9em; }
  .quote { background: #f7f7f0; border-left: 4px solid #b58900; padding: 0.6em 1em;
           margin: 0.6em 0; }
  table { border-collapse: collapse; font-size: 0.88em; margin: 0.8em 0; }
  th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: right; vertical-align: top; }
  th { background: #eee; }
  td.l, th.l { text-align: left; }
  .fails { color: #b2182b; font-weight: bold; }
  .passes { color: #1b7837; font-weight: bold; }
  .records { columns: 3; font-size: 0.85em; }
  figure { margin: 1em 0; }
  figcaption { font-size: 0.88em; color: #444; }
"""


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
