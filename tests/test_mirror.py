"""Mirror inversion: the table derived from the joint axes, every mirror function, and a mirrored
motion in the simulator."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from behaviors.joint_control import JointCommands
from behaviors.mirror import (
    MIRROR_TABLE,
    ObservationLayout,
    Segment,
    mirror_accelerometer,
    mirror_action,
    mirror_direction_deg,
    mirror_effector_speeds,
    mirror_field_point,
    mirror_gyro,
    mirror_joint_angles,
    mirror_keyframes,
    mirror_observation,
    mirror_vector_native,
    twin_name,
)
from sim.session import Session, SessionConfig
from world.effectors import EffectorMessage, write_effectors
from world.nao_model import ROBOT_TYPES, RobotSpec, robot_spec
from world.perception import parse_perception

TYPE4 = robot_spec(4)  # every joint of every type (type 4 adds the toes)
ALL_JOINTS = TYPE4.perceptor_names
TYPE0_JOINTS = robot_spec(0).perceptor_names

finite = st.floats(-1e6, 1e6, allow_nan=False)


# --------------------------------------------------------------------------------------------
# The table
# --------------------------------------------------------------------------------------------


def test_table_pairs_every_joint_with_its_twin():
    assert set(MIRROR_TABLE) == set(ALL_JOINTS)
    for name, entry in MIRROR_TABLE.items():
        assert MIRROR_TABLE[entry.twin].twin == name
        assert MIRROR_TABLE[entry.twin].sign == entry.sign
        assert entry.twin == (name if name.startswith("h") else twin_name(name))
        assert entry.twin != name or name.startswith("h")


def test_pitch_joints_keep_their_sign_roll_and_yaw_flip():
    keeps = {name for name, entry in MIRROR_TABLE.items() if entry.sign == 1}
    pitch = {"hj2", "raj1", "laj1"} | {f"{s}lj{i}" for s in "rl" for i in (3, 4, 5, 7)}
    hip_yaw_pitch = {"rlj1", "llj1"}  # as derived from their axes: the sign is kept
    assert keeps == pitch | hip_yaw_pitch


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_mirrored_joint_limits_are_the_twins_limits(robot_type):
    spec = robot_spec(robot_type)
    for joint in spec.joints:
        entry = MIRROR_TABLE[joint.perceptor]
        twin = spec.joint(entry.twin)
        low, high = sorted((entry.sign * joint.min_deg, entry.sign * joint.max_deg))
        assert (low, high) == (twin.min_deg, twin.max_deg), joint.perceptor


def _rotation(axis, angle_deg: float) -> np.ndarray:
    """Rodrigues' formula: rotation by ``angle_deg`` about the unit vector along ``axis``."""
    k = np.asarray(axis, dtype=float)
    k = k / np.linalg.norm(k)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    q = math.radians(angle_deg)
    return np.eye(3) + math.sin(q) * cross + (1 - math.cos(q)) * cross @ cross


def _body_poses(spec: RobotSpec, angles: dict[str, float]) -> dict[str, np.ndarray]:
    """Forward kinematics: each body's 4x4 transform from its zero-pose place (torso fixed)."""
    poses = {"torso": np.eye(4)}
    for joint in spec.joints:  # parents come before children
        anchor = np.asarray(joint.anchor)
        hinge = np.eye(4)
        hinge[:3, :3] = _rotation(joint.axis, angles[joint.perceptor])
        hinge[:3, 3] = anchor - hinge[:3, :3] @ anchor
        poses[joint.child] = poses[joint.parent] @ hinge
    return poses


def _twin_body(name: str) -> str:
    return name if name in ("torso", "neck", "head") else {"r": "l", "l": "r"}[name[0]] + name[1:]


@pytest.mark.parametrize("robot_type", [0, 3, 4])
@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_mirrored_angles_give_the_reflected_robot(robot_type, data):
    """The table is right if mirrored angles put every twin body where the reflection of the
    original body is: ``pose(twin, mirrored) == M pose(body) M`` for rotation and position."""
    spec = robot_spec(robot_type)
    angles = {
        j.perceptor: data.draw(st.floats(j.min_deg, j.max_deg), label=j.perceptor)
        for j in spec.joints
    }
    reflection = np.diag([-1.0, 1.0, 1.0, 1.0])
    original = _body_poses(spec, angles)
    mirrored = _body_poses(spec, mirror_joint_angles(angles))
    for body, pose in original.items():
        expected = reflection @ pose @ reflection
        np.testing.assert_allclose(mirrored[_twin_body(body)], expected, atol=1e-9, err_msg=body)


def test_a_wrong_sign_would_be_caught_by_the_kinematics():
    """The kinematic check is not vacuous: keeping the sign of a roll joint breaks it."""
    angles = dict.fromkeys(TYPE0_JOINTS, 0.0) | {"raj2": -40.0}
    wrong = mirror_joint_angles(angles) | {"laj2": -40.0}
    left = _body_poses(robot_spec(0), wrong)["llowerarm"]
    reflection = np.diag([-1.0, 1.0, 1.0, 1.0])
    right = reflection @ _body_poses(robot_spec(0), angles)["rlowerarm"] @ reflection
    assert not np.allclose(left, right, atol=1e-3)


# --------------------------------------------------------------------------------------------
# The functions: known values, involutions, errors
# --------------------------------------------------------------------------------------------


def test_known_values():
    assert mirror_joint_angles({"raj2": -40.0, "hj1": 30.0, "rlj3": 20.0}) == {
        "laj2": 40.0,
        "hj1": -30.0,
        "llj3": 20.0,
    }
    assert mirror_effector_speeds({"rae2": 1.0, "lle1": -0.5, "he2": 0.25}) == {
        "lae2": -1.0,
        "rle1": -0.5,
        "he2": 0.25,
    }
    np.testing.assert_array_equal(mirror_gyro([1.0, 2.0, 3.0]), [1.0, -2.0, -3.0])
    np.testing.assert_array_equal(mirror_accelerometer([1.0, 2.0, 9.8]), [-1.0, 2.0, 9.8])
    np.testing.assert_array_equal(mirror_vector_native([0.3, 0.5]), [-0.3, 0.5])
    np.testing.assert_array_equal(mirror_field_point([4.0, 2.0, 0.04]), [4.0, -2.0, 0.04])
    assert mirror_direction_deg(30.0) == -30.0
    frames = mirror_keyframes([({"raj1": -90.0, "rlj2": 5.0}, 0.5), ({"hj1": 10.0}, 0.2)])
    assert frames == [({"laj1": -90.0, "llj2": -5.0}, 0.5), ({"hj1": -10.0}, 0.2)]


def test_observation_mirrors_segment_by_segment():
    layout = ObservationLayout(
        (
            Segment.joints(("raj2", "laj2", "hj1")),
            Segment.gyro(),
            Segment.accelerometer(),
            Segment.native(3),
            Segment.field(2),
            Segment.negate(1),
            Segment.scalar(2),
        )
    )
    assert layout.size == 3 + 3 + 3 + 3 + 2 + 1 + 2
    obs = np.arange(1.0, 18.0)
    expected = [-2, -1, -3, 4, -5, -6, -7, 8, 9, -10, 11, 12, 13, -14, -15, 16, 17]
    np.testing.assert_array_equal(mirror_observation(obs, layout), expected)
    batch = np.stack([obs, 2 * obs])
    np.testing.assert_array_equal(mirror_observation(batch, layout)[1], 2 * np.array(expected))


def test_action_in_joint_order_matches_the_dict_mirror():
    order = JointCommands().joint_names
    rng = np.random.default_rng(0)
    action = rng.uniform(-1, 1, size=len(order))
    by_name = mirror_joint_angles(dict(zip(order, action.tolist())))
    np.testing.assert_allclose(mirror_action(action, order), [by_name[n] for n in order])


@given(st.dictionaries(st.sampled_from(ALL_JOINTS), finite))
def test_joint_dicts_mirror_back(angles):
    assert mirror_joint_angles(mirror_joint_angles(angles)) == angles


@given(st.dictionaries(st.sampled_from(TYPE4.effector_names), finite))
def test_effector_speeds_mirror_back(speeds):
    assert mirror_effector_speeds(mirror_effector_speeds(speeds)) == speeds


@given(st.lists(st.tuples(st.dictionaries(st.sampled_from(ALL_JOINTS), finite), finite)))
def test_keyframes_mirror_back(frames):
    assert mirror_keyframes(mirror_keyframes(frames)) == [(dict(t), d) for t, d in frames]


@given(st.permutations(ALL_JOINTS), st.data())
def test_actions_mirror_back_in_any_joint_order(order, data):
    rows = data.draw(st.integers(1, 3))
    action = np.array(
        data.draw(st.lists(finite, min_size=len(order) * rows, max_size=len(order) * rows))
    )
    action = action.reshape(rows, len(order))
    np.testing.assert_array_equal(mirror_action(mirror_action(action, order), order), action)


@given(st.lists(finite, min_size=3, max_size=3), st.lists(finite, min_size=2, max_size=2), finite)
def test_vectors_and_directions_mirror_back(v3, v2, angle):
    for mirror in (mirror_vector_native, mirror_gyro, mirror_accelerometer, mirror_field_point):
        np.testing.assert_array_equal(mirror(mirror(v3)), v3)
    for mirror in (mirror_vector_native, mirror_field_point):
        np.testing.assert_array_equal(mirror(mirror(v2)), v2)
    assert mirror_direction_deg(mirror_direction_deg(angle)) == angle


_segments = st.one_of(
    st.just(Segment.gyro()),
    st.just(Segment.accelerometer()),
    st.sampled_from([2, 3]).map(Segment.native),
    st.sampled_from([2, 3]).map(Segment.field),
    st.integers(1, 4).map(Segment.negate),
    st.integers(1, 4).map(Segment.scalar),
    st.permutations(TYPE0_JOINTS).map(Segment.joints),
)


@given(st.lists(_segments, min_size=1, max_size=6), st.data())
def test_observations_mirror_back(segments, data):
    layout = ObservationLayout(tuple(segments))
    obs = np.array(data.draw(st.lists(finite, min_size=layout.size, max_size=layout.size)))
    np.testing.assert_array_equal(mirror_observation(mirror_observation(obs, layout), layout), obs)


def test_bad_inputs_are_refused_with_reasons():
    with pytest.raises(KeyError, match="raj1"):
        mirror_joint_angles({"rj1": 0.0})
    with pytest.raises(ValueError, match="twin laj1"):
        mirror_action([0.0, 0.0], ["raj1", "hj1"])
    with pytest.raises(ValueError, match="expected"):
        mirror_action([0.0, 0.0, 0.0], ["raj1", "laj1"])
    with pytest.raises(ValueError, match="twice"):
        mirror_action([0.0, 0.0], ["hj1", "hj1"])
    with pytest.raises(ValueError, match="twin"):
        ObservationLayout((Segment.joints(("rlj1",)),))
    with pytest.raises(ValueError, match="layout describes 3"):
        mirror_observation([1.0, 2.0], ObservationLayout((Segment.gyro(),)))
    with pytest.raises(ValueError, match="gyro"):
        Segment("gyro", 2)


# --------------------------------------------------------------------------------------------
# In the simulator: a mirrored motion gives the mirrored trajectory
# --------------------------------------------------------------------------------------------

#: Both hips rolled and the right arm raised sideways: the robot tips over sideways. A fall is
#: used because it is large and decisive; gentle sideways leans rock on the sole edges, where
#: the simulator's own small left-right asymmetry (about 1 degree of sway after a beam) is of
#: the same size as the effect.
TIP_OVER = [({"rlj2": -20.0, "llj2": -20.0, "raj2": -80.0, "hj1": 45.0}, 0.6)]


def _torso_track(frames, extra_cycles: int = 50) -> tuple[np.ndarray, np.ndarray]:
    """Play keyframes (targets held for their duration) on a standing robot facing +x at y=0;
    the torso's sideways offset (m) and roll (degrees) every cycle."""
    session = Session(SessionConfig(seed=1, beam_noise=False, vision_noise=False))
    try:
        agent = session.join("Alpha", 1, beam=(-2.0, 0.0, 0.0), settle_cycles=40)
        robot = session.agents[agent].robot
        start_y = robot.torso_position()[1]
        schedule = [targets for targets, seconds in frames for _ in range(round(seconds / 0.02))]
        schedule += [frames[-1][0]] * extra_cycles
        commands = JointCommands()
        ys, rolls = [], []
        for targets in schedule:
            session.step()
            joints = parse_perception(session.perception(agent)).joints
            commands.clear()
            commands.set_targets(targets)
            message = EffectorMessage(joint_speeds=commands.effector_speeds(joints), syn=True)
            session.handle_message(agent, write_effectors(message))
            rotation = robot.torso_world_transform()[:3, :3]
            ys.append(robot.torso_position()[1] - start_y)
            rolls.append(math.degrees(math.atan2(rotation[2, 0], rotation[2, 2])))
        return np.array(ys), np.array(rolls)
    finally:
        session.close()


def test_mirrored_keyframes_give_the_mirrored_motion():
    y, roll = _torso_track(TIP_OVER)
    y_m, roll_m = _torso_track(mirror_keyframes(TIP_OVER))
    assert abs(y[-1]) > 0.3 and abs(roll[-1]) > 45, "the motion must be large to mean anything"
    assert np.max(np.abs(y + y_m)) < 0.08
    assert y[-1] == pytest.approx(-y_m[-1], abs=0.02)
    assert roll[-1] == pytest.approx(-roll_m[-1], abs=3.0)


def test_swapping_sides_without_the_signs_does_not_mirror():
    """The counter-check: twin names with unchanged signs tip the robot the same way."""
    unsigned = [({MIRROR_TABLE[k].twin: v for k, v in t.items()}, d) for t, d in TIP_OVER]
    y, _ = _torso_track(TIP_OVER, extra_cycles=10)
    y_u, _ = _torso_track(unsigned, extra_cycles=10)
    assert np.sign(y[-1]) == np.sign(y_u[-1])
