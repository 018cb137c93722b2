"""Per-record results kept while a run is under way, so an interrupted run can resume.

Each record's :class:`~audit.engine.run.record_audit.RecordAudit` is pickled into ``DIR/.partial/`` as
soon as it is computed (written to a temporary name, then renamed: a kill leaves either the
whole file or none). The file name and the stored key hash everything the part depends on:
the tool version, the procedures (names, classes, attributes), the :class:`AuditSettings`
(grid, free motion, band, ε, g) and the record (id, site, facts, file SHA-256, a digest of
the acceleration samples as audited, so scaled records differ, of the vertical samples where
there are some, and pulse parameters). A
resumed run reuses a part only when the key matches. Pickle is safe here: these are the
tool's own files, in the run's output directory.
"""

from __future__ import annotations

from pathlib import Path

from audit import __version__

PARTIAL_DIR = ".partial"
# hashlib, json, pickle and the atomic write are imported where a part is keyed or stored: the API's
# front door imports this module for PARTIAL_DIR and kept_parts


def motion_digest(motion) -> str:
    """SHA-256 of the samples [m/s²] and step [s] of a motion: its identity as audited.

    Parameters
    ----------
    motion : records.GroundMotion
        The motion.
    """
    import hashlib
    digest = hashlib.sha256(motion.acceleration.tobytes())
    digest.update(repr(float(motion.dt)).encode())
    return digest.hexdigest()


def _sha(text: str) -> str:
    import hashlib
    return hashlib.sha256(text.encode()).hexdigest()


def run_key(procedures, settings) -> str:
    """Hash of the tool version, the procedures and the settings of a run.

    Parameters
    ----------
    procedures : sequence of procedures.base.Procedure
        The procedures run.
    settings : AuditSettings
        The run's settings (anything with ``as_dict()``).
    """
    import json
    return _sha(json.dumps({
        "version": __version__,
        "procedures": [[p.name, f"{type(p).__module__}.{type(p).__qualname__}",
                        repr(sorted(vars(p).items()))] for p in procedures],
        "settings": settings.as_dict(),
    }, sort_keys=True, default=repr))


def record_key(entry) -> str:
    """Hash of what a record contributes to its part of the audit.

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    """
    import hashlib
    import json
    motion = entry.motion
    item = {"id": entry.id, "site": entry.site, "facts": repr(entry.facts),
            "component": entry.component, "missing_reason": entry.missing_reason}
    if motion is not None:
        item.update(sha256=motion.sha256, samples=motion_digest(motion), pulse=repr(motion.pulse))
        if motion.vertical is not None:
            item["vertical"] = hashlib.sha256(motion.vertical.tobytes()).hexdigest()
    return _sha(json.dumps(item, sort_keys=True, default=repr))


def kept_parts(directory) -> list[Path]:
    """The parts stored in ``directory`` (temporary files of a write under way excluded).

    Parameters
    ----------
    directory : str or pathlib.Path
        The folder of the parts (``partial_dir``).
    """
    directory = Path(directory)
    return sorted(directory.glob("[!.]*.pkl")) if directory.is_dir() else []


class PartialStore:
    """The ``.partial`` folder of a run.

    Parameters
    ----------
    directory : str or Path
        ``DIR/.partial``.
    procedures : list of procedures.Procedure
    settings : audit.engine.run.settings.AuditSettings
    resume : bool
        Keep parts already there (reused where their key matches); otherwise the folder is
        cleared first.
    """

    def __init__(self, directory, procedures, settings, resume: bool):
        self.directory = Path(directory)
        self.key = run_key(procedures, settings)
        self.resume = resume  # whether its parts are reused (computed_parts asks)
        if not resume:
            self.remove()

    def _path_and_key(self, entry) -> tuple[Path, str]:
        key = _sha(self.key + record_key(entry))
        return self.directory / f"{key[:40]}.pkl", key

    def load(self, entry):
        """The stored part of ``entry`` when it matches this run, else None.

        Parameters
        ----------
        entry : records.RecordEntry
            The record.
        """
        import pickle
        path, key = self._path_and_key(entry)
        try:
            with open(path, "rb") as file:
                stored = pickle.load(file)
        except FileNotFoundError:
            return None
        except Exception:  # an unreadable part is recomputed, never trusted
            return None
        if not isinstance(stored, dict) or stored.get("key") != key:
            return None
        return stored["part"]

    def save(self, entry, part) -> None:
        """Store the part of ``entry`` atomically (temporary file, then rename).

        Parameters
        ----------
        entry : records.RecordEntry
            The record.
        part : object
            Its part of the run (a :class:`~audit.engine.run.record_audit.RecordAudit`), pickled.
        """
        import pickle

        from audit.files import write_file_atomically
        path, key = self._path_and_key(entry)
        write_file_atomically(path, pickle.dumps({"key": key, "record": entry.id, "part": part},
                                                 protocol=pickle.HIGHEST_PROTOCOL))

    def remove(self) -> None:
        """Delete the folder (after the final outputs are saved, or to start afresh)."""
        import shutil
        shutil.rmtree(self.directory, ignore_errors=True)


__all__ = ["PARTIAL_DIR", "PartialStore", "kept_parts", "motion_digest", "record_key", "run_key"]
