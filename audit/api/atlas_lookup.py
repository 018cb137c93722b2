"""Which atlas answers a request: :func:`atlas_settings` (what an atlas of records on a floor is,
and its key), :func:`stored_atlas` (the complete one in the cache), and the ``method`` of
:func:`audit.check` (:func:`check_atlas`) and of :func:`audit.margins` / :func:`audit.fragility`
(:func:`atlas_reading`). Shared by :mod:`audit.api.atlas` and the commands that read an atlas
(apart from :mod:`audit.api.atlas`, which imports :mod:`audit.api.object_check`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from audit.engine.shared.defaults import DEFAULT_CHECK_RECORDS, DEFAULT_IM

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
    records : Records, str, path or records.RecordSuite
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
    name = str(records_named(getattr(records, "source", records), suite))
    return entries, AtlasSettings(name, records_digest(entries), im,
                                  floor_words(site.floor), solver.restitution, solver.g,
                                  solver.free_motion_s,
                                  tuple(float(a) for a in alpha_deg),
                                  tuple(float(s) for s in size_s), runtime.jobs)


def stored_atlas(records, *, im=DEFAULT_IM, solver: Solver | None = None,
                 floor: Floor | None = None):
    """(the complete atlas, its key) of ``records`` on the floor, or None: the default grid's,
    else one on another grid (:func:`~audit.engine.atlas.store.complete_atlas_like`).

    Parameters
    ----------
    records, im, solver, floor :
        As for :func:`atlas_settings`.
    """
    atlas, key = _lookup(records, im, solver, floor)
    return None if atlas is None else (atlas, key)


def _lookup(records, im, solver, floor):
    """(the complete atlas or None, the key of the one asked for) (:func:`stored_atlas`)."""
    from audit.engine.atlas.answers import Atlas
    from audit.engine.atlas.store import complete_atlas_like
    _, settings = atlas_settings(records, im=im, solver=solver, floor=floor)
    found = complete_atlas_like(settings.as_dict(), settings.key())
    return (Atlas(found.directory), found.key) if found is not None else (None, settings.key())


def records_named(named, records):
    """``named`` where it is a name or a path, else ``records``' description: the records as
    the user named them, for what builds their atlas."""
    import os
    return named if isinstance(named, (str, os.PathLike)) else getattr(records, "description",
                                                                       records)


def check_atlas(method, records, *, named, im, solver: Solver, floor: Floor):
    """(atlas, key) the exact side of :func:`audit.check` reads, or None where it solves:
    ``method`` None reads the atlas of ``records`` on the floor (with this intensity measure,
    restitution, g and free motion) where one is built, ``"direct"`` never, ``"atlas"``
    always (:class:`~audit.errors.NoAtlas` naming ``method`` where none is built).

    Parameters
    ----------
    method : {None, "atlas", "direct"}
    records : records.RecordSuite
        The records read (before the site is applied).
    named : str, path or records.RecordSuite
        ``records`` as the caller named them (for what builds the atlas).
    im : str
    solver : Solver
    floor : Floor
    """
    from audit.engine.atlas.fragility_read import checked_method
    from audit.errors import NoAtlas
    if checked_method(method) == "direct":
        return None
    found = stored_atlas(records, im=im, solver=solver, floor=floor)
    if found is None and method == "atlas":
        raise NoAtlas("no atlas of these records, intensity measure, floor, restitution, g and "
                      "free motion", {"records": records_named(named, records), "im": im,
                                      "solver": solver, "floor": floor})
    return found


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
        The records as the user named them (for what builds the atlas); default the suite's
        description.
    """
    from audit.engine.atlas.fragility_read import atlas_for, checked_method
    if checked_method(method) == "direct":
        return None
    im = getattr(im, "name", im)
    atlas, key = _lookup(records, im, solver, floor)
    return atlas_for(method, atlas, key, *blocks,
                     {"records": records_named(named, records), "im": im, "solver": solver,
                      "floor": floor}, stripes=stripes)


__all__ = ["atlas_settings", "stored_atlas", "records_named", "check_atlas", "atlas_reading"]
