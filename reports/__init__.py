"""HTML rendering of an audit: jinja2 templates and matplotlib figures."""

from reports.render import render_report

__all__ = ["render_report"]
