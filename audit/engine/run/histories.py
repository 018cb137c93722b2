"""The blocks of a record worth a time history, and their simulated histories.

Each procedure's worst blocks per class (:data:`~audit.engine.run.ranking.WORST_CLASSES`) and
representative rocking blocks at α ≈ 15° (Figures 8.2, 8.5, …): the report draws these.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from audit.engine.run.ranking import WORST_CLASSES, worst_positions
from audit.engine.run.settings import HISTORY_POINTS, AuditSettings
from audit.engine.shared.blocks import Block
from audit.physics.rocking import simulate

def _representative_sizes(spectrum, alpha_index: int, count: int = 2) -> list[float]:
    """Sizes of blocks that rock and survive, spread over the range."""
    rocking = (spectrum.uplifted[alpha_index] & ~spectrum.overturned[alpha_index]
               & (spectrum.theta_ratio[alpha_index] > 0.05))
    sizes = spectrum.size_s[rocking]
    if sizes.size == 0:
        return []
    picks = np.unique(np.quantile(np.arange(sizes.size), np.linspace(0.25, 0.75, count))
                      .round().astype(int))
    return [float(sizes[i]) for i in picks]


def history_blocks(results: pd.DataFrame, spectrum, alpha_deg, per_class: int = 1) -> list[dict]:
    """The blocks of one record worth a time history.

    Parameters
    ----------
    results : pandas.DataFrame
        The record's ``results.csv`` rows.
    spectrum : audit.physics.rocking.RockingSpectrum
        The record's exact rocking spectrum on the grid.
    alpha_deg : sequence of float
        The grid's slendernesses [degrees].
    per_class : int
        Blocks picked per procedure and worst verdict class.

    Returns
    -------
    list of dict
        ``alpha_deg``, ``size_s`` and ``reason`` (why it was picked; reasons of a block picked
        several times are joined with "; "), in order of first pick.
    """
    picks = {}

    def pick(alpha, size, reason):
        key = (round(float(alpha), 9), round(float(size), 9))
        picks.setdefault(key, []).append(reason)

    # ranked on the columns' arrays (rank_worst's order), each procedure's rows in turn
    names = results["procedure"].to_numpy()
    verdicts = results["verdict"].to_numpy()
    fragile = results["exact_fragile"].eq(True).to_numpy()
    alphas, sizes = results["alpha_deg"].to_numpy(), results["size_s"].to_numpy()
    ranked = {column: results[column].to_numpy(dtype=float) for _, column, _, _ in WORST_CLASSES}
    for procedure in pd.unique(names):
        rows = np.flatnonzero(names == procedure)
        for verdict, column, largest, reason in WORST_CLASSES:
            for i in rows[worst_positions(verdicts[rows], fragile[rows], ranked[column][rows],
                                          verdict, largest, per_class)]:
                pick(alphas[i], sizes[i], f"{reason}, {procedure}")
    alpha_index = int(np.argmin(np.abs(np.asarray(alpha_deg) - 15.0)))
    for size in _representative_sizes(spectrum, alpha_index):
        pick(alpha_deg[alpha_index], size, "representative")
    return [{"alpha_deg": alpha, "size_s": size, "reason": "; ".join(reasons)}
            for (alpha, size), reasons in picks.items()]


def simulate_histories(entry, results: pd.DataFrame, exact, alpha_deg, settings: AuditSettings):
    """The time histories of :func:`history_blocks` under the record ``entry``.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    results : pandas.DataFrame
        Its ``results.csv`` rows.
    exact : audit.physics.rocking.RockingSpectrum
        Its exact rocking spectrum on the grid.
    alpha_deg : sequence of float
        The grid's slendernesses [degrees].
    settings : AuditSettings
        The audit's settings (``g``, ``free_motion_s``).

    Returns
    -------
    frames : list of pandas.DataFrame
        ``histories.csv`` rows, :data:`~audit.engine.run.settings.HISTORY_POINTS` samples at most each.
    meta : list of dict
        Per history: the pick, rocking cycles, first and last impacts, peak θ/α, overturning.
    """
    frames, meta = [], []
    for pick in history_blocks(results, exact, alpha_deg):
        block = Block(alpha_deg=pick["alpha_deg"], size_s=pick["size_s"], g=settings.g)
        response = simulate(block.rigid, entry.motion, settings.free_motion_s)
        stride = max(1, response.time.size // HISTORY_POINTS)
        frames.append(pd.DataFrame({
            "record": entry.id, "alpha_deg": pick["alpha_deg"], "size_s": pick["size_s"],
            "time_s": response.time[::stride],
            "theta_ratio": response.theta[::stride] / response.block.alpha,
            "omega_rad_s": response.omega[::stride]}))
        impacts = response.impact_times
        meta.append({
            # arrays (8 bytes a value, not a float object): the driver keeps every record's
            # drawn histories until summary.json is written
            "record": entry.id, **pick, "cycle_starts_s": response.cycle_starts,
            "cycle_durations_s": response.cycle_durations,
            "first_impact_s": float(impacts[0]) if response.n_impacts else None,
            "last_impact_s": float(impacts[-1]) if response.n_impacts else None,
            "peak_rotation_ratio": response.peak_rotation_ratio,
            "overturned": bool(response.overturned),
            "overturn_time_s": float(response.overturn_time) if response.overturned else None,
            "excitation_end_s": response.excitation_end})
    return frames, meta


__all__ = ["history_blocks", "simulate_histories"]
