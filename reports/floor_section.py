"""The floor section of the check page: the median floor spectrum against the ground's at the
site, and each record's peak floor acceleration and velocity (from ``check.json``'s ``floor``)."""

from __future__ import annotations

from reports.plots import _axis, _layout, to_json

GROUND_COLOUR = "#888888"
FLOOR_COLOUR = "#d62728"


def floor_spectra_figure(floor: dict) -> str | None:
    """The plotly spec (JSON) of the two median spectra, or None on the ground."""
    spectra = floor.get("spectra")
    if not spectra:
        return None
    data = [{"type": "scatter", "mode": "lines", "x": spectra["period_s"],
             "y": spectra[f"{where}_median_sa_g"], "name": name,
             "line": {"color": colour, "width": 2}}
            for where, name, colour in (("ground", "ground, median of the records at the site",
                                         GROUND_COLOUR),
                                        ("floor", f"floor {floor['description']}, median",
                                         FLOOR_COLOUR))]
    layout = _layout(380, xaxis=_axis("period T [s]", type="log"),
                     yaxis=_axis(f"S_a, {spectra['damping']:.0%} damped [g]"))
    return to_json({"data": data, "layout": layout})


__all__ = ["floor_spectra_figure"]
