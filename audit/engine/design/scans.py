"""Fine amplitude scans of chosen blocks of a design-level audit (``scan.csv``): why the first
overturning intensity is not a number to build on."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from audit.engine.design.fragility import overturning_pattern
from audit.engine.design.margins import MarginsRun
from audit.engine.design.settings import MarginsSettings
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.schemas import block_labels
from audit.physics.rocking import RockingOptions, rocking_blocks


#: Blocks drawn with a fine amplitude scan: the named blocks, else the grid's most islanded.
SCAN_BLOCKS = 3
#: Step of the fine amplitude scan, as a ratio of scale factors (0.2 %).
SCAN_STEP = 1.002


def amplitude_scans(run: MarginsRun, suite, settings: MarginsSettings,
                    runtime: Runtime) -> pd.DataFrame:
    """A fine amplitude scan of chosen blocks: why the first overturning intensity is not a
    number to build on.

    The blocks are the named ones (``--block``), else the :data:`SCAN_BLOCKS` grid blocks with
    the most records showing islands; for each, the record whose stripes show islands (else
    the one overturning it at the lowest stripe) is scaled in steps of :data:`SCAN_STEP` from
    the stripe below its first overturning stripe to two stripes above it.

    Parameters
    ----------
    run : MarginsRun
        The design-level audit (its fragility, stripes and levels).
    suite : records.RecordSuite
        The records.
    settings : MarginsSettings
        The design-level settings.
    runtime : Runtime
        How it runs (its jobs).

    Returns
    -------
    pandas.DataFrame
        ``record, alpha_deg, size_s, width_m, height_m, scale_factor, im_level, exact_overturned,
        exact_theta_rad`` (the columns of ``scan.csv``).
    """
    restitution, g, free_motion_s = settings.restitution, settings.g, settings.free_motion_s
    jobs = runtime.jobs
    fragility, stripes = run.fragility, run.stripes
    named = fragility[fragility["width_m"].notna()]
    chosen = named if len(named) else fragility.sort_values(
        ["records_with_islands", "island_share"], ascending=False, kind="stable").head(SCAN_BLOCKS)
    motions = {entry.id: entry.motion for entry in suite if entry.motion is not None}
    levels = np.asarray(run.summary["levels"])
    frames, labels, chosen_labels = [], block_labels(stripes), block_labels(chosen)
    for block in chosen.itertuples():
        rows = stripes[(stripes["alpha_deg"] == block.alpha_deg)
                       & (stripes["size_s"] == block.size_s)
                       & (labels == chosen_labels[block.Index])]
        over = rows.pivot(index="record", columns="im_level", values="exact_overturned")
        if not over.to_numpy().any():
            continue
        pattern = overturning_pattern(over.to_numpy(dtype=bool))
        first = np.where(pattern.first_stripe < 0, levels.size, pattern.first_stripe)
        k = int(np.argmax(pattern.islands)) if pattern.islands.any() else int(np.argmin(first))
        record = over.index[k]
        first_row = rows.loc[rows["record"] == record].iloc[0]
        # per unit of intensity, on the motion as audited (scaled to the site, where it was)
        factor_per_im = float(first_row["scale_factor"] / first_row["site_factor"]
                              / first_row["im_level"])
        low = levels[max(first[k] - 1, 0)]
        high = levels[min(first[k] + 2, levels.size - 1)]
        im_levels = low * SCAN_STEP ** np.arange(int(np.log(high / low) / np.log(SCAN_STEP)) + 1)
        peaks = [rocking_blocks(motions[record].scaled(float(level * factor_per_im)),
                                [block.size_s], [math.radians(block.alpha_deg)], r=restitution,
                                options=RockingOptions(g, free_motion_s), jobs=jobs)
                 for level in im_levels]
        frames.append(pd.DataFrame({
            "record": record, "alpha_deg": block.alpha_deg, "size_s": block.size_s,
            "width_m": block.width_m, "height_m": block.height_m,
            "scale_factor": im_levels * factor_per_im * float(first_row["site_factor"]),
            "im_level": im_levels,
            "exact_overturned": np.concatenate([one.overturned for one in peaks]),
            "exact_theta_rad": np.concatenate([one.theta_peak for one in peaks])}))
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=SCAN_COLUMNS)


SCAN_COLUMNS = ["record", "alpha_deg", "size_s", "width_m", "height_m", "scale_factor",
                "im_level", "exact_overturned", "exact_theta_rad"]


__all__ = ["amplitude_scans", "SCAN_COLUMNS", "SCAN_BLOCKS", "SCAN_STEP"]
