"""Guideline procedures for the peak rotation of rocking blocks, one module per publication."""

from procedures.base import Estimate, Procedure, iterate_rotation
from procedures.registry import available_procedures, get_procedures

__all__ = ["Estimate", "Procedure", "iterate_rotation", "available_procedures", "get_procedures"]
