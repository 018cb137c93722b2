"""Reproduction checklist of the reference report (Sections 4–9), evaluated on an audit run.

The claims are data (``claims.toml`` beside this module): each names an evaluator of
:mod:`audit.engine.claims.evaluators` and its parameters, the report's value and a tolerance fixed
from the report's own precision. :func:`evaluate_claims` runs every claim and grades it with a
status of :data:`audit.engine.shared.verdicts.CLAIM_STATUSES`.
"""

from __future__ import annotations

import math
import tomllib
from functools import cached_property
from importlib import resources

import pandas as pd

from audit import G
from audit.engine.claims.evaluators import EVALUATORS, evaluate_method
from audit.engine.claims.value import CLAIMS_FILE, CannotCheck
from audit.engine.shared.schemas import CLAIM_COLUMNS
from audit.engine.shared.verdicts import CLAIM_STATUSES, names
from audit.errors import InputError
from audit.physics.rocking import DEFAULT_FREE_MOTION_S
from procedures.context import RecordContext
from procedures.registry import available_procedures

CLAIM_FIELDS = ("id", "section", "claim", "reference_value", "records", "method", "tolerance",
                "note")
STATUSES = names(CLAIM_STATUSES)
TOLERANCE_KINDS = ("relative", "absolute", "at_least", "at_most", "exact")
def load_claims(path=None) -> list[dict]:
    """The claims of ``claims.toml`` (or of ``path``), checked for the required fields.

    Parameters
    ----------
    path : str or pathlib.Path, optional
        A claims file; the shipped ``claims.toml`` when not given.

    Raises
    ------
    InputError
        Naming the file and the claim when a field is missing, an id repeats, or an evaluator
        or tolerance kind is unknown.
    """
    if path is None:
        text = (resources.files("audit.engine.claims").joinpath(CLAIMS_FILE)
                .read_text(encoding="utf-8"))
        where = CLAIMS_FILE
    else:
        text, where = open(path, encoding="utf-8").read(), str(path)
    try:
        claims = tomllib.loads(text).get("claim", [])
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{where}: not valid TOML: {exc}") from None
    seen = set()
    for number, claim in enumerate(claims, start=1):
        name = claim.get("id", f"claim {number}")
        missing = [f for f in CLAIM_FIELDS if f not in claim]
        if missing:
            raise InputError(f"{where}: {name}: missing {', '.join(missing)}")
        if name in seen:
            raise InputError(f"{where}: {name}: id appears twice")
        seen.add(name)
        if claim["method"].get("name") not in EVALUATORS:
            raise InputError(f"{where}: {name}: method: unknown evaluator "
                             f"'{claim['method'].get('name')}'")
        if claim["tolerance"].get("kind") not in TOLERANCE_KINDS:
            raise InputError(f"{where}: {name}: tolerance: unknown kind "
                             f"'{claim['tolerance'].get('kind')}'")
    return claims


# ------------------------------------------------------------------------------ grading

def grade(tool_value, reference, tolerance: dict) -> str:
    """``agrees``, ``close`` or ``differs`` for a tool value against the report's value.

    Parameters
    ----------
    tool_value : float, int, bool or None
        What the tool computes.
    reference : float, int or bool
        The report's value.
    tolerance : dict
        The claim's ``tolerance``: ``kind`` (``exact``, ``absolute``, ``relative``, ``at_least``,
        ``at_most``), ``agree`` and ``close``, in the value's unit (a fraction for ``relative``).
    """
    if tool_value is None or (isinstance(tool_value, float) and math.isnan(tool_value)):
        return "differs"
    kind = tolerance["kind"]
    if kind == "exact":
        return "agrees" if tool_value == reference else "differs"
    close = tolerance.get("close", 0.0)
    if kind == "at_least":
        return ("agrees" if tool_value >= reference else
                "close" if tool_value >= reference - close else "differs")
    if kind == "at_most":
        return ("agrees" if tool_value <= reference else
                "close" if tool_value <= reference + close else "differs")
    error = abs(tool_value - reference)
    if kind == "relative":
        error /= abs(reference)
    return ("agrees" if error <= tolerance["agree"] else
            "close" if error <= close else "differs")


# ------------------------------------------------------------------------------ context

class ClaimContext:
    """What the evaluators may ask of a run: its tables, its records' motions, cached physics.

    Parameters
    ----------
    run : audit.engine.run.audit_run.AuditRun
    suite : records.RecordSuite, optional
        The records of the run. Single-block claims on a record simulate from its motion when
        given; otherwise they read the run's grid (and cannot check blocks off the grid).
    """

    def __init__(self, run, suite=None):
        self.run = run
        self.suite = suite
        settings = run.summary.get("settings", {})
        self.g = settings.get("g", G)
        self.free_motion_s = settings.get("free_motion_s", DEFAULT_FREE_MOTION_S)
        self.records = {item["id"]: item for item in run.summary.get("records", [])}
        self.scaling = run.summary.get("scaling")
        self._contexts = {}
        self._procedures = None

    def require(self, record_id: str) -> None:
        """CannotCheck unless the run holds ``record_id`` with a file, as recorded.

        Parameters
        ----------
        record_id : str
            The record.
        """
        self.require_unscaled()
        item = self.records.get(record_id)
        if item is None:
            raise CannotCheck(f"record {record_id} is absent from this run")
        if item.get("missing"):
            raise CannotCheck(f"record {record_id} has no file in this run "
                              f"({item.get('missing_reason') or 'missing'})")

    def require_unscaled(self) -> None:
        """CannotCheck when the run's records are scaled: the report's are as recorded."""
        if self.scaling:
            raise CannotCheck(f"the records of this run are scaled ({self.scaling}); the "
                              "report's claims are about the records as recorded")

    def entry(self, record_id: str):
        """The suite's entry of a record with a file, or None without a suite.

        Parameters
        ----------
        record_id : str
            The record.
        """
        self.require(record_id)
        if self.suite is None:
            return None
        return self.suite.get(record_id)

    def record_context(self, entry) -> RecordContext:
        """The procedures' cache of one record's spectra (shared by the claims).

        Parameters
        ----------
        entry : records.RecordEntry
            The record.
        """
        if entry.id not in self._contexts:
            self._contexts[entry.id] = RecordContext(entry, self.free_motion_s)
        return self._contexts[entry.id]

    @cached_property
    def estimates(self) -> pd.DataFrame:
        """Every procedure estimate of the run: ``results`` and, for the records without a file
        (kept apart from the verdicts), ``estimates_only``; joined once for all the claims."""
        return pd.concat([self.run.results, self.run.estimates_only], ignore_index=True)

    def procedure(self, name: str):
        """An instance of the registered procedure ``name`` (the registry, whose plug-ins are
        found by scanning the installed distributions, read once for all the claims).

        Parameters
        ----------
        name : str
            The procedure's registered name.
        """
        if self._procedures is None:
            self._procedures = available_procedures()
        return self._procedures[name]()


# ------------------------------------------------------------------------------ checklist

def evaluate_claim(ctx: ClaimContext, claim: dict) -> dict:
    """One row of the checklist (columns :data:`audit.engine.shared.schemas.CLAIM_COLUMNS`).

    Parameters
    ----------
    ctx : ClaimContext
        The run and the records.
    claim : dict
        One claim of :func:`load_claims`.
    """
    row = {key: claim[key] for key in ("id", "section", "claim", "reference_value")}
    notes = [claim["note"]] if claim["note"] else []
    try:
        for record in claim["records"]:
            ctx.require(record)
        result = evaluate_method(ctx, claim["method"])
    except CannotCheck as reason:
        row.update(tool_value=None, status="cannot-check", note="; ".join([str(reason)] + notes))
        return row
    value = result.value
    if result.branches:  # a cycle: the report read one of its branches as converged
        value = min(result.branches, key=lambda b: abs(b - claim["reference_value"]))
    status = grade(value, claim["reference_value"], claim["tolerance"])
    if result.branches and status == "agrees":
        status = "close"
    if result.note:
        notes.insert(0, result.note)
    row.update(tool_value=round(value, 6) if isinstance(value, float) else value,
               status=status, note="; ".join(notes))
    return row


def claimed_records(claims: list[dict] | None = None) -> set[str]:
    """Ids of the records the claims (default: every claim of ``claims.toml``) are about: the
    only records whose rows :func:`evaluate_claims` reads.

    Parameters
    ----------
    claims : list of dict, optional
        Claims of :func:`load_claims`.
    """
    return {record for claim in (load_claims() if claims is None else claims)
            for record in claim["records"]}


def evaluate_claims(run, suite=None, claims: list[dict] | None = None) -> pd.DataFrame:
    """The reproduction checklist of the reference report for an audit run.

    Parameters
    ----------
    run : audit.engine.run.audit_run.AuditRun
        The run (its ``results``, ``rocking`` and ``summary`` are read).
    suite : records.RecordSuite, optional
        The run's records; with it, single-block claims are simulated from the record (any
        block, any grid); without it they read the run's grid.
    claims : list of dict, optional
        Default: every claim of ``claims.toml``.

    Returns
    -------
    pandas.DataFrame
        Columns ``id, section, claim, reference_value, tool_value, status, note``; status one
        of ``agrees``, ``close``, ``differs``, ``cannot-check``.
    """
    ctx = ClaimContext(run, suite)
    rows = [evaluate_claim(ctx, claim) for claim in (load_claims() if claims is None else claims)]
    return pd.DataFrame(rows, columns=CLAIM_COLUMNS)


__all__ = ["evaluate_claims", "claimed_records", "load_claims", "grade", "STATUSES",
           "EVALUATORS"]
