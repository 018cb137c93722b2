"""Cost guards: the work of a command estimated before it starts, refused or announced.

The estimate counts the solver's inner loops (the exact rocking kernel visits every sample
of the record and of its free-motion tail for every block; the oscillator recurrence every
sample for every period and damping ratio) and divides by throughputs measured on a 2-core
machine, kept low so the estimate is an upper bound in practice. Above
:data:`WARN_SECONDS` a command prints one line with the estimate and proceeds; above
:data:`REFUSE_SECONDS` or :data:`REFUSE_MEMORY_BYTES` it stops with an InputError unless
``force`` is given, naming what makes the work large: of the settings the work is
proportional to (the free motion, the longest record, the number of records, the command's grids),
the one furthest beyond its usual size, by its field (the command line puts its flags in their
place). Light: no scientific import.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

from audit.errors import InputError
from audit.physics.defaults import DEFAULT_FREE_MOTION_S

#: Rocking-kernel samples (one block × one sample) per second and thread, a low measured figure.
ROCKING_SAMPLES_PER_S = 1.0e7
#: Oscillator-recurrence samples (one period × one damping × one sample) per second.
OSCILLATOR_SAMPLES_PER_S = 1.5e7
#: Bytes held per stored sample while a record is processed (the record and its copies; the
#: oscillator also stores the free-motion tail as zeros, the rocking kernel does not).
BYTES_PER_SAMPLE = 64
#: Estimated time above which a command says how long it will take [s].
WARN_SECONDS = 60.0
#: Estimated time above which a command refuses to start without ``--force`` [s].
REFUSE_SECONDS = 900.0
#: Estimated memory above which a command refuses to start without ``--force`` [byte].
REFUSE_MEMORY_BYTES = 2.0e9
#: Records of a usual suite: the largest built-in one (FEMA P695 near-field, 56 components).
USUAL_RECORDS = 56
#: Samples of a usual record: the longest of the FEMA P695 sets (90–100 s).
USUAL_RECORD_SAMPLES = 18_000


@dataclass(frozen=True)
class Setting:
    """A setting of a command that the work is proportional to.

    Attributes
    ----------
    option : str
        The setting's field, e.g. ``"size_s"``.
    count : int
        Values it gives (sizes, slendernesses, stripes, periods, ...).
    default : int
        Values it gives by default (0 where it has none: one value counts as usual).
    """

    option: str
    count: int
    default: int


@dataclass(frozen=True)
class Cause:
    """One factor of the work and how many times its usual size it is [-]."""

    ratio: float
    text: str


@dataclass(frozen=True)
class Estimate:
    """Expected cost of a command.

    Attributes
    ----------
    seconds : float
        Expected computing time [s] (an upper bound in practice).
    memory_bytes : float
        Expected peak memory of the data [byte].
    work : str
        What is being computed, in words (e.g. "453 blocks × 2 records × 14,000 samples").
    cause : str
        The factor of the time furthest beyond its usual size, with what to do about it.
    memory_cause : str
        The same for the memory (the longest record, or its free motion where it is stored).
    """

    seconds: float
    memory_bytes: float
    work: str
    cause: str = ""
    memory_cause: str = ""
    #: The fields the causes may name.
    fields: tuple = ()


def suite_motions(suite) -> list:
    """The motions of ``suite``'s entries that have one (a missing record costs nothing).

    Parameters
    ----------
    suite : records.RecordSuite
    """
    return [entry.motion for entry in suite if entry.motion is not None]


def samples_with_tail(motion, free_motion_s: float) -> int:
    """Samples the solvers visit for ``motion``: the record and its free-motion tail.

    Parameters
    ----------
    motion : records.GroundMotion
        The record.
    free_motion_s : float
        Free-motion time solved after the record ends [s].
    """
    return motion.acceleration.size + int(math.ceil(free_motion_s / motion.dt))


def estimate(motions, free_motion_s: float, blocks: int = 0, oscillators: int = 0,
             jobs: int = 1, settings: tuple[Setting, ...] = (),
             free_motion_option: str = "free_motion_s") -> Estimate:
    """Cost of ``blocks`` rocking runs and ``oscillators`` (period × damping) runs per motion.

    Parameters
    ----------
    motions : iterable of records.GroundMotion
    free_motion_s : float
        Free motion after each motion [s].
    blocks : int
        Blocks (α × size) simulated per motion.
    oscillators : int
        Oscillators (period × damping ratio) per motion.
    jobs : int
        Threads sharing the rocking runs.
    settings : tuple of Setting
        The command's options that ``blocks`` and ``oscillators`` are proportional to.
    free_motion_option : str
        The field that sets the free motion.
    """
    motions = list(motions)
    samples = [samples_with_tail(m, free_motion_s) for m in motions]
    stored = samples if oscillators else [m.acceleration.size for m in motions]
    total = float(sum(samples))
    seconds = (total * blocks / (ROCKING_SAMPLES_PER_S * max(1, min(jobs, blocks or 1)))
               + total * oscillators / OSCILLATOR_SAMPLES_PER_S)
    parts = [f"{blocks:,} blocks"] if blocks else []
    parts += [f"{oscillators:,} oscillators"] if oscillators else []
    work = (f"{' and '.join(parts)} × {len(samples)} record(s) × "
            f"up to {max(samples, default=0):,} samples")
    if not motions:
        return Estimate(seconds, 0.0, work)
    free_motion = _free_motion_cause(motions, samples, free_motion_s, free_motion_option)
    record = _record_cause(max(motions, key=lambda m: m.acceleration.size))
    causes = [free_motion, record,
              Cause(len(motions) / USUAL_RECORDS,
                    f"records, {len(motions):,} of them (usually at most {USUAL_RECORDS}): "
                    "audit fewer"),
              *(Cause(s.count / max(s.default, 1),
                      f"{s.option}, {s.count:,} "
                      + (f"values ({s.default:,} by default)" if s.default else "of them")
                      + ": give fewer")
                for s in settings)]
    memory = max([free_motion, record] if oscillators else [record], key=lambda c: c.ratio)
    return Estimate(seconds, max(stored) * BYTES_PER_SAMPLE, work,
                    max(causes, key=lambda c: c.ratio).text, memory.text,
                    ("records", free_motion_option, *(s.option for s in settings)))


def _free_motion_cause(motions, samples, free_motion_s: float, option: str) -> Cause:
    """The free motion, as the factor by which it multiplies the samples beyond those of the
    default free motion (or none, where it is shorter)."""
    usual = sum(samples_with_tail(m, min(free_motion_s, DEFAULT_FREE_MOTION_S)) for m in motions)
    return Cause(sum(samples) / usual,
                 f"{option} {free_motion_s:g} s (free motion after each record): shorten it")


def _record_cause(motion) -> Cause:
    """The longest record, against the usual length."""
    return Cause(motion.acceleration.size / USUAL_RECORD_SAMPLES,
                 f"record {motion.id}, {motion.duration:g} s long "
                 f"({motion.acceleration.size:,} samples): shorten it or leave it out")


def check(cost: Estimate, force: bool, out=None, force_field: str = "force") -> None:
    """Refuse ``cost`` above the limits unless ``force``; warn on one line above the lower one.

    Parameters
    ----------
    cost : Estimate
        The work estimated (:func:`estimate`).
    force : bool
        Run whatever the estimate.
    out : file-like, optional
        Where the warning goes; standard error when not given.
    force_field : str
        The argument that says ``force`` (``runtime.force``), for the message.
    """
    out = out or sys.stderr
    too_long = cost.seconds > REFUSE_SECONDS
    too_big = cost.memory_bytes > REFUSE_MEMORY_BYTES
    if (too_long or too_big) and not force:
        reason, cause = ((f"about {_duration(cost.seconds)}", cost.cause) if too_long
                         else (f"about {cost.memory_bytes / 1e9:.1f} GB of memory",
                               cost.memory_cause))
        raise InputError(f"work: {cost.work} would take {reason}, beyond the limit of "
                         f"{_duration(REFUSE_SECONDS)} / {REFUSE_MEMORY_BYTES / 1e9:g} GB, "
                         f"mostly because of {cause}; or pass {force_field}=True", *cost.fields,
                         force_field)
    if cost.seconds > WARN_SECONDS:
        print(f"warning: {cost.work}: this may take up to {_duration(cost.seconds)}",
              file=out)


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"
