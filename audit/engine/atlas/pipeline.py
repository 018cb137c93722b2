"""Building an atlas: each record scaled to every stripe of the check's lattice, every block of
the (α, 2π/p) grid solved there in one solver call (as
:func:`audit.engine.design.stripes.record_stripes` solves a check's), one chunk per record kept
as it completes (:class:`~audit.engine.atlas.store.AtlasParts`), on this process's threads or
a Dask cluster (:func:`~audit.engine.shared.scheduler.computed_parts`); the chunks joined into
``atlas.npz`` at the end.
"""

from __future__ import annotations

import json
import math
import shutil
import time

import numpy as np

from audit.engine.atlas.settings import AtlasSettings
from audit.engine.atlas.store import (ATLAS_JSON, ATLAS_NPZ, PARTS_DIR, AtlasParts, atlas_dir,
                                      npz_bytes)
from audit.files import write_file_atomically
from audit.physics.rocking import RockingOptions, rocking_blocks


def atlas_record(entry, procedures, settings: AtlasSettings) -> dict:
    """One record's chunk: whether it overturns each block of the grid at each stripe (bits
    packed, shape (stripe, α, size)), the peak θ/α (float16; inf where it overturns), and the
    record's intensity. ``procedures`` is empty (the interface of a record's task).

    Parameters
    ----------
    entry : records.RecordEntry
    procedures : list
        Unused (empty).
    settings : AtlasSettings
    """
    levels = settings.levels
    alpha = np.radians(np.asarray(settings.alpha_deg))
    size = np.asarray(settings.size_s)
    grid_alpha, grid_size = (a.ravel() for a in np.meshgrid(alpha, size, indexing="ij"))
    intensity = settings.im.of_record(entry.motion, settings.free_motion_s)
    blocks = grid_alpha.size
    peaks = rocking_blocks(entry.motion, np.tile(grid_size, levels.size),
                           np.tile(grid_alpha, levels.size), r=settings.restitution,
                           options=RockingOptions(settings.g, settings.free_motion_s),
                           jobs=settings.jobs, scale=np.repeat(levels / intensity, blocks))
    shape = (levels.size, alpha.size, size.size)
    overturned = peaks.overturned.reshape(shape)
    ratio = np.where(overturned, np.inf, peaks.theta_peak.reshape(shape)
                     / alpha[None, :, None])
    return {"overturned": np.packbits(overturned.ravel()), "theta_over_alpha":
            ratio.astype(np.float16), "intensity": np.array(intensity)}


def build_atlas(entries, settings: AtlasSettings, scheduler, progress=None) -> dict:
    """Build (or complete) the atlas of ``entries``: its folder's ``atlas.npz`` and
    ``atlas.json``; chunks of an interrupted build are reused.

    Parameters
    ----------
    entries : list of records.RecordEntry
        The records (on their floor already).
    settings : AtlasSettings
    scheduler : str or scheduler
        ``local``, ``dask`` or ``tcp://HOST:PORT`` (:mod:`audit.engine.shared.scheduler`).
    progress : audit.engine.shared.progress.Progress, optional

    Returns
    -------
    dict
        The provenance written (with the build's ``seconds``, ``reused`` chunks and ``where``).
    """
    from audit.engine.shared.scheduler import computed_parts
    directory = atlas_dir(settings.key())
    directory.mkdir(parents=True, exist_ok=True)
    provenance = {**settings.as_dict(), "record_ids": [e.id for e in entries]}
    write_file_atomically(directory / ATLAS_JSON,
                          json.dumps(provenance, indent=1).encode())  # listed while under way
    store = AtlasParts(directory)
    start = time.perf_counter()
    reused = store.count()

    def report(done, total, record_id, how):  # the ETA from the chunks computed in this build
        if progress is None:
            return
        computed = done - reused
        left = total - done
        eta = ((time.perf_counter() - start) / computed * left if computed > 0 and left
               else math.nan)
        progress(done, total, record_id,
                 how + (f", about {eta:.0f} s left" if math.isfinite(eta) else ""))

    parts, resumed, where = computed_parts(atlas_record, entries, [], settings, scheduler,
                                           store=store, progress=report)
    levels = settings.levels
    shape = (len(entries), levels.size, len(settings.alpha_deg), len(settings.size_s))
    bits = np.stack([np.unpackbits(part["overturned"])[:int(np.prod(shape[1:]))]
                     for part in parts]).astype(bool).reshape(shape)
    arrays = {"overturned": np.packbits(bits.ravel()), "shape": np.array(shape),
              "theta_over_alpha": np.stack([part["theta_over_alpha"] for part in parts]),
              "intensity": np.array([float(part["intensity"]) for part in parts]),
              "levels": levels, "alpha_deg": np.asarray(settings.alpha_deg),
              "size_s": np.asarray(settings.size_s)}
    seconds = time.perf_counter() - start
    provenance.update(seconds=seconds, reused=len(resumed), where=where,
                      solves=int(np.prod(shape)))
    write_file_atomically(directory / ATLAS_NPZ, npz_bytes(**arrays))
    write_file_atomically(directory / ATLAS_JSON, json.dumps(provenance, indent=1).encode())
    shutil.rmtree(directory / PARTS_DIR, ignore_errors=True)
    return provenance


__all__ = ["atlas_record", "build_atlas"]
