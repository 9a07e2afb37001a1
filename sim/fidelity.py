"""Replay motions recorded on the real rcssserver3d in the stand-in and measure the difference.

The recordings (``shared/reference/rcssserver3d-traces/fidelity/*.jsonl``) hold, per cycle, the
perception, the joint speeds sent in answer and the torso's world matrix from the monitor. The
replay places a robot where the real one stood after its beam (the real beam adds noise, so the
first recorded torso pose is used), lets it settle for the run's settle cycles, then sends the
same speeds with the real server's latency: a speed answering perception ``k`` first shows in
perception ``k + 2``, i.e. it is applied after one more step.

Torso "turn" is the angle between the torso's up axis and the world vertical (0 upright, 90
lying): it is what the traces' README reports for the falls.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from sim.contact_models import ContactPhysics
from sim.physics import PhysicsWorld
from sim.robot import RobotPhysics, SimRobot

_SPEED = re.compile(r"\((\w+) ([-+0-9.eE]+)\)")
_FRP_Z = re.compile(r"\(FRP \(n \w+\) \(c [^)]*\) \(f [-0-9.]+ [-0-9.]+ ([-0-9.]+)\)\)")


@dataclass(frozen=True)
class Recording:
    """One recorded motion."""

    name: str
    robot_type: int
    settle_cycles: int
    sent: list[dict[str, float]]
    #: torso world matrices (4x4, native axes: the mesh's extra rotation removed)
    torso: list[np.ndarray]
    frp_force_z: list[float]


@dataclass(frozen=True)
class Comparison:
    """Per-cycle torso height and turn, real and simulated, plus summed foot forces."""

    name: str
    real_height: np.ndarray
    sim_height: np.ndarray
    real_turn: np.ndarray
    sim_turn: np.ndarray
    real_force: np.ndarray
    sim_force: np.ndarray

    @property
    def height_error(self) -> np.ndarray:
        return np.abs(self.sim_height - self.real_height)

    @property
    def turn_error(self) -> np.ndarray:
        return np.abs(self.sim_turn - self.real_turn)

    def figures(self) -> dict[str, float]:
        """``name: value`` figures for reports: mean/max/final errors."""
        n = self.name
        figures = {
            f"{n}.height_err_mean_m": float(self.height_error.mean()),
            f"{n}.height_err_max_m": float(self.height_error.max()),
            f"{n}.height_err_final_m": float(self.height_error[-1]),
            f"{n}.turn_err_mean_deg": float(self.turn_error.mean()),
            f"{n}.turn_err_final_deg": float(self.turn_error[-1]),
            f"{n}.real_final_height_m": float(self.real_height[-1]),
            f"{n}.sim_final_height_m": float(self.sim_height[-1]),
            f"{n}.real_final_turn_deg": float(self.real_turn[-1]),
            f"{n}.sim_final_turn_deg": float(self.sim_turn[-1]),
        }
        if self.real_force.any():
            figures[f"{n}.frp_sum_err_mean_n"] = float(
                np.abs(self.sim_force - self.real_force).mean()
            )
        return figures


# The monitor's torso mesh node is rotated against the body: mesh x = -native x,
# mesh y = native z, mesh z = native y. Columns of the mesh matrix -> native axes:
_MESH_TO_NATIVE = np.array([[-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]])


def _native_matrix(column_major: list[float]) -> np.ndarray:
    mesh = np.asarray(column_major, dtype=float).reshape(4, 4).T
    native = np.eye(4)
    native[:3, :3] = mesh[:3, :3] @ _MESH_TO_NATIVE
    native[:3, 3] = mesh[:3, 3]
    return native


def load_recording(path: Path) -> Recording:
    lines = path.read_text().splitlines()
    header = json.loads(lines[0])
    rows = [json.loads(line) for line in lines[1:]]
    sent = [{k: float(v) for k, v in _SPEED.findall(r["sent"])} for r in rows]
    torso = [_native_matrix(r["torso_world"]) for r in rows]
    forces = [sum(float(f) for f in _FRP_Z.findall(r["perc"])) for r in rows]
    return Recording(
        path.stem, int(header["robot_type"]), int(header["settle_cycles"]), sent, torso, forces
    )


def turn_deg(transform: np.ndarray) -> float:
    """Angle between the torso's up axis and the world vertical."""
    return math.degrees(math.acos(float(np.clip(transform[2, 2], -1.0, 1.0))))


def replay(
    recording: Recording,
    physics: RobotPhysics | None = None,
    substeps: int = 2,
    build_ground: Callable[[PhysicsWorld], object] | None = None,
) -> Comparison:
    """Run ``recording``'s speeds on a fresh stand-in robot and compare with the real torso.

    The robot, ground and bounce threshold are those a default session plays
    (:func:`sim.session.default_contacts`) unless ``physics`` or ``build_ground`` replace them."""
    from sim.session import default_contacts  # the session imports far more than a replay

    contact = default_contacts()
    world = PhysicsWorld(substeps=substeps, min_bounce_speed=contact.min_bounce_speed)
    try:
        _ground(world, build_ground, contact)
        robot = SimRobot(world, recording.robot_type, physics=physics or contact.robot)
        start = recording.torso[0]
        yaw = math.degrees(math.atan2(start[1, 1], start[0, 1]))
        robot.place(float(start[0, 3]), float(start[1, 3]), 0.4, yaw)
        for _ in range(recording.settle_cycles):
            world.step_cycle()
            robot.update_sensors()
        zero = dict.fromkeys(robot.effector_names, 0.0)
        heights, turns, forces = [], [], []
        for cycle in range(len(recording.sent)):
            transform = robot.torso_world_transform()
            heights.append(transform[2, 3])
            turns.append(turn_deg(transform))
            forces.append(sum(f.force[2] for f in robot.force_resistance().values()))
            if cycle >= 1:
                robot.set_joint_speeds(zero | recording.sent[cycle - 1])
            world.step_cycle()
            robot.update_sensors()
    finally:
        world.close()
    return Comparison(
        recording.name,
        np.array([t[2, 3] for t in recording.torso]),
        np.array(heights),
        np.array([turn_deg(t) for t in recording.torso]),
        np.array(turns),
        np.array(recording.frp_force_z),
        np.array(forces),
    )


def _ground(
    world: PhysicsWorld,
    build_ground: Callable[[PhysicsWorld], object] | None,
    contact: ContactPhysics,
) -> None:
    if build_ground is not None:
        build_ground(world)
        return
    try:
        from sim.field import build_field  # the game's own field when it is there
    except ImportError:
        import pybullet

        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=world.client)
        pybullet.createMultiBody(0, plane, physicsClientId=world.client)
        return
    build_field(world, contact.ground, contact.post_restitution)
