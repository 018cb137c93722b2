"""Writing output files all or nothing; light on purpose (no pandas), so every command can use it."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path


def write_files_atomically(out_dir: str | Path, files: dict[str, bytes]) -> None:
    """Write ``files`` (name → content) into ``out_dir``, all or nothing.

    Everything is written into a temporary directory next to ``out_dir`` first; each file is
    then moved into place with an atomic rename.
    """
    out_dir = Path(out_dir)
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}-", dir=out_dir.parent))
    try:
        for name, content in files.items():
            (staging / name).write_bytes(content)
        out_dir.mkdir(exist_ok=True)
        for name in files:
            os.replace(staging / name, out_dir / name)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
