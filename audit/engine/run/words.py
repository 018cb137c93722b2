"""What ``audit run`` prints: the audit's bottom line in a few lines of text, from its
``summary.json`` (:mod:`audit.engine.run.results`)."""

from __future__ import annotations


def audit_summary_text(summary: dict) -> str:
    """The lines ``audit run`` prints of an audit whose ``summary.json`` is ``summary``: what
    was audited where, what could not be (one line per procedure and reason, whatever the
    number of records), and the count of each verdict; each line ends in a newline.

    Parameters
    ----------
    summary : dict
        ``summary.json`` of the run.
    """
    names = ", ".join(p["name"] for p in summary["procedures"])
    lines = [f"Audited {names} on {summary['records_source']} in {summary['scheduler']}"
             + (f"; reused {len(summary['resumed'])} records of an interrupted run"
                if summary["resumed"] else "")]
    grouped = {}
    for item in summary["unauditable"]:
        grouped.setdefault((item["procedure"], item["reason"]), []).append(item["record"])
    for (procedure, reason), records in grouped.items():
        which = records[0] if len(records) == 1 else f"{len(records)} records"
        lines.append(f"  not audited: {procedure} × {which}: {reason}")
    counts = {}
    for line in summary["bottom_line"]:
        for verdict, n in line["count"].items():
            counts[verdict] = counts.get(verdict, 0) + n
    lines.append("Verdicts: " + ", ".join(f"{v} {n}" for v, n in
                                          sorted(counts.items(), key=lambda item: -item[1])
                                          if n))
    return "".join(f"{line}\n" for line in lines)


__all__ = ["audit_summary_text"]
