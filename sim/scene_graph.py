"""The monitor protocol's scene graph: what rcssserver3d 0.7.2 sends on port 3200.

RoboViz and other monitor tools draw a game from these messages alone, so our server writes the
same node types, mesh files, materials, tree shape and node order as the real server
(``soccer.rsg`` for the field, ``nao_hetero.rsg`` and its ``naoneckhead``/``naoarm``/``naoleg``/
``naolegtoe`` parts for each robot), checked against the recorded messages in
``shared/reference/rcssserver3d-traces`` (07, 07b, 08, ``raw_monitor_*``).

Message forms (see ``protocol-facts.md``, section Monitor):

- full state: ``(HEADER)(RSG 0 1)(TREE)`` where HEADER holds the static settings
  (``FieldLength`` ... ``play_modes``) and every dynamic key; the tree writes every node with
  all its data: ``(nd TRF (SLT m0 .. m15) CHILD...)`` (a column-major 4x4 matrix relative to
  the parent), ``(nd StaticMesh ...)``, ``(nd SMN ...)`` (a primitive with one material) and
  ``(nd Light ...)``.
- update: ``((time T) CHANGED-KEYS)(RDS 0 1)(TREE)`` with exactly the shape of the last full
  state: every node is ``(nd ...)``; a transform carries ``(SLT ...)`` only when one of its 16
  numbers moved more than 0.005 since it was last sent (the real server's ``precision``);
  meshes carry ``(setVisible v)`` in the first update after a full state only (as recorded).

Nodes the real server writes but that hold nothing visible are kept, because monitors walk the
update tree by position: the goals' six collider transforms, the four corner-flag transforms,
the 21 field-line transforms and, for a robot, the selection-marker cylinder (invisible).

A robot's subtree: an identity transform (the agent's node, there from the moment the agent
connected), then one transform per body in the server's order (torso, neck, head, right arm,
left arm, right leg, left leg) holding the body's world pose. Torso and head meshes sit under
one more fixed transform, ``(setLocalRotation -90 0 180)``, that
turns the mesh files' axes into the model's; all other meshes hang directly below their body.

Body poses use the model's native frame (``nao-model-facts.md``): x = the robot's right,
y = forward, z = up, origin at the body centre; a robot standing upright facing world +y has
identity rotations. The numbers are written like C++ streams write floats (``%g``: six
significant digits, ``-4.37114e-08``, ``1``, ``-0``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from world.field_geometry import (
    BALL_MASS,
    BALL_RADIUS,
    FIELD_LENGTH,
    FIELD_WIDTH,
    FREE_KICK_DISTANCE,
    GOAL_DEPTH,
    GOAL_HEIGHT,
    GOAL_WIDTH,
    HALF_LENGTH,
    HALF_WIDTH,
)
from world.nao_model import ROBOT_TYPES, TYPE_OFFSETS
from world.play_modes import PLAY_MODES, play_mode_index

#: A 4x4 homogeneous transform (rows/columns as in mathematics: translation in ``m[:3, 3]``).
Matrix4 = np.ndarray
Side = Literal["left", "right"]
RGBA = tuple[float, float, float, float]
Vec3 = tuple[float, float, float]

#: A transform is re-sent when any of its 16 numbers moved more than this since last sent.
SLT_PRECISION = 0.005

_IDENTITY = np.eye(4)


def format_number(value: float) -> str:
    """A number as the real server writes it (C++ ``ostream`` default: ``%g``, 6 digits)."""
    return format(value, "g")


def rsg_rotation(x_deg: float, y_deg: float, z_deg: float) -> Matrix4:
    """The matrix of the rsg command ``(setLocalRotation x y z)``: ``Rx @ Ry @ Rz``.

    Computed in float32 as the server does, so static matrices print the same tiny residues
    (``-4.37114e-08`` for cos 90 deg) as the recorded messages.
    """
    f32 = np.float32

    def axis_rotation(deg: float, first: int, second: int) -> np.ndarray:
        angle = f32(deg) * f32(math.pi) / f32(180)
        c, s = np.cos(angle, dtype=f32), np.sin(angle, dtype=f32)
        m = np.eye(4, dtype=f32)
        m[first, first], m[first, second] = c, -s
        m[second, first], m[second, second] = s, c
        return m

    rx = axis_rotation(x_deg, 1, 2)
    ry = axis_rotation(y_deg, 2, 0)
    rz = axis_rotation(z_deg, 0, 1)
    return (rx @ ry @ rz).astype(np.float64)


def translation(x: float, y: float, z: float) -> Matrix4:
    """A pure translation (``setLocalPos x y z``)."""
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


# ----------------------------------------------------------------------------- header


@dataclass(frozen=True, slots=True)
class MonitorHeader:
    """The game-state part of a monitor message.

    The dynamic keys (``time`` ... ``team_right``) change during a game; the rest are the
    settings the real server sends once per full state (values of rcssserver3d 0.7.2; note that
    ``BorderSize`` is reported as 0 there). ``play_mode`` is a name of :data:`PLAY_MODES` (an
    index is accepted too); the wire carries its index. A team name of ``None`` is not known yet
    and is left out.
    """

    time: float = 0.0
    half: int = 1
    score_left: int = 0
    score_right: int = 0
    play_mode: str | int = "BeforeKickOff"
    team_left: str | None = None
    team_right: str | None = None
    field_length: float = FIELD_LENGTH
    field_width: float = FIELD_WIDTH
    field_height: float = 40.0
    goal_width: float = GOAL_WIDTH
    goal_depth: float = GOAL_DEPTH
    goal_height: float = GOAL_HEIGHT
    border_size: float = 0.0
    free_kick_distance: float = FREE_KICK_DISTANCE
    wait_before_kick_off: float = 30.0
    agent_radius: float = 0.4
    ball_radius: float = BALL_RADIUS
    ball_mass: float = BALL_MASS
    rule_goal_pause_time: float = 3.0
    rule_kick_in_pause_time: float = 1.0
    rule_half_time: float = 300.0
    play_modes: tuple[str, ...] = PLAY_MODES

    def play_mode_index(self) -> int:
        """The play mode as the wire encodes it (an index into ``play_modes``)."""
        mode = self.play_mode
        if isinstance(mode, int) and not isinstance(mode, bool):
            if not 0 <= mode < len(self.play_modes):
                raise ValueError(f"play mode index {mode} outside 0..{len(self.play_modes) - 1}")
            return mode
        if mode in self.play_modes:
            return self.play_modes.index(mode)
        return play_mode_index(str(mode))  # raises with the list of valid names

    def settings(self) -> list[tuple[str, str]]:
        """The static keys in the real server's order, values already written."""
        numbers = (
            ("FieldLength", self.field_length),
            ("FieldWidth", self.field_width),
            ("FieldHeight", self.field_height),
            ("GoalWidth", self.goal_width),
            ("GoalDepth", self.goal_depth),
            ("GoalHeight", self.goal_height),
            ("BorderSize", self.border_size),
            ("FreeKickDistance", self.free_kick_distance),
            ("WaitBeforeKickOff", self.wait_before_kick_off),
            ("AgentRadius", self.agent_radius),
            ("BallRadius", self.ball_radius),
            ("BallMass", self.ball_mass),
            ("RuleGoalPauseTime", self.rule_goal_pause_time),
            ("RuleKickInPauseTime", self.rule_kick_in_pause_time),
            ("RuleHalfTime", self.rule_half_time),
        )
        items = [(key, format_number(value)) for key, value in numbers]
        items.append(("play_modes", " ".join(self.play_modes)))
        return items

    def dynamic(self) -> dict[str, str]:
        """The dynamic keys in the real server's order (``time`` first), values written; team
        names only when known."""
        items = {"time": format_number(self.time)}
        if self.team_left:
            items["team_left"] = self.team_left
        if self.team_right:
            items["team_right"] = self.team_right
        items["half"] = str(int(self.half))
        items["score_left"] = str(int(self.score_left))
        items["score_right"] = str(int(self.score_right))
        items["play_mode"] = str(self.play_mode_index())
        return items


def _write_header(items: list[tuple[str, str]]) -> str:
    return "(" + "".join(f"({key} {value})" for key, value in items) + ")"


# ----------------------------------------------------------------------------- nodes


@dataclass(eq=False, slots=True)
class _Light:
    diffuse: RGBA
    ambient: RGBA
    specular: RGBA


@dataclass(eq=False, slots=True)
class _Mesh:
    """A ``StaticMesh`` (a model file with its own materials) or, with ``single_material``, an
    ``SMN`` (a primitive such as ``StdUnitSphere`` drawn in one material)."""

    load: str
    scale: Vec3
    materials: tuple[str, ...]
    params: tuple[str, ...] = ()
    single_material: bool = False
    visible: bool = True
    transparent: bool = False


@dataclass(eq=False, slots=True)
class _Transform:
    """A ``TRF`` node; ``sent`` is the matrix the monitors last received (None: never).

    ``dynamic`` transforms (ball, robot bodies) get a new ``matrix`` every message; the others
    never move, so updates skip comparing them.
    """

    matrix: Matrix4
    children: list[_Node] = field(default_factory=list)
    sent: Matrix4 | None = None
    dynamic: bool = False


_Node = _Transform | _Mesh | _Light


def _rgba(values: RGBA) -> str:
    return " ".join(format_number(v) for v in values)


_SLT_FORMAT = " (SLT " + " ".join(["{:g}"] * 16) + ")"


def _slt(matrix: Matrix4) -> str:
    """`` (SLT m0 .. m15)`` with the matrix written column by column (one format call: this
    is the hot spot of a monitor message)."""
    return _SLT_FORMAT.format(*matrix.ravel(order="F").tolist())


def _write_full(node: _Node, out: list[str]) -> None:
    """Every node with all its data, as in ``(RSG 0 1)``; marks transforms as sent."""
    if isinstance(node, _Transform):
        out.append("(nd TRF" + _slt(node.matrix))
        node.sent = np.array(node.matrix, dtype=np.float64)
        for child in node.children:
            _write_full(child, out)
        out.append(")")
    elif isinstance(node, _Mesh):
        out.append(_full_mesh(node))
    else:
        out.append(
            f"(nd Light (setDiffuse {_rgba(node.diffuse)}) (setAmbient {_rgba(node.ambient)}) "
            f"(setSpecular {_rgba(node.specular)}))"
        )


def _full_mesh(mesh: _Mesh) -> str:
    kind = "SMN" if mesh.single_material else "StaticMesh"
    parts = [f"(nd {kind} (setVisible {int(mesh.visible)})"]
    if mesh.transparent:
        parts.append(" (setTransparent)")
    parts.append(" (load " + " ".join((mesh.load, *mesh.params)) + ")")
    parts.append(" (sSc " + " ".join(format_number(s) for s in mesh.scale) + ")")
    if mesh.single_material:
        parts.append(f" (sMat {mesh.materials[0]})")
    else:
        parts.append("(resetMaterials " + " ".join(mesh.materials) + ")")
    parts.append(")")
    return "".join(parts)


def _moved(matrix: Matrix4, sent: Matrix4) -> bool:
    """Whether any of the 16 numbers moved more than :data:`SLT_PRECISION` since sent."""
    return bool((abs(matrix - sent) > SLT_PRECISION).any())


def _write_update(node: _Node, out: list[str], with_visibility: bool) -> None:
    """The update form: the same shape, ``(SLT ...)`` only for transforms that moved."""
    if isinstance(node, _Transform):
        sent = node.sent
        if sent is None or (node.dynamic and _moved(node.matrix, sent)):
            out.append("(nd" + _slt(node.matrix))
            node.sent = np.array(node.matrix, dtype=np.float64)
        else:
            out.append("(nd")
        for child in node.children:
            _write_update(child, out, with_visibility)
        out.append(")")
    elif isinstance(node, _Mesh):
        kind = "SMN" if node.single_material else "StaticMesh"
        if with_visibility:
            out.append(f"(nd {kind} (setVisible {int(node.visible)}))")
        else:
            out.append(f"(nd {kind})")
    else:
        out.append("(nd)")


# ----------------------------------------------------------------------------- the field


def _goal(x: float, turn_deg: float, mesh_file: str, colour: str) -> _Transform:
    """A goal (``goal.rsg``): the mesh under a fixed rotation, then six collider transforms
    (side walls, back wall, roof, the two post markers) that have nothing to draw."""
    half_width = GOAL_WIDTH / 2
    mesh = _Mesh(
        mesh_file,
        (GOAL_WIDTH + 0.08, GOAL_HEIGHT + 0.08, GOAL_DEPTH + 0.08),
        ("naogoalnet", colour),
        transparent=True,
    )
    mesh_transform = rsg_rotation(90, 90, 0)
    mesh_transform[:3, 3] = (GOAL_DEPTH / 2, 0.0, -GOAL_HEIGHT / 2)
    colliders = [
        (0.0, -(half_width + 0.02), 0.0),
        (0.0, half_width + 0.02, 0.0),
        (-(GOAL_DEPTH / 2 - 0.02), 0.0, 0.0),
        (0.0, 0.0, GOAL_HEIGHT / 2 + 0.02),
        (GOAL_DEPTH / 2, half_width, GOAL_HEIGHT / 2),
        (GOAL_DEPTH / 2, -half_width, GOAL_HEIGHT / 2),
    ]
    root = rsg_rotation(0, 0, turn_deg)
    root[:3, 3] = (x, 0.0, GOAL_HEIGHT / 2)
    children: list[_Node] = [_Transform(mesh_transform, [mesh])]
    children += [_Transform(translation(*p)) for p in colliders]
    return _Transform(root, children)


def _wall(x: float, y: float, size: Vec3) -> _Transform:
    return _Transform(
        translation(x, y, 0.0),
        [_Mesh("StdUnitBox", size, ("matGrey",), single_material=True)],
    )


#: Field-line transforms the real server keeps at the origin (identity, nothing drawn).
FIELD_LINE_NODES = 21


def _field_nodes(ball: _Transform) -> list[_Node]:
    """The static scene of ``soccer.rsg`` in the server's order, with ``ball`` near the end."""
    field_rotation = rsg_rotation(90, 180, 0)
    border_x = FIELD_LENGTH * 0.333  # the rsg's BorderLength / BorderWidth
    border_y = FIELD_WIDTH * 0.75
    wall_x = HALF_LENGTH + border_x
    wall_y = HALF_WIDTH + border_y
    side_length = 1 + FIELD_LENGTH + 2 * border_x
    side_width = 1 + FIELD_WIDTH + 2 * border_y
    nodes: list[_Node] = [
        _Transform(
            translation(-10, 10, 10),
            [_Light((1, 1, 1, 1), (0.8, 0.8, 0.8, 1), (0.1, 0.1, 0.1, 1))],
        ),
        _Transform(
            translation(10, -10, 10), [_Light((1, 1, 1, 1), (0, 0, 0, 1), (0.1, 0.1, 0.1, 1))]
        ),
        _Transform(
            field_rotation,
            [
                _Mesh(
                    "models/naosoccerfield.obj",
                    (FIELD_LENGTH / 12, 1, FIELD_WIDTH / 8),
                    ("None_rcs-naofield.png",),
                )
            ],
        ),
        _Transform(
            field_rotation.copy(),
            [
                _Mesh(
                    "models/skybox.obj",
                    (10, 10, 10),
                    tuple(f"Material_skyrender_000{i}.tif" for i in range(1, 7)),
                )
            ],
        ),
        _goal(-(HALF_LENGTH + GOAL_DEPTH / 2), 0, "models/leftsoccergoal.obj", "yellow"),
        _goal(HALF_LENGTH + GOAL_DEPTH / 2, 180, "models/rightsoccergoal.obj", "sky-blue"),
        _wall(-wall_x, 0, (1, side_width, 1)),
        _wall(wall_x, 0, (1, side_width, 1)),
        _wall(0, wall_y, (side_length, 1, 1)),
        _wall(0, -wall_y, (side_length, 1, 1)),
    ]
    for x, y in ((-1, 1), (-1, -1), (1, 1), (1, -1)):  # F1L F2L F1R F2R
        nodes.append(_Transform(translation(x * HALF_LENGTH, y * HALF_WIDTH, 0.0)))
    nodes += [_Transform(np.eye(4)) for _ in range(FIELD_LINE_NODES)]
    nodes.append(ball)
    return nodes


def _ball_node() -> _Transform:
    mesh = _Mesh(
        "models/soccerball.obj",
        (BALL_RADIUS, BALL_RADIUS, BALL_RADIUS),
        ("soccerball_rcs-soccerball.png",),
    )
    return _Transform(translation(0, 0, BALL_RADIUS), [mesh], dynamic=True)


# ----------------------------------------------------------------------------- robots

_ARM_PARTS = ("shoulder", "upperarm", "elbow", "lowerarm")
_LEG_PARTS = ("hip1", "hip2", "thigh", "shank", "ankle", "foot")


def body_names(robot_type: int) -> tuple[str, ...]:
    """The bodies of a robot type in the order the real server's scene graph lists them."""
    if robot_type not in ROBOT_TYPES:
        raise ValueError(f"robot type must be one of {ROBOT_TYPES}, got {robot_type!r}")
    legs = _LEG_PARTS + (("toe",) if TYPE_OFFSETS[robot_type].toe_length else ())
    arms = [s + p for s in "rl" for p in _ARM_PARTS]
    return ("torso", "neck", "head", *arms, *(s + p for s in "rl" for p in legs))


@dataclass(frozen=True, slots=True)
class _Identity:
    """What the materials show: team colour and shirt number once the agent sent ``init``."""

    side: Side | None = None
    unum: int | None = None

    @property
    def team(self) -> str:
        return {"left": "matLeft", "right": "matRight"}.get(self.side or "", "matTeam")

    @property
    def number(self) -> str:
        return "matNum" if self.unum is None else f"matNum{self.unum}"


_MESH_ROTATION = rsg_rotation(-90, 0, 180)  # naobody*.obj / naohead.obj axes -> model axes
_JOINT_SPHERE_MATERIAL = {
    "shoulder": "matYellow",
    "elbow": "matYellow",
    "hip1": "matYellow",
    "hip2": "matYellow",
    "ankle": "matRed",
}


def _foot_scales(robot_type: int) -> tuple[Vec3, Vec3]:
    """Scales of the foot mesh and (type 4) of the toe, which reuses the foot mesh squeezed to
    the toe box (``naolegtoe.rsg``), computed in float32 like the server."""
    toe = TYPE_OFFSETS[robot_type].toe_length
    if not toe:
        return (0.08, 0.08, 0.08), (0.08, 0.08, 0.08)
    f32 = np.float32
    foot_y = f32(0.16) - f32(toe)
    foot = (0.08, float(f32(0.08) * (foot_y / f32(0.16))), 0.08)
    toe_scale = (0.08, float(f32(0.08) * (f32(toe) / foot_y)), float(f32(0.08) * f32(0.5)))
    return foot, toe_scale


def _body_visuals(body: str, robot_type: int, who: _Identity) -> list[_Node]:
    """The nodes below one body's transform (``nao_hetero.rsg`` and its parts)."""
    team, t = who.team, robot_type
    if body == "torso":
        mesh = _Mesh(
            f"models/naobody{t}.obj", (0.1, 0.1, 0.1), (who.number, team, f"matType{t}", "naowhite")
        )
        marker = _Mesh(
            "StdUnitCylinder",
            (0.2, 0.2, 0.02),
            ("matSelect",),
            params=("1", "1"),
            single_material=True,
            visible=False,
            transparent=True,
        )
        return [_Transform(_MESH_ROTATION.copy(), [mesh]), _Transform(np.eye(4), [marker])]
    if body == "neck":
        return [
            _Mesh(
                "StdCapsule", (1, 1, 1), ("matDarkGrey",), ("0.015", "0.08"), single_material=True
            )
        ]
    if body == "head":
        mesh = _Mesh(
            "models/naohead.obj", (0.1, 0.1, 0.1), (team, "naoblack", "naogrey", "naowhite")
        )
        return [_Transform(_MESH_ROTATION.copy(), [mesh])]
    side, part = body[0], body[1:]
    if part in _JOINT_SPHERE_MATERIAL:
        material = (_JOINT_SPHERE_MATERIAL[part],)
        return [_Mesh("StdUnitSphere", (0.01, 0.01, 0.01), material, single_material=True)]
    foot_scale, toe_scale = _foot_scales(t)
    meshes = {
        "upperarm": (f"upperarm{t}", (0.07,) * 3, (team, f"matType{t}", "naowhite")),
        "lowerarm": ("lowerarm", (0.05,) * 3, (team, "naowhite")),
        "thigh": ("thigh", (0.07,) * 3, (who.number, team, "naowhite")[side == "l" :]),
        "shank": (f"shank{t}", (0.08,) * 3, (team, f"matType{t}", "naowhite")),
        "foot": ("foot", foot_scale, (team, "naowhite")),
        "toe": ("foot", toe_scale, (team, "naowhite")),
    }
    if part not in meshes:
        raise ValueError(f"no visual for body {body!r}")
    name, scale, materials = meshes[part]
    return [_Mesh(f"models/{side}{name}.obj", scale, materials)]


@dataclass(eq=False, slots=True)
class _Robot:
    """One agent's subtree. ``robot_type`` None: connected, robot not built yet."""

    robot_type: int | None
    identity: _Identity = field(default_factory=_Identity)
    root: _Transform = field(default_factory=lambda: _Transform(np.eye(4)))
    bodies: dict[str, _Transform] = field(default_factory=dict)

    def build(self) -> None:
        """(Re)create the body nodes, e.g. after a material change; poses are kept."""
        self.root.children.clear()
        if self.robot_type is None:
            self.bodies = {}
            return
        old = self.bodies
        self.bodies = {}
        for name in body_names(self.robot_type):
            pose = old[name].matrix if name in old else np.eye(4)
            visuals = _body_visuals(name, self.robot_type, self.identity)
            node = _Transform(pose, visuals, dynamic=True)
            self.bodies[name] = node
            self.root.children.append(node)

    def set_poses(self, robot_id: str, poses: Mapping[str, Matrix4]) -> None:
        for name, node in self.bodies.items():
            try:
                pose = poses[name]
            except KeyError:
                raise KeyError(
                    f"robot {robot_id!r}: no world transform for body {name!r}"
                ) from None
            node.matrix = _as_matrix(pose, f"robot {robot_id!r} body {name!r}")


def _as_matrix(value: Matrix4, what: str) -> Matrix4:
    matrix = np.asarray(value, dtype=np.float64)
    if matrix.shape != (4, 4):
        raise ValueError(f"{what}: expected a 4x4 transform, got shape {matrix.shape}")
    return matrix


# ----------------------------------------------------------------------------- the graph


class SceneGraph:
    """The scene as monitors see it: the static field, the ball and every agent's robot.

    One instance serves all monitors of a session (they all receive the same messages). Call
    :meth:`full_state` or :meth:`update` once per monitor interval with the current world
    transforms; :meth:`update` falls back to a full state by itself when the scene's shape or
    materials changed (robot added, removed or identified) or one was requested.
    """

    def __init__(self) -> None:
        self._ball = _ball_node()
        self._field = _field_nodes(self._ball)
        self._robots: dict[str, _Robot] = {}
        self._needs_full_state = True
        self._visibility_due = False
        self._sent_header: dict[str, str] = {}

    # -- scene changes -----------------------------------------------------------------------
    def add_pending_robot(self, robot_id: str) -> None:
        """An agent that connected but has not chosen its robot yet (no ``scene`` message).

        The real server already shows it as an empty transform at the end of the tree (trace
        07); :meth:`add_robot` later fills that node in place.
        """
        if robot_id in self._robots:
            raise ValueError(f"robot {robot_id!r} is already in the scene")
        self._robots[robot_id] = _Robot(None)
        self._needs_full_state = True

    def add_robot(self, robot_id: str, robot_type: int) -> None:
        """Add the robot of an agent (its ``scene`` message); it shows team-neutral materials
        until :meth:`set_robot_identity`."""
        body_names(robot_type)  # validates the type
        robot = self._robots.get(robot_id)
        if robot is None:
            robot = self._robots[robot_id] = _Robot(robot_type)
        elif robot.robot_type is not None:
            raise ValueError(f"robot {robot_id!r} is already in the scene")
        robot.robot_type = robot_type
        robot.build()
        self._needs_full_state = True

    def set_robot_identity(self, robot_id: str, side: Side, unum: int) -> None:
        """Team colour and number (after ``init``): the materials change, so the next message
        is a full state, as on the real server."""
        if side not in ("left", "right"):
            raise ValueError(f"side must be 'left' or 'right', got {side!r}")
        if isinstance(unum, bool) or not isinstance(unum, int) or unum < 0:
            raise ValueError(f"unum must be a non-negative int, got {unum!r}")
        robot = self._robot(robot_id)
        robot.identity = _Identity(side, unum)
        robot.build()
        self._needs_full_state = True

    def remove_robot(self, robot_id: str) -> None:
        """Remove an agent's robot (disconnect or kill); the next message is a full state."""
        self._robot(robot_id)
        del self._robots[robot_id]
        self._needs_full_state = True

    def request_full_state(self) -> None:
        """Make the next :meth:`update` a full state (a new monitor, or ``(reqfullstate)``)."""
        self._needs_full_state = True

    @property
    def robot_ids(self) -> tuple[str, ...]:
        """The agents in the scene, in tree order."""
        return tuple(self._robots)

    # -- messages ----------------------------------------------------------------------------
    def full_state(
        self, header: MonitorHeader, ball: Matrix4, robots: Mapping[str, Mapping[str, Matrix4]]
    ) -> bytes:
        """``(HEADER)(RSG 0 1)(TREE)`` with every node and every header key."""
        self._set_poses(ball, robots)
        dynamic = header.dynamic()
        out = [_write_header(header.settings() + list(dynamic.items())), "(RSG 0 1)("]
        for node in self._tree():
            _write_full(node, out)
        out.append(")")
        self._sent_header = dynamic
        self._needs_full_state = False
        self._visibility_due = True
        return "".join(out).encode("ascii")

    def update(
        self, header: MonitorHeader, ball: Matrix4, robots: Mapping[str, Mapping[str, Matrix4]]
    ) -> bytes:
        """``((time T) CHANGED)(RDS 0 1)(TREE)``, or a full state when one is due."""
        if self._needs_full_state:
            return self.full_state(header, ball, robots)
        self._set_poses(ball, robots)
        dynamic = header.dynamic()
        changed = [
            (key, value)
            for key, value in dynamic.items()
            if key == "time" or self._sent_header.get(key) != value
        ]
        out = [_write_header(changed), "(RDS 0 1)("]
        for node in self._tree():
            _write_update(node, out, self._visibility_due)
        out.append(")")
        self._sent_header.update(dynamic)
        self._visibility_due = False
        return "".join(out).encode("ascii")

    # -- helpers -----------------------------------------------------------------------------
    def _robot(self, robot_id: str) -> _Robot:
        try:
            return self._robots[robot_id]
        except KeyError:
            raise KeyError(
                f"robot {robot_id!r} is not in the scene; robots: {list(self._robots)}"
            ) from None

    def _tree(self) -> list[_Node]:
        return [*self._field, *(robot.root for robot in self._robots.values())]

    def _set_poses(self, ball: Matrix4, robots: Mapping[str, Mapping[str, Matrix4]]) -> None:
        unknown = set(robots) - set(self._robots)
        if unknown:
            raise KeyError(f"transforms for robots not in the scene: {sorted(unknown)}")
        self._ball.matrix = _as_matrix(ball, "ball")
        for robot_id, robot in self._robots.items():
            if robot.robot_type is None:
                continue
            if robot_id not in robots:
                raise KeyError(f"no body transforms for robot {robot_id!r}")
            robot.set_poses(robot_id, robots[robot_id])
