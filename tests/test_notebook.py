"""The quick-start notebook in docs/ runs from top to bottom, so it cannot rot."""

from __future__ import annotations

from pathlib import Path

import nbclient
import nbformat
import pytest

NOTEBOOK = Path(__file__).resolve().parents[1] / "docs" / "quickstart.ipynb"


@pytest.mark.slow  # end to end: a Jupyter kernel runs the notebook
def test_quickstart_notebook_runs(monkeypatch):
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)  # the shipped seed records
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(NOTEBOOK.parent)}}).execute()
    outputs = [cell.get("outputs", []) for cell in notebook.cells if cell.cell_type == "code"]
    text = "\n".join(str(item.get("data", {}).get("text/plain", item.get("text", "")))
                     for cell in outputs for item in cell)
    # the two cabinets of width/height 0.4 (α = atan 0.4 = 21.8014°): the smaller one
    # overturns, the larger one survives under Rinaldi (the scale effect)
    assert "α = 21.8014°, 2π/p = 2.40397 s: overturns" in text
    assert "α = 21.8014°, 2π/p = 2.94425 s: peak θ/α" in text
    assert any("image/png" in item.get("data", {}) for cell in outputs for item in cell)
    html = "\n".join(str(item.get("data", {}).get("text/html", ""))
                     for cell in outputs for item in cell)
    assert "NTC 2018 / Circolare 2019" in html and "Priestley et al. (1978) with 2β" in html
    assert "'report.html'" in text and "'results.csv'" in text
