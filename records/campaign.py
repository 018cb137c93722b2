"""Reader of a shake-table campaign folder (the format of ``docs/validation.md``).

A campaign is ``tests.csv`` (one row per test) beside the table-motion files it names. Columns:

- ``test``: unique test id;
- ``ground_motion``: the record the table reproduced (tests of one record share it; the
  cross-validation keeps them in one fold);
- ``motion_file``: path relative to the folder of a CSV file (``.gz`` allowed) with columns
  ``time_s, acc_g`` at a constant time step;
- ``SPECIMEN_overturned``: one column per specimen, 1 (overturned), 0 (stood) or empty
  (unknown: the test is predicted);
- optionally ``numerical_SPECIMEN_...`` or ``numerical_spN_...``: another model's 0/1
  predictions for specimen ``SPECIMEN`` (``spN`` for a specimen named ``...N``).

Columns ``SPECIMEN_peak_rotation_rad`` (measured peaks instead of outcomes) are recognised and
refused with a message: this version fits outcomes only.
"""

from __future__ import annotations

import lzma
import re
import warnings
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from audit import G
from audit.errors import InputError, InputWarning
from records.motion import GroundMotion
from records.readers import PLAUSIBLE_PGA_G

TESTS_CSV = "tests.csv"
REQUIRED_COLUMNS = ("test", "ground_motion", "motion_file")
OUTCOME_SUFFIX = "_overturned"
PEAK_ROTATION_SUFFIX = "_peak_rotation_rad"
PEER_PREFIX = "numerical_"
#: Relative spread of the time steps accepted as one constant step.
_DT_TOLERANCE = 1e-3
#: Time steps of a table motion accepted [s]: shake-table controllers and their acquisition
#: sample at 20 Hz to 10 kHz; coarser than 0.05 s (Nyquist 10 Hz) a record cannot carry what
#: rocks a block, and a time column in milliseconds (steps of 1–20 "s") lands well above it.
TABLE_DT_S = (1e-4, 0.05)
#: Median peak of a campaign's table motions above which it is warned of as m/s² under acc_g
#: [g]: rocking campaigns shake at 0.05–1.5 g, while a real campaign of strong tests could
#: exceed it, so a warning, not a refusal (cm/s² land above any recorded peak: refused).
MEDIAN_PEAK_WARN_G = 1.5


@dataclass(frozen=True)
class Campaign:
    """A shake-table campaign: tests, their table motions and observed outcomes.

    Attributes
    ----------
    folder : pathlib.Path
    tests : pandas.DataFrame
        ``test`` (str), ``ground_motion`` (str), ``motion_file`` (str), in file order.
    motions : tuple of GroundMotion
        Table acceleration of each test [m/s²], as stored.
    outcomes : dict
        Specimen name → float array per test (1 overturned, 0 stood, NaN unknown).
    peers : dict
        Specimen name → {peer column: float array per test (0/1, NaN where not given)}.
    """

    folder: Path
    tests: pd.DataFrame
    motions: tuple
    outcomes: dict
    peers: dict

    @property
    def specimens(self) -> tuple:
        return tuple(self.outcomes)


def _binary(frame: pd.DataFrame, column: str, where: str) -> np.ndarray:
    values = pd.to_numeric(frame[column], errors="coerce").to_numpy(dtype=float)
    bad = ~np.isnan(values) & ~np.isin(values, (0.0, 1.0))
    bad |= np.isnan(values) & frame[column].notna().to_numpy()
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise InputError(f"{where}: {column}: row {row + 2} holds {frame[column].iloc[row]!r}, "
                         f"expected 0, 1 or empty")
    return values


def _peer_specimen(column: str, specimens: tuple) -> str | None:
    rest = column[len(PEER_PREFIX):]
    for name in specimens:
        number = re.search(r"(\d+)$", name)
        aliases = (name, f"sp{number.group(1)}") if number else (name,)
        if any(rest.startswith(alias + "_") for alias in aliases):
            return name
    return None


def read_table_motion(path: Path, name: str) -> GroundMotion:
    """A table acceleration file (``time_s, acc_g``, constant step) as a GroundMotion [m/s²]."""
    try:
        frame = pd.read_csv(path)
    except FileNotFoundError:
        raise InputError(f"{path}: motion_file of test {name}: no such file") from None
    except (ValueError, OSError, EOFError, zlib.error, lzma.LZMAError,
            zipfile.BadZipFile) as exc:  # a corrupt compressed stream raises the codec's error
        raise InputError(f"{path}: motion_file of test {name}: unreadable ({exc})") from None
    missing = [c for c in ("time_s", "acc_g") if c not in frame.columns]
    if missing:
        raise InputError(f"{path}: column {missing[0]}: missing (needs time_s, acc_g)")
    time = pd.to_numeric(frame["time_s"], errors="coerce").to_numpy(dtype=float)
    acc = pd.to_numeric(frame["acc_g"], errors="coerce").to_numpy(dtype=float)
    for column, values in (("time_s", time), ("acc_g", acc)):
        if not np.all(np.isfinite(values)):
            row = int(np.flatnonzero(~np.isfinite(values))[0])
            raise InputError(f"{path}: {column}: row {row + 2} is not a number")
    if time.size < 2:
        raise InputError(f"{path}: acc_g: needs at least 2 samples, got {time.size}")
    steps = np.diff(time)
    dt = float(np.median(steps))
    if not (dt > 0 and np.all(np.abs(steps - dt) <= _DT_TOLERANCE * dt + 1e-9)):
        raise InputError(f"{path}: time_s: the time step is not constant")
    if not TABLE_DT_S[0] <= dt <= TABLE_DT_S[1]:
        raise InputError(f"{path}: time_s: a step of {dt:g} s is not a table motion's (expected "
                         f"{TABLE_DT_S[0]:g}–{TABLE_DT_S[1]:g} s); is the time in "
                         f"{'milliseconds' if dt > TABLE_DT_S[1] else 'another unit'}?")
    peak = float(np.max(np.abs(acc)))
    if peak > PLAUSIBLE_PGA_G:  # no recorded motion exceeds ~4.4 g; cm/s² land far above
        raise InputError(f"{path}: acc_g: a peak of {peak:.3g} g is beyond any recorded motion "
                         f"(at most ~4.4 g); is it in cm/s² ({peak / 100 / G:.2g} g) or m/s² "
                         f"({peak / G:.2g} g)? The column must hold g")
    return GroundMotion(name, acc * G, dt, component="shake-table acceleration",
                        source=str(path))


def read_campaign(folder) -> Campaign:
    """Read a campaign folder (see the module docstring); InputError naming file and field."""
    folder = Path(folder)
    where = folder / TESTS_CSV
    if not where.is_file():
        raise InputError(f"{where}: no such file (a campaign folder holds tests.csv)")
    try:
        frame = pd.read_csv(where, dtype=str, keep_default_na=False, na_values=[""])
    except (ValueError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}: unreadable CSV ({exc})") from None
    for column in REQUIRED_COLUMNS:
        if column not in frame.columns:
            raise InputError(f"{where}: column {column}: missing")
        if frame[column].isna().any():
            row = int(np.flatnonzero(frame[column].isna().to_numpy())[0])
            raise InputError(f"{where}: {column}: row {row + 2} is empty")
    if frame["test"].duplicated().any():
        raise InputError(f"{where}: test: {frame['test'][frame['test'].duplicated()].iloc[0]} "
                         f"appears twice")
    rotations = [c for c in frame.columns if c.endswith(PEAK_ROTATION_SUFFIX)]
    if rotations:
        raise InputError(f"{where}: {rotations[0]}: measured peak rotations are not supported "
                         f"yet; give SPECIMEN_overturned outcomes (see docs/validation.md)")
    specimens = tuple(c[:-len(OUTCOME_SUFFIX)] for c in frame.columns
                      if c.endswith(OUTCOME_SUFFIX) and not c.startswith(PEER_PREFIX))
    if not specimens:
        raise InputError(f"{where}: no SPECIMEN_overturned column")
    outcomes = {name: _binary(frame, name + OUTCOME_SUFFIX, str(where)) for name in specimens}
    peers = {name: {} for name in specimens}
    for column in (c for c in frame.columns if c.startswith(PEER_PREFIX)):
        owner = _peer_specimen(column, specimens)
        if owner is not None:
            peers[owner][column] = _binary(frame, column, str(where))
    motions = tuple(read_table_motion(folder / path, name)
                    for name, path in zip(frame["test"], frame["motion_file"]))
    median_g = float(np.median([m.pga_g for m in motions]))
    if median_g > MEDIAN_PEAK_WARN_G:
        warnings.warn(f"{where}: acc_g: the median peak of the table motions is {median_g:.3g} g; "
                      f"are they in m/s² ({median_g / G:.2g} g)? The column must hold g",
                      InputWarning, stacklevel=2)
    tests = frame[list(REQUIRED_COLUMNS)].reset_index(drop=True)
    return Campaign(folder, tests, motions, outcomes, peers)


GEOMETRY_CSV = "specimens.csv"
GEOMETRY_COLUMNS = ("specimen", "alpha_deg", "p_rad_s", "note")


def read_geometry(path) -> pd.DataFrame:
    """Geometric estimates of the specimens' blocks: ``specimen, alpha_deg, p_rad_s, note``
    (α [degrees] and p [rad/s] may be empty where the geometry does not say)."""
    path = Path(path)
    try:
        frame = pd.read_csv(path, dtype={"specimen": str, "note": str}, keep_default_na=False,
                            na_values={"alpha_deg": [""], "p_rad_s": [""]})
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (ValueError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: unreadable CSV ({exc})") from None
    for column in GEOMETRY_COLUMNS:
        if column not in frame.columns:
            raise InputError(f"{path}: column {column}: missing")
    for column in ("alpha_deg", "p_rad_s"):
        values = pd.to_numeric(frame[column], errors="coerce")
        if (values.isna() & frame[column].notna()).any() or (values <= 0).any():
            raise InputError(f"{path}: {column}: every value must be a positive number or empty")
        frame[column] = values.astype(float)
    return frame[list(GEOMETRY_COLUMNS)]


def campaign_geometry(campaign: Campaign, path=None) -> pd.DataFrame:
    """The geometric estimates of ``path``, else of the folder's ``specimens.csv``, else none."""
    if path is None and (campaign.folder / GEOMETRY_CSV).is_file():
        path = campaign.folder / GEOMETRY_CSV
    if path is None:
        return pd.DataFrame({c: pd.Series(dtype=float if c in ("alpha_deg", "p_rad_s") else str)
                             for c in GEOMETRY_COLUMNS})
    frame = read_geometry(path)
    unknown = sorted(set(frame["specimen"]) - set(campaign.specimens))
    if unknown:
        raise InputError(f"{path}: specimen: {unknown[0]} is not a specimen of the campaign "
                         f"({', '.join(campaign.specimens)})")
    return frame


__all__ = ["Campaign", "read_campaign", "read_table_motion", "read_geometry", "campaign_geometry",
           "TESTS_CSV", "GEOMETRY_CSV"]
