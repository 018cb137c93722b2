"""Makris & Roussos (2000) on real records: the pulse from Shahi & Baker's (2014) identification
of the FEMA P695 near-field pulse set (two components), and `audit pulse`."""

from __future__ import annotations

import csv
import gzip
import io
import math
from contextlib import redirect_stdout
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from audit import G
from audit.cli import main
from audit.physics.pulses.record_pulse import record_pulse
from procedures.makris_roussos_2000 import MakrisRoussos2000
from records import p695_suite

DATA = Path(__file__).resolve().parents[1] / "physics" / "data"


@pytest.fixture(scope="module")
def near_field_pulse():
    return {entry.id: entry for entry in p695_suite("p695-near-field-pulse")}


def test_rinaldi_is_judged_with_the_fitted_pulse_along_its_component(near_field_pulse):
    entry = near_field_pulse["rsn1063_rrs_032"]
    found = record_pulse(entry)
    # the filer's independent classification: pulse-like, along the fault-normal 032 component
    assert found.pulse_like and abs(found.direction_deg) < 10.0
    procedure = MakrisRoussos2000()
    assert procedure.unmet_requirements(entry) is None
    p = 2 * np.pi / np.array([1.0, 3.0])
    alpha = math.radians(12)
    check, = procedure.checks(entry, p, alpha, 0.9, None, G)
    # one-cosine published criterion a_p0 = αg (1 + ω_p/(4p)) at T_p = 1/f_p of the fit
    omega = 2 * np.pi * found.fit.frequency_hz
    np.testing.assert_allclose(check.capacity_m_s2, alpha * G * (1 + omega / p / 4), rtol=1e-12)
    np.testing.assert_allclose(check.demand_m_s2,
                               found.fit.peak_acceleration_m_s2 * abs(found.component_factor))
    assert f"T_p = {found.tp_s:.3g} s" in check.detail and "Shahi & Baker" in check.detail
    assert f"T_p = {found.fit.period_s:g} s" in check.detail


def test_a_scaled_record_keeps_its_pulse_and_a_floor_motion_is_not_judged(near_field_pulse):
    """The station's pulse is the pulse of the station's component scaled (its amplitude × the
    factor); a motion that is not that component scaled, as a floor's, is not judged by it
    (before, its "scale" was the floor motion over the record at one sample: a negative
    demand on a roof)."""
    entry = near_field_pulse["rsn1063_rrs_032"]
    as_read = record_pulse(entry)
    scaled = record_pulse(replace(entry, motion=entry.motion.scaled(2.5)))
    assert scaled.pulse_like and scaled.fit == as_read.fit
    np.testing.assert_allclose(scaled.amplitude_m_s2, 2.5 * as_read.amplitude_m_s2, rtol=1e-9)
    shaken = entry.motion.acceleration.copy()
    shaken[1:] = 0.5 * (shaken[1:] + shaken[:-1])  # a filtered motion: no longer proportional
    floor = replace(entry, motion=replace(entry.motion, acceleration=shaken))
    assert not record_pulse(floor).pulse_like
    reason = MakrisRoussos2000().unmet_requirements(floor)
    assert reason.startswith("no pulse identified: not classified: the motion audited is not")


def test_izmit_is_not_pulse_like_and_not_judged(near_field_pulse):
    """The filer's independent classification: Izmit is not pulse-like under either method."""
    reason = MakrisRoussos2000().unmet_requirements(near_field_pulse["rsn1165_izt_180"])
    assert reason.startswith("not pulse-like (PI -")


@pytest.mark.slow
def test_the_p695_pulse_set_is_pulse_like_but_izmit(near_field_pulse):
    """13 of the 14 stations pulse-like (both components see the station's classification)."""
    verdicts = {entry_id: record_pulse(entry).pulse_like
                for entry_id, entry in near_field_pulse.items()}
    assert {key for key, pulse_like in verdicts.items() if not pulse_like} == {
        "rsn1165_izt_180", "rsn1165_izt_270"}


def test_pulse_command_on_one_component_finds_the_matlab_pulse(tmp_path):
    """El Centro #4's 230 component alone: the authors' MATLAB found the pair's pulse at 89.4°
    from the 140 component, i.e. along this one: T_p 4.788 s, PI 20.06."""
    record = tmp_path / "el_centro_4_230.AT2"
    record.write_bytes(gzip.decompress((DATA / "el_centro_4_230.AT2.gz").read_bytes()))
    out = io.StringIO()
    with redirect_stdout(out):
        assert main(["pulse", "--records", str(record)]) == 0
    row, = csv.DictReader(io.StringIO(out.getvalue()))
    assert row["pulse_like"] == "True"
    assert float(row["tp_s"]) == pytest.approx(4.788, abs=1e-3)
    assert float(row["pulse_indicator"]) == pytest.approx(20.06, abs=0.5)
    assert float(row["mp_tp_s"]) == pytest.approx(4.788, rel=0.15)


def test_a_pair_of_unequal_lengths_is_not_classified():
    """Manjil, Abbar (P695 far-field): components of 2676 and 2300 samples; the MATLAB skips a
    pair that differs by more than 20."""
    entry = next(e for e in p695_suite("p695-far-field") if e.id == "rsn1633_abbar_l")
    reason = MakrisRoussos2000().unmet_requirements(entry)
    assert reason.startswith("no pulse identified: not classified") and "376 samples" in reason
