"""A record's true response spectra at one damping, kept between runs (:func:`stored_spectra`).

The guidelines read each record's spectra at dampings fixed by their text (NTC 2018's ξ of SLV
and SLC, Housner's 2 %) on one period table, whatever the object: a record's property, like its
pulse. Computing them was most of one object's check (about 3.5 s of thread time for the 44
far-field records), so they are kept in the user cache, ``spectra/`` beside the records', one
file per record, damping and free motion, named by the SHA-256 of everything they depend on
(the samples and step, the periods, the damping, the free motion, whether Sd alone, and the
sources of the kernels and of :mod:`audit.physics.response_spectra`): a change of any of them
is another file, and the values read are the values computed, bit for bit.
"""

from __future__ import annotations

import functools
import hashlib
import io
import zipfile
import zlib
from pathlib import Path

import numpy as np

from audit.errors import InputError
from audit.files import write_file_atomically
from audit.physics import response_spectra as spectra_module
from audit.physics.kernel_cache import kernel_sources_digest
from audit.physics.response_spectra import ResponseSpectra, response_spectra
from records.p695 import cache_dir

#: Part of every key: bump when what a file holds changes.
FORMAT = "spectra-1"


@functools.cache
def _code_digest() -> bytes:
    return hashlib.sha256(kernel_sources_digest()
                          + Path(spectra_module.__file__).read_bytes()).digest()


def _samples_digest(motion, period_s: np.ndarray, damping: float, free_motion_s: float):
    """SHA-256 of everything a file depends on but whether it holds Sd alone (hashed once a
    request: a record's samples are its bulk)."""
    digest = hashlib.sha256(f"{FORMAT} {motion.dt!r} {damping!r} {free_motion_s!r} ".encode()
                            + _code_digest())
    digest.update(np.ascontiguousarray(period_s, dtype=float).tobytes())
    digest.update(np.ascontiguousarray(motion.acceleration, dtype=float).tobytes())
    return digest


def _key(samples, displacement_only: bool) -> str:
    digest = samples.copy()
    digest.update(f" {displacement_only}".encode())
    return digest.hexdigest()


def _path(key: str) -> Path:
    return cache_dir() / "spectra" / key[:2] / f"{key}.npz"


def _read(path: Path, period_s: np.ndarray, damping: float) -> ResponseSpectra | None:
    try:
        with np.load(path, allow_pickle=False) as stored:
            sd, sv, sa = stored["sd"], stored["sv"], stored["sa"]
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile, zlib.error):
        return None
    if not sd.shape == sv.shape == sa.shape == (1, period_s.size):
        return None
    return ResponseSpectra(period_s, np.array([damping]), sd, sv, sa)


def stored_spectra(motion, period_s, damping: float, free_motion_s: float, jobs: int = 1,
                   displacement_only: bool = False) -> ResponseSpectra:
    """:func:`~audit.physics.response_spectra.response_spectra` of ``motion`` at one damping,
    read from the user cache where computed before (full spectra serve a request for Sd alone),
    else computed and kept there.

    Parameters
    ----------
    motion : records.GroundMotion
        Ground acceleration [m/s²].
    period_s : array_like of float
        Periods T ≥ 0 [s].
    damping : float
        Damping ratio ξ [-].
    free_motion_s : float
        Free vibration after the record [s].
    jobs : int
        Threads computing them where not kept.
    displacement_only : bool
        Sd alone is asked (Sv and Sa NaN where computed for it).
    """
    period_s = np.asarray(period_s, dtype=float)
    damping = float(damping)
    samples = _samples_digest(motion, period_s, damping, free_motion_s)
    keys = [_key(samples, False)] + ([_key(samples, True)] if displacement_only else [])
    for key in keys:
        found = _read(_path(key), period_s, damping)
        if found is not None:
            return found
    spectra = response_spectra(motion, period_s, [damping], free_motion_s, jobs=jobs,
                               displacement_only=displacement_only)
    content = io.BytesIO()
    np.savez(content, sd=spectra.sd, sv=spectra.sv, sa=spectra.sa)
    try:
        write_file_atomically(_path(keys[-1]), content.getvalue())
    except InputError:  # the cache is an optimisation: never a reason to stop
        pass
    return spectra


__all__ = ["stored_spectra", "FORMAT"]
