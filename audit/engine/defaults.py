"""Defaults of an audit, the one place the engine, the Python API and the command line read them.

Light on purpose (no numpy), so ``--help`` can show them without a scientific import.
"""

from audit.physics.defaults import DEFAULT_FREE_MOTION_S

#: Slendernesses α of the grid [degrees].
DEFAULT_ALPHA_DEG = (10.0, 15.0, 20.0)
#: Block sizes 2π/p of the grid: START, STOP (inclusive), STEP [s].
DEFAULT_SIZES = (0.5, 8.0, 0.05)
#: Half-width of the agreement band on approx/exact [-].
DEFAULT_AGREE_BAND = 0.10
#: Relative scaling ε of the record for the fragile-overturning flag [-] (0 turns it off).
DEFAULT_ROBUSTNESS = 0.03
#: Threads of the exact solver (or Dask worker processes).
DEFAULT_JOBS = 2
#: Where records are audited: ``local``, ``dask`` or ``tcp://HOST:PORT``.
DEFAULT_SCHEDULER = "local"


def alpha_text(alpha_deg=DEFAULT_ALPHA_DEG) -> str:
    """Slendernesses as typed on the command line, e.g. ``10,15,20``."""
    return ",".join(f"{a:g}" for a in alpha_deg)


def sizes_text(sizes=DEFAULT_SIZES) -> str:
    """A size grid as typed on the command line, e.g. ``0.5:8:0.05``."""
    return ":".join(f"{v:g}" for v in sizes)


__all__ = ["DEFAULT_ALPHA_DEG", "DEFAULT_SIZES", "DEFAULT_AGREE_BAND", "DEFAULT_ROBUSTNESS",
           "DEFAULT_JOBS", "DEFAULT_SCHEDULER", "DEFAULT_FREE_MOTION_S", "alpha_text",
           "sizes_text"]
