"""Defaults of an audit, the one place the engine, the Python API and the command line read them.

Light on purpose (no numpy), so ``--help`` can show them without a scientific import.
"""

from audit.physics.building.floor import DEFAULT_BUILDING_DAMPING, DEFAULT_BUILDING_MODEL
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
#: Anchor period of the FEMA P695 scaling to a design spectrum [s].
DEFAULT_ANCHOR_PERIOD_S = 1.0
#: Response spectra: damping ratios [%] and oscillator periods START, STOP, STEP [s].
DEFAULT_DAMPING_PCT = (5.0, 10.0, 15.0)
DEFAULT_PERIODS = (0.02, 10.0, 0.02)
#: Design spectra: damping ratios [%] and periods START, STOP, STEP [s].
DEFAULT_DESIGN_DAMPING_PCT = (5.0,)
DEFAULT_DESIGN_PERIODS = (0.0, 8.0, 0.02)
#: Free motion after the record of oscillator response spectra [s] (none: the record's own).
DEFAULT_RESPONSE_FREE_MOTION_S = 0.0
#: The probabilistic procedure audited by ``fragility``, and its records.
DEFAULT_PROBABILISTIC_PROCEDURE = "femap58"
DEFAULT_FRAGILITY_RECORDS = "p695-far-field"
#: Records of ``check``: the FEMA P695 far-field set, scaled to the site.
DEFAULT_CHECK_RECORDS = "p695-far-field"
#: The exact solver's impact model: Eq. 4.8 (Housner's).
DEFAULT_RESTITUTION = "housner"
#: Intensity measure of the design-level audit (``margins``): the 5 %-damped pseudo-spectral
#: acceleration ω²·S_d at 1 s [g].
DEFAULT_IM = "sa:1.0"
#: Block sizes 2π/p of the design-level audit's grid: START, STOP (inclusive), STEP [s].
DEFAULT_MARGINS_SIZES = (0.5, 8.0, 0.25)
#: How many stripes the design-level audit solves when none are given: the fixed lattice's
#: levels, 2^(k/4) for k = −16 … 10 (:func:`audit.engine.shared.lattice.stripe_lattice`; a
#: number here, so this module stays free of numpy).
DEFAULT_STRIPES = 27


def alpha_text(alpha_deg=DEFAULT_ALPHA_DEG) -> str:
    """Slendernesses as typed on the command line, e.g. ``10,15,20``.

    Parameters
    ----------
    alpha_deg : sequence of float
        Slendernesses [degrees].
    """
    return ",".join(f"{a:g}" for a in alpha_deg)


def sizes_text(sizes=DEFAULT_SIZES) -> str:
    """A size grid as typed on the command line, e.g. ``0.5:8:0.05``.

    Parameters
    ----------
    sizes : tuple of float
        The grid (start, stop, step) of sizes 2π/p [s].
    """
    return ":".join(f"{v:g}" for v in sizes)


#: Hazard levels the site's spectral values may be given at, and the factor to the MCE: FEMA
#: P695's collapse margin is over the MCE intensity, 1.5 × the design one (ASCE 7: S_MS =
#: 1.5 S_DS, S_M1 = 1.5 S_D1).
SITE_LEVELS = {"mce": 1.0, "design": 1.5}
#: Limit states of a guideline that names its own (NTC 2018) a check's site may be for
#: (``site.limit_state``); BOTH reports each.
LIMIT_STATES = ("SLV", "SLC")
BOTH = "both"
#: The hazard level the site's spectral values are taken at.
DEFAULT_SITE_LEVEL = "mce"
#: The risk target of the risk-targeted slenderness: probability of overturning in 50 years.
DEFAULT_RISK_TARGET = 0.01


__all__ = ["DEFAULT_BUILDING_DAMPING", "DEFAULT_BUILDING_MODEL", "DEFAULT_ALPHA_DEG", "DEFAULT_SIZES", "DEFAULT_AGREE_BAND", "DEFAULT_ROBUSTNESS",
           "DEFAULT_JOBS", "DEFAULT_SCHEDULER", "DEFAULT_FREE_MOTION_S", "DEFAULT_RESTITUTION", "DEFAULT_ANCHOR_PERIOD_S", "DEFAULT_DAMPING_PCT", "DEFAULT_PERIODS",
           "DEFAULT_DESIGN_DAMPING_PCT", "DEFAULT_DESIGN_PERIODS", "DEFAULT_RESPONSE_FREE_MOTION_S",
           "DEFAULT_PROBABILISTIC_PROCEDURE", "DEFAULT_FRAGILITY_RECORDS", "DEFAULT_CHECK_RECORDS",
           "DEFAULT_IM", "DEFAULT_MARGINS_SIZES", "DEFAULT_STRIPES", "alpha_text",
           "sizes_text", "SITE_LEVELS", "DEFAULT_SITE_LEVEL", "DEFAULT_RISK_TARGET",
           "LIMIT_STATES", "BOTH"]

