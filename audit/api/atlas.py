"""``audit.api.build_atlas``, ``find_atlas``, ``atlas_check``: the exact-fragility atlas
of a record set on a floor (:mod:`audit.engine.atlas`), built once into the user cache and read
for answers in seconds.

    from audit import api
    api.build_atlas("p695-far-field")                       # once: minutes
    answer = api.atlas_check(["0.6x1.8"], site=(1.5, 0.9), records="p695-far-field")
    answer[0]["p_overturn_at_site"]
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from audit.engine.shared.defaults import DEFAULT_CHECK_RECORDS, DEFAULT_IM, DEFAULT_SCHEDULER

if TYPE_CHECKING:
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.solver import Solver
    from audit.physics.building.floor import Floor


def atlas_settings(records=DEFAULT_CHECK_RECORDS, *, im=DEFAULT_IM, solver: Solver | None = None,
                   floor: Floor | None = None, runtime: Runtime | None = None, grid=None):
    """(the records on their floor, :class:`~audit.engine.atlas.settings.AtlasSettings`): what
    an atlas of ``records`` on the floor is, each argument checked (InputError naming it).

    Parameters
    ----------
    records : str, path or records.RecordSuite
    im : str
        ``sa:T``, ``pga`` or ``pgv`` (the IM of ``fragility``'s stripes).
    solver : Solver, optional
        The solver's ``restitution``, ``free_motion_s`` [s] and ``g`` [m/s²].
    floor : Floor, optional
        The floor, as for :func:`audit.rock`.
    runtime : Runtime, optional
        ``jobs``: solver threads of a record (worker processes of ``scheduler="dask"``).
    grid : (sequence, sequence), optional
        The (α [degrees], 2π/p [s]) grid; default the atlas's
        (:data:`~audit.engine.atlas.settings.ALPHA_DEG`, :data:`~audit.engine.atlas.settings.SIZE_S`).
    """
    from audit.api.inputs import floor_group, record_suite, runtime_of, solver_of
    from audit.engine.atlas.settings import ALPHA_DEG, SIZE_S, AtlasSettings, floor_words, \
        records_digest
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.intensity import IntensityMeasure
    solver = solver_of(solver, "atlas", ("restitution", "free_motion_s", "g"))
    # the IM on its own (not check's settings, which refuse PGV: a design spectrum has none):
    # fragility's stripes are PGV
    im = im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im)
    runtime = runtime_of(runtime, "atlas", ("jobs",))
    site = DesignSite(None, floor_group(floor))
    suite = site.apply(record_suite(records))
    entries = [entry for entry in suite if entry.motion is not None]
    alpha_deg, size_s = grid if grid is not None else (ALPHA_DEG, SIZE_S)
    name = records if isinstance(records, str) else str(getattr(records, "description", records))
    return entries, AtlasSettings(name, records_digest(entries), im,
                                  floor_words(site.floor), solver.restitution, solver.g,
                                  solver.free_motion_s,
                                  tuple(float(a) for a in alpha_deg),
                                  tuple(float(s) for s in size_s), runtime.jobs)


def atlas_reading(method, records, blocks, *, im, solver: Solver | None = None,
                  floor: Floor | None = None, stripes=None, named=None):
    """The atlas a fragility reads by ``method`` (:func:`~audit.engine.atlas.fragility_read.atlas_for`):
    an :class:`~audit.engine.atlas.fragility_read.AtlasReading`, or None for the direct solve.
    ``direct`` reads no record for it.

    Parameters
    ----------
    method : {None, "atlas", "direct"}
    records : str, path or records.RecordSuite
        The records as read (before a floor or a site scaled them: a fragility on the lattice
        does not depend on the scaling, and the atlas applies the floor itself).
    blocks : (sequence, sequence)
        The blocks' (α [degrees], 2π/p [s]).
    im, solver, floor :
        What names the atlas, as for :func:`atlas_settings`.
    stripes : sequence of float, optional
        Stripes asked for explicitly (refused where not all the atlas's).
    named : str or path, optional
        The records as the user named them (the build command the message gives); default
        the suite's description.
    """
    import os

    from audit.engine.atlas.answers import Atlas
    from audit.engine.atlas.fragility_read import atlas_for, checked_method
    from audit.engine.atlas.store import ATLAS_NPZ, atlas_dir
    if checked_method(method) == "direct":
        return None
    im = getattr(im, "name", im)
    _, settings = atlas_settings(records, im=im, solver=solver, floor=floor)
    key = settings.key()
    directory = atlas_dir(key)
    atlas = Atlas(directory) if (directory / ATLAS_NPZ).is_file() else None
    name = named if isinstance(named, (str, os.PathLike)) else getattr(records, "description",
                                                                        records)
    return atlas_for(method, atlas, key, *blocks,
                     {"records": name, "im": im, "solver": solver, "floor": floor},
                     stripes=stripes)


def build_atlas(records=DEFAULT_CHECK_RECORDS, *, scheduler=DEFAULT_SCHEDULER,
                progress=False, **keywords) -> dict:
    """Build the atlas (or complete an interrupted build: its chunks are reused) and return
    its provenance. Keywords as :func:`atlas_settings`; ``scheduler`` ``local``, ``dask`` or
    ``tcp://HOST:PORT``; ``progress`` a bar on standard error."""
    from audit.engine.atlas.pipeline import build_atlas as build
    from audit.engine.shared.progress import Progress
    from audit.engine.shared.runtime import check_scheduler
    scheduler = check_scheduler(scheduler)
    entries, settings = atlas_settings(records, **keywords)
    bar = Progress(len(entries), "record") if progress else None
    try:
        return build(entries, settings, scheduler, progress=bar)
    finally:
        if bar is not None:
            bar.done()


def find_atlas(records=DEFAULT_CHECK_RECORDS, **keywords):
    """The complete atlas of ``records`` on the floor (keywords as :func:`atlas_settings`), or
    None where none is built."""
    from audit.engine.atlas.answers import Atlas
    from audit.engine.atlas.store import ATLAS_NPZ, atlas_dir
    _, settings = atlas_settings(records, **keywords)
    directory = atlas_dir(settings.key())
    return Atlas(directory) if (directory / ATLAS_NPZ).is_file() else None


def atlas_check(objects, site, records=DEFAULT_CHECK_RECORDS, *, seed=None, **keywords) -> list:
    """Each object's exact P(overturn) at the site and its exact widths for P ≤ 10 % and
    ≤ 50 % at its height, read from the atlas of ``records`` on the floor (InputError naming
    ``records`` where none is built), each P with the atlas's error there.

    Parameters
    ----------
    objects :
        As for :func:`audit.check`.
    site : (float, float)
        S_XS, S_X1 [g] of the hazard level assessed.
    records :
        The record set of the atlas.
    seed : int, optional
        The bootstrap's seed.
    **keywords
        Of :func:`atlas_settings` (the atlas's intensity measure, floor, restitution, ...):
        explicit there, passed on unchanged.

    Returns
    -------
    list of dict
        Per object: ``name``, ``width_m``, ``height_m``, ``alpha_deg``, ``size_s``,
        ``p_overturn_at_site`` (as ``check.json``'s, with ``method`` ``atlas`` and ``error``),
        ``exact_required_width_m`` (per target); both None, and ``outside`` saying why, for an
        object outside the atlas's grid.
    """
    import numpy as np

    from audit.api.object_check import _objects
    from audit.engine.atlas.answers import atlas_required_widths
    from audit.engine.check.pipeline import TARGETS
    from audit.errors import InputError
    atlas = find_atlas(records, **keywords)
    if atlas is None:
        raise InputError(f"records: no atlas of {records} on this floor; build it with "
                         "'python -m audit atlas build'", "records")
    chosen = _objects(objects, atlas.provenance["g"])
    from audit.engine.shared.design_site import Site
    from audit.engine.shared.intensity import IntensityMeasure
    sxs_g, sx1_g = Site.parse(site).values_g
    site_im = IntensityMeasure.parse(atlas.provenance["im"]).of_design_site(
        {"sxs_g": sxs_g, "sx1_g": sx1_g})
    g = atlas.provenance["g"]
    inside = atlas.covers([o.alpha_deg for o in chosen], [o.size_s for o in chosen])
    mine = [o for o, covered in zip(chosen, inside) if covered]
    heights, height_of = np.unique([o.height_m for o in mine], return_inverse=True)
    widths = iter(atlas_required_widths(atlas, heights, site_im, TARGETS, g)[height_of]
                  if mine else [])
    points = iter(atlas.at([o.alpha_deg for o in mine], [o.size_s for o in mine], site_im,
                           seed) if mine else [])
    out = []
    for obj, covered in zip(chosen, inside):
        answer = {"name": obj.name, "width_m": obj.width_m, "height_m": obj.height_m,
                  "alpha_deg": obj.alpha_deg, "size_s": obj.size_s, "site_im": site_im}
        if not covered:  # answered by the direct check, not here
            answer.update(p_overturn_at_site=None, exact_required_width_m=None,
                          outside=f"α {obj.alpha_deg:.3g}°, 2π/p {obj.size_s:.3g} s: outside "
                                  f"the atlas (α {atlas.alpha_deg[0]:g}–"
                                  f"{atlas.alpha_deg[-1]:g}°, 2π/p {atlas.size_s[0]:g}–"
                                  f"{atlas.size_s[-1]:g} s); check it directly")
            out.append(answer)
            continue
        point, width = next(points), next(widths)
        p = {**point.site.as_dict(), "method": "atlas", "error": point.error,
             "count_at_site": "each record's outcome interpolated between the lattice's "
                              "stripes around the site (linear in ln IM), the count rounded "
                              "to a whole record",
             "text": f"{point.site.words()}, from the atlas, ±{100 * point.error:.1f} %"}
        answer.update(p_overturn_at_site=p, exact_required_width_m={
            f"{100 * t:g}%": float(w) for t, w in zip(TARGETS, width)})
        out.append(answer)
    return out


def list_atlases() -> list:
    """The atlases in the cache (:class:`~audit.engine.atlas.store.StoredAtlas`: folder,
    provenance, whether complete)."""
    from audit.engine.atlas.store import stored_atlases
    return stored_atlases()


def remove_atlas(key: str) -> list[str]:
    """Remove the atlases whose key starts with ``key``; their keys (InputError naming ``key``
    where there is none)."""
    from audit.engine.atlas.store import remove_atlas as remove
    from audit.errors import InputError
    gone = remove(key)
    if not gone:
        raise InputError(f"key: no atlas whose key starts with {key!r} (see 'atlas list')",
                         "key")
    return gone


def atlas_folder():
    """The folder of every atlas (``$ROCKING_AUDIT_ATLAS_DIR``, else the user cache's)."""
    from audit.engine.atlas.store import atlas_root
    return atlas_root()


__all__ = ["atlas_settings", "build_atlas", "find_atlas", "atlas_check", "list_atlases",
           "remove_atlas", "atlas_folder"]
