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

Each name is loaded from its module on first use, so that a command that needs one of them
(``rock``: no pandas) stays light.
"""

from __future__ import annotations

import importlib

#: Name → the module that holds it.
_WHERE = {"Block": "audit.api.rocking", "RockingResponse": "audit.api.rocking",
          "rock": "audit.api.rocking", "run": "audit.api.runs", "AuditResult": "audit.api.runs",
          "typed": "audit.api.runs", "design_suite": "audit.api.runs",
          "margins": "audit.api.design_level", "MarginsResult": "audit.api.design_level",
          "with_page": "audit.api.result_shape", "fragility": "audit.api.probabilistic",
          "FragilityResult": "audit.api.probabilistic",
          "FRAGILITY_HTML": "audit.api.probabilistic",
          "rocking_spectrum": "audit.api.spectra", "response_spectra": "audit.api.spectra",
          "design_spectrum": "audit.api.spectra", "load_result": "audit.api.runs",
          "risk": "audit.api.site_risk", "read_hazard": "audit.api.site_risk",
          "check": "audit.api.object_check", "CheckResult": "audit.api.object_check",
          # an inventory, --block and --alpha/--size as objects of a check, checked
          "read_objects": "audit.api.object_check", "parse_block_text": "audit.api.object_check",
          "object_by_slenderness": "audit.api.object_check",
          "build_atlas": "audit.api.atlas", "find_atlas": "audit.api.atlas",
          "atlas_check": "audit.api.atlas", "list_atlases": "audit.api.atlas",
          "remove_atlas": "audit.api.atlas", "atlas_folder": "audit.api.atlas",
          "floor_motion": "audit.api.floors", "FloorMotion": "audit.api.floors",
          "validate": "audit.api.validation", "ValidationResult": "audit.api.validation",
          # what travels together, each checked by its own parse (docs/api.md)
          "Building": "audit.physics.building.floor", "Floor": "audit.physics.building.floor",
          "Site": "audit.engine.shared.design_site", "Hazard": "audit.engine.shared.hazard",
          "Solver": "audit.engine.shared.solver", "Runtime": "audit.engine.shared.runtime",
          "Records": "records.request",
          # the registered procedures, the grid of START:STOP:STEP, the folder of a run's parts
          # and its report, for the command line
          "available_procedures": "procedures.registry", "size_grid": "audit.engine.shared.grid",
          "within_limits": "audit.engine.shared.blocks",
          # the compiled kernels' threads, stopped before a command leaves after Ctrl-C
          "stop_kernels": "audit.physics.kernel_threads",
          "KERNEL_THREADS": "audit.physics.kernel_threads",
          "kept_parts": "audit.engine.shared.partial", "PARTIAL_DIR": "audit.engine.shared.partial",
          "REPORT_HTML": "audit.engine.run.results",
          # the one place records are read, the suites built in, and an analytic pulse
          "record_suite": "audit.api.inputs", "built_in_suites": "audit.api.inputs",
          "PULSE_SUITE": "records", "one_pulse": "records", "mp_pulse": "records",
          "record_pulses": "audit.api.pulses", "pulse_words": "audit.api.pulses",
          # the figures the command line saves as PNG
          "new_figure": "reports.figures", "png_bytes": "reports.figures",
          "draw_rocking_spectra": "reports.figures", "draw_response_spectra": "reports.figures"}


#: The defaults of the API's keywords, as the command line's ``--help`` shows them (light: no
#: numpy, so that parsing the flags stays quick).
_DEFAULTS = "audit.engine.shared.defaults"


def __getattr__(name):
    if name in _WHERE:
        return getattr(importlib.import_module(_WHERE[name]), name)
    defaults = importlib.import_module(_DEFAULTS)
    if name in defaults.__all__:
        return getattr(defaults, name)
    raise AttributeError(f"module 'audit.api' has no attribute {name!r}")


def __dir__():
    return sorted(__all__)


__all__ = ["Block", "RockingResponse", "rock", "run", "AuditResult", "design_suite", "margins",
           "MarginsResult", "fragility", "FragilityResult", "typed", "with_page", "PARTIAL_DIR",
           "REPORT_HTML", "FRAGILITY_HTML", "rocking_spectrum", "response_spectra",
           "design_spectrum", "load_result", "available_procedures", "size_grid", "kept_parts",
           "within_limits", "stop_kernels", "KERNEL_THREADS",
           "risk", "read_hazard", "check", "CheckResult", "validate", "ValidationResult",
           "read_objects", "parse_block_text", "object_by_slenderness",
           "floor_motion", "FloorMotion", "record_suite", "built_in_suites", "PULSE_SUITE",
           "one_pulse", "mp_pulse", "record_pulses", "pulse_words",
           "new_figure", "png_bytes", "draw_rocking_spectra",
           "draw_response_spectra", "build_atlas", "find_atlas", "atlas_check", "list_atlases",
           "remove_atlas", "atlas_folder", "Building", "Floor", "Site", "Hazard", "Solver",
           "Runtime", "Records"]
