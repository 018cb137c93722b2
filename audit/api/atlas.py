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

from audit.api.atlas_lookup import atlas_settings, records_named, stored_atlas
from audit.engine.shared.defaults import DEFAULT_CHECK_RECORDS, DEFAULT_IM, DEFAULT_SCHEDULER

if TYPE_CHECKING:
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.solver import Solver
    from audit.physics.building.floor import Floor


def build_atlas(records=DEFAULT_CHECK_RECORDS, *, im=DEFAULT_IM, solver: Solver | None = None,
                floor: Floor | None = None, runtime: Runtime | None = None, grid=None,
                scheduler=DEFAULT_SCHEDULER, progress=False) -> dict:
    """Build the atlas (or complete an interrupted build: its chunks are reused) and return
    its provenance. Arguments as :func:`~audit.api.atlas_lookup.atlas_settings`; ``scheduler``
    ``local``, ``dask`` or ``tcp://HOST:PORT``; ``progress`` a bar on standard error."""
    from audit.engine.atlas.pipeline import build_atlas as build
    from audit.engine.shared.progress import Progress
    from audit.engine.shared.runtime import check_scheduler
    scheduler = check_scheduler(scheduler)
    entries, settings = atlas_settings(records, im=im, solver=solver, floor=floor,
                                       runtime=runtime, grid=grid)
    bar = Progress(len(entries), "record") if progress else None
    try:
        return build(entries, settings, scheduler, progress=bar)
    finally:
        if bar is not None:
            bar.done()


def find_atlas(records=DEFAULT_CHECK_RECORDS, *, im=DEFAULT_IM, solver: Solver | None = None,
               floor: Floor | None = None):
    """The complete atlas of ``records`` on the floor (arguments as
    :func:`~audit.api.atlas_lookup.atlas_settings`), or None where none is built."""
    found = stored_atlas(records, im=im, solver=solver, floor=floor)
    return found[0] if found is not None else None


def atlas_check(objects, site, records=DEFAULT_CHECK_RECORDS, *, seed=None, im=DEFAULT_IM,
                solver: Solver | None = None, floor: Floor | None = None) -> list:
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
    im, solver, floor :
        The atlas's intensity measure, solver (impact model, free motion, gravity) and floor,
        as for :func:`~audit.api.atlas_lookup.atlas_settings`.

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
    from audit.errors import InputError, NoAtlas
    atlas = find_atlas(records, im=im, solver=solver, floor=floor)
    if atlas is None:
        named = records_named(None, records)
        raise NoAtlas(f"no atlas of {named} on this floor", {
            "records": named, "im": im, "solver": solver, "floor": floor}, "records")
    chosen = _objects(objects, atlas.provenance["g"])
    from audit.engine.shared.design_site import Site
    from audit.engine.shared.intensity import IntensityMeasure
    parsed = Site.parse(site, "check")
    if parsed is None or parsed.values_g is None:
        raise InputError("site: required, S_XS, S_X1 [g] of the hazard level assessed", "site")
    sxs_g, sx1_g = parsed.values_g
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
