"""JointCommands: targets and speeds to speed effectors, and the gain against the server latency.

The simulator tests drive a robot through ``sim.session.Session`` with the very bytes an agent
sends, so the two-cycle action latency is the real one.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from behaviors.joint_control import CYCLE_SECONDS, DEFAULT_GAIN, JointCommands
from sim.session import Session, SessionConfig
from world.effectors import EffectorMessage, write_effectors
from world.nao_model import robot_spec
from world.perception import parse_perception

# --------------------------------------------------------------------------------------------
# Unit behaviour
# --------------------------------------------------------------------------------------------


def test_target_gives_proportional_speed_on_its_effector():
    commands = JointCommands()
    commands.set_targets({"hj1": 10.0})
    speeds = commands.effector_speeds({"hj1": 4.0})
    assert speeds["he1"] == pytest.approx(DEFAULT_GAIN * math.radians(6.0) / CYCLE_SECONDS)
    assert set(speeds) == set(robot_spec(0).effector_names)
    assert all(v == 0.0 for k, v in speeds.items() if k != "he1"), "uncommanded joints hold"


def test_speeds_are_clipped_to_the_joint_speed_limit():
    commands = JointCommands(robot_type=2)  # type 2 has its own ankle speed limits
    commands.set_targets({"hj1": 120.0, "rlj6": 45.0})
    commands.set_speeds({"rlj5": 100.0})
    speeds = commands.effector_speeds({"hj1": -120.0, "rlj6": -25.0})
    spec = robot_spec(2)
    assert speeds["he1"] == pytest.approx(spec.joint("hj1").max_speed)
    assert speeds["rle6"] == pytest.approx(spec.joint("rlj6").max_speed)
    assert speeds["rle5"] == pytest.approx(spec.joint("rlj5").max_speed)
    assert spec.joint("rlj5").max_speed != spec.joint("hj1").max_speed


def test_targets_are_clipped_to_the_joint_range():
    commands = JointCommands()
    commands.set_targets({"raj2": 30.0, "laj2": -30.0, "rlj4": -200.0})
    assert commands.targets() == {"raj2": 1.0, "laj2": -1.0, "rlj4": -130.0}


def test_last_of_target_or_speed_wins_and_clear_forgets_both():
    commands = JointCommands()
    commands.set_targets({"hj1": 30.0})
    commands.set_speeds({"hj1": -1.0})
    assert commands.targets() == {} and commands.speeds() == {"hj1": -1.0}
    commands.set_targets({"hj1": 30.0})
    assert commands.targets() == {"hj1": 30.0} and commands.speeds() == {}
    commands.clear()
    assert commands.effector_speeds({"hj1": 0.0})["he1"] == 0.0


def test_bad_commands_are_refused_with_the_joint_list():
    commands = JointCommands()
    with pytest.raises(KeyError, match="llj6"):
        commands.set_targets({"llj7": 0.0})  # toes exist on type 4 only
    with pytest.raises(ValueError, match="finite"):
        commands.set_targets({"hj1": math.nan})
    with pytest.raises(ValueError, match="finite"):
        commands.set_speeds({"hj1": math.inf})
    with pytest.raises(ValueError, match="gain"):
        commands.set_targets({"hj1": 0.0}, gain=1.5)
    assert "llj7" in JointCommands(robot_type=4).joint_names


def _latency_model(gain: float, delay: int, cycles: int = 80) -> np.ndarray:
    """A joint as the server moves it: the speed answering perception k acts in the cycle that
    ends at perception k + delay; speeds are clipped to the default limit. Target 60 degrees."""
    limit = math.degrees(robot_spec(0).joint("hj1").max_speed) * CYCLE_SECONDS
    angle = np.zeros(cycles + 1)
    step = np.zeros(cycles + 1)  # degrees moved per cycle, by the cycle's command index
    for k in range(cycles):
        command = k + 1 - delay
        angle[k + 1] = angle[k] + (step[command] if command >= 0 else 0.0)
        step[k + 1] = np.clip(gain * (60.0 - angle[k + 1]), -limit, limit)
    return angle


def test_default_gain_cannot_overshoot_with_a_two_cycle_latency():
    angle = _latency_model(DEFAULT_GAIN, delay=2)
    assert angle.max() <= 60.0 + 1e-9
    assert np.all(np.diff(angle) >= -1e-9), "monotone approach: no oscillation"
    assert angle[-1] == pytest.approx(60.0, abs=0.01)
    assert _latency_model(0.5, delay=2).max() > 61.0, "the old gain of 0.5 overshoots"
    assert _latency_model(DEFAULT_GAIN, delay=1).max() <= 60.0 + 1e-9
    assert _latency_model(DEFAULT_GAIN, delay=3)[-1] == pytest.approx(60.0, abs=0.01)


# --------------------------------------------------------------------------------------------
# In the simulator
# --------------------------------------------------------------------------------------------


@pytest.fixture
def standing():
    """A session with one robot beamed in and standing still, and its agent id."""
    session = Session(SessionConfig(seed=1, beam_noise=False, vision_noise=False))
    agent = session.join("Alpha", 1, beam=(-2.0, 0.0, 0.0), settle_cycles=40)
    yield session, agent
    session.close()


def _track(session, agent, targets, gain=DEFAULT_GAIN, cycles=50) -> dict[str, np.ndarray]:
    """Aim joints at ``targets`` every cycle, as an agent would; each joint's perceived angles."""
    commands = JointCommands()
    seen = {name: [] for name in targets}
    for _ in range(cycles):
        session.step()
        joints = parse_perception(session.perception(agent)).joints
        for name in targets:
            seen[name].append(joints[name])
        commands.clear()
        commands.set_targets(targets, gain)
        speeds = commands.effector_speeds(joints)
        session.handle_message(
            agent, write_effectors(EffectorMessage(joint_speeds=speeds, syn=True))
        )
    return {name: np.array(values) for name, values in seen.items()}


def _overshoot(angles: np.ndarray, target: float) -> float:
    direction = 1.0 if target > angles[0] else -1.0
    return max(0.0, float(np.max(direction * (angles - target))))


def _error_sign_changes(angles: np.ndarray, target: float, dead_band: float = 0.5) -> int:
    """How often the error changes sign, ignoring errors within ``dead_band`` degrees."""
    error = angles - target
    error = error[np.abs(error) > dead_band]
    return int(np.sum(np.sign(error[1:]) != np.sign(error[:-1])))


@pytest.mark.parametrize(
    "targets",
    [
        {"hj1": 60.0, "hj2": -30.0},
        {"hj1": 3.0},
        {"raj1": 45.0, "laj2": 40.0, "raj4": 60.0},
        {"raj2": -60.0, "laj3": -60.0, "laj4": -30.0},
        {"raj1": 90.0, "raj3": 80.0},
    ],
    ids=["head", "small", "arms-a", "arms-b", "arm-up"],
)
def test_unloaded_joints_reach_targets_without_overshoot(standing, targets):
    """Alone, a head or arm joint overshoots by < 0.1 degree; moving a shoulder and its elbow
    together couples them (the elbow overshoots about 0.9 degree)."""
    angles = _track(*standing, targets)
    for name, target in targets.items():
        assert _overshoot(angles[name], target) < 1.0, (name, angles[name])
        # at most the one crossing of a small overshoot; never back and forth
        assert _error_sign_changes(angles[name], target) <= 1, (name, angles[name])
        assert angles[name][-1] == pytest.approx(target, abs=0.2)


def test_gain_of_one_half_would_overshoot(standing):
    """The check above can fail: the previous default gain overshoots the same head step."""
    angles = _track(*standing, {"hj1": 60.0}, gain=0.5)
    assert _overshoot(angles["hj1"], 60.0) > 2.0


def test_squat_under_load_settles_on_target(standing):
    """Leg joints carry the body: it sways a little, the joints settle within a degree."""
    squat = {"rlj3": 30.0, "llj3": 30.0, "rlj4": -60.0, "llj4": -60.0, "rlj5": 30.0, "llj5": 30.0}
    angles = _track(*standing, squat, cycles=60)
    for name, target in squat.items():
        assert _overshoot(angles[name], target) < 3.0, (name, angles[name])
        assert np.all(np.abs(angles[name][-15:] - target) < 1.0), (name, angles[name])
