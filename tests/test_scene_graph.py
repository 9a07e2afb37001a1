"""The monitor scene graph against messages recorded from the real rcssserver3d 0.7.2."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from sim.scene_graph import (
    MonitorHeader,
    SceneGraph,
    body_names,
    format_number,
    rsg_rotation,
    translation,
)
from world.nao_model import robot_spec
from world.sexp import parse

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"


def _trace(name: str) -> str:
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")
    return (TRACES / name).read_text()


def _raw_monitor(name: str) -> list[str]:
    return [json.loads(line)["msg"] for line in _trace(name).splitlines() if line.strip()]


def _no_negative_zero(text: str) -> str:
    """The real server writes some static zeros as ``-0`` (a float32 sign artefact)."""
    return re.sub(r"(?<=[ (])-0(?=[ )])", "0", text)


def _slt_matrix(node: list) -> np.ndarray:
    """The 4x4 matrix of a ``(nd TRF (SLT m0..m15) ...)`` or ``(nd (SLT ...) ...)`` node."""
    slt = next(item for item in node if isinstance(item, list) and item[0] == "SLT")
    return np.array([float(v) for v in slt[1:]]).reshape(4, 4, order="F")


def _has_slt(node: list) -> bool:
    return any(isinstance(item, list) and item and item[0] == "SLT" for item in node)


def _robot_poses(message: str, robot_type: int = 0) -> dict[str, np.ndarray]:
    """Body name -> world transform of the (only) robot in a recorded message."""
    tree = parse(message)[2]
    robot = tree[-1]
    bodies = [child for child in robot if isinstance(child, list) and child[0] == "nd"]
    names = body_names(robot_type)
    assert len(bodies) == len(names)
    return {name: _slt_matrix(node) for name, node in zip(names, bodies, strict=True)}


def _ball_pose(message: str) -> np.ndarray:
    tree = parse(message)[2]
    return _slt_matrix(tree[-2])


def _numbers_close(ours: list | str, theirs: list | str, path: str = "") -> None:
    """Same tree, same names; numbers within 1e-4."""
    if isinstance(theirs, str):
        assert isinstance(ours, str), path
        try:
            assert float(ours) == pytest.approx(float(theirs), abs=1e-4), path
        except ValueError:
            assert ours == theirs, path
        return
    assert isinstance(ours, list) and len(ours) == len(theirs), f"{path}: {ours} vs {theirs}"
    for i, (a, b) in enumerate(zip(ours, theirs, strict=True)):
        _numbers_close(a, b, f"{path}/{i}")


def _zero_pose(torso: np.ndarray, robot_type: int = 0) -> dict[str, np.ndarray]:
    """Every body where the model puts it with all joints at 0, given the torso's pose."""
    poses = {}
    for body in robot_spec(robot_type).bodies:
        pose = torso.copy()
        pose[:3, 3] = torso[:3, :3] @ np.array(body.centre) + torso[:3, 3]
        poses[body.name] = pose
    return poses


# ----------------------------------------------------------------------------- full state


def test_empty_field_with_connecting_agent_is_trace_07() -> None:
    recorded = _trace("07_monitor_first_full_state.txt")
    scene = SceneGraph()
    scene.add_pending_robot("agent1")  # trace 07: the agent had connected, no robot yet
    ours = scene.full_state(MonitorHeader(), _ball_pose(recorded), {}).decode()
    assert _no_negative_zero(ours) == _no_negative_zero(recorded)


def test_field_without_agents_is_trace_07_minus_the_agent_node() -> None:
    recorded = parse(_trace("07_monitor_first_full_state.txt"))
    ours = parse(SceneGraph().full_state(MonitorHeader(), _slt_matrix(recorded[2][-2]), {}))
    assert ours[0] == recorded[0]  # header, exactly
    assert ours[1] == ["RSG", "0", "1"]
    _numbers_close(ours[2], recorded[2][:-1])


def test_robot_full_state_is_trace_07b_given_its_poses() -> None:
    recorded = _trace("07b_monitor_full_state_with_agent.txt")
    scene = SceneGraph()
    scene.add_robot("agent1", 0)
    ours = scene.full_state(
        MonitorHeader(), _ball_pose(recorded), {"agent1": _robot_poses(recorded)}
    ).decode()
    assert _no_negative_zero(ours) == _no_negative_zero(recorded)


def test_trace_robot_nodes_follow_one_torso_pose() -> None:
    """Before it moves, every body node of the recorded robot sits where the model's zero pose
    puts it relative to the torso node: our body->node mapping is the server's."""
    for message in (
        _trace("07b_monitor_full_state_with_agent.txt"),
        _raw_monitor("raw_monitor_t1.jsonl")[2],
    ):
        recorded = parse(message)
        torso = _robot_poses(message)["torso"]
        scene = SceneGraph()
        scene.add_robot("agent1", 0)
        if "matLeft" in message:
            scene.set_robot_identity("agent1", "left", 1)
        header = MonitorHeader(team_left="Probe" if "team_left" in message else None)
        ours = parse(scene.full_state(header, _ball_pose(message), {"agent1": _zero_pose(torso)}))
        assert ours[0] == recorded[0]
        _numbers_close(ours[2], recorded[2])


def test_identified_robot_is_trace_t1_second_full_state() -> None:
    recorded = _raw_monitor("raw_monitor_t1.jsonl")[2]
    scene = SceneGraph()
    scene.add_robot("agent1", 0)
    scene.set_robot_identity("agent1", "left", 1)
    header = MonitorHeader(team_left="Probe")
    ours = scene.full_state(header, _ball_pose(recorded), {"agent1": _robot_poses(recorded)})
    assert _no_negative_zero(ours.decode()) == _no_negative_zero(recorded)
    assert b"(resetMaterials matNum1 matLeft matType0 naowhite)" in ours
    assert b"(resetMaterials matLeft naoblack naogrey naowhite)" in ours


# ----------------------------------------------------------------------------- updates


def _replay_t1() -> tuple[SceneGraph, list[str], np.ndarray]:
    messages = _raw_monitor("raw_monitor_t1.jsonl")
    scene = SceneGraph()
    scene.add_robot("agent1", 0)
    scene.set_robot_identity("agent1", "left", 1)
    ball = _ball_pose(messages[2])
    scene.full_state(MonitorHeader(team_left="Probe"), ball, {"agent1": _robot_poses(messages[2])})
    return scene, messages, ball


def test_first_update_is_trace_08_byte_for_byte() -> None:
    scene, _messages, ball = _replay_t1()
    recorded = _trace("08_monitor_incremental_RDS.txt")
    poses = _robot_poses(recorded.replace("(RDS 0 1)", "(RSG 0 1)"))
    ours = scene.update(MonitorHeader(team_left="Probe"), ball, {"agent1": poses})
    assert ours.decode() == recorded


def test_later_updates_have_the_recorded_shape() -> None:
    """Message 4 (every body moved again, no ``setVisible``) and 5 (nothing moved >0.005)."""
    scene, messages, ball = _replay_t1()
    header = MonitorHeader(team_left="Probe")
    third = _robot_poses(messages[3])
    scene.update(header, ball, {"agent1": third})
    fourth = _robot_poses(messages[4])
    assert scene.update(header, ball, {"agent1": fourth}).decode() == messages[4]
    nudged = {name: pose + 0.004 for name, pose in fourth.items()}
    ours = scene.update(MonitorHeader(time=0.08, team_left="Probe"), ball, {"agent1": nudged})
    assert ours.decode() == messages[5]


def _scene_with_robot(robot_type: int = 0) -> tuple[SceneGraph, dict[str, np.ndarray]]:
    scene = SceneGraph()
    scene.add_robot("a", robot_type)
    scene.set_robot_identity("a", "right", 7)
    torso = rsg_rotation(0, 0, 30)
    torso[:3, 3] = (2.0, -1.0, 0.38)
    return scene, _zero_pose(torso, robot_type)


def _moved_nodes(message: bytes) -> list[int]:
    """Indices (in tree order) of the transforms that carry an SLT in an update."""
    moved, counter = [], [0]

    def walk(node: list) -> None:
        if node[:1] != ["nd"]:
            return
        if _has_slt(node):
            moved.append(counter[0])
        counter[0] += 1
        for child in node[1:]:
            if isinstance(child, list):
                walk(child)

    for node in parse(message)[2]:
        walk(node)
    return moved


def test_moved_body_gets_slt_only_where_it_moved() -> None:
    scene, poses = _scene_with_robot()
    header = MonitorHeader()
    ball = translation(0, 0, 0.042)
    scene.full_state(header, ball, {"a": poses})
    assert _moved_nodes(scene.update(header, ball, {"a": poses})) == []

    arm = dict(poses)
    arm["rlowerarm"] = translation(0.01, 0, 0) @ poses["rlowerarm"]
    message = scene.update(header, ball, {"a": arm})
    assert message.count(b"(SLT") == 1
    expected = " ".join(format_number(v) for v in arm["rlowerarm"].ravel(order="F"))
    assert f"(SLT {expected})".encode() in message


def test_small_moves_accumulate_against_the_last_sent_pose() -> None:
    scene, poses = _scene_with_robot()
    header, ball = MonitorHeader(), translation(0, 0, 0.042)
    scene.full_state(header, ball, {"a": poses})
    for step, expected_slts in ((1, 0), (2, 1), (3, 0)):
        moved = {k: translation(0.003 * step, 0, 0) @ v for k, v in poses.items()}
        message = scene.update(header, ball, {"a": moved})
        assert message.count(b"(SLT") == expected_slts * len(poses), step


def test_moving_ball_updates_only_the_ball() -> None:
    scene, poses = _scene_with_robot()
    header = MonitorHeader()
    scene.full_state(header, translation(0, 0, 0.042), {"a": poses})
    message = scene.update(header, translation(1, 0, 0.042), {"a": poses})
    assert message.count(b"(SLT") == 1
    assert b"(SLT 1 0 0 0 0 1 0 0 0 0 1 0 1 0 0.042 1)(nd StaticMesh" in message


def test_update_tree_has_the_full_state_shape_for_every_type() -> None:
    def shape(node: list | str) -> list | None:
        if isinstance(node, str) or node[:1] != ["nd"]:
            return None
        return [s for s in (shape(c) for c in node[1:]) if s is not None]

    for robot_type in range(5):
        scene, poses = _scene_with_robot(robot_type)
        full = parse(scene.full_state(MonitorHeader(), np.eye(4), {"a": poses}))
        update = parse(scene.update(MonitorHeader(), np.eye(4), {"a": poses}))
        assert [shape(n) for n in full[2]] == [shape(n) for n in update[2]]
        assert update[1] == ["RDS", "0", "1"]


def test_type4_robot_has_toes_and_type_specific_meshes() -> None:
    scene, poses = _scene_with_robot(4)
    message = scene.full_state(MonitorHeader(), np.eye(4), {"a": poses}).decode()
    assert "models/naobody4.obj" in message and "models/rshank4.obj" in message
    assert "models/lupperarm4.obj" in message
    assert message.count("models/rfoot.obj") == 2  # foot and toe share the foot mesh
    assert "(sSc 0.08 0.0622412 0.08)" in message
    assert "matNum7 matRight matType4 naowhite" in message
    assert len(body_names(4)) == len(robot_spec(4).bodies) == 25


def test_body_names_cover_the_model() -> None:
    for robot_type in range(5):
        assert sorted(body_names(robot_type)) == sorted(
            b.name for b in robot_spec(robot_type).bodies
        )


# ----------------------------------------------------------------------------- header, changes


def test_update_header_has_time_and_changed_keys_only() -> None:
    scene, poses = _scene_with_robot()
    ball = np.eye(4)
    scene.full_state(MonitorHeader(), ball, {"a": poses})
    assert scene.update(MonitorHeader(time=0.04), ball, {"a": poses}).startswith(
        b"((time 0.04))(RDS"
    )
    changed = MonitorHeader(time=0.06, play_mode="PlayOn", score_right=1, team_right="Them")
    assert scene.update(changed, ball, {"a": poses}).startswith(
        b"((time 0.06)(team_right Them)(score_right 1)(play_mode 3))(RDS"
    )
    assert scene.update(changed, ball, {"a": poses}).startswith(b"((time 0.06))(RDS")


def test_full_state_header_lists_every_key() -> None:
    header = MonitorHeader(time=12.5, play_mode=3, team_left="A", team_right="B", half=2)
    message = SceneGraph().full_state(header, np.eye(4), {})
    assert message.startswith(b"((FieldLength 30)(FieldWidth 20)(FieldHeight 40)")
    assert b"(time 12.5)(team_left A)(team_right B)(half 2)(score_left 0)(score_right 0)" in message
    assert b"(play_mode 3))(RSG 0 1)(" in message


def test_scene_changes_force_a_full_state() -> None:
    scene, poses = _scene_with_robot()
    header, ball = MonitorHeader(), np.eye(4)

    def kind() -> bytes:
        robots = {"a": poses} if "a" in scene.robot_ids else {}
        return parse(scene.update(header, ball, robots))[1][0].encode()

    assert kind() == b"RSG"
    assert kind() == b"RDS"
    scene.set_robot_identity("a", "left", 3)
    assert kind() == b"RSG"
    scene.request_full_state()
    assert kind() == b"RSG"
    scene.add_pending_robot("b")
    assert kind() == b"RSG"
    assert kind() == b"RDS"
    scene.remove_robot("b")
    scene.remove_robot("a")
    assert kind() == b"RSG"
    assert scene.robot_ids == ()


def test_bad_input_is_refused_with_a_clear_error() -> None:
    scene, poses = _scene_with_robot()
    with pytest.raises(KeyError, match="no body transforms for robot 'a'"):
        scene.full_state(MonitorHeader(), np.eye(4), {})
    with pytest.raises(KeyError, match="'ghost'"):
        scene.full_state(MonitorHeader(), np.eye(4), {"a": poses, "ghost": poses})
    missing = {k: v for k, v in poses.items() if k != "lfoot"}
    with pytest.raises(KeyError, match="lfoot"):
        scene.full_state(MonitorHeader(), np.eye(4), {"a": missing})
    with pytest.raises(ValueError, match="4x4"):
        scene.full_state(MonitorHeader(), np.eye(3), {"a": poses})
    with pytest.raises(ValueError, match="side"):
        scene.set_robot_identity("a", "middle", 1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="already"):
        scene.add_robot("a", 0)
    with pytest.raises(ValueError, match="robot type"):
        scene.add_robot("b", 5)
    with pytest.raises(ValueError, match="unknown play mode"):
        MonitorHeader(play_mode="Halftime").dynamic()
    with pytest.raises(KeyError, match="not in the scene"):
        scene.remove_robot("nobody")


def test_numbers_are_written_like_the_server() -> None:
    assert [format_number(v) for v in (1.0, -0.0, 0.3, -4.371139e-08, 1.476470001, 300)] == [
        "1",
        "-0",
        "0.3",
        "-4.37114e-08",
        "1.47647",
        "300",
    ]
