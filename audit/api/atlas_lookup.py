"""Which atlas answers a request: :func:`atlas_settings` (what an atlas of records on a floor is,
and its key), :func:`stored_atlas` (the complete one in the cache), and ``method`` of
:func:`audit.check` (:func:`check_atlas`). Shared by :mod:`audit.api.atlas` and
:mod:`audit.api.object_check`."""

from __future__ import annotations

import os

from audit import G
from audit.engine.shared.defaults import (DEFAULT_CHECK_RECORDS, DEFAULT_FREE_MOTION_S,
                                          DEFAULT_IM, DEFAULT_JOBS, DEFAULT_RESTITUTION)
from audit.physics.building.floor import DEFAULT_BUILDING_DAMPING


def atlas_settings(records=DEFAULT_CHECK_RECORDS, *, im=DEFAULT_IM,
                   restitution=DEFAULT_RESTITUTION, free_motion_s=DEFAULT_FREE_MOTION_S,
                   g=G, floor: float = 0.0, building=None, building_model=None,
                   building_damping=DEFAULT_BUILDING_DAMPING, jobs: int = DEFAULT_JOBS,
                   grid=None):
    """(the records on their floor, :class:`~audit.engine.atlas.settings.AtlasSettings`): what
    an atlas of ``records`` on the floor is, each argument checked (InputError naming it).

    Parameters
    ----------
    records : str, path or records.RecordSuite
    im : str
        ``sa:T`` or ``pga``.
    restitution : str
    free_motion_s, g : float
    floor, building, building_model, building_damping :
        The floor, as for :func:`audit.check`.
    jobs : int
        Solver threads of a record (worker processes of ``scheduler="dask"``).
    grid : (sequence, sequence), optional
        The (α [degrees], 2π/p [s]) grid; default the atlas's
        (:data:`~audit.engine.atlas.settings.ALPHA_DEG`, :data:`~audit.engine.atlas.settings.SIZE_S`).
    """
    from audit.api.inputs import record_suite
    from audit.engine.atlas.settings import ALPHA_DEG, SIZE_S, AtlasSettings, floor_words, \
        records_digest
    from audit.engine.check.settings import CheckSettings
    from audit.engine.shared.design_site import DesignSite
    from audit.engine.shared.runtime import Runtime
    checked = CheckSettings.parse(im=im, restitution=restitution, free_motion_s=free_motion_s,
                                  g=g)
    runtime = Runtime.parse(jobs=jobs)
    site = DesignSite.parse(floor=floor, building=building, building_model=building_model,
                            building_damping=building_damping)
    suite = site.apply(record_suite(records))
    entries = [entry for entry in suite if entry.motion is not None]
    alpha_deg, size_s = grid if grid is not None else (ALPHA_DEG, SIZE_S)
    name = records if isinstance(records, str) else str(getattr(records, "description", records))
    return entries, AtlasSettings(name, records_digest(entries), checked.im,
                                  floor_words(site.floor), checked.restitution, checked.g,
                                  checked.free_motion_s,
                                  tuple(float(a) for a in alpha_deg),
                                  tuple(float(s) for s in size_s), runtime.jobs)


def stored_atlas(records, *, im, restitution, free_motion_s, g, floor, building,
                  building_model, building_damping):
    """(the complete atlas, its key) of ``records`` on the floor, or None: the default grid's,
    else one on another grid (:func:`~audit.engine.atlas.store.complete_atlas_like`)."""
    from audit.engine.atlas.answers import Atlas
    from audit.engine.atlas.store import complete_atlas_like
    _, settings = atlas_settings(records, im=im, restitution=restitution,
                                 free_motion_s=free_motion_s, g=g, floor=floor,
                                 building=building, building_model=building_model,
                                 building_damping=building_damping)
    found = complete_atlas_like(settings.as_dict(), settings.key())
    return (Atlas(found.directory), found.key) if found is not None else None


#: ``method`` of :func:`audit.check`: the atlas where one exists (None), or always one way.
METHODS = ("atlas", "direct")


def checked_method(method):
    """``method`` of :func:`audit.check`, checked (InputError naming it).

    Parameters
    ----------
    method : {None, "atlas", "direct"}
    """
    from audit.errors import InputError
    if method is not None and method not in METHODS:
        raise InputError(f"method: expected 'atlas', 'direct' or None (the atlas where one "
                         f"is built), got {method!r}", "method")
    return method


def check_atlas(method, records, *, named, im, restitution, free_motion_s, g, floor, building,
                building_model, building_damping):
    """(atlas, key) the exact side of :func:`audit.check` reads, or None where it solves:
    ``method`` None reads the atlas of ``records`` on the floor (with this intensity measure,
    restitution, g and free motion) where one is built, ``"direct"`` never, ``"atlas"``
    always (InputError naming ``method`` where none is built, with the command that builds
    it).

    Parameters
    ----------
    method : {None, "atlas", "direct"}
    records : records.RecordSuite
        The records read (before the site is applied).
    named : str, path or records.RecordSuite
        ``records`` as the caller named them (for the command that builds the atlas).
    im : str
    restitution : str or float
    free_motion_s, g : float
    floor, building, building_model, building_damping :
        The floor, as for :func:`audit.check`.
    """
    from audit.errors import InputError
    if checked_method(method) == "direct":
        return None
    found = stored_atlas(records, im=im, restitution=restitution,
                          free_motion_s=free_motion_s, g=g, floor=floor, building=building,
                          building_model=building_model, building_damping=building_damping)
    if found is None and method == "atlas":
        name = named if isinstance(named, (str, os.PathLike)) else "RECORDS"
        flags = f" --im {im}"
        if building is not None:
            flags += f" --floor {floor:g} --building {building:g}"
            if building_model is not None:
                flags += f" --building-model {building_model}"
            if building_damping != DEFAULT_BUILDING_DAMPING:
                flags += f" --building-damping {building_damping:g}"
        if str(restitution) != str(DEFAULT_RESTITUTION):
            flags += f" --restitution {restitution}"
        if free_motion_s != DEFAULT_FREE_MOTION_S:
            flags += f" --free-motion {free_motion_s:g}"
        raise InputError(f"method: 'atlas': no atlas of these records for {im} (floor "
                         f"{floor:g}, restitution {restitution}, g {g:g}, free motion "
                         f"{free_motion_s:g} s); build it with 'python -m audit atlas build "
                         f"--records {name}{flags}'", "method")
    return found


__all__ = ["atlas_settings", "stored_atlas", "checked_method", "check_atlas", "METHODS"]
