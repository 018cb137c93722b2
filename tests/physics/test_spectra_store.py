"""The record spectra kept between runs (audit.physics.spectra_store): the values read are the
values computed, bit for bit, and every input they depend on is another file."""

import numpy as np
import pytest

from audit.physics import spectra_store
from audit.physics.response_spectra import response_spectra
from procedures.base import SPECTRUM_PERIODS_S
from records import GroundMotion, RecordEntry
from procedures.context import RecordContext


@pytest.fixture
def store(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    return tmp_path / "rocking-audit" / "spectra"


def _motion(amplitude=1.0):
    time = np.arange(0.0, 3.0, 0.01)
    return GroundMotion("m", amplitude * np.sin(2 * np.pi * time / 0.7) * np.exp(-time), 0.01)


def _no_kernel(monkeypatch):
    monkeypatch.setattr(spectra_store, "response_spectra",
                        lambda *args, **kwargs: pytest.fail("computed again"))


def test_kept_spectra_are_the_computed_ones_bit_for_bit(store, monkeypatch):
    motion = _motion()
    direct = response_spectra(motion, SPECTRUM_PERIODS_S, [0.02], 1.5)
    first = spectra_store.stored_spectra(motion, SPECTRUM_PERIODS_S, 0.02, 1.5)
    assert len(list(store.rglob("*.npz"))) == 1
    _no_kernel(monkeypatch)
    kept = spectra_store.stored_spectra(motion, SPECTRUM_PERIODS_S, 0.02, 1.5)
    for name in ("sd", "sv", "sa"):
        np.testing.assert_array_equal(getattr(first, name), getattr(direct, name))
        np.testing.assert_array_equal(getattr(kept, name), getattr(direct, name))
    # the full spectra serve a request for Sd alone
    only_sd = spectra_store.stored_spectra(motion, SPECTRUM_PERIODS_S, 0.02, 1.5,
                                           displacement_only=True)
    np.testing.assert_array_equal(only_sd.sd, direct.sd)


@pytest.mark.parametrize("change", ["samples", "damping", "free motion", "periods"])
def test_another_input_is_another_file(store, change):
    motion, periods, damping, free = _motion(), SPECTRUM_PERIODS_S, 0.02, 1.5
    spectra_store.stored_spectra(motion, periods, damping, free)
    if change == "samples":
        motion = _motion(1.0 + 1e-12)
    elif change == "damping":
        damping = 0.05
    elif change == "free motion":
        free = 2.0
    else:
        periods = SPECTRUM_PERIODS_S[::2]
    other = spectra_store.stored_spectra(motion, periods, damping, free)
    direct = response_spectra(motion, periods, [damping], free)
    np.testing.assert_array_equal(other.sd, direct.sd)
    assert len(list(store.rglob("*.npz"))) == 2


def test_a_record_context_reads_them_from_the_store(store, monkeypatch):
    """A fresh process's context (a new RecordContext) reads a record's fixed-damping spectra
    from the store: what made one object's check ~2 s faster."""
    entry = RecordEntry("m", _motion())
    computed = RecordContext(entry, 1.5).true_spectra(0.02)
    _no_kernel(monkeypatch)
    read = RecordContext(entry, 1.5).true_spectra(0.02)
    np.testing.assert_array_equal(read.sv, computed.sv)
    # a corrupt file is computed again, not read
    (path,) = store.rglob("*.npz")
    path.write_bytes(b"not an npz")
    monkeypatch.undo()
    monkeypatch.setenv("XDG_CACHE_HOME", str(store.parent.parent))
    again = RecordContext(entry, 1.5).true_spectra(0.02)
    np.testing.assert_array_equal(again.sv, computed.sv)
