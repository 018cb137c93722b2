"""The command line's flags for the API's argument names, in one table: a message from below
the command line names the argument (``sizes_s: …``); the command line shows its flag
(``--sizes: …``) instead."""

from __future__ import annotations

import re

#: Argument (settings field) → flag, for every command.
FLAGS = {
    "alpha_deg": "--alpha", "sizes_s": "--sizes", "free_motion_s": "--free-motion",
    "agree_band": "--agree-band", "robustness": "--robustness", "restitution": "--restitution",
    "vertical": "--vertical", "friction": "--friction", "sensitivity": "--sensitivity",
    "site": "--site", "site_override": "--site-override", "scale_to_site": "--scale-to-site",
    "anchor_period_s": "--anchor-period", "ntc_site": "--ntc-site", "jobs": "--jobs",
    "scheduler": "--scheduler", "resume": "--resume", "detail": "--detail",
    "records": "--records", "motion": "--record", "force": "--force", "im": "--im",
    "stripes": "--stripes", "blocks": "--block", "block": "--block", "procedure": "--procedure",
    "width_m": "--block", "height_m": "--block", "skip_bad": "--skip-bad-records",
    "periods_s": "--periods", "damping_pct": "--damping", "sxs_g": "--sxs", "sx1_g": "--sx1",
    "ag_g": "--ag", "f0": "--f0", "tc_star_s": "--tc-star", "site_level": "--level",
    "hazard": "--hazard", "objects": "--objects", "site_location": "--site-location", "risk_target": "--risk-target",
    "floor": "--floor", "building": "--building", "building_model": "--building-model",
    "building_damping": "--building-damping",
}
#: Where a command's flag for an argument differs from :data:`FLAGS`.
COMMAND_FLAGS = {"rock": {"free_motion_s": "--duration"}}


def with_flags(message: str, fields, command: str | None = None) -> str:
    """``message`` with each of ``fields`` it names replaced by the command's flag (a boolean
    ``field=True`` by the flag alone)."""
    table = {**FLAGS, **COMMAND_FLAGS.get(command, {})}
    for field in dict.fromkeys(fields):
        flag = table.get(field)
        if flag:
            message = re.sub(rf"(?<![\w-]){re.escape(field)}(=True)?(?!\w)", flag, message)
    return message


__all__ = ["FLAGS", "COMMAND_FLAGS", "with_flags"]
