"""The Python API: the engine the command line runs, for notebooks and scripts.

    import audit, records
    block = audit.Block.from_dimensions(width_m=0.8, height_m=2.4)
    response = audit.rock(block, "pacoima_dam_1971", records="pulses")
    result = audit.run("all", records="p695-far-field",
                       site=audit.Site(1.5, 0.9, scale_records=True),
                       runtime=audit.Runtime(jobs=4))
    result.bottom_line                       # a DataFrame; result.write("out") for the files

Angles are given in degrees and accelerations in g at this edge, as on the command line;
everything inside is SI. Every argument is checked before any work starts; a bad one raises
:class:`audit.errors.InputError` naming it (the command line prints the same message with its
flag in the argument's place). A run's settings are fields of settings objects
(:class:`~audit.engine.run.settings.AuditSettings`,
:class:`~audit.engine.design.settings.MarginsSettings`,
:class:`~audit.engine.check.settings.CheckSettings`), given as keyword arguments; what travels
together is one small group checked by its own ``parse`` and accepted beside its shorthand
(:class:`Building`, :class:`Floor`, :class:`Site`, :class:`Hazard`, :class:`Solver`,
:class:`Runtime`, :class:`Records`), whose fields a message names as ``argument.field``
(``floor.building.period_s``).

Every name is imported plainly from its module. Importing them is light (no numpy, pandas,
numba or matplotlib): each module loads its scientific imports inside the functions that use
them, so a command that needs little (``rock``: no pandas; ``--help``: no numpy) stays quick.
"""

from __future__ import annotations

from audit.api.atlas import (atlas_check, atlas_folder, build_atlas, find_atlas, list_atlases,
                             remove_atlas)
from audit.api.design_level import MarginsResult, margins
from audit.api.figures import png_bytes, spectra_figure
from audit.api.floors import FloorMotion, floor_motion
from audit.api.inputs import available_procedures, built_in_suites, pulse_motion, record_suite
from audit.api.object_check import (CheckResult, check, object_by_slenderness, parse_block_text,
                                    read_objects)
from audit.api.probabilistic import FRAGILITY_HTML, FragilityResult, fragility
from audit.api.pulses import pulse_words, record_pulses
from audit.api.result_shape import with_page
from audit.api.rocking import Block, RockingResponse, rock
from audit.api.runs import REPORT_HTML, AuditResult, design_suite, load_result, run, typed
from audit.api.site_risk import read_hazard, risk
from audit.api.spectra import design_spectrum, response_spectra, rocking_spectrum
from audit.api.validation import ValidationResult, validate
# what travels together, each checked by its own parse (docs/api.md)
from audit.engine.shared.design_site import Site
from audit.engine.shared.hazard import Hazard
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.solver import Solver
from audit.physics.building.floor import Building, Floor
from audit.engine.shared.record_request import Records
# the grid of START:STOP:STEP, the limits of a block a user names, the folder of a run's parts
# and the compiled kernels' threads (stopped before a command leaves after Ctrl-C), for the
# command line
from audit.engine.shared.blocks import within_limits
from audit.engine.shared.grid import size_grid
from audit.engine.shared.partial import PARTIAL_DIR, kept_parts
from audit.physics.kernel_threads import KERNEL_THREADS, stop_kernels
# the defaults of the API's keywords, as the command line's --help shows them
from audit.engine.shared.defaults import (
    DEFAULT_AGREE_BAND, DEFAULT_ALPHA_DEG, DEFAULT_ANCHOR_PERIOD_S, DEFAULT_BUILDING_DAMPING,
    DEFAULT_BUILDING_MODEL, DEFAULT_CHECK_RECORDS, DEFAULT_DAMPING_PCT,
    DEFAULT_DESIGN_DAMPING_PCT, DEFAULT_DESIGN_PERIODS, DEFAULT_FRAGILITY_RECORDS,
    DEFAULT_FREE_MOTION_S, DEFAULT_IM, DEFAULT_JOBS, DEFAULT_MARGINS_SIZES,
    DEFAULT_PERIODS, DEFAULT_PROBABILISTIC_PROCEDURE, DEFAULT_RESPONSE_FREE_MOTION_S,
    DEFAULT_RESTITUTION, DEFAULT_RISK_TARGET, DEFAULT_ROBUSTNESS, DEFAULT_SCHEDULER,
    DEFAULT_SITE_LEVEL, DEFAULT_SIZES, DEFAULT_STRIPES, SITE_LEVELS, alpha_text, sizes_text)

__all__ = ["Block", "RockingResponse", "rock", "run", "AuditResult", "design_suite", "margins",
           "MarginsResult", "fragility", "FragilityResult", "typed", "with_page", "PARTIAL_DIR",
           "REPORT_HTML", "FRAGILITY_HTML", "rocking_spectrum", "response_spectra",
           "design_spectrum", "load_result", "available_procedures", "size_grid", "kept_parts",
           "within_limits", "stop_kernels", "KERNEL_THREADS",
           "risk", "read_hazard", "check", "CheckResult", "validate", "ValidationResult",
           "read_objects", "parse_block_text", "object_by_slenderness",
           "floor_motion", "FloorMotion", "record_suite", "built_in_suites", "pulse_motion",
           "record_pulses", "pulse_words", "png_bytes", "spectra_figure",
           "build_atlas", "find_atlas", "atlas_check", "list_atlases", "remove_atlas",
           "atlas_folder", "Building", "Floor", "Site", "Hazard", "Solver", "Runtime", "Records",
           "DEFAULT_AGREE_BAND", "DEFAULT_ALPHA_DEG", "DEFAULT_ANCHOR_PERIOD_S",
           "DEFAULT_BUILDING_DAMPING", "DEFAULT_BUILDING_MODEL", "DEFAULT_CHECK_RECORDS",
           "DEFAULT_DAMPING_PCT", "DEFAULT_DESIGN_DAMPING_PCT", "DEFAULT_DESIGN_PERIODS",
           "DEFAULT_FRAGILITY_RECORDS", "DEFAULT_FREE_MOTION_S", "DEFAULT_IM", "DEFAULT_JOBS",
           "DEFAULT_MARGINS_SIZES", "DEFAULT_PERIODS",
           "DEFAULT_PROBABILISTIC_PROCEDURE", "DEFAULT_RESPONSE_FREE_MOTION_S",
           "DEFAULT_RESTITUTION", "DEFAULT_RISK_TARGET", "DEFAULT_ROBUSTNESS", "DEFAULT_SCHEDULER",
           "DEFAULT_SITE_LEVEL", "DEFAULT_SIZES", "DEFAULT_STRIPES", "SITE_LEVELS", "alpha_text",
           "sizes_text"]
