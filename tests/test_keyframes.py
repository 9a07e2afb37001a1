"""Poses and keyframe sequences: packaged files, validation messages, playback, the skills."""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from types import SimpleNamespace

import pytest

from behaviors.joint_control import CYCLE_SECONDS, JointCommands
from behaviors.keyframes import (
    KeyframePlayer,
    KeyframeSequence,
    default_sequences,
    ease,
    get_sequence,
    load_sequences,
    mirrored,
    parse_sequences,
)
from behaviors.poses import PoseError, default_poses, load_poses, parse_poses, pose_reached
from world.nao_model import robot_spec


def test_packaged_poses_and_sequences_load_and_cover_every_joint():
    poses = default_poses()
    assert {"stand", "zero", "squat"} <= set(poses)
    every_joint = set(robot_spec(4).perceptor_names)
    assert set(poses["stand"].joints) == every_joint
    assert set(poses["zero"].joints) == every_joint and not any(poses["zero"].joints.values())
    assert {"get_up_front", "get_up_back", "roll_left_to_back"} <= set(default_sequences())


def test_stand_keeps_the_feet_flat():
    stand = default_poses()["stand"].joints
    for side in "rl":
        # the foot's pitch relative to the torso is the sum of hip, knee and ankle pitch: a
        # small positive sum leans the torso forward over flat feet
        pitch = stand[f"{side}lj3"] + stand[f"{side}lj4"] + stand[f"{side}lj5"]
        assert 0 <= pitch <= 10


@pytest.mark.parametrize(
    ("entry", "message"),
    [
        ({"joints": {"rlj9": 0}}, "p.yaml: pose 'bad' joints.rlj9: unknown joint; valid joints: "),
        ({"joints": {"rlj4": 20}}, "joints.rlj4: 20 deg is outside the joint range [-130, 1]"),
        ({"joints": {"hj1": "x"}}, "pose 'bad' joints.hj1: expected a number"),
        ({"description": "no joints"}, "p.yaml: pose 'bad': missing field(s) joints"),
        ({"joints": {}, "colour": 1}, "unknown field(s) colour; valid fields: description, joints"),
    ],
)  # fmt: skip
def test_pose_errors_name_the_file_and_key(entry, message):
    with pytest.raises(PoseError) as info:
        parse_poses({"bad": entry}, "p.yaml")
    assert message in str(info.value)


@pytest.mark.parametrize(
    ("frame", "message"),
    [
        ({"joints": {"hj1": 0}}, "s.yaml: sequence 'm'.frames[0]: missing field(s) duration"),
        ({"duration": 1}, "frames[0]: a frame needs 'pose' or 'joints'"),
        ({"duration": 1, "pose": "sit"}, "frames[0].pose: unknown pose 'sit'; poses: zero"),
        ({"duration": 1, "joints": {"hj2": 50}}, "joints.hj2: 50 deg is outside the joint range"),
        ({"duration": -1, "joints": {"hj1": 0}}, "duration and hold must be >= 0 s"),
        ({"duration": 1, "joints": {}, "interpolation": "cubic"}, "is not one of linear, smooth"),
        ({"duration": 1, "joints": {"hj1": 0}, "gain": 2}, "frames[0].gain: must be in (0, 1]"),
    ],
)  # fmt: skip
def test_keyframe_errors_name_the_file_and_key(frame, message):
    poses = default_poses()
    with pytest.raises(PoseError) as info:
        parse_sequences({"m": {"frames": [frame]}}, "s.yaml", poses)
    assert message in str(info.value)


def test_empty_frame_list_and_duplicate_names_are_refused(tmp_path: Path):
    with pytest.raises(PoseError, match="non-empty list"):
        parse_sequences({"m": {"frames": []}}, "s.yaml")
    one = tmp_path / "a.yaml"
    one.write_text("m: {frames: [{duration: 1, joints: {hj1: 1}}]}\n")
    two = tmp_path / "b.yaml"
    two.write_text(one.read_text())
    with pytest.raises(PoseError, match=r"b.yaml: sequence 'm' is already defined"):
        load_sequences(one, two)


def test_unreadable_or_non_mapping_files_name_the_file(tmp_path: Path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("- just\n- a list\n")
    with pytest.raises(PoseError, match=r"bad\.yaml: the top level must be a mapping"):
        load_poses(bad)
    with pytest.raises(PoseError, match="cannot read"):
        load_poses(tmp_path / "missing.yaml")


def test_ease_curves():
    assert ease("linear", 0.25) == pytest.approx(0.25)
    assert ease("smooth", 0.5) == pytest.approx(0.5)
    assert ease("smooth", 0.1) < 0.1  # slow start ...
    assert ease("smooth", 0.9) > 0.9  # ... and slow finish
    assert ease("step", 0.01) == 1.0
    assert ease("linear", 2.0) == 1.0 and ease("linear", -1.0) == 0.0


def _sequence(frames: list[dict]) -> KeyframeSequence:
    return parse_sequences({"m": {"frames": frames}}, "test")["m"]


def _play(sequence: KeyframeSequence, start: dict[str, float], robot_type: int = 0):
    """Targets sent per cycle, pretending each joint follows its target exactly."""
    player = KeyframePlayer(sequence)
    joints = dict(start)
    sent = []
    for _ in range(1000):
        commands = JointCommands(robot_type)
        finished = player.step(commands, joints)
        sent.append(commands.targets())
        joints.update(commands.targets())
        if finished:
            return sent
    raise AssertionError("the sequence never finished")


def test_linear_frames_interpolate_from_the_measured_angles_then_hold():
    sequence = _sequence(
        [
            {"duration": 0.1, "interpolation": "linear", "joints": {"hj1": 50}, "hold": 0.04},
            {"duration": 0.1, "interpolation": "linear", "joints": {"hj2": -40}},
        ]
    )
    sent = _play(sequence, {"hj1": 0.0, "hj2": 10.0})
    assert len(sent) == round(sequence.duration / CYCLE_SECONDS) == 12
    assert [round(s["hj1"]) for s in sent[:7]] == [10, 20, 30, 40, 50, 50, 50]
    assert "hj2" not in sent[0]  # joints a frame does not name are left to others
    assert [round(s["hj2"]) for s in sent[7:]] == [0, -10, -20, -30, -40]
    assert all(s["hj1"] == 50 for s in sent[7:])  # ... and keep the earlier frame's target


def test_step_frames_jump_and_smooth_frames_ease():
    sent = _play(
        _sequence([{"duration": 0.1, "interpolation": "step", "joints": {"hj1": 30}}]), {"hj1": 0}
    )
    assert [s["hj1"] for s in sent] == [30] * 5
    sent = _play(_sequence([{"duration": 0.2, "joints": {"hj1": 100}}]), {"hj1": 0})
    steps = [b["hj1"] - a["hj1"] for a, b in itertools.pairwise(sent)]
    assert steps[0] < steps[4] > steps[-1]  # accelerate, then decelerate
    assert sent[-1]["hj1"] == pytest.approx(100)


def test_pose_frames_fill_from_the_pose_and_toes_are_dropped_without_toes():
    sequence = _sequence([{"duration": 0.02, "pose": "stand", "joints": {"rlj3": 30}}])
    sent = _play(sequence, {})
    assert sent[-1]["rlj3"] == 30 and sent[-1]["llj3"] == default_poses()["stand"].joints["llj3"]
    assert "rlj7" not in sent[-1]
    assert "rlj7" in _play(sequence, {}, robot_type=4)[-1]


def test_mirrored_sequence_swaps_sides():
    sequence = get_sequence("roll_left_to_back")
    mirror = mirrored(sequence)
    assert mirror.duration == sequence.duration
    first, twin = sequence.frames[0].joints, mirror.frames[0].joints
    assert twin["laj1"] == first["raj1"]  # shoulder pitch keeps its sign
    assert twin["llj3"] == first["rlj3"]
    assert get_sequence("roll_left_to_back", mirror=True).frames == mirror.frames


def test_pose_reached_tolerance():
    assert pose_reached({"hj1": 2.0}, {"hj1": 0.0})
    assert not pose_reached({"hj1": 5.0}, {"hj1": 0.0})
    assert not pose_reached({}, {"hj1": 0.0})


# ------------------------------------------------------------------ in the simulator
def test_pose_and_keyframe_skills_through_the_manager():
    pytest.importorskip("pybullet")
    import numpy as np

    from learning.falls import join_at_random_spot as join
    from sim.session import Session, SessionConfig

    session = Session(SessionConfig(seed=5, beam_noise=False))
    try:
        driver = join(session, 0, np.random.default_rng(5))  # runs "pose stand" for 1 s
        assert driver.run("pose", "stand")
        assert driver.is_standing()
        cycles = 0
        while not driver.run("keyframe", "stand_up_slowly"):
            cycles += 1
        assert cycles + 1 == round(get_sequence("stand_up_slowly").duration / CYCLE_SECONDS)
        assert driver.is_standing()
        stand = default_poses()["stand"].joints
        worst = max(abs(driver.state.joints_deg[n] - stand[n]) for n in driver.state.joints_deg)
        assert worst < 4.0
        assert not math.isnan(worst)
    finally:
        session.close()


def test_keyframe_skill_restarts_on_another_sequence():
    from behaviors.keyframes import KeyframeSkill

    state = SimpleNamespace(joints_deg={"hj1": 0.0})
    skill = KeyframeSkill()
    context = SimpleNamespace(world=SimpleNamespace(robot=state), commands=JointCommands(0))
    skill.step(context, "stand_up_slowly")
    first = skill._player
    skill.step(context, "stand_up_slowly")
    assert skill._player is first
    skill.step(context, "stand_up_slowly", True)
    assert skill._player is not first
