"""Earthquake records: catalogue, file readers, analytic pulses and manifests."""

from records.catalogue import SEED_CATALOGUE, RecordFacts, record_facts
from records.manifest import (ENV_VARIABLE, RecordEntry, RecordSuite, load_manifest, load_path,
                              load_records, pulse_suite, resolve_motion)
from records.motion import GroundMotion, Pulse
from records.pulses import one_pulse, pulse_acceleration
from records.readers import read_at2, read_columns

__all__ = ["SEED_CATALOGUE", "RecordFacts", "record_facts", "ENV_VARIABLE", "RecordEntry",
           "RecordSuite", "load_manifest", "load_path", "load_records", "pulse_suite",
           "resolve_motion", "GroundMotion", "Pulse", "one_pulse", "pulse_acceleration",
           "read_at2", "read_columns"]
