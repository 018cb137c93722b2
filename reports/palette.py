"""Colours shared by the interactive report and the static CLI plots: the same colour for the
same slenderness α, damping ratio and verdict everywhere."""

from __future__ import annotations

from audit.engine.shared.verdicts import CHECK_VERDICTS, ROTATION_VERDICTS, colours

ALPHA_COLOURS = {10.0: "#1f77b4", 15.0: "#d62728", 20.0: "#2ca02c"}
DAMPING_COLOURS = {0.05: "#1f77b4", 0.10: "#ff7f0e", 0.15: "#9467bd"}
_EXTRA_COLOURS = ("#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
#: The verdict colours of the engine's one vocabulary (:mod:`audit.engine.shared.verdicts`).
VERDICT_COLOURS = colours(ROTATION_VERDICTS)
CHECK_COLOURS = colours(CHECK_VERDICTS)


def alpha_colour(alpha_deg: float) -> str:
    """Colour of a slenderness [degrees], the same in every figure."""
    key = round(float(alpha_deg), 6)
    return ALPHA_COLOURS.get(key, _EXTRA_COLOURS[int(key * 7) % len(_EXTRA_COLOURS)])


def damping_colour(damping: float) -> str:
    """Colour of a damping ratio [-]."""
    key = round(float(damping), 6)
    return DAMPING_COLOURS.get(key, _EXTRA_COLOURS[int(key * 1000) % len(_EXTRA_COLOURS)])
