"""Guideline procedures for rocking blocks, one module per publication, and their contract."""

from procedures.base import Check, Estimate, Evaluation, Procedure, estimate_rotation
from procedures.iteration import iterate_rotation
from procedures.registry import available_procedures, get_procedures

__all__ = ["Check", "Estimate", "Evaluation", "Procedure", "estimate_rotation",
           "iterate_rotation", "available_procedures", "get_procedures"]
