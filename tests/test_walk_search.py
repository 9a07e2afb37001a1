"""The walk-speed search's bookkeeping (its runs are the locomotion benchmark's own)."""

from __future__ import annotations

import pytest

from behaviors.walk import WALK_FILE, walk_parameters
from benchmarks.dribble import with_settings
from learning.param_search import overrides
from learning.walk_search import KNOBS, SCENARIOS, score_runs, start_values, typed_knobs


@pytest.mark.parametrize("robot_type", [0, 1, 2, 3, 4])
def test_the_search_starts_from_the_packaged_walk_and_writes_it_back_unchanged(
    robot_type, tmp_path
):
    start = start_values(robot_type)
    for knob, value in zip(KNOBS, start, strict=True):
        assert knob.low <= value <= knob.high
    changes = overrides(typed_knobs(robot_type), start)
    assert changes[0].startswith(f"type{robot_type}.step.max_forward=")
    path = with_settings(changes, tmp_path, WALK_FILE)
    assert walk_parameters(robot_type, path) == walk_parameters(robot_type)


def test_a_fall_costs_the_penalty_and_its_speed():
    names = [s.name for s in SCENARIOS]
    speeds = [0.8 if n == "straight" else 0.6 if n == "curve" else 0.0 for n in names]
    upright = score_runs(speeds, fall_penalty=0.6)
    assert upright.falls == 0
    assert upright.score == pytest.approx(0.8 + 0.5 * 0.6)
    speeds[names.index("straight")] = -1.0
    fallen = score_runs(speeds, fall_penalty=0.6)
    assert fallen.falls == 1
    assert fallen.straight_mps == pytest.approx(0.4)
    assert fallen.score == pytest.approx(0.4 + 0.3 - 0.6)
