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


def test_a_fall_costs_the_penalty_and_its_figure():
    figures = {"forward": 0.8, "side": 0.3, "turn": 70.0, "stop": 0.0, "mixed": 0.0}
    upright = [(figures[s.figure], False) for s in SCENARIOS]
    scored = score_runs(upright, fall_penalty=0.6)
    assert scored.falls == 0
    weights = {s.name: s.weight for s in SCENARIOS}
    expected = 0.8 + weights["curve"] * 0.8 + weights["side"] * 0.3 + weights["turn"] * 70.0
    assert scored.score == pytest.approx(expected)
    assert scored.figures["straight"] == pytest.approx(0.8)
    names = [s.name for s in SCENARIOS]
    fallen = list(upright)
    fallen[names.index("straight")] = (0.9, True)  # the distance before a fall does not count
    fallen[names.index("stop")] = (0.0, True)
    scored = score_runs(fallen, fall_penalty=0.6)
    assert scored.falls == 2
    assert scored.figures["straight"] == pytest.approx(0.4)
    assert scored.score == pytest.approx(expected - 0.4 - 2 * 0.6)


def test_mixed_runs_draw_reproducible_commands_within_the_environments_ranges():
    from learning.walk_search import MIXED_EVERY_S, MIXED_S, mixed_commands

    commands = mixed_commands(6)
    assert commands == mixed_commands(6) != mixed_commands(7)
    assert len(commands) == round(MIXED_S / MIXED_EVERY_S)
    for forward, side, turn in commands:
        assert 0.0 <= forward <= 1.0 and abs(side) <= 0.2 and abs(turn) <= 45.0
