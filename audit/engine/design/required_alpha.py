"""Required slenderness: for each block size, the most slender block (smallest α) a guideline
accepts for a suite of site-scaled records, against the smallest α the exact response allows.

The exact share of records that overturn a block is not monotonic in α (nor in intensity), so
each exact curve is defined as "the smallest α above which the share stays ≤ the target on the
search": α on a grid (:data:`GRID_DEG`), the bracket of the last crossing, then
:data:`BISECTIONS` halvings of that bracket with every record solved at the midpoint; the
answer is the bracket's upper end, a slenderness at which the share was found within the
target. A procedure accepts a block when it predicts overturning for at most half the records
it can evaluate (a site-based one: for none); its curve is read on the same grid, the last
crossing interpolated linearly — bisecting it too would evaluate every procedure once more per
record, size and halving, which costs more than the rest of the design-level audit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from audit.engine.design.stripes import procedure_predictions
from audit.engine.design.settings import MarginsSettings
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.scheduler import computed_parts
from audit.physics.block import Restitution
from audit.physics.rocking import RockingOptions, rocking_blocks, rocking_spectrum
from procedures.context import RecordContext

#: Slendernesses of the search grid [degrees], 2° apart.
GRID_DEG = np.arange(2.0, 40.01, 2.0)
#: Exact shares of records overturning a block that the exact curves target.
TARGETS = (0.10, 0.50)
#: Halvings of the exact curves' last bracket (2° / 2⁴ = 0.125°).
BISECTIONS = 4
#: The share of records a procedure may predict to overturn a block it accepts.
ACCEPTED_SHARE = 0.5


@dataclass(frozen=True)
class SearchSettings:
    """Blocks given one by one (``size_s[i]``, ``alpha_deg[i]``) and how to solve them."""

    size_s: tuple
    alpha_deg: tuple
    restitution: Restitution
    g: float
    free_motion_s: float
    jobs: int


@dataclass
class RecordGrid:
    """One record's part of the grid pass: arrays shaped (α, size)."""

    exact_overturned: np.ndarray
    predicted: dict
    evaluated: dict


def record_grid(entry, procedures, settings: SearchSettings) -> RecordGrid:
    """Exact overturning and every procedure's prediction on the (α, size) search grid.

    Parameters
    ----------
    entry : records.RecordEntry
        The record, scaled.
    procedures : sequence of procedures.base.Procedure
        The procedures audited.
    settings : SearchSettings
        The search grid and solver settings.
    """
    size_s, alpha_rad = np.asarray(settings.size_s), np.radians(settings.alpha_deg)
    exact = rocking_spectrum(entry.motion, size_s, alpha_rad, r=settings.restitution,
                             options=RockingOptions(settings.g, settings.free_motion_s),
                             jobs=settings.jobs, reactions=False).overturned
    # verdicts alone: the iterations read the spectra only where they go, at ~20 dampings
    context = RecordContext(entry, settings.free_motion_s, settings.jobs).on_demand()
    # every slenderness of the grid at once, each with all the sizes: blocks (α, size) flat
    p = np.tile(2.0 * np.pi / size_s, alpha_rad.size)
    groups = [(alpha, np.arange(i * size_s.size, (i + 1) * size_s.size),
               float(settings.restitution.r(alpha))) for i, alpha in enumerate(alpha_rad)]
    predicted, evaluated = {}, {}
    for proc in procedures:
        evaluated[proc.name] = proc.unmet_requirements(entry) is None
        predicted[proc.name] = np.zeros(exact.shape, dtype=bool)
        if evaluated[proc.name]:
            predicted[proc.name] = procedure_predictions(proc, [(entry, context)], p, groups,
                                                         settings.g).reshape(exact.shape)
    return RecordGrid(exact, predicted, evaluated)


def record_blocks(entry, procedures, settings: SearchSettings) -> np.ndarray:
    """Exact overturning of the blocks of ``settings`` under one record (a bisection step).

    Parameters
    ----------
    entry : records.RecordEntry
        The record, scaled.
    procedures : list
        Unused (the exact solver alone), for the scheduler's ``task(entry, procedures,
        settings)``.
    settings : SearchSettings
        The blocks and solver settings.
    """
    return rocking_blocks(entry.motion, settings.size_s, np.radians(settings.alpha_deg),
                          r=settings.restitution,
                          options=RockingOptions(settings.g, settings.free_motion_s),
                          jobs=settings.jobs).overturned


def last_crossing(share, limit) -> int | None:
    """Index j of the grid's last point where ``share`` exceeds ``limit`` (the bracket is
    [j, j + 1]); -1 when it never does, None when it still does at the last point.

    Parameters
    ----------
    share : numpy.ndarray
        A share over the grid (e.g. of records overturning) [-].
    limit : float
        The limit [-].
    """
    over = np.flatnonzero(share > limit)
    if over.size == 0:
        return -1
    return None if over[-1] == share.size - 1 else int(over[-1])


def interpolated_alpha(alpha_deg, share, limit) -> float:
    """The smallest α above which ``share`` stays ≤ ``limit`` on the grid, the last crossing
    interpolated linearly; the grid's first α if it never exceeds, NaN if it still does at the
    last.

    Parameters
    ----------
    alpha_deg : array_like of float
        The grid's slendernesses, ascending [degrees].
    share : numpy.ndarray
        The share at each [-].
    limit : float
        The limit [-].
    """
    j = last_crossing(share, limit)
    if j is None:
        return math.nan
    if j < 0:
        return float(alpha_deg[0])
    t = (share[j] - limit) / (share[j] - share[j + 1])
    return float(alpha_deg[j] + t * (alpha_deg[j + 1] - alpha_deg[j]))


def required_alpha(procedures, suite, settings: MarginsSettings, runtime: Runtime,
                   grid_deg=GRID_DEG, targets=TARGETS, bisections: int = BISECTIONS) -> pd.DataFrame:
    """For each size, the smallest slenderness each procedure accepts for the suite as given
    (the site-scaled records), against the smallest α for which the exact share of those
    records that overturn the block stays ≤ each target (see the module's docstring).

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
    settings : audit.engine.design.settings.MarginsSettings
        Its block sizes 2π/p [s], impact model, gravity and free motion.
    runtime : audit.engine.shared.runtime.Runtime
        As for :func:`audit.engine.design.margins.margins_tables`.
    grid_deg : array
        Slendernesses of the search grid [degrees], ascending.
    targets : sequence of float
        Exact shares the exact curves target [-].
    bisections : int
        Halvings of each exact curve's last bracket.

    Returns
    -------
    pandas.DataFrame
        ``procedure, size_s, required_alpha_deg, exact_overturning_share`` (the exact share of
        the records that overturn the block the curve accepts); the exact curves are named
        ``exact@0.10`` and ``exact@0.50``.
    """
    entries = [entry for entry in suite if entry.motion is not None]
    size_s = np.asarray(settings.size_s, dtype=float)
    grid_deg = np.asarray(grid_deg, dtype=float)
    restitution, g, free_motion_s = settings.restitution, settings.g, settings.free_motion_s
    jobs, scheduler, progress = runtime.jobs, runtime.scheduler, runtime.progress

    def settings(sizes, alphas):
        return SearchSettings(tuple(map(float, sizes)), tuple(map(float, alphas)), restitution,
                              float(g), float(free_motion_s), int(jobs))

    grid, _, _ = computed_parts(record_grid, entries, procedures, settings(size_s, grid_deg),
                                scheduler, progress=progress)
    grid_overturned = np.array([part.exact_overturned for part in grid])  # (record, α, size)
    exact_share = np.mean(grid_overturned, axis=0)
    # the last bracket of every exact curve and size, all halved together: one solve per
    # record and open bracket at each halving
    curves = [(target, s) for target in targets for s in range(size_s.size)]
    crossings = [last_crossing(exact_share[:, s], target) for target, s in curves]
    # share > target at ``low``, ≤ at ``high``; NaN where the share never falls within it
    low = np.array([grid_deg[j] if j is not None and j >= 0 else np.nan for j in crossings])
    high = np.array([np.nan if j is None else grid_deg[j + 1] if j >= 0 else grid_deg[0]
                     for j in crossings])
    # every record's outcome at ``high``, kept with it: the exact share of the block a curve
    # accepts is read there, not solved again
    at_high = np.array([grid_overturned[:, j + 1 if j >= 0 else 0, s] if j is not None
                        else np.zeros(len(entries), dtype=bool)
                        for j, (_, s) in zip(crossings, curves)])
    searched = np.flatnonzero(np.isfinite(low))
    limit = np.array([target for target, _ in curves])[searched]
    for _ in range(bisections if searched.size else 0):
        middle = 0.5 * (low[searched] + high[searched])
        sizes = size_s[[curves[k][1] for k in searched]]
        overturned, _, _ = computed_parts(record_blocks, entries, procedures,
                                          settings(sizes, middle), scheduler)
        overturned = np.array(overturned)  # (record, curve searched)
        above = np.mean(overturned, axis=0) > limit
        low[searched[above]] = middle[above]
        high[searched[~above]] = middle[~above]
        at_high[searched[~above]] = overturned[:, ~above].T
    rows = [{"procedure": f"exact@{target:.2f}", "size_s": float(size_s[s]),
             "required_alpha_deg": float(value),
             "exact_overturning_share": float(np.mean(outcomes)) if np.isfinite(value)
             else np.nan}
            for (target, s), value, outcomes in zip(curves, high, at_high)]
    for proc in procedures:
        mine = [part.predicted[proc.name] for part in grid if part.evaluated[proc.name]]
        if not mine:  # a procedure that can evaluate no record draws no curve
            continue
        share = np.mean(mine, axis=0)
        rows += [{"procedure": proc.name, "size_s": float(size),
                  "required_alpha_deg": interpolated_alpha(grid_deg, share[:, s], ACCEPTED_SHARE),
                  "exact_overturning_share": np.nan}
                 for s, size in enumerate(size_s)]
    table = pd.DataFrame(rows)
    # how safe the block each guideline accepts is: the exact share of the records overturning it
    found = table.index[np.isfinite(table["required_alpha_deg"])
                        & ~table["procedure"].str.startswith("exact@")]
    if len(found):
        overturned, _, _ = computed_parts(record_blocks, entries, procedures, settings(
            table.loc[found, "size_s"], table.loc[found, "required_alpha_deg"]), scheduler)
        table.loc[found, "exact_overturning_share"] = np.mean(overturned, axis=0)
    return table


__all__ = ["required_alpha", "interpolated_alpha", "last_crossing", "record_grid",
           "record_blocks", "GRID_DEG", "TARGETS", "BISECTIONS", "ACCEPTED_SHARE"]
