"""The one shape of every result of the API: ``.table`` (a DataFrame), ``.summary`` (a dict),
``.summary_text()`` (what the command line prints), ``.write(folder)``, ``.report(path)`` and
``_repr_html_`` for notebooks.

A result whose files are made in memory (:meth:`Files.files`, the page among them) gets
``write`` and ``report`` from :class:`Files`; its page is always drawn from the files as saved
(:func:`with_page`)."""

from __future__ import annotations

from pathlib import Path


class Files:
    """``write`` and ``report`` of a result that makes its files in memory: a subclass gives
    :meth:`files` and :attr:`PAGE`, the name of its HTML page among them."""

    PAGE = ""

    def files(self) -> dict[str, bytes]:
        raise NotImplementedError

    def write(self, out_dir) -> Path:
        """Write every file, the page too, into ``out_dir`` (atomically, together)."""
        from audit.engine.shared import fields
        from audit.files import write_files_atomically
        out_dir = fields.path("out_dir", out_dir, "a folder")
        write_files_atomically(out_dir, self.files())
        return out_dir

    def report(self, path) -> Path:
        """Write the HTML page alone to ``path``."""
        from audit.engine.shared import fields
        from audit.files import write_file_atomically
        path = fields.path("path", path, "a file name")
        write_file_atomically(path, self.files()[self.PAGE])
        return path


def with_page(files: dict, page_name: str, render) -> dict:
    """``files`` and the page ``render(folder)`` draws from them as saved (in a scratch folder),
    so that a page is always the picture of exactly the files beside it."""
    import tempfile

    from audit.files import write_files_atomically
    with tempfile.TemporaryDirectory() as saved:
        write_files_atomically(saved, files)
        return {**files, page_name: render(saved).encode()}


def table_html(table, lead: str) -> str:
    """A result's ``_repr_html_``: a paragraph of text (HTML-escaped) and a table."""
    import html
    return (f"<p>{html.escape(lead)}</p>"
            + table.to_html(index=False, float_format=lambda v: f"{v:.3g}", na_rep="—"))


__all__ = ["Files", "with_page", "table_html"]
