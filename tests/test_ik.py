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


@pytest.mark.parametrize("robot_type", [1, 3])
def test_unreachable_target_is_reported_with_the_hip_pitch_offset(robot_type):
    """Types 1 and 3 (hip-pitch anchor below the hip): a sole beyond the stretched leg is
    reported unreachable, and the knee is straight."""
    ik = leg_ik_for(robot_type)
    below = ik.sole_position_zero("left") - np.array([0.0, 0.0, 0.05])
    solution = ik.solve_sole("left", below)
    assert not solution.reachable
    assert solution.angles_deg["llj4"] == pytest.approx(0.0, abs=1.0)


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


#: Solutions of the first implementation (numpy, Newton steps on types 1 and 3), kept as the
#: reference the plain-float closed form must reproduce: (robot type, side, sole position (ego),
#: (roll, pitch, yaw), lj1..lj6 degrees). The second target of each leg is beyond lj1's range,
#: so it also pins the clipping.
# fmt: off
REFERENCE_SOLUTIONS = [
    (0, "left", (0.03, 0.07, -0.3), (0.05, -0.1, 0.2),
     (-15.7635755929, 2.9231110357, 46.2032630437, -98.9320250768, 47.3803844718, 1.0646214073)),
    (0, "left", (-0.04, 0.05, -0.28), (0.0, 0.08, -0.3),
     (1.0000000000, -3.7406864670, 53.7731622428, -113.3941143857, 72.9278574263, 6.3989137573)),
    (0, "right", (0.03, -0.07, -0.3), (-0.05, -0.1, -0.2),
     (-15.7635755929, -2.9231110357, 46.2032630437, -98.9320250768, 47.3803844718, -1.0646214073)),
    (0, "right", (-0.04, -0.05, -0.28), (0.0, 0.08, 0.3),
     (1.0000000000, 3.7406864670, 53.7731622428, -113.3941143857, 72.9278574263, -6.3989137573)),
    (1, "left", (0.03, 0.07, -0.3), (0.05, -0.1, 0.2),
     (-15.7635755929, 2.9231110357, 61.0149167074, -115.9909788970, 49.6276846283, 1.0646214073)),
    (1, "left", (-0.04, 0.05, -0.28), (0.0, 0.08, -0.3),
     (1.0000000000, -3.7406864670, 69.6261627867, -127.9986673132, 71.6794098099, 6.3989137573)),
    (1, "right", (0.03, -0.07, -0.3), (-0.05, -0.1, -0.2),
     (-15.7635755929, -2.9231110357, 61.0149167074, -115.9909788970, 49.6276846283, -1.0646214073)),
    (1, "right", (-0.04, -0.05, -0.28), (0.0, 0.08, 0.3),
     (1.0000000000, 3.7406864670, 69.6261627867, -127.9986673132, 71.6794098099, -6.3989137573)),
    (2, "left", (0.03, 0.07, -0.3), (0.05, -0.1, 0.2),
     (-15.7635755929, 2.9231110357, 46.2032630437, -98.9320250768, 47.3803844718, 1.0646214073)),
    (2, "left", (-0.04, 0.05, -0.28), (0.0, 0.08, -0.3),
     (1.0000000000, -3.7406864670, 53.7731622428, -113.3941143857, 72.9278574263, 6.3989137573)),
    (2, "right", (0.03, -0.07, -0.3), (-0.05, -0.1, -0.2),
     (-15.7635755929, -2.9231110357, 46.2032630437, -98.9320250768, 47.3803844718, -1.0646214073)),
    (2, "right", (-0.04, -0.05, -0.28), (0.0, 0.08, 0.3),
     (1.0000000000, 3.7406864670, 53.7731622428, -113.3941143857, 72.9278574263, -6.3989137573)),
    (3, "left", (0.03, 0.07, -0.3), (0.05, -0.1, 0.2),
     (-16.7615794765, -4.0735401974, 66.9760987885, -123.9361218279, 50.8975616652, 8.0958820777)),
    (3, "left", (-0.04, 0.05, -0.28), (0.0, 0.08, -0.3),
     (1.0000000000, -11.3445258041, 85.3028933214, -130.0000000000, 64.1555723538, 14.2537469345)),
    (3, "right", (0.03, -0.07, -0.3), (-0.05, -0.1, -0.2),
     (-16.7615794765, 4.0735401974, 66.9760987885, -123.9361218279, 50.8975616652, -8.0958820777)),
    (3, "right", (-0.04, -0.05, -0.28), (0.0, 0.08, 0.3),
     (1.0000000000, 11.3445258041, 85.3028933214, -130.0000000000, 64.1555723538, -14.2537469345)),
    (4, "left", (0.03, 0.07, -0.3), (0.05, -0.1, 0.2),
     (-15.7635755929, 2.9231110357, 52.0770012133, -96.1466916816, 38.7213129070, 1.0646214073)),
    (4, "left", (-0.04, 0.05, -0.28), (0.0, 0.08, -0.3),
     (1.0000000000, -3.7406864670, 62.5690284467, -113.8683239596, 64.6062007963, 6.3989137573)),
    (4, "right", (0.03, -0.07, -0.3), (-0.05, -0.1, -0.2),
     (-15.7635755929, -2.9231110357, 52.0770012133, -96.1466916816, 38.7213129070, -1.0646214073)),
    (4, "right", (-0.04, -0.05, -0.28), (0.0, 0.08, 0.3),
     (1.0000000000, 3.7406864670, 62.5690284467, -113.8683239596, 64.6062007963, -6.3989137573)),
]
# fmt: on


@pytest.mark.parametrize(("robot_type", "side", "position", "rpy", "expected"), REFERENCE_SOLUTIONS)
def test_solutions_match_the_reference_implementation(robot_type, side, position, rpy, expected):
    """Types 0, 2, 4 to 1e-9 degrees; types 1 and 3, where the reference stopped its Newton
    steps at 1e-6 m, to what that tolerance allows."""
    solution = leg_ik_for(robot_type).solve_sole(side, position, *rpy)
    tolerance = 1e-9 if robot_type in (0, 2, 4) else 1e-3
    assert list(solution.angles_deg.values()) == pytest.approx(expected, abs=tolerance)


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_closed_form_is_exact_to_a_nanometre(robot_type):
    """FK(IK) meets the target to 1e-9 m (and its rotation to 1e-9), also on types 1 and 3
    whose hip-pitch anchor lies below the other two hip axes."""
    spec = robot_spec(robot_type)
    ik = leg_ik_for(robot_type)
    rng = np.random.default_rng(7 + robot_type)
    for side in ("left", "right"):
        names = ik.joint_names(side)
        foot = f"{side[0]}foot"
        for _ in range(20):
            target = body_transforms(spec, _random_leg_angles(spec, names, rng))[foot]
            solution = ik.solve(side, target)
            reached = body_transforms(spec, solution.angles_deg)[foot]
            assert np.abs(reached[:3, 3] - target[:3, 3]).max() < 1e-9
            assert np.abs(reached[:3, :3] - target[:3, :3]).max() < 1e-9


def test_rotation_rpy_is_the_product_of_elementary_rotations():
    roll, pitch, yaw = 0.3, -0.7, 1.9
    c, s = math.cos, math.sin
    rx = np.array([[1, 0, 0], [0, c(roll), -s(roll)], [0, s(roll), c(roll)]])
    ry = np.array([[c(pitch), 0, s(pitch)], [0, 1, 0], [-s(pitch), 0, c(pitch)]])
    rz = np.array([[c(yaw), -s(yaw), 0], [s(yaw), c(yaw), 0], [0, 0, 1]])
    assert np.abs(rotation_rpy(roll, pitch, yaw) - rz @ ry @ rx).max() < 1e-15
