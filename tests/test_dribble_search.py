"""The dribble-speed search's bookkeeping (its runs are the dribble benchmark's own)."""

from __future__ import annotations

import pytest

from behaviors.dribble import dribble_gait, dribble_walk_parameters
from benchmarks.dribble import with_settings
from learning.dribble_search import score_runs, start_values, typed_knobs
from learning.param_search import overrides


@pytest.mark.parametrize("kind", ["lfdl", "dfdl"])
def test_the_search_starts_from_the_packaged_gait_and_writes_it_back_unchanged(kind, tmp_path):
    knobs = typed_knobs(kind, 3)
    start = start_values(kind, 3)
    for knob, value in zip(knobs, start, strict=True):
        assert knob.low <= value <= knob.high
        assert knob.key.startswith(f"{kind}.walk.type3.") or knob.key.startswith(
            f"{kind}.controller.type3."
        )
    path = with_settings(overrides(knobs, start), tmp_path)
    assert dribble_walk_parameters(kind, 3, path) == dribble_walk_parameters(kind, 3)
    assert dribble_gait(kind, 3, path) == dribble_gait(kind, 3)


def test_losses_and_falls_cost_their_penalties_per_run():
    clean = score_runs([(0.6, 0, False), (0.8, 0, False)], loss_penalty=0.3, fall_penalty=0.6)
    assert clean.score == pytest.approx(0.7) and (clean.losses, clean.falls) == (0, 0)
    rough = score_runs([(0.6, 2, False), (0.2, 0, True)], loss_penalty=0.3, fall_penalty=0.6)
    assert (rough.losses, rough.falls) == (2, 1)
    assert rough.speed == pytest.approx(0.3)  # the fallen run's ball speed does not count
    assert rough.score == pytest.approx(0.3 - (0.6 + 0.6) / 2)
