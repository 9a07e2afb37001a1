"""The stand-in against motions recorded on the real rcssserver3d (``sim.fidelity``).

Tolerances: the real server repeats itself to 0.0034 m of torso height and 0.9 deg of turn on
average (traces README). Quiet motions must stay within a few times that; the falls are chaotic
(a tiny difference decides where a limb lands), so they are held to their end state.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from sim.fidelity import Comparison, load_recording, replay

FOLDER = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"


def _compare(motion: str) -> Comparison:
    path = FOLDER / "fidelity" / f"{motion}.jsonl"
    if not path.exists():
        pytest.skip(f"real-server recordings missing: {path} (the shared/ folder beside the repo)")
    return replay(load_recording(path))


def test_stand_matches_height_and_foot_forces() -> None:
    c = _compare("stand_t0")
    assert c.height_error.max() < 0.01
    assert c.height_error.mean() < 0.003
    assert abs(c.sim_force.mean() - c.real_force.mean()) < 2.0  # 45.2 N on the real server
    assert c.sim_turn.max() < 3.0


@pytest.mark.parametrize("motion", ["crouch_t0", "crouch_t4"])
def test_crouch_follows_the_real_torso(motion: str) -> None:
    c = _compare(motion)
    assert c.height_error.mean() < 0.01
    assert c.height_error.max() < 0.02
    assert c.sim_height.min() == pytest.approx(c.real_height.min(), abs=0.01)
    assert c.sim_turn.max() < 5.0


def test_fall_ends_lying_like_the_real_robot() -> None:
    c = _compare("fall_t0")
    assert abs(c.sim_height[-1] - c.real_height[-1]) < 0.05
    assert abs(c.sim_turn[-1] - c.real_turn[-1]) < 20.0
    assert c.height_error.mean() < 0.02


@pytest.mark.xfail(
    strict=True,
    reason="known gap: on the real server the fast leg swing topples the robot; ours stays up "
    "since the solver runs 60 iterations (sim/physics.py; 30 before session 27, where it "
    "stayed up too). With 10 it fell, but then loaded "
    "joints sagged and held poses rocked, which made walking and getting up impossible.",
)
def test_swing_falls_too() -> None:
    c = _compare("swing_t0")
    assert c.sim_height[-1] < 0.25
    assert abs(c.sim_turn[-1] - c.real_turn[-1]) < 35.0
