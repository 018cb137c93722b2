"""What an evaluator of a claim (:mod:`audit.engine.claims.evaluators`) gives back: a
:class:`Value`, or :class:`CannotCheck` when the run lacks what the claim needs; and the file of
the claims, which the evaluators' errors name.
"""

from __future__ import annotations

from dataclasses import dataclass

#: The claims the evaluators serve, beside :mod:`audit.engine.claims.checklist` (named in their errors).
CLAIMS_FILE = "claims.toml"


class CannotCheck(Exception):
    """The run lacks what a claim needs; the message says what."""


@dataclass(frozen=True)
class Value:
    """An evaluator's answer: the number (or yes/no), a note, or the branches of a cycle."""

    value: float | bool | None
    note: str = ""
    #: Values of the branches of a cycle the procedure settled in instead of a fixed point.
    branches: tuple = ()
