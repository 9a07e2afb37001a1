"""Left-right mirroring: joint angles, actions, observations, keyframes and field quantities.

A motion for one side becomes the motion for the other by reflecting the robot about its
sagittal plane (native frame x -> -x; ``M = diag(-1, 1, 1)``). Reflecting a rotation of angle
``q`` about axis ``a`` gives a rotation of ``-q`` about ``M a``; each joint's mirror image is
therefore its twin (``r`` <-> ``l``, the head joints themselves) turned by ``-q`` if the twin's
axis equals ``M a`` and by ``+q`` if it is ``-M a``. :data:`MIRROR_TABLE` is derived that way from
the axes in :mod:`world.nao_model`, so the signs can never drift from the model; it also checks
that twins sit at mirrored anchors, so an asymmetric model fails at import instead of giving wrong
mirrors. The outcome: pitch joints keep their sign, roll and yaw joints flip, and the hip
yaw-pitch joints (axes (-1, 0, 1)/sqrt2 and (-1, 0, -1)/sqrt2) keep theirs.

Sensor and frame rules: the gyro is a pseudovector (``w' = -M w``), the accelerometer and other
native-frame vectors are vectors (``v' = M v``); in the field frame (x towards the opponent goal,
y to the left) the mirror plane is y = 0, so points flip y and directions negate.

Every function here is an involution: applying it twice gives back the input.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal

import numpy as np

from world.effectors import effector_for_joint, joint_for_effector
from world.nao_model import ROBOT_TYPES, RobotSpec, robot_spec

#: The reflection about the sagittal plane in the model's native frame (x = right).
REFLECTION = np.diag([-1.0, 1.0, 1.0])
#: How closely mirrored axes and anchors must agree to count as equal (the model's axes carry
#: 0.7071 for 1/sqrt 2, so exact comparison would be wrong).
_TOLERANCE = 1e-3


@dataclass(frozen=True, slots=True)
class MirrorEntry:
    """How one joint maps under reflection: its angle ``q`` becomes ``sign * q`` on ``twin``."""

    twin: str
    sign: int


def twin_name(perceptor: str) -> str:
    """The same joint on the other side, by name: ``raj2 -> laj2``, ``hj1 -> hj1``."""
    if perceptor.startswith("h"):
        return perceptor
    swap = {"r": "l", "l": "r"}
    if perceptor[:1] not in swap:
        raise KeyError(f"{perceptor!r} is not a joint perceptor name")
    return swap[perceptor[0]] + perceptor[1:]


def _derive_table(spec: RobotSpec) -> dict[str, MirrorEntry]:
    """Twin and sign of every joint of ``spec``, from its axes and anchors."""
    joints = {j.perceptor: j for j in spec.joints}
    table = {}
    for name, joint in joints.items():
        twin = joints[twin_name(name)]
        axis = np.asarray(joint.axis, dtype=float)
        mirrored_axis = REFLECTION @ (axis / np.linalg.norm(axis))
        twin_axis = np.asarray(twin.axis, dtype=float) / np.linalg.norm(twin.axis)
        mirrored_anchor = REFLECTION @ np.asarray(joint.anchor, dtype=float)
        if not np.allclose(mirrored_anchor, twin.anchor, atol=_TOLERANCE):
            raise ValueError(f"{name} and {twin.perceptor} are not at mirrored anchors")
        if np.allclose(mirrored_axis, twin_axis, atol=_TOLERANCE):
            sign = -1
        elif np.allclose(mirrored_axis, -twin_axis, atol=_TOLERANCE):
            sign = 1
        else:
            raise ValueError(
                f"the mirror of {name}'s axis {joint.axis} is neither {twin.perceptor}'s axis "
                f"{twin.axis} nor its opposite: the model is not left-right symmetric"
            )
        table[name] = MirrorEntry(twin.perceptor, sign)
    return table


def _derive_all_types() -> Mapping[str, MirrorEntry]:
    """One table for every robot type: types share axes, type 4 only adds the toe joints."""
    merged: dict[str, MirrorEntry] = {}
    for robot_type in ROBOT_TYPES:
        for name, entry in _derive_table(robot_spec(robot_type)).items():
            if merged.setdefault(name, entry) != entry:
                raise ValueError(f"robot type {robot_type} mirrors {name} differently")
    return MappingProxyType(merged)


#: Perceptor name -> (twin, sign) for every joint of every robot type (read-only).
MIRROR_TABLE: Mapping[str, MirrorEntry] = _derive_all_types()


def _entry(perceptor: str) -> MirrorEntry:
    try:
        return MIRROR_TABLE[perceptor]
    except KeyError:
        raise KeyError(
            f"no joint {perceptor!r} to mirror; joints: {', '.join(MIRROR_TABLE)}"
        ) from None


# --------------------------------------------------------------------------------------------
# Joints: dicts by name, vectors in a given order, keyframes
# --------------------------------------------------------------------------------------------


def mirror_joint_angles(angles: Mapping[str, float]) -> dict[str, float]:
    """Perceptor name -> angle, mirrored: each value moves to the twin, with the twin's sign.

    Works on partial dicts (a keyframe that moves only the right arm becomes one that moves only
    the left arm) and on anything linear in the angle (degrees, radians, speeds).
    """
    out = {}
    for name, value in angles.items():
        entry = _entry(name)
        out[entry.twin] = entry.sign * value
    return out


def mirror_effector_speeds(speeds: Mapping[str, float]) -> dict[str, float]:
    """Effector name (he1, rae2, lle6, ...) -> rad/s, mirrored like the joints they drive."""
    out = {}
    for effector, value in speeds.items():
        entry = _entry(joint_for_effector(effector))
        out[effector_for_joint(entry.twin)] = entry.sign * value
    return out


def _joint_permutation(joint_order: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
    """Index of each position's source and its sign, for a vector of joints in ``joint_order``.

    The mirrored value at position ``i`` (joint ``k``) is ``sign * value`` of ``twin(k)``.
    """
    position = {name: i for i, name in enumerate(joint_order)}
    if len(position) != len(joint_order):
        raise ValueError(f"joint order names a joint twice: {list(joint_order)}")
    source = np.empty(len(joint_order), dtype=int)
    signs = np.empty(len(joint_order))
    for i, name in enumerate(joint_order):
        entry = _entry(name)
        if entry.twin not in position:
            raise ValueError(
                f"joint order has {name} but not its twin {entry.twin}: cannot mirror it"
            )
        source[i] = position[entry.twin]
        signs[i] = entry.sign
    return source, signs


def mirror_action(action: Sequence[float] | np.ndarray, joint_order: Sequence[str]) -> np.ndarray:
    """A vector of per-joint values (targets, speeds, ...) in ``joint_order``, mirrored.

    ``joint_order`` holds perceptor names and must contain each joint's twin. The leading
    dimensions of a batch (``(..., len(joint_order))``) are kept.
    """
    values = np.asarray(action, dtype=float)
    if values.shape[-1:] != (len(joint_order),):
        raise ValueError(
            f"action has shape {values.shape}, expected (..., {len(joint_order)}) for "
            f"joints {list(joint_order)}"
        )
    source, signs = _joint_permutation(joint_order)
    return values[..., source] * signs


Keyframe = tuple[Mapping[str, float], float]


def mirror_keyframes(frames: Iterable[Keyframe]) -> list[tuple[dict[str, float], float]]:
    """A sequence of (joint targets by perceptor name, duration) frames for the other side."""
    return [(mirror_joint_angles(targets), duration) for targets, duration in frames]


# --------------------------------------------------------------------------------------------
# Vectors: native frame, sensors, field frame
# --------------------------------------------------------------------------------------------


def mirror_vector_native(v: Sequence[float] | np.ndarray) -> np.ndarray:
    """A vector in the robot's native frame (x right): x flips. Takes 2 (x, y) or 3 values."""
    out = np.array(v, dtype=float)
    out[..., 0] = -out[..., 0]
    return out


def mirror_gyro(omega: Sequence[float] | np.ndarray) -> np.ndarray:
    """An angular velocity (a pseudovector) in the native frame: ``-M w``, i.e. y and z flip."""
    out = np.array(omega, dtype=float)
    out[..., 1:3] = -out[..., 1:3]
    return out


def mirror_accelerometer(acceleration: Sequence[float] | np.ndarray) -> np.ndarray:
    """An acceleration (a vector) in the native frame: x flips."""
    return mirror_vector_native(acceleration)


def mirror_field_point(p: Sequence[float] | np.ndarray) -> np.ndarray:
    """A point or vector in the field frame (x to the opponent goal, y left): y flips."""
    out = np.array(p, dtype=float)
    out[..., 1] = -out[..., 1]
    return out


def mirror_direction_deg(direction: float) -> float:
    """A heading or bearing in the field frame (counter-clockwise from +x, degrees): it negates.

    No wrapping, so that mirroring twice gives back exactly the input.
    """
    return -float(direction)


# --------------------------------------------------------------------------------------------
# Observations: a flat vector described by a layout
# --------------------------------------------------------------------------------------------

SegmentKind = Literal["joints", "gyro", "accelerometer", "native", "field", "negate", "scalar"]


@dataclass(frozen=True, slots=True)
class Segment:
    """One stretch of an observation vector and how it mirrors.

    ``joints``: per-joint values in ``joint_order`` (angles, speeds; linear in the angle);
    ``gyro`` (3) and ``accelerometer`` (3): native-frame sensor readings; ``native``: a 2- or
    3-vector in the native frame (x flips); ``field``: a 2- or 3-vector in the field frame
    (y flips); ``negate``: values that change sign (field angles, lateral offsets, yaw rates);
    ``scalar``: values that stay (heights, distances, time, play mode flags).
    Build them with the class methods rather than by hand.
    """

    kind: SegmentKind
    size: int
    joint_order: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        fixed = {"gyro": (3,), "accelerometer": (3,), "native": (2, 3), "field": (2, 3)}
        if self.kind in fixed and self.size not in fixed[self.kind]:
            raise ValueError(
                f"a {self.kind} segment has {fixed[self.kind]} values, not {self.size}"
            )
        if self.kind == "joints" and self.size != len(self.joint_order):
            raise ValueError("a joints segment's size is the length of its joint order")
        if self.size < 1:
            raise ValueError(f"a segment needs at least one value, got {self.size}")

    @classmethod
    def joints(cls, joint_order: Sequence[str]) -> Segment:
        return cls("joints", len(joint_order), tuple(joint_order))

    @classmethod
    def gyro(cls) -> Segment:
        return cls("gyro", 3)

    @classmethod
    def accelerometer(cls) -> Segment:
        return cls("accelerometer", 3)

    @classmethod
    def native(cls, size: int = 3) -> Segment:
        return cls("native", size)

    @classmethod
    def field(cls, size: int = 2) -> Segment:
        return cls("field", size)

    @classmethod
    def negate(cls, size: int = 1) -> Segment:
        return cls("negate", size)

    @classmethod
    def scalar(cls, size: int = 1) -> Segment:
        return cls("scalar", size)


@dataclass(frozen=True, slots=True)
class ObservationLayout:
    """An observation vector as consecutive segments; ``size`` is the vector's length."""

    segments: tuple[Segment, ...]

    def __post_init__(self) -> None:
        for segment in self.segments:
            if segment.kind == "joints":
                _joint_permutation(segment.joint_order)  # fails early if a twin is missing

    @property
    def size(self) -> int:
        return sum(s.size for s in self.segments)


def _mirror_segment(values: np.ndarray, segment: Segment) -> np.ndarray:
    if segment.kind == "joints":
        return mirror_action(values, segment.joint_order)
    if segment.kind == "gyro":
        return mirror_gyro(values)
    if segment.kind in ("accelerometer", "native"):
        return mirror_vector_native(values)
    if segment.kind == "field":
        return mirror_field_point(values)
    if segment.kind == "negate":
        return -values
    return values.copy()


def mirror_observation(
    observation: Sequence[float] | np.ndarray, layout: ObservationLayout
) -> np.ndarray:
    """An observation vector (or a batch, ``(..., layout.size)``) mirrored segment by segment."""
    values = np.asarray(observation, dtype=float)
    if values.shape[-1:] != (layout.size,):
        raise ValueError(
            f"observation has shape {values.shape}, the layout describes {layout.size} values"
        )
    parts = []
    start = 0
    for segment in layout.segments:
        parts.append(_mirror_segment(values[..., start : start + segment.size], segment))
        start += segment.size
    return np.concatenate(parts, axis=-1)
