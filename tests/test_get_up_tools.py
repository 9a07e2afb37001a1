"""The get-up screens' variant syntax: module constants (``knob:``) set per variant, with
per-robot-type mappings, so decision thresholds are screened on the benchmark's own falls."""

from __future__ import annotations

import pytest

pytest.importorskip("pybullet")

from scripts.get_up.screen_sequences import apply_variant, variant_knobs
from scripts.get_up.sweep_knobs import parse_variant


def test_knob_values_parse_as_numbers_none_and_per_type_mappings():
    assert parse_variant("base") == {}
    assert parse_variant("SETTLED_CYCLES=2,EARLY_STAND_DEG=None") == {
        "SETTLED_CYCLES": 2.0,
        "EARLY_STAND_DEG": None,
    }
    assert parse_variant("RETRY_NEVER_UP_TILT_DEG=0:30/3:None") == {
        "RETRY_NEVER_UP_TILT_DEG": {0: 30.0, 3: None}
    }
    with pytest.raises(SystemExit, match="no constant"):
        parse_variant("NO_SUCH_KNOB=1")


def test_a_screen_variant_mixes_knobs_and_sequence_edits():
    variant = "knob:ABORT_BACK_DEG=35;get_up_back:5:duration=0.4;knob:SETTLED_CYCLES=2"
    assert variant_knobs(variant) == {"ABORT_BACK_DEG": 35.0, "SETTLED_CYCLES": 2.0}
    entries = {"get_up_back": {"frames": [{"duration": 0.1}] * 5 + [{"duration": 0.5}]}}
    edited = apply_variant(entries, variant)
    assert edited["get_up_back"]["frames"][5]["duration"] == 0.4
    assert entries["get_up_back"]["frames"][5]["duration"] == 0.5
    assert variant_knobs("base") == {}
