"""Rocking Audit: exact rocking response of rigid blocks and the audit of design guidelines.

Equation numbers refer to Makris & Konstantinidis, *The Rocking Spectrum and the
Shortcomings of Design Guidelines*, PEER 2001/07.

The Python API (:mod:`audit.api`) is here too: ``audit.Block``, ``audit.rock``, ``audit.run``,
``audit.margins``, ``audit.check``, ``audit.risk``, ``audit.fragility``, ``audit.floor_motion`` (loaded on first use, so that the command line starts
light).
"""

__version__ = "0.1.0"

#: Acceleration of gravity [m/s²] used throughout unless configured otherwise.
G = 9.81

#: The Python API (:mod:`audit.api`), loaded on first use so that the command line starts light.
_API = ("Block", "RockingResponse", "AuditResult", "MarginsResult", "FragilityResult", "rock",
        "run", "margins", "fragility", "design_suite", "risk", "read_hazard", "check",
        "CheckResult", "validate", "ValidationResult", "floor_motion", "FloorMotion")


def __getattr__(name):
    if name in _API:
        from audit import api
        return getattr(api, name)
    raise AttributeError(f"module 'audit' has no attribute {name!r}")


def __dir__():
    return sorted({*(name for name in globals() if not name.startswith("_")), "__version__",
                   *_API})
