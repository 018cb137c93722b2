"""The command line's flags for the API's argument names, in one table: a message from below
the command line names the argument (``size_s: …``); the command line shows its flag
(``--size: …``) instead."""

from __future__ import annotations

import re

#: Argument (settings field) → flag, for every command.
FLAGS = {
    "alpha_deg": "--alpha", "size_s": "--size", "free_motion_s": "--free-motion",
    "agree_band": "--agree-band", "robustness": "--robustness", "restitution": "--restitution",
    "vertical": "--vertical", "friction": "--friction", "sensitivity": "--sensitivity",
    "site": "--site", "site_override": "--site-override", "scale_to_site": "--scale-to-site",
    "anchor_period_s": "--anchor-period", "ntc_site": "--ntc-site", "jobs": "--jobs",
    "scheduler": "--scheduler", "resume": "--resume", "detail": "--detail",
    "records": "--records", "motion": "--record", "force": "--force", "im": "--im",
    "stripes": "--stripes", "blocks": "--block", "block": "--block", "procedure": "--procedure",
    "width_m": "--block", "height_m": "--block", "skip_bad": "--skip-bad-records",
    "skip_bad_records": "--skip-bad-records", "out_dir": "--out", "partial_dir": "--out",
    "periods_s": "--periods", "damping_pct": "--damping", "sxs_g": "--sxs", "sx1_g": "--sx1",
    "ag_g": "--ag", "f0": "--f0", "tc_star_s": "--tc-star", "site_level": "--level",
    "hazard": "--hazard", "objects": "--objects", "site_location": "--site-location", "risk_target": "--risk-target",
    "hazard_imt": "--hazard-imt", "return_period": "--return-period", "poe": "--poe",
    "floor": "--floor", "building": "--building", "building_model": "--building-model",
    "building_damping": "--building-damping",
    "dt_s": "--dt", "units": "--units", "params": "--param", "mass_kg": "--mass",
    "limit_state": "--limit-state", "method": "--method",
}


def with_flags(message: str, fields) -> str:
    """``message`` with each of ``fields`` it names replaced by its flag (a boolean
    ``field=True`` by the flag alone).

    A field of one plain word (``hazard``, ``records``) is also an ordinary word, which a
    message quotes from a file or a description (a curve's source "USGS hazard service", a
    suite's title): it is replaced only outside parentheses and quotes, where the message
    speaks of the argument itself. A field with an underscore (``site_location``) is the
    argument wherever it appears."""
    for field in dict.fromkeys(fields):
        flag = FLAGS.get(field)
        if flag:
            pattern = re.compile(rf"(?<![\w-]){re.escape(field)}(=True)?(?!\w)")
            if "_" in field:
                message = pattern.sub(flag, message)
            else:
                message = "".join(pattern.sub(flag, part) if outside else part
                                  for part, outside in _spoken_parts(message))
    return message


def _spoken_parts(message: str):
    """``(text, outside)`` pieces of ``message``: ``outside`` false for text in parentheses
    (nested too) or in single or double quotes, which the message quotes from elsewhere."""
    depth, quote, start, out = 0, None, 0, []

    def cut(end, outside):
        if end > start:
            out.append((message[start:end], outside))
        return end

    for i, char in enumerate(message):
        if quote:
            if char == quote:
                start = cut(i + 1, False)
                quote = None
        elif char in "'\"" and depth == 0 and (i == 0 or not message[i - 1].isalnum()):
            start = cut(i, True)
            quote = char
        elif char == "(":
            if depth == 0:
                start = cut(i, True)
            depth += 1
        elif char == ")" and depth:
            depth -= 1
            if depth == 0:
                start = cut(i + 1, False)
    cut(len(message), depth == 0 and quote is None)
    return out


__all__ = ["FLAGS", "with_flags"]
