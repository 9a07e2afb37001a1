"""The kick's landing catch (``behaviors/kick_recovery.py``): its parameters, the foot's goal on
a tilted ground, the torso's move to the middle, and when it starts. No simulator: the
geometry is checked against forward kinematics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from behaviors.joint_control import JointCommands
from behaviors.kick import default_kicks, parse_kicks
from behaviors.kick_recovery import (
    CatchParams,
    LandingCatch,
    TorsoToMiddle,
    foot_on_ground,
    ground_frame,
    parse_catch,
)
from behaviors.poses import PoseError, get_pose
from world.kinematics import body_transforms
from world.nao_model import robot_spec

STAND = dict(get_pose("stand").joints)
#: the kick's weight shift onto the right leg (kick_left's first frame)
SHIFT = {
    **STAND,
    "rlj2": 13.6,
    "llj2": 13.6,
    "rlj6": -13.6,
    "llj6": -13.6,
    "rlj3": 15.0,
    "rlj4": -30.0,
    "rlj5": 17.0,
    "llj3": 15.0,
    "llj4": -30.0,
    "llj5": 17.0,
}


def _up_rolled_right(degrees: float) -> np.ndarray:
    """World up in the torso's native frame (x right) when the torso leans right."""
    r = math.radians(degrees)
    return np.array([-math.sin(r), 0.0, math.cos(r)])


@pytest.mark.parametrize(
    ("block", "message"),
    [
        ({"catch_s": 0.0}, "catch_s"),
        ({"width_m": 0.3}, "width_m"),
        ({"press_m": -0.01}, "press_m"),
        ({"early_s": -0.1}, "early_s"),
        ({"wdth_m": 0.2}, "unknown field"),
        ({"hold_s": "long"}, "expected a number"),
    ],
)
def test_bad_catch_blocks_name_the_problem(block, message):
    with pytest.raises(PoseError, match=message):
        parse_catch(block, "kicks.yaml: kick 'k'.catch")


def test_a_kick_file_carries_its_catch_and_the_window_runs_from_the_swing_end_to_the_stand():
    entry = {
        "frames": [{"duration": 0.5, "pose": "stand"}, {"duration": 0.2, "pose": "stand"}]
        + [{"duration": 0.3, "pose": "stand"}] * 2,
        "swing": {"frames": [1], "fast_s": 0.2, "slow_s": 0.4},
        "catch": {"width_m": 0.2},
    }
    motion = parse_kicks({"k": entry}, "test")["k"]
    assert motion.catch == CatchParams(width_m=0.2)
    assert motion.catch_window(1.0) == pytest.approx((0.7, 1.0))
    assert motion.catch_window(0.0) == pytest.approx((0.9, 1.2))  # the slower swing ends later


def test_the_packaged_catch_sits_on_the_kicks_after_the_approach_only():
    kicks = default_kicks()
    assert kicks["kick_left"].catch is None  # kicks from a stand keep their landing
    aligned = [m for name, m in kicks.items() if "_aligned" in name]
    assert len({m.catch for m in aligned}) == 1


def test_the_foot_goal_is_the_stand_on_level_ground_and_reaches_down_under_a_rolled_torso():
    level = foot_on_ground(0, STAND, np.array([0.0, 0.0, 1.0]), "left", 0.11, 0.0)
    assert level["llj2"] == pytest.approx(0.0, abs=0.1)
    assert level["llj6"] == pytest.approx(0.0, abs=0.1)
    assert level["llj4"] == pytest.approx(STAND["llj4"], abs=2.0)
    rolled = foot_on_ground(0, STAND, _up_rolled_right(10.0), "left", 0.11, 0.0)
    assert rolled["llj4"] > level["llj4"] + 10.0  # the knee straightens to reach the ground
    # the foot lands flat on the world's ground: its sole turned back against the roll
    feet = body_transforms(robot_spec(0), {**STAND, **rolled})
    frame, _ = ground_frame(0, STAND, _up_rolled_right(10.0), "right")
    assert feet["lfoot"][:3, 2] @ frame[:3, 2] == pytest.approx(1.0, abs=1e-6)
    assert (feet["lfoot"][:3, 3] - frame[:3, 3]) @ frame[:3, 2] == pytest.approx(
        robot_spec(0).body("lfoot").size[2] / 2, abs=1e-4
    )


def test_a_wider_landing_puts_the_foot_further_out_across_the_support_foot():
    frame, _ = ground_frame(0, SHIFT, np.array([0.0, 0.0, 1.0]), "right")
    for width in (0.11, 0.13):
        angles = foot_on_ground(0, SHIFT, np.array([0.0, 0.0, 1.0]), "left", width, 0.0)
        foot = body_transforms(robot_spec(0), {**SHIFT, **angles})["lfoot"]
        across = (foot[:3, 3] - frame[:3, 3]) @ frame[:3, 0]  # + = to the right
        assert across == pytest.approx(-width, abs=2e-3)


def test_the_torso_moves_from_over_the_support_foot_to_the_stand():
    move = TorsoToMiddle(0, SHIFT, np.array([0.0, 0.0, 1.0]), "right", 0.2)
    commands = JointCommands(0)
    first = None
    for _ in range(30):
        done = move.step(commands)
        first = first or commands.targets()
        if done:
            break
    assert done
    assert first["rlj2"] == pytest.approx(SHIFT["rlj2"], abs=2.0)  # it starts where it is
    for name, value in commands.targets().items():
        assert value == pytest.approx(STAND[name], abs=2.5), name


def test_the_catch_starts_on_roll_towards_either_side_mirrored_for_the_right_foot():
    params = CatchParams(support_roll_deg=5.0, kicking_roll_deg=4.0, rate_deg_s=60.0)
    left = LandingCatch(params, 0, mirror=False)  # the right leg supports; + roll = right
    assert not left.triggered(4.0, 0.0)
    assert left.triggered(5.5, 0.0)
    assert left.triggered(-4.5, 0.0)
    assert left.triggered(0.0, 70.0)
    right = LandingCatch(params, 0, mirror=True)
    assert right.triggered(-5.5, 0.0)
    assert not right.triggered(3.5, 0.0)
    assert right.triggered(4.5, 0.0)


def test_the_catch_lowers_the_kicking_foot_then_stands():
    params = CatchParams(catch_s=0.1, hold_s=0.1, stand_s=0.1, stand_hold_s=0.0, width_m=0.16)
    catch = LandingCatch(params, 0, mirror=False)
    lifted = {**SHIFT, "llj3": 60.0, "llj4": -40.0, "llj5": 0.0}
    catch.start(lifted, np.array([0.0, 0.0, 1.0]), 0.0, {})
    commands = JointCommands(0)
    for _ in range(5):
        commands.clear()
        assert not catch.step(commands, lifted, np.array([0.0, 0.0, 1.0]))
    goal = commands.targets()
    assert set(goal) == {f"llj{i}" for i in range(1, 7)}  # only the kicking leg so far
    assert goal["llj3"] < 30.0
    done = False
    for _ in range(40):
        commands.clear()
        done = catch.step(commands, SHIFT, np.array([0.0, 0.0, 1.0]), 30.0)
        if done:
            break
    assert done
    assert commands.targets()["rlj2"] == pytest.approx(STAND["rlj2"], abs=0.5)
