"""Rocking Audit: exact rocking response of rigid blocks and the audit of design guidelines.

Equation numbers refer to Makris & Konstantinidis, *The Rocking Spectrum and the
Shortcomings of Design Guidelines*, PEER 2001/07.
"""

__version__ = "0.1.0"

#: Acceleration of gravity [m/s²] used throughout unless configured otherwise.
G = 9.81

#: The Python API (:mod:`audit.api`), loaded on first use so that the command line starts light.
_API = ("Block", "RockingResponse", "AuditResult", "MarginsResult", "rock", "run", "margins",
        "validate", "ValidationResult")


def __getattr__(name):
    if name in _API:
        from audit import api
        return getattr(api, name)
    raise AttributeError(f"module 'audit' has no attribute {name!r}")
