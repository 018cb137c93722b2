"""Cost guards: the work of a command estimated before it starts, refused or announced.

The estimate counts the solver's inner loops (the exact rocking kernel visits every sample
of the record and of its free-motion tail for every block; the oscillator recurrence every
sample for every period and damping ratio) and divides by throughputs measured on a 2-core
machine, kept low so the estimate is an upper bound in practice. Above
:data:`WARN_SECONDS` a command prints one line with the estimate and proceeds; above
:data:`REFUSE_SECONDS` or :data:`REFUSE_MEMORY_BYTES` it stops with an InputError unless
``--force`` is given. Light: no scientific import.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

from audit.errors import InputError

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
    """

    seconds: float
    memory_bytes: float
    work: str


def samples_with_tail(motion, free_motion_s: float) -> int:
    """Samples the solvers visit for ``motion``: the record and its free-motion tail."""
    return motion.acceleration.size + int(math.ceil(free_motion_s / motion.dt))


def estimate(motions, free_motion_s: float, blocks: int = 0, oscillators: int = 0,
             jobs: int = 1) -> Estimate:
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
    return Estimate(seconds, max(stored, default=0) * BYTES_PER_SAMPLE, work)


def check(cost: Estimate, force: bool, out=None) -> None:
    """Refuse ``cost`` above the limits unless ``force``; warn on one line above the lower one."""
    out = out or sys.stderr
    too_long = cost.seconds > REFUSE_SECONDS
    too_big = cost.memory_bytes > REFUSE_MEMORY_BYTES
    if (too_long or too_big) and not force:
        reason = (f"about {_duration(cost.seconds)}" if too_long
                  else f"about {cost.memory_bytes / 1e9:.1f} GB of memory")
        raise InputError(f"work: {cost.work} would take {reason}, beyond the limit of "
                         f"{_duration(REFUSE_SECONDS)} / {REFUSE_MEMORY_BYTES / 1e9:g} GB; "
                         f"reduce it (coarser --sizes, fewer records) or add --force")
    if cost.seconds > WARN_SECONDS:
        print(f"warning: {cost.work}: this may take up to {_duration(cost.seconds)}",
              file=out)


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"
