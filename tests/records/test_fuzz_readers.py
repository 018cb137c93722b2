"""Property-based tests: random mutations of the real record files and manifests.

Every mutation of a real ``.AT2`` file, column text file or TOML manifest must either read as
a valid :class:`~records.GroundMotion` (finite samples, at least two, a sampling step in the
accepted range) or raise :class:`~audit.errors.InputError` — never any other exception.
"""

import math
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from audit.errors import InputError, InputWarning
from records import GroundMotion, load_manifest, read_at2, read_columns
from records.readers import MAX_DT_S, MIN_DT_S

#: Examples per property; the four properties together run in well under a minute.
EXAMPLES = 200
FUZZ = settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

AT2_FILES = ("RSN77_SFERN_PUL164.AT2", "NGA_no_1063_RRS228.AT2", "Rinaldi228.AT2")
TEXT_FILES = ("rinaldi.txt", "erzikan.txt", "sylmar.txt")

# Pieces a hostile or careless edit puts into a file.
TOKENS = [b"nan", b"NaN", b"inf", b"-inf", b"1e400", b"1e-400", b"0", b"-0", b"", b" ", b"\n",
          b"\r\n", b"\t", b"\x00", b"\xff\xfe", b"NPTS=", b"DT=", b",", b".", b"--", b"E+",
          b"9" * 40, b"units: g", b"cm/s2", b"dt = 0", b"dt = 1e-12", b"npts = 3", b"%", b"#",
          b"[[record]]", b"[record]", b'"', b"=", b"true", b"[", b"]", "é".encode(), b"\xe9"]


def _mutations():
    """One edit: (kind, position fraction, length fraction, token)."""
    return st.tuples(st.sampled_from(["delete", "insert", "replace", "truncate", "duplicate",
                                      "flip"]),
                     st.floats(0.0, 1.0), st.floats(0.0, 0.2), st.sampled_from(TOKENS),
                     st.binary(min_size=1, max_size=8))


def _mutate(raw: bytes, edits) -> bytes:
    for kind, where, length, token, noise in edits:
        at = int(where * len(raw))
        span = int(length * len(raw))
        if kind == "delete":
            raw = raw[:at] + raw[at + span:]
        elif kind == "insert":
            raw = raw[:at] + token + raw[at:]
        elif kind == "replace":
            raw = raw[:at] + token + raw[at + max(1, span // 50):]
        elif kind == "truncate":
            raw = raw[:at]
        elif kind == "duplicate":
            raw = raw[:at] + raw[at:at + span] + raw[at:]
        else:
            raw = raw[:at] + noise + raw[at + len(noise):]
    return raw


def _valid(motion):
    assert isinstance(motion, GroundMotion)
    assert motion.acceleration.ndim == 1 and motion.acceleration.size >= 2
    assert np.all(np.isfinite(motion.acceleration))
    assert MIN_DT_S <= motion.dt <= MAX_DT_S and math.isfinite(motion.pga)


def _read_mutated(name: str, raw: bytes, read):
    """``read(path)`` of ``raw`` written as ``name``: a valid motion, or InputError."""
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore", InputWarning)
        path = Path(folder) / name
        path.write_bytes(raw)
        try:
            result = read(path)
        except InputError as exc:
            assert str(exc) and "\n" not in str(exc)
            return None
        return result


@pytest.fixture(scope="module")
def raw_dir(records_dir):
    return records_dir / "raw"


@FUZZ
@given(data=st.data())
def test_mutated_at2_reads_or_raises_input_error(raw_dir, data):
    name = data.draw(st.sampled_from(AT2_FILES))
    edits = data.draw(st.lists(_mutations(), min_size=1, max_size=4))
    motion = _read_mutated(name, _mutate((raw_dir / name).read_bytes(), edits), read_at2)
    if motion is not None:
        _valid(motion)


@pytest.mark.slow  # ~20 s of mutated files
@FUZZ
@given(data=st.data())
def test_mutated_text_reads_or_raises_input_error(raw_dir, data):
    name = data.draw(st.sampled_from(TEXT_FILES))
    edits = data.draw(st.lists(_mutations(), min_size=1, max_size=4))
    column = data.draw(st.sampled_from([1, 2, 3]))
    declared = data.draw(st.booleans())

    def read(path):
        if declared:
            return read_columns(path, column, 0.005, "cm/s2")
        return read_columns(path, column)

    motion = _read_mutated(name, _mutate((raw_dir / name).read_bytes(), edits), read)
    if motion is not None:
        _valid(motion)


def _absolute_manifest(path: Path) -> bytes:
    """The manifest with its record paths made absolute, so a copy elsewhere still finds them."""
    return path.read_text().replace('file = "', f'file = "{path.parent}/').encode()


@pytest.mark.slow  # ~30 s of mutated manifests
@FUZZ
@given(data=st.data())
def test_mutated_manifest_loads_or_raises_input_error(seed_manifest, data):
    name = data.draw(st.sampled_from(["seed-suite.toml", "extras.toml"]))
    raw = _absolute_manifest(seed_manifest.parent / name)
    edits = data.draw(st.lists(_mutations(), min_size=1, max_size=3))
    skip_bad = data.draw(st.booleans())
    suite = _read_mutated(name, _mutate(raw, edits), lambda p: load_manifest(p, skip_bad))
    if suite is not None:
        assert len(suite) >= 1
        for entry in suite:
            if entry.motion is not None:
                _valid(entry.motion)
        for bad in suite.rejected:
            assert set(bad) == {"record", "file", "reason"} and bad["reason"]


VALUES = st.one_of(st.integers(-3, 10 ** 6), st.floats(allow_nan=True, allow_infinity=True),
                   st.text(max_size=6), st.booleans(), st.lists(st.integers(), max_size=2))


@FUZZ
@given(data=st.data())
def test_manifest_fields_of_any_toml_type(seed_manifest, data):
    """Each field of a real record replaced by a value of any type or range."""
    field = data.draw(st.sampled_from(["id", "file", "format", "column", "dt", "units",
                                       "component", "missing", "site_class", "sxs_g", "sx1_g"]))
    value = data.draw(VALUES)
    if isinstance(value, float) and not math.isfinite(value):
        toml_value = "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    elif isinstance(value, bool):
        toml_value = "true" if value else "false"
    elif isinstance(value, str):
        toml_value = '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    else:
        toml_value = repr(value)
    text = (f'[[record]]\nid = "rec"\nfile = "{seed_manifest.parent}/raw/rinaldi.txt"\n'
            f'format = "columns"\ncolumn = 1\ndt = 0.005\nunits = "cm/s2"\n')
    lines = [line for line in text.splitlines() if not line.startswith(f"{field} =")]
    raw = ("\n".join(lines) + f"\n{field} = {toml_value}\n").encode("utf-8", "surrogatepass")
    suite = _read_mutated("m.toml", raw, load_manifest)
    if suite is not None:
        for entry in suite:
            if entry.motion is not None:
                _valid(entry.motion)
