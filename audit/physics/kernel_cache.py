"""How the project's kernels are compiled (:func:`kernel`), and numba's cache of them stamped with
the sources of all of them.

numba checks a cached kernel against its own file only (its notes on caching: cache invalidation
fails to recognise changes in symbols defined in a different file), yet a kernel compiles in the
kernels it calls from other modules. After an update that changed ``motion_equation.py`` alone,
``kernel.py``'s cached solver would go on integrating the old equation of motion, silently. The
kernels of ``audit/physics`` and ``procedures`` are stamped instead with one digest of every
module that defines kernels, so that a change to any of them recompiles them all (once, about
40 s). The cache stays where numba puts it: ``NUMBA_CACHE_DIR`` if set, else ``__pycache__``
beside the source, else numba's folder in the user's cache.
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

import numba
from numba.core import caching

#: The folders of the modules that define kernels: this package and ``procedures`` beside it.
KERNEL_FOLDERS = (Path(__file__).resolve().parent,
                  Path(__file__).resolve().parents[2] / "procedures")
#: What marks a module that defines kernels (this one holds it too, and counts: it says how
#: they are compiled).
_DEFINES_KERNELS = b"@kernel("


def kernel(inline: str = "never"):
    """``numba.njit`` as every kernel of the project is compiled: cached (stamped with
    :func:`kernel_sources_digest`), the GIL released while it runs; ``inline="always"`` for the
    small helpers whose callers should compile them in."""
    return numba.njit(cache=True, nogil=True, inline=inline)


def _kernel_sources() -> list[tuple[Path, bytes]]:
    """The modules that define kernels and their contents, in a fixed order (each read once)."""
    sources = ((path, path.read_bytes()) for folder in KERNEL_FOLDERS
               for path in folder.rglob("*.py"))
    return sorted((path, text) for path, text in sources if _DEFINES_KERNELS in text)


def kernel_modules() -> list[Path]:
    """The modules that define kernels, in a fixed order."""
    return [path for path, _ in _kernel_sources()]


@functools.cache
def kernel_sources_digest() -> bytes:
    """SHA-256 of the names and contents of every module that defines kernels (read once per
    process)."""
    digest = hashlib.sha256()
    for path, text in _kernel_sources():
        digest.update(path.name.encode() + b"\0" + text + b"\0")
    return digest.digest()


def _ours(py_file) -> bool:
    path = Path(py_file).resolve()
    return any(path.is_relative_to(folder) for folder in KERNEL_FOLDERS)


class _StampedByAllKernels:
    """A numba cache locator for the project's kernels alone, stamped with
    :func:`kernel_sources_digest` instead of the kernel's own file."""

    def get_source_stamp(self):
        return kernel_sources_digest()

    @classmethod
    def from_function(cls, py_func, py_file):
        return super().from_function(py_func, py_file) if _ours(py_file) else None


class _UserProvided(_StampedByAllKernels, caching.UserProvidedCacheLocator):
    pass


class _InTree(_StampedByAllKernels, caching.InTreeCacheLocator):
    pass


class _UserWide(_StampedByAllKernels, caching.UserWideCacheLocator):
    pass


# tried first, in numba's own order of places; any other function finds numba's locators as
# before. The list is not public API (CacheImpl in recent numba, _CacheImpl in older ones): a
# numba without it keeps its own stamps, as before this module, rather than fail to import
# (tests/physics/test_kernel_cache.py fails there, so that it is seen).
_IMPLEMENTATION = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
_LOCATORS = getattr(_IMPLEMENTATION, "_locator_classes", None)
if isinstance(_LOCATORS, list) and _InTree not in _LOCATORS:
    _IMPLEMENTATION._locator_classes = [_UserProvided, _InTree, _UserWide, *_LOCATORS]


__all__ = ["kernel", "kernel_modules", "kernel_sources_digest", "KERNEL_FOLDERS"]
