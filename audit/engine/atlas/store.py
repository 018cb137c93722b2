"""Where atlases live: ``$ROCKING_AUDIT_ATLAS_DIR``, else ``atlas/`` in the user cache
(:func:`records.p695.cache_dir`, where the FEMA P695 records are kept), one folder per atlas
named by its key (:meth:`~audit.engine.atlas.settings.AtlasSettings.key`).

A folder holds ``atlas.json`` (the provenance) and ``atlas.npz`` once complete; while a build is
under way, ``parts/`` holds one ``.npz`` per record (written to a temporary name and renamed: a
kill leaves a whole chunk or none), which a build started again reuses.
"""

from __future__ import annotations

import io
import json
import os
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from audit.files import write_file_atomically

#: Environment variable naming the folder of atlases (tests point it at a temporary folder).
ATLAS_DIR_ENV = "ROCKING_AUDIT_ATLAS_DIR"
ATLAS_NPZ, ATLAS_JSON, PARTS_DIR = "atlas.npz", "atlas.json", "parts"


def atlas_root() -> Path:
    """The folder of every atlas (see the module)."""
    given = os.environ.get(ATLAS_DIR_ENV)
    if given:
        return Path(given)
    from records.p695 import cache_dir
    return cache_dir() / "atlas"


def npz_bytes(**arrays) -> bytes:
    """``arrays`` as the bytes of a compressed ``.npz``.

    Parameters
    ----------
    **arrays : numpy.ndarray
        By name.
    """
    buffer = io.BytesIO()
    np.savez_compressed(buffer, **arrays)
    return buffer.getvalue()


class AtlasParts:
    """The per-record chunks of a build, in the interface
    :func:`~audit.engine.shared.scheduler.computed_parts` keeps parts in (``resume``, ``load``,
    ``save``).

    Parameters
    ----------
    directory : pathlib.Path
        The atlas's folder.
    """

    resume = True  # a chunk is keyed by the atlas and the record: one that is there is valid

    def __init__(self, directory: Path):
        self.directory = Path(directory) / PARTS_DIR

    def _path(self, entry) -> Path:
        from audit.engine.shared.partial import record_key
        return self.directory / f"{record_key(entry)[:40]}.npz"

    def load(self, entry):
        """The record's chunk, or None where it is not there yet.

        Parameters
        ----------
        entry : records.RecordEntry
        """
        path = self._path(entry)
        if not path.is_file():
            return None
        with np.load(path) as data:
            return {name: data[name] for name in data.files}

    def save(self, entry, part) -> None:
        """Keep the record's chunk (atomically).

        Parameters
        ----------
        entry : records.RecordEntry
        part : dict
            Its arrays by name (:func:`~audit.engine.atlas.pipeline.atlas_record`).
        """
        self.directory.mkdir(parents=True, exist_ok=True)
        write_file_atomically(self._path(entry), npz_bytes(**part))

    def count(self) -> int:
        return len(list(self.directory.glob("[!.]*.npz"))) if self.directory.is_dir() else 0


@dataclass(frozen=True)
class StoredAtlas:
    """An atlas in the cache: its folder and provenance, and whether it is complete."""

    directory: Path
    provenance: dict
    complete: bool

    @property
    def key(self) -> str:
        return self.directory.name

    def size_bytes(self) -> int:
        return sum(p.stat().st_size for p in self.directory.rglob("*") if p.is_file())


def atlas_dir(key: str) -> Path:
    """The folder of the atlas of ``key``.

    Parameters
    ----------
    key : str
        :meth:`~audit.engine.atlas.settings.AtlasSettings.key`.
    """
    return atlas_root() / key


def stored_atlases() -> list[StoredAtlas]:
    """Every atlas in the cache (complete or with chunks of an interrupted build)."""
    root = atlas_root()
    out = []
    for directory in sorted(root.iterdir()) if root.is_dir() else []:
        meta = directory / ATLAS_JSON
        if meta.is_file():
            out.append(StoredAtlas(directory, json.loads(meta.read_text()),
                                   (directory / ATLAS_NPZ).is_file()))
    return out


#: What an atlas's grid is: an atlas of other provenance but these answers the same objects.
GRID_FIELDS = ("alpha_deg", "size_s")


def complete_atlas_like(provenance: dict, key: str) -> StoredAtlas | None:
    """The complete atlas of ``key``, else one whose provenance is ``provenance`` but for the
    grid (and the record set's name, which its digest stands for): a finer or smaller grid
    answers the same objects inside it; None where there is none.

    Parameters
    ----------
    provenance : dict
        :meth:`~audit.engine.atlas.settings.AtlasSettings.as_dict` of the atlas wanted.
    key : str
        Its key.
    """
    if (atlas_dir(key) / ATLAS_NPZ).is_file():
        return StoredAtlas(atlas_dir(key), json.loads((atlas_dir(key) / ATLAS_JSON).read_text()),
                           True)
    wanted = {k: v for k, v in provenance.items() if k not in (*GRID_FIELDS, "records")}
    for stored in stored_atlases():
        if stored.complete and all(stored.provenance.get(k) == v for k, v in wanted.items()):
            return stored
    return None


def remove_atlas(key_prefix: str) -> list[str]:
    """Remove the atlases whose key starts with ``key_prefix``; their keys.

    Parameters
    ----------
    key_prefix : str
        The key or its first characters (as ``atlas list`` shows them).
    """
    gone = [a.key for a in stored_atlases() if a.key.startswith(key_prefix)]
    for key in gone:
        shutil.rmtree(atlas_dir(key))
    return gone


__all__ = ["atlas_root", "AtlasParts", "StoredAtlas", "stored_atlases", "remove_atlas", "atlas_dir",
           "complete_atlas_like", "npz_bytes", "GRID_FIELDS", "ATLAS_DIR_ENV", "ATLAS_NPZ", "ATLAS_JSON", "PARTS_DIR"]
