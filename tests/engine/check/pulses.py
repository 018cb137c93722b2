"""The records the check's tests share: eight one-cosine pulses of 0.5 g, short and long, each
exact response known independently of the check."""

from __future__ import annotations

from records import RecordEntry, RecordSuite, one_pulse

PERIODS_S = (0.4, 0.6, 0.8, 1.0, 1.3, 1.6, 2.0, 2.5)


def eight_pulses() -> RecordSuite:
    """A one-cosine pulse of 0.5 g at each of :data:`PERIODS_S` [s], a suite."""
    return RecordSuite(tuple(RecordEntry(f"cosine_{t:g}s", one_pulse("cosine", 0.5, t,
                                                                     record_id=f"c{t:g}"))
                             for t in PERIODS_S), "eight one-cosine pulses")
