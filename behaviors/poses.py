"""Named whole-body poses (joint targets in degrees) and the ``pose`` skill that holds one.

Poses live in ``behaviors/data/poses.yaml`` as ``name: {description: ..., joints: {hj1: 0, ...}}``.
They are validated on load against the NAO joint table, so a typo in a joint name or an angle
outside the joint's range fails at start-up with the file and key named, instead of silently
doing nothing on the field. The toe joints (``llj7``, ``rlj7``) are accepted everywhere and
simply dropped on robot types without toes, so one file serves all five types.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from behaviors.skill import Skill, SkillContext
from world.kinematics import body_transforms
from world.nao_model import robot_spec

DATA_DIR = Path(__file__).resolve().parent / "data"
POSES_FILE = DATA_DIR / "poses.yaml"
#: Type 4 has every joint of the other types plus the toes: the superset to validate against.
_ALL_JOINTS = {j.perceptor: (j.min_deg, j.max_deg) for j in robot_spec(4).joints}
#: A joint counts as arrived within this many degrees of its target.
REACHED_TOLERANCE_DEG = 3.0


class PoseError(ValueError):
    """A pose or keyframe file is malformed; the message names the file and the key."""


@dataclass(frozen=True)
class Pose:
    """Joint targets in degrees by perceptor name (``hj1``, ``rlj3``, ...)."""

    name: str
    joints: Mapping[str, float]
    description: str = ""

    def for_robot(self, joint_names: tuple[str, ...] | frozenset[str]) -> dict[str, float]:
        """The targets this robot has joints for (drops the toes on types 0-3)."""
        return {name: value for name, value in self.joints.items() if name in joint_names}


def read_yaml_mapping(path: Path) -> dict[str, Any]:
    """Load a YAML file whose top level must be a mapping; errors name the file."""
    try:
        data = yaml.safe_load(path.read_text())
    except OSError as exc:
        raise PoseError(f"cannot read {path}: {exc}") from None
    except yaml.YAMLError as exc:
        raise PoseError(f"{path} is not valid YAML: {exc}") from None
    if not isinstance(data, dict):
        raise PoseError(f"{path}: the top level must be a mapping of names, got {type(data)}")
    return data


def check_fields(data: Any, where: str, required: set[str], optional: set[str]) -> None:
    """Reject a non-mapping, missing required keys and unknown keys, naming ``where``."""
    if not isinstance(data, dict):
        raise PoseError(f"{where}: expected a mapping, got {type(data).__name__}")
    missing = sorted(required - set(data))
    if missing:
        raise PoseError(f"{where}: missing field(s) {', '.join(missing)}")
    unknown = sorted(set(data) - required - optional)
    if unknown:
        raise PoseError(
            f"{where}: unknown field(s) {', '.join(map(str, unknown))}; "
            f"valid fields: {', '.join(sorted(required | optional))}"
        )


def check_number(value: Any, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PoseError(f"{where}: expected a number, got {value!r}")
    return float(value)


def validate_joint_targets(data: Any, where: str) -> dict[str, float]:
    """Check a ``{perceptor: degrees}`` mapping against the joint table and return it as floats.

    Unknown names list the valid ones; out-of-range angles state the joint's range.
    """
    if not isinstance(data, dict):
        raise PoseError(f"{where}: joints must be a mapping of joint name to degrees")
    targets = {}
    for name, value in data.items():
        key = f"{where}.{name}"
        if name not in _ALL_JOINTS:
            raise PoseError(f"{key}: unknown joint; valid joints: {', '.join(_ALL_JOINTS)}")
        angle = check_number(value, key)
        low, high = _ALL_JOINTS[name]
        if not low <= angle <= high:
            raise PoseError(f"{key}: {angle:g} deg is outside the joint range [{low:g}, {high:g}]")
        targets[name] = angle
    return targets


def parse_poses(data: Mapping[str, Any], source: str) -> dict[str, Pose]:
    """Build poses from the mapping read out of ``source`` (a file name, for messages)."""
    poses = {}
    for name, entry in data.items():
        where = f"{source}: pose {name!r}"
        check_fields(entry, where, {"joints"}, {"description"})
        joints = validate_joint_targets(entry["joints"], f"{where} joints")
        poses[str(name)] = Pose(str(name), joints, str(entry.get("description", "")))
    return poses


def load_poses(path: str | Path = POSES_FILE) -> dict[str, Pose]:
    """Read and validate a pose file (default: the packaged ``poses.yaml``)."""
    path = Path(path)
    return parse_poses(read_yaml_mapping(path), str(path))


@cache
def default_poses() -> dict[str, Pose]:
    """The packaged poses, read once per process (they are immutable)."""
    return load_poses(POSES_FILE)


def get_pose(name: str) -> Pose:
    poses = default_poses()
    try:
        return poses[name]
    except KeyError:
        raise KeyError(
            f"unknown pose {name!r}; poses in {POSES_FILE}: {', '.join(poses)}"
        ) from None


def pose_reached(
    joints_deg: Mapping[str, float],
    targets: Mapping[str, float],
    tolerance_deg: float = REACHED_TOLERANCE_DEG,
) -> bool:
    """Whether every targeted joint is within ``tolerance_deg`` of its target."""
    return all(
        abs(joints_deg.get(n, float("inf")) - t) <= tolerance_deg for n, t in targets.items()
    )


def support_margin(joints_deg: Mapping[str, float], robot_type: int = 0) -> float:
    """How far (m) the centre of mass lies inside the feet's support area; negative: outside.

    Why: a pose that a motion ends in or passes through slowly must keep the centre of mass
    over the feet, or the robot tips over however well the joints follow. Computed from the
    pose alone: forward kinematics of every body centre weighted by its mass, seen in the
    frame of the right sole laid flat on the ground, against the rectangle spanned by both
    foot boxes (toes left out: the conservative support). Meant for symmetric standing
    poses, where both soles lie flat at once.
    """
    spec = robot_spec(robot_type)
    transforms = body_transforms(spec, joints_deg)
    masses = np.array([body.mass for body in spec.bodies])
    centres = np.array([transforms[body.name][:3, 3] for body in spec.bodies])
    com = masses @ centres / masses.sum()
    sole = transforms["rfoot"]
    level = sole[:3, :3].T  # torso frame -> right-foot frame (flat foot: level ground)
    corners = []
    for foot in ("rfoot", "lfoot"):
        half = np.array(spec.body(foot).size[:2]) / 2
        centre = level @ (transforms[foot][:3, 3] - sole[:3, 3])
        corners += [centre[:2] - half, centre[:2] + half]
    low, high = np.min(corners, axis=0), np.max(corners, axis=0)
    point = (level @ (com - sole[:3, 3]))[:2]
    return float(min(np.min(point - low), np.min(high - point)))


class PoseSkill(Skill):
    """``execute("pose", "stand")``: drive every joint to a named pose and hold it there.

    Finished (True) once all joints are within :data:`REACHED_TOLERANCE_DEG`; the skill keeps
    holding the pose for as long as it is called.
    """

    name = "pose"

    def step(self, context: SkillContext, pose_name: str = "stand") -> bool:
        robot = context.world.robot
        targets = get_pose(pose_name).for_robot(frozenset(context.commands.joint_names))
        context.commands.set_targets(targets)
        return pose_reached(robot.joints_deg, targets)
