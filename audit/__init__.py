"""Rocking Audit: exact rocking response of rigid blocks and the audit of design guidelines.

Equation numbers refer to Makris & Konstantinidis, *The Rocking Spectrum and the
Shortcomings of Design Guidelines*, PEER 2001/07.

The Python API (:mod:`audit.api`) is here too: ``audit.Block``, ``audit.rock``, ``audit.run``,
``audit.margins``, ``audit.check``, ``audit.risk``, ``audit.fragility``, ``audit.validate``,
``audit.rocking_spectrum``, ``audit.design_spectrum``, ``audit.load_result``,
``audit.floor_motion``, ``audit.record_pulses``, imported plainly from it (a light import:
the API loads numpy, pandas and the solver inside the functions that use them).
"""

__version__ = "0.1.0"

# records, reports and procedures are generic names: a foreign one found first is named here,
# not met later as a puzzling ImportError inside the audit (docs/install.md)
from audit.top_level import check_siblings as _check_siblings  # noqa: E402

_check_siblings()

#: Acceleration of gravity [m/s²] used throughout unless configured otherwise.
G = 9.81

# the Python API, imported after G and the version it reads
from audit.api import (AuditResult, Block, Building, CheckResult, Floor,  # noqa: E402
                       FloorMotion, FragilityResult, Hazard, MarginsResult, Records,
                       RockingResponse, Runtime, Site, Solver, ValidationResult, check,
                       design_spectrum, design_suite, floor_motion, fragility, load_result,
                       margins, read_hazard, record_pulses, response_spectra, risk, rock,
                       rocking_spectrum, run, validate)

__all__ = ["G", "__version__", "Block", "RockingResponse", "AuditResult", "MarginsResult",
           "FragilityResult", "rock", "run", "margins", "fragility", "design_suite", "risk",
           "read_hazard", "check", "CheckResult", "validate", "ValidationResult",
           "rocking_spectrum", "response_spectra", "design_spectrum", "load_result",
           "floor_motion", "FloorMotion", "record_pulses", "Building", "Floor", "Site", "Hazard",
           "Solver", "Runtime", "Records"]
