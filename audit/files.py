"""Output files and folders: checked before any work, written all or nothing (the one place
the tool writes files atomically: every layer, records included, writes through here).

Light on purpose (no pandas, no numpy), so every command can validate and write its outputs
without loading the scientific stack.
"""

from __future__ import annotations

import fnmatch
import os
import shutil
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

from audit.errors import InputError


#: Start of this run: staging folders older than it, of processes no longer alive, are stale.
_RUN_STARTED = time.time()
#: The process's file-creation mask (read by setting it, then put back), for files made by
#: mkstemp to get the permissions any other new file gets.
_UMASK = os.umask(0o022)
os.umask(_UMASK)


def _staging_prefix(out_dir: Path) -> str:
    return f".{out_dir.name}-staging-"


def _writable(folder: Path, what: str, path: Path) -> None:
    """InputError unless a folder can be created in ``folder`` (tried, then removed): the
    permission bits say nothing for root or on a read-only file system."""
    try:
        os.rmdir(tempfile.mkdtemp(prefix=f".{path.name}-probe-", dir=folder))
    except OSError as exc:
        raise InputError(f"{what}: {path}: folder {folder} is not writable "
                         f"({exc.strerror})") from None


def _writable_ancestor(path: Path, what: str) -> None:
    """InputError unless the nearest existing ancestor of ``path`` is a writable folder."""
    ancestor = path.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise InputError(f"{what}: {path}: {ancestor} is a file, not a folder")
    _writable(ancestor, what, path)


def check_output_dir(out_dir: str | Path, what: str = "out_dir") -> Path:
    """``out_dir`` if it can receive a run's files: a writable folder, or one that can be made.

    Called before any computation, so a bad output path costs nothing; ``what`` names the
    option in the one-line InputError.
    """
    out_dir = Path(out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        raise InputError(f"{what}: {out_dir} is a file, expected a folder")
    _writable_ancestor(out_dir, what)
    if out_dir.is_dir():
        _writable(out_dir, what, out_dir)
    return out_dir


def check_output_file(path: str | Path, what: str) -> Path:
    """``path`` if a file can be written there: not a folder, in a writable or creatable one."""
    text = str(path)
    path = Path(path)
    if path.is_dir() or text.endswith(("/", os.sep)):
        raise InputError(f"{what}: {text} is a folder, expected a file name")
    _writable_ancestor(path, what)
    return path


def _same(a: Path, b: Path) -> bool:
    """Whether ``a`` and ``b`` name one file or folder (links and ``..`` resolved)."""
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist yet
        return a.resolve() == b.resolve()


def check_outputs(*, files=None, folders=None, inputs=None) -> dict[str, Path | None]:
    """Every output of a command, checked together before any work: one InputError naming the
    option of the first output that would overwrite an input, another output, or a folder, or
    that cannot be written.

    Parameters
    ----------
    files : dict, optional
        Option → path of each output file (None or "-": not given, or standard output).
    folders : dict, optional
        Option → ``(path, names)`` of each output folder and the file names (glob patterns)
        the command writes in it.
    inputs : dict, optional
        Option → path, or list of paths, the command reads. A value that names no existing
        file or folder (a built-in suite, a record id) is not a path and is skipped.

    Returns
    -------
    dict
        Option → checked path (None for an output not given or standard output).
    """
    files = {option: path for option, path in (files or {}).items()}
    folders = {option: spec for option, spec in (folders or {}).items() if spec[0] is not None}
    read = []
    for option, value in (inputs or {}).items():
        for item in value if isinstance(value, (list, tuple)) else (value,):
            if item is not None and str(item) not in ("", "-") and os.path.exists(item):
                read.append((option, Path(item)))
    checked: dict[str, Path | None] = {}
    for option, (path, names) in folders.items():
        out_dir = check_output_dir(path, option)
        for source, item in read:
            if _same(item, out_dir):
                raise InputError(f"{option}: {path} is the input of {source}; choose another "
                                 "output folder")
            if (_same(item.parent, out_dir)
                    and any(fnmatch.fnmatch(item.name, name) for name in names)):
                raise InputError(f"{option}: {path} would receive {item.name} over the input "
                                 f"of {source} ({item}); choose another output folder")
        checked[option] = out_dir
    for option, path in files.items():
        if path in (None, "-"):
            checked[option] = None
            continue
        for folder_option, (folder, names) in folders.items():
            folder = Path(folder)
            if _same(Path(path), folder):
                raise InputError(f"{option}: {path} is the {folder_option} folder; give a "
                                 "file name")
            if (_same(Path(path).parent, folder)
                    and any(fnmatch.fnmatch(Path(path).name, name) for name in names)):
                raise InputError(f"{option}: {path} is a file that {folder_option} writes; "
                                 "choose another file name")
        target = check_output_file(path, option)
        for source, item in read:
            if _same(item, target):
                raise InputError(f"{option}: {path} is the input of {source}; choose another "
                                 "file")
        for other, done in checked.items():
            if done is not None and other not in folders and _same(done, target):
                raise InputError(f"{option}: {path} is also the {other} output; give each "
                                 "output its own file")
        checked[option] = target
    return checked


def clean_stale_staging(out_dir: Path) -> None:
    """Remove staging folders of ``out_dir`` left by a run that was killed (a run writes its
    files there as its records complete).

    Only folders named with this tool's staging prefix, older than the current run, whose
    process is no longer alive.
    """
    prefix = _staging_prefix(out_dir)
    if not out_dir.parent.is_dir():
        return
    for folder in out_dir.parent.glob(prefix + "*"):
        pid = folder.name[len(prefix):].split("-")[0]
        if not (folder.is_dir() and pid.isdigit() and folder.stat().st_mtime < _RUN_STARTED):
            continue
        try:
            os.kill(int(pid), 0)
            continue  # its process still runs
        except ProcessLookupError:
            shutil.rmtree(folder, ignore_errors=True)
        except PermissionError:
            continue


@contextmanager
def staged_folder(out_dir: str | Path):
    """A staging folder whose files replace those of ``out_dir`` when the block ends without an
    error, all or nothing.

    The folder is made next to ``out_dir`` (named ``.NAME-staging-PID-…``; stale ones of killed
    runs are removed here) so that each file then moves into place with an atomic rename; it is
    removed in any case. Files of ``out_dir`` that are not staged are left alone, and so are
    the staging folder's own folders. An OS error names ``out_dir``, never the staging folder.
    """
    out_dir = check_output_dir(out_dir, "output folder")
    clean_stale_staging(out_dir)
    try:
        out_dir.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f"{_staging_prefix(out_dir)}{os.getpid()}-",
                                        dir=out_dir.parent))
    except OSError as exc:
        raise InputError(f"{out_dir}: cannot write: {exc.strerror}") from None
    try:
        yield staging
        names = sorted(path.name for path in staging.iterdir() if path.is_file())
        out_dir.mkdir(exist_ok=True)
        for name in names:
            if (out_dir / name).is_dir():
                raise InputError(f"{out_dir / name}: is a folder, cannot be replaced by a file")
        for name in names:
            os.replace(staging / name, out_dir / name)
    except OSError as exc:
        raise InputError(f"{out_dir}: cannot write: {exc.strerror}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def write_files_atomically(out_dir: str | Path, files: dict[str, bytes]) -> None:
    """Write ``files`` (name → content) into ``out_dir``, all or nothing
    (:func:`staged_folder`)."""
    with staged_folder(out_dir) as staging:
        for name, content in files.items():
            (staging / name).write_bytes(content)


def write_atomically(files: dict[Path, bytes]) -> None:
    """Write every output file of a command together: all are staged beside their targets
    first and renamed into place only when every one is complete, so a failure leaves none."""
    staged = []
    try:
        for path, content in files.items():
            path.parent.mkdir(parents=True, exist_ok=True)
            handle, temp = tempfile.mkstemp(prefix=f".{path.name}-staging-{os.getpid()}-",
                                            dir=path.parent)
            staged.append(temp)
            os.chmod(temp, 0o666 & ~_UMASK)  # mkstemp's 0600 would keep a report private
            with os.fdopen(handle, "wb") as stream:
                stream.write(content)
        for temp, path in zip(staged, files):
            os.replace(temp, path)
    except OSError as exc:
        raise InputError(f"{path}: cannot write: {exc.strerror}") from None
    finally:
        for temp in staged:
            if os.path.exists(temp):
                os.remove(temp)


def write_file_atomically(path: str | Path, content: bytes) -> None:
    """Write one file atomically (see :func:`write_atomically`)."""
    write_atomically({Path(path): content})
