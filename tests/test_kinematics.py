"""Forward kinematics against the simulator's own bodies, and the frame helpers."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from sim.physics import PhysicsWorld
from sim.robot import SimRobot
from sim.vision import _angles
from world.kinematics import (
    body_transforms,
    camera_transform,
    kinematic_model,
    level_rotation,
    polar_to_camera,
)
from world.nao_model import ROBOT_TYPES, robot_spec


@pytest.fixture(scope="module")
def world():
    w = PhysicsWorld()
    yield w
    w.close()


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_every_body_matches_the_simulator(world, robot_type):
    """Random joint angles within the limits, random placement: every body's transform
    relative to the torso agrees with Bullet's to 1e-6, from the angles the robot reports."""
    rng = np.random.default_rng(robot_type)
    robot = SimRobot(world, robot_type)
    spec = robot_spec(robot_type)
    try:
        for _ in range(8):
            angles = {j.perceptor: float(rng.uniform(j.min_deg, j.max_deg)) for j in spec.joints}
            yaw = float(rng.uniform(-180.0, 180.0))
            robot.place(*rng.uniform(-5.0, 5.0, size=2), 1.0, yaw_deg=yaw, joint_angles_deg=angles)
            truth = robot.body_world_transforms()
            to_torso = np.linalg.inv(truth["torso"])
            reported = robot.joint_angles_deg()
            ours = body_transforms(spec, reported)
            assert set(ours) == set(truth)
            for name, matrix in truth.items():
                np.testing.assert_allclose(ours[name], to_torso @ matrix, atol=1e-6, err_msg=name)
            camera = to_torso @ robot.camera_world_transform()
            np.testing.assert_allclose(camera_transform(spec, reported), camera, atol=1e-6)
    finally:
        robot.remove()


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_zero_pose_puts_bodies_at_their_spec_centres(robot_type):
    spec = robot_spec(robot_type)
    transforms = body_transforms(spec, {})
    for body in spec.bodies:
        np.testing.assert_allclose(transforms[body.name][:3, 3], body.centre, atol=1e-12)
        np.testing.assert_allclose(transforms[body.name][:3, :3], np.eye(3), atol=1e-12)


def test_head_turn_moves_the_camera_as_the_neck_says():
    """hj1 = 90 deg turns the head to the robot's left: its forward axis becomes -x."""
    spec = robot_spec(0)
    camera = camera_transform(spec, {"hj1": 90.0})
    np.testing.assert_allclose(camera[:3, 1], [-1.0, 0.0, 0.0], atol=1e-12)
    # the head centre stays above the neck joint: turning about z does not move it
    np.testing.assert_allclose(camera[:3, 3], spec.body("head").centre, atol=1e-12)
    tilted = camera_transform(spec, {"hj2": 30.0})
    assert tilted[2, 1] == pytest.approx(math.sin(math.radians(30.0)))  # looks up


def test_models_are_shared_per_type():
    assert kinematic_model(robot_spec(2)) is kinematic_model(robot_spec(2))


def test_polar_to_camera_inverts_the_servers_angles():
    rng = np.random.default_rng(1)
    points = rng.uniform(-10.0, 10.0, size=(200, 3))
    points[:, 1] = np.abs(points[:, 1]) + 0.2  # in front of the camera
    phi, theta = _angles(points)
    polars = np.column_stack([np.linalg.norm(points, axis=1), phi, theta])
    np.testing.assert_allclose(polar_to_camera(polars), points, atol=1e-9)


def _rotation(yaw_deg: float, roll_deg: float, pitch_deg: float) -> np.ndarray:
    """A torso orientation: tilted about its own x (pitch) and y (roll), then turned."""

    def about(axis: int, deg: float) -> np.ndarray:
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        i, j = [k for k in range(3) if k != axis]
        m = np.eye(3)
        m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
        return m

    return about(2, yaw_deg) @ about(1, roll_deg) @ about(0, pitch_deg)


@pytest.mark.parametrize(
    ("yaw", "roll", "pitch"), [(0, 0, 0), (30, 10, -5), (-100, -20, 25), (170, 3, 40)]
)
def test_level_rotation_keeps_the_heading_and_removes_the_tilt(yaw, roll, pitch):
    torso = _rotation(yaw, roll, pitch)  # torso axes in world coordinates
    up = torso.T @ np.array([0.0, 0.0, 1.0])  # what RobotState.up holds
    level = level_rotation(up)
    np.testing.assert_allclose(level @ level.T, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(level @ up, [0.0, 0.0, 1.0], atol=1e-12)
    # level -> world is a pure turn by the torso's heading (forward axis on the ground)
    to_world = torso @ level.T
    forward = torso[:, 1]
    heading = math.atan2(forward[1], forward[0]) - math.pi / 2  # native forward is +y
    c, s = math.cos(heading), math.sin(heading)
    np.testing.assert_allclose(to_world, [[c, -s, 0], [s, c, 0], [0, 0, 1]], atol=1e-12)


def test_level_rotation_when_lying_on_the_back():
    up = np.array([0.0, -1.0, 0.0])  # forward axis points at the sky
    level = level_rotation(up)
    np.testing.assert_allclose(level @ level.T, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(level @ up, [0.0, 0.0, 1.0], atol=1e-12)


def test_world_model_modules_do_not_import_pybullet_or_torch():
    code = (
        "import sys, world.kinematics, world.localization, world.ball_model, world.players, "
        "world.world_model; print(','.join(m for m in ('pybullet', 'torch') if m in sys.modules))"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == ""
