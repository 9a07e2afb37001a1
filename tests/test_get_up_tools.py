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


def test_a_saved_trial_list_reads_back_grouped_by_its_benchmark_seed(tmp_path):
    from scripts.get_up.screen_sequences import benchmark_seed, read_trials

    path = tmp_path / "front.txt"
    path.write_text("3:front:3012\n0:back:512\n4:front:14015\n")
    trials = read_trials(path)
    assert trials == [(3, "front", 3012), (0, "back", 512), (4, "front", 14015)]
    # trial k of type T at benchmark seed S has seed S + 1000 T + k
    assert [benchmark_seed(t) for t in trials] == [0, 500, 10000]


def test_the_benchmark_summary_counts_first_attempts_apart_from_late_retries():
    from benchmarks.get_up import TrialResult, summary

    results = [
        TrialResult(0, "back", 0, "back", True, 2.1, attempts=1),
        TrialResult(0, "front", 1, "front", True, 3.9, attempts=2),
        TrialResult(0, "left", 2, "back", False, None, attempts=3),
        TrialResult(0, "right", 3, "back", True, 2.4, attempts=1),
    ]
    lines = summary(results, [0], show_failures=True).splitlines()
    assert "get_up_success_rate: 0.750" in lines
    assert "get_up_first_attempt_rate: 0.500" in lines
    assert "get_up_first_attempt_rate[type=0]: 0.500" in lines
    assert "failed: type 0 left seed 2 lying back" in lines


def test_an_es_candidate_becomes_a_screen_variant_and_a_balance():
    import numpy as np

    from scripts.get_up.es_search import (
        BALANCE_DIMENSIONS,
        Dimension,
        candidate_balance,
        candidate_variant,
    )

    dims = [
        Dimension(3, "llj3", 65.8, 2.0, -90.0, 100.0),
        Dimension(3, "duration", 0.38, 0.015, 0.1, 0.8),
        Dimension(4, "laj1", -90.0, 2.0, -120.0, 120.0),
        *BALANCE_DIMENSIONS,
    ]
    values = np.array([70.0, 0.3, -80.0, -5.0, 2.0, 0.0])
    variant = candidate_variant("get_up_back_type3", dims, values)
    assert variant == ("get_up_back_type3:3:lj3=70.00,duration=0.30;get_up_back_type3:4:aj1=-80.00")
    assert variant_knobs(variant) == {}
    balance = candidate_balance(dims, values, from_frame=3)
    assert balance is not None and balance.from_frame == 3
    assert balance.offsets(-10.0) == {"llj3": 10.0, "rlj3": 10.0, "llj5": 0.0, "rlj5": 0.0}
    assert candidate_balance(dims, np.array([70.0, 0.3, -80.0, -5.0, 0.0, 0.0]), 3) is None
