"""The simulated NAO (SimSpark's ``nao_hetero`` model, robot types 0-4) as pure data.

The server builds its robots from these tables and the agent's forward kinematics reads them, so
both sides share one description. Values are transcribed from
``shared/reference/nao-model-facts.md`` (rcssserver3d 0.7.2).

Frame: the model's native frame, **x = robot's right, y = forward, z = up**, origin at the torso
centre, every joint at 0 (arms straight forward, legs straight down). Units: metres, kilograms,
joint limits in degrees, joint speeds in rad/s.

Type 0 is written out as a table. Types 1-3 move bodies and joint anchors by the per-type offsets
of the facts (longer thighs/ankles/forearms, wider hips); type 4 splits each foot into a foot and
a toe. The derivation is checked against the facts' derived tables in ``tests/test_nao_model.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Literal

Vec3 = tuple[float, float, float]
Shape = Literal["box", "sphere", "capsule"]

#: SimSpark's default joint speed cap (351.77 deg/s).
DEFAULT_MAX_SPEED = 6.1395
#: ODE motor force cap (fMax) of every hinge, N m.
MAX_MOTOR_TORQUE = 10.0
#: Linear and angular drag of every body's DragController.
BODY_DRAG = 0.01
ROBOT_TYPES = (0, 1, 2, 3, 4)


@dataclass(frozen=True, slots=True)
class BodySpec:
    """One rigid body.

    ``size`` is ``(x, y, z)`` for a box, ``(radius,)`` for a sphere and ``(radius, length)`` for a
    capsule whose cylindrical part (``length``) lies along z. ``centre`` is relative to the torso
    centre in the zero pose. Bodies without ``collider`` carry mass only (no collision shape).
    """

    name: str
    shape: Shape
    size: tuple[float, ...]
    mass: float
    centre: Vec3
    collider: bool


@dataclass(frozen=True, slots=True)
class JointSpec:
    """One hinge: ``child`` turns relative to ``parent`` about ``axis`` (right-hand rule) through
    ``anchor`` (relative to the torso centre in the zero pose). The perceptor reports the angle,
    the effector sets a target speed clipped to ``max_speed``."""

    perceptor: str
    effector: str
    child: str
    parent: str
    anchor: Vec3
    axis: Vec3
    min_deg: float
    max_deg: float
    max_speed: float = DEFAULT_MAX_SPEED


@dataclass(frozen=True, slots=True)
class RobotSpec:
    """A whole robot type: bodies (torso first, parents before children) and joints in the order
    the server sends its ``HJ`` perceptors."""

    robot_type: int
    bodies: tuple[BodySpec, ...]
    joints: tuple[JointSpec, ...]

    @property
    def total_mass(self) -> float:
        return sum(b.mass for b in self.bodies)

    @property
    def has_toes(self) -> bool:
        return any(b.name.endswith("toe") for b in self.bodies)

    @property
    def perceptor_names(self) -> tuple[str, ...]:
        return tuple(j.perceptor for j in self.joints)

    @property
    def effector_names(self) -> tuple[str, ...]:
        return tuple(j.effector for j in self.joints)

    @property
    def foot_sensors(self) -> dict[str, str]:
        """Force-resistance perceptor name -> the body it measures (``lf``, ``rf``[, ``lf1``,
        ``rf1``])."""
        sensors = {"lf": "lfoot", "rf": "rfoot"}
        if self.has_toes:
            sensors |= {"lf1": "ltoe", "rf1": "rtoe"}
        return sensors

    def body(self, name: str) -> BodySpec:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(f"no body {name!r}; bodies: {[b.name for b in self.bodies]}")

    def joint(self, name: str) -> JointSpec:
        """The joint with this perceptor or effector name."""
        for j in self.joints:
            if name in (j.perceptor, j.effector):
                return j
        raise KeyError(f"no joint {name!r}; perceptors: {list(self.perceptor_names)}")

    def sole_height(self) -> float:
        """Distance from the torso centre down to the sole in the zero pose."""
        foot = self.body("rfoot")
        return -(foot.centre[2] - foot.size[2] / 2)


# --------------------------------------------------------------------------------------------
# Type 0 tables (right side; the left side mirrors x and has its own axes and limits)
# --------------------------------------------------------------------------------------------

_TORSO_HEAD_BODIES = (
    BodySpec("torso", "box", (0.1, 0.1, 0.18), 1.2171, (0.0, 0.0, 0.0), True),
    BodySpec("neck", "capsule", (0.015, 0.08), 0.05, (0.0, 0.0, 0.09), True),
    BodySpec("head", "sphere", (0.065,), 0.35, (0.0, 0.0, 0.155), True),
)

#: (name without side prefix, shape, size, mass, right-side centre, collider)
_LIMB_BODIES: tuple[tuple[str, Shape, tuple[float, ...], float, Vec3, bool], ...] = (
    ("shoulder", "sphere", (0.01,), 0.07, (0.098, 0.0, 0.075), False),
    ("upperarm", "box", (0.07, 0.08, 0.06), 0.15, (0.108, 0.02, 0.075), True),
    ("elbow", "sphere", (0.01,), 0.035, (0.098, 0.09, 0.084), False),
    ("lowerarm", "box", (0.05, 0.11, 0.05), 0.2, (0.098, 0.14, 0.084), True),
    ("hip1", "sphere", (0.01,), 0.09, (0.055, -0.01, -0.115), False),
    ("hip2", "sphere", (0.01,), 0.125, (0.055, -0.01, -0.115), False),
    ("thigh", "box", (0.07, 0.07, 0.14), 0.275, (0.055, 0.0, -0.155), True),
    ("shank", "box", (0.08, 0.07, 0.11), 0.225, (0.055, 0.005, -0.28), True),
    ("ankle", "sphere", (0.01,), 0.125, (0.055, -0.005, -0.335), False),
    ("foot", "box", (0.08, 0.16, 0.02), 0.2, (0.055, 0.025, -0.375), True),
)

_HEAD_JOINTS = (
    JointSpec("hj1", "he1", "neck", "torso", (0.0, 0.0, 0.09), (0.0, 0.0, 1.0), -120, 120),
    JointSpec("hj2", "he2", "head", "neck", (0.0, 0.0, 0.15), (1.0, 0.0, 0.0), -45, 45),
)

_S = 0.7071
#: (joint number, child, parent, right anchor, right axis, right limits, left axis, left limits)
_ARM_JOINTS: tuple[tuple[int, str, str, Vec3, Vec3, tuple[float, float], Vec3, tuple], ...] = (
    (1, "shoulder", "torso", (0.098, 0.0, 0.075), (1, 0, 0), (-120, 120), (1, 0, 0), (-120, 120)),
    (2, "upperarm", "shoulder", (0.098, 0.0, 0.075), (0, 0, 1), (-95, 1), (0, 0, 1), (-1, 95)),
    (3, "elbow", "upperarm", (0.098, 0.09, 0.084), (0, 1, 0), (-120, 120), (0, 1, 0), (-120, 120)),
    (4, "lowerarm", "elbow", (0.098, 0.09, 0.084), (0, 0, 1), (-1, 90), (0, 0, 1), (-90, 1)),
)
_LEG_JOINTS: tuple[tuple[int, str, str, Vec3, Vec3, tuple[float, float], Vec3, tuple], ...] = (
    (1, "hip1", "torso", (0.055, -0.01, -0.115), (-_S, 0, _S), (-90, 1), (-_S, 0, -_S), (-90, 1)),
    (2, "hip2", "hip1", (0.055, -0.01, -0.115), (0, 1, 0), (-45, 25), (0, 1, 0), (-25, 45)),
    (3, "thigh", "hip2", (0.055, -0.01, -0.115), (1, 0, 0), (-25, 100), (1, 0, 0), (-25, 100)),
    (4, "shank", "thigh", (0.055, -0.005, -0.235), (1, 0, 0), (-130, 1), (1, 0, 0), (-130, 1)),
    (5, "ankle", "shank", (0.055, -0.005, -0.335), (1, 0, 0), (-45, 75), (1, 0, 0), (-45, 75)),
    (6, "foot", "ankle", (0.055, -0.005, -0.34), (0, 1, 0), (-25, 45), (0, 1, 0), (-45, 25)),
)


@dataclass(frozen=True, slots=True)
class TypeOffsets:
    """The per-type differences of the facts' hetero table."""

    hip_x: float = 0.055
    thigh_rel_hip2_z: float = -0.04
    ankle_rel_shank_z: float = -0.055
    elbow_rel_upperarm_y: float = 0.07
    lj5_max_speed: float = DEFAULT_MAX_SPEED
    lj6_max_speed: float = DEFAULT_MAX_SPEED
    toe_length: float | None = None


TYPE_OFFSETS: dict[int, TypeOffsets] = {
    0: TypeOffsets(),
    1: TypeOffsets(
        thigh_rel_hip2_z=-0.05832, ankle_rel_shank_z=-0.07332, elbow_rel_upperarm_y=0.10664
    ),
    2: TypeOffsets(lj5_max_speed=8.80667, lj6_max_speed=3.47234),
    3: TypeOffsets(
        hip_x=0.072954143,
        thigh_rel_hip2_z=-0.067868424,
        ankle_rel_shank_z=-0.082868424,
        elbow_rel_upperarm_y=0.125736848,
    ),
    4: TypeOffsets(toe_length=0.035517656),
}

#: Which type-0 offset shifts each limb part (its body centre and the anchor of the joint that
#: moves it): everything below a lengthened segment moves with it.
_ELBOW_PARTS = frozenset({"elbow", "lowerarm"})
_THIGH_PARTS = frozenset({"thigh", "shank", "ankle", "foot", "toe"})
_ANKLE_PARTS = frozenset({"ankle", "foot", "toe"})
_LEG_PARTS = frozenset({"hip1", "hip2"}) | _THIGH_PARTS


def _shift(part: str, point: Vec3, off: TypeOffsets) -> Vec3:
    """Move a right-side type-0 point of limb part ``part`` to where robot type ``off`` has it."""
    base = TYPE_OFFSETS[0]
    x, y, z = point
    if part in _LEG_PARTS:
        x += off.hip_x - base.hip_x
    if part in _THIGH_PARTS:
        z += off.thigh_rel_hip2_z - base.thigh_rel_hip2_z
    if part in _ANKLE_PARTS:
        z += off.ankle_rel_shank_z - base.ankle_rel_shank_z
    if part in _ELBOW_PARTS:
        y += off.elbow_rel_upperarm_y - base.elbow_rel_upperarm_y
    return (x, y, z)


def _mirror(point: Vec3, sign: int) -> Vec3:
    return (sign * point[0], point[1], point[2])


def _limb_bodies(off: TypeOffsets, prefix: str, sign: int) -> list[BodySpec]:
    bodies = []
    for part, shape, size, mass, centre, collider in _LIMB_BODIES:
        centre = _shift(part, centre, off)
        if part == "foot" and off.toe_length is not None:
            bodies.extend(_split_foot(off.toe_length, size, mass, centre, prefix, sign))
            continue
        bodies.append(BodySpec(prefix + part, shape, size, mass, _mirror(centre, sign), collider))
    return bodies


def _split_foot(
    toe: float, size: tuple[float, ...], mass: float, centre: Vec3, prefix: str, sign: int
) -> list[BodySpec]:
    """Type 4: the front ``toe`` metres of the foot box become a half-height toe box at the sole,
    with the same density (so foot + toe keep the type-0 foot's mass)."""
    sx, sy, sz = size
    density = mass / (sx * sy * sz)
    foot_size = (sx, sy - toe, sz)
    toe_size = (sx, toe, sz / 2)
    x, y, z = centre
    foot_centre = (x, y - toe / 2, z)
    toe_centre = (x, y + sy / 2 - toe / 2, z - sz / 4)
    toe_mass = density * toe_size[0] * toe_size[1] * toe_size[2]
    return [
        BodySpec(
            prefix + "foot", "box", foot_size, mass - toe_mass, _mirror(foot_centre, sign), True
        ),
        BodySpec(prefix + "toe", "box", toe_size, toe_mass, _mirror(toe_centre, sign), True),
    ]


def _limb_joints(
    table: tuple, letter: str, prefix: str, sign: int, off: TypeOffsets, bodies: dict[str, BodySpec]
) -> list[JointSpec]:
    side = "r" if sign > 0 else "l"
    joints = []
    for number, child, parent, anchor, r_axis, r_lim, l_axis, l_lim in table:
        axis, lim = (r_axis, r_lim) if sign > 0 else (l_axis, l_lim)
        anchor = _shift(child, anchor, off)
        speed = DEFAULT_MAX_SPEED
        if letter == "l" and number == 5:
            speed = off.lj5_max_speed
        if letter == "l" and number == 6:
            speed = off.lj6_max_speed
            if off.toe_length is not None:
                # The ankle-roll anchor keeps its place relative to the (shortened) foot centre.
                anchor = (anchor[0], anchor[1] - off.toe_length / 2, anchor[2])
        parent_name = parent if parent == "torso" else prefix + parent
        joints.append(
            JointSpec(
                f"{side}{letter}j{number}",
                f"{side}{letter}e{number}",
                prefix + child,
                parent_name,
                _mirror(anchor, sign),
                tuple(float(a) for a in axis),
                float(lim[0]),
                float(lim[1]),
                speed,
            )
        )
    if letter == "l" and off.toe_length is not None:
        foot = bodies[prefix + "foot"]
        front = foot.centre[1] + foot.size[1] / 2
        sole = foot.centre[2] - foot.size[2] / 2
        joints.append(
            JointSpec(
                f"{side}lj7",
                f"{side}le7",
                prefix + "toe",
                prefix + "foot",
                (foot.centre[0], front, sole),
                (1.0, 0.0, 0.0),
                -1.0,
                70.0,
            )
        )
    return joints


@cache
def _build(robot_type: int) -> RobotSpec:
    off = TYPE_OFFSETS[robot_type]
    right = _limb_bodies(off, "r", 1)
    left = _limb_bodies(off, "l", -1)
    bodies = (*_TORSO_HEAD_BODIES, *right, *left)
    by_name = {b.name: b for b in bodies}
    joints = (
        *_HEAD_JOINTS,
        *_limb_joints(_ARM_JOINTS, "a", "r", 1, off, by_name),
        *_limb_joints(_ARM_JOINTS, "a", "l", -1, off, by_name),
        *_limb_joints(_LEG_JOINTS, "l", "r", 1, off, by_name),
        *_limb_joints(_LEG_JOINTS, "l", "l", -1, off, by_name),
    )
    return RobotSpec(robot_type, bodies, joints)


def robot_spec(robot_type: int) -> RobotSpec:
    """The full description of robot type ``robot_type`` (0-4)."""
    if isinstance(robot_type, bool) or robot_type not in ROBOT_TYPES:
        raise ValueError(f"robot type must be one of 0, 1, 2, 3, 4; got {robot_type!r}")
    return _build(robot_type)
