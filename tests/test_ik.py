"""Leg inverse kinematics against the forward kinematics, every robot type and both legs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from behaviors.ik import leg_ik, leg_ik_for, rotation_rpy
from world.kinematics import body_transforms
from world.nao_model import ROBOT_TYPES, robot_spec


def _random_leg_angles(spec, names, rng) -> dict[str, float]:
    """Angles inside every joint's range (knee bent at least 5 degrees: a straight knee is a
    singular pose whose ankle angles are not unique)."""
    angles = {}
    for name in names:
        joint = spec.joint(name)
        angles[name] = float(rng.uniform(joint.min_deg, joint.max_deg))
    knee = next(n for n in names if n.endswith("lj4"))
    angles[knee] = float(rng.uniform(-125.0, -5.0))
    return angles


def _rotation_error(a: np.ndarray, b: np.ndarray) -> float:
    """Angle (rad) of the rotation between two rotation matrices."""
    cos = (np.trace(a.T @ b) - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, cos)))


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
@pytest.mark.parametrize("side", ["left", "right"])
def test_fk_of_ik_meets_reachable_targets(robot_type, side):
    spec = robot_spec(robot_type)
    ik = leg_ik_for(robot_type)
    names = ik.joint_names(side)
    foot = f"{side[0]}foot"
    rng = np.random.default_rng(robot_type * 10 + (side == "left"))
    for _ in range(60):
        target = body_transforms(spec, _random_leg_angles(spec, names, rng))[foot]
        solution = leg_ik(robot_type, side, target)
        assert solution.exact
        reached = body_transforms(spec, solution.angles_deg)[foot]
        assert np.abs(reached[:3, 3] - target[:3, 3]).max() < 1e-4
        assert _rotation_error(reached[:3, :3], target[:3, :3]) < 1e-3


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_zero_pose_sole_gives_zero_angles(robot_type):
    ik = leg_ik_for(robot_type)
    for side in ("left", "right"):
        solution = ik.solve_sole(side, ik.sole_position_zero(side))
        assert solution.exact
        assert max(abs(a) for a in solution.angles_deg.values()) < 1e-6


def test_sole_target_matches_forward_kinematics_in_ego_axes():
    """A crouched, turned and tilted sole target: the foot body ends where the ego-frame
    target says (ego x forward = native y, ego y left = native -x)."""
    spec = robot_spec(0)
    ik = leg_ik_for(0)
    position = np.array([0.03, 0.07, -0.30])
    solution = ik.solve_sole("left", position, roll=0.05, pitch=-0.1, yaw=0.2)
    assert solution.exact
    foot = body_transforms(spec, solution.angles_deg)["lfoot"]
    joint, body = spec.joint("llj6"), spec.body("lfoot")
    sole_in_foot = np.array(
        [joint.anchor[0] - body.centre[0], joint.anchor[1] - body.centre[1], -body.size[2] / 2]
    )
    sole = foot[:3, :3] @ sole_in_foot + foot[:3, 3]
    assert sole == pytest.approx([-position[1], position[0], position[2]], abs=1e-6)
    to_native = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    expected = to_native @ rotation_rpy(0.05, -0.1, 0.2) @ to_native.T
    assert _rotation_error(foot[:3, :3], expected) < 1e-6


def test_unreachable_target_is_reported_and_clipped():
    ik = leg_ik_for(0)
    too_far = ik.solve_sole("right", (0.0, -0.055, -0.6))
    assert not too_far.reachable
    assert too_far.angles_deg["rlj4"] == pytest.approx(0.0, abs=1.0)  # knee straight
    twisted = ik.solve_sole("right", (0.0, -0.055, -0.3), yaw=-1.5)  # beyond lj1's range
    assert not twisted.within_limits
    spec = robot_spec(0)
    for name, value in twisted.angles_deg.items():
        joint = spec.joint(name)
        assert joint.min_deg <= value <= joint.max_deg


def test_legs_mirror_each_other():
    """The left leg's solution for a target mirrored across the sagittal plane is the right
    leg's with the roll-like joints negated (the 45-degree yaw-pitch joint keeps its sign)."""
    ik = leg_ik_for(1)
    right = ik.solve_sole("right", (0.02, -0.07, -0.32), roll=0.1, pitch=0.05, yaw=-0.2)
    left = ik.solve_sole("left", (0.02, 0.07, -0.32), roll=-0.1, pitch=0.05, yaw=0.2)
    assert left.exact and right.exact
    for joint, sign in zip(range(1, 7), (1, -1, 1, 1, 1, -1), strict=True):
        assert left.angles_deg[f"llj{joint}"] == pytest.approx(
            sign * right.angles_deg[f"rlj{joint}"], abs=1e-6
        )
