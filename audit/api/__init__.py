"""The Python API: the engine the command line runs, for notebooks and scripts.

    import audit, records
    block = audit.Block.from_dimensions(width_m=0.8, height_m=2.4)
    response = audit.rock(block, "pacoima_dam_1971", records="pulses")
    result = audit.run("all", records="p695-far-field", site=(1.5, 0.9), scale_to_site=True)
    result.bottom_line                       # a DataFrame; result.write("out") for the files

Angles are given in degrees and accelerations in g at this edge, as on the command line;
everything inside is SI. Every argument is checked before any work starts; a bad one raises
:class:`audit.errors.InputError` naming it (the command line prints the same message with its
flag in the argument's place). A run's settings are fields of settings objects
(:class:`~audit.engine.settings.AuditSettings`,
:class:`~audit.engine.margins_settings.MarginsSettings`,
:class:`~audit.engine.design_site.DesignSite`, :class:`~audit.engine.runtime.Runtime`), given
as keyword arguments.
"""

from __future__ import annotations

from audit.api.design_level import MarginsResult, margins, with_page
from audit.api.probabilistic import FRAGILITY_HTML, FragilityResult, fragility
from audit.api.rocking import Block, RockingResponse, rock
from audit.api.runs import AuditResult, run, typed
from audit.engine.partial import PARTIAL_DIR
from audit.engine.results import REPORT_HTML


def design_suite(suite, **site):
    """``suite`` with the design site and scaling of the fields of
    :class:`~audit.engine.design_site.DesignSite` (``site``, ``site_override``,
    ``scale_to_site``, ``anchor_period_s``, ``ntc_site``)."""
    from audit.engine.design_site import DesignSite
    return DesignSite.parse(**site).apply(suite)


def __dir__():
    return sorted(__all__)


__all__ = ["Block", "RockingResponse", "rock", "run", "AuditResult", "design_suite", "margins",
           "MarginsResult", "fragility", "FragilityResult", "typed", "with_page", "PARTIAL_DIR",
           "REPORT_HTML", "FRAGILITY_HTML"]
