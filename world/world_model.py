"""Everything an agent knows, rebuilt from perception messages only.

:class:`WorldModel` takes each parsed :class:`~world.perception.Perception` and keeps: the
robot's own body (:class:`~world.robot_state.RobotState`, forward kinematics of this cycle), the
game state, its pose on the field (:mod:`world.localization`), the ball (:mod:`world.ball_model`),
the other robots (:mod:`world.players`) and what was heard. It never looks at the simulator.

Frames used here:

* **torso** (native): origin at the torso centre, x = the robot's right, y = forward, z = up,
  turning and tilting with the torso. Forward kinematics and ``ball.relative`` use it.
* **ego**: same origin, levelled: x forward along the ground, y to the left, z up (the torso's
  level frame turned to the usual ground-robot axes; ``world.kinematics.level_rotation``).
* **team** (field): x towards the opponent goal, y to the left, z up, origin at the centre
  spot. For the right team every world position is mirrored: (x, y) -> (-x, -y).

Cost: :meth:`WorldModel.update` reads the body sensors, the tilt and the gyro's turn every
cycle; the kinematics is computed when first asked for in a cycle (always when an image
comes); vision work (one array of all polars, a few small filter updates) happens only every
third cycle, when an image comes. ``benchmarks/localization.py`` measures it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from world.ball_model import BallModel
from world.field_geometry import BALL_RADIUS
from world.kinematics import kinematic_model, level_rotation, polar_to_camera
from world.localization import Localizer, Pose2D
from world.perception import Heard, Perception, Vision
from world.players import PlayerTracker
from world.robot_state import CYCLE_SECONDS, RobotState

__all__ = ["WorldModel"]

Array = NDArray[np.float64]

#: Other robots whose parts are this close (m) to the own torso are the robot's own arms.
OWN_PARTS_DISTANCE = 0.6
#: Longest gap between two perceptions that still counts as continuous time (s).
MAX_CYCLE_GAP = 0.5


class WorldModel:
    """The agent's belief about itself and the game, updated once per perception.

    ``robot_type`` picks the kinematic model (0-4, as sent in ``scene``). ``team_name`` tells
    teammates from opponents among the robots vision reports; without it the model learns it
    from the robot's own arms (vision reports them under the own team and number).
    """

    def __init__(self, robot_type: int = 0, team_name: str | None = None) -> None:
        self.robot = RobotState(robot_type)
        self.team_name = team_name
        self._kinematics = kinematic_model(self.robot.spec)
        self._head_index = self._kinematics.body_names.index("head")
        self._feet = [
            i
            for i, b in enumerate(self.robot.spec.bodies)
            if b.name.endswith(("foot", "toe")) and b.shape == "box"
        ]
        self._sole_corners = np.array(
            [_bottom_corners(self.robot.spec.bodies[i].size) for i in self._feet]
        )  # (feet, 4, 4) homogeneous points in each foot's frame

        self.time: float | None = None
        self.game_time = 0.0
        self.play_mode = "BeforeKickOff"
        self.side: str | None = None
        self.unum: int | None = None
        self.score_left = 0
        self.score_right = 0
        self.heard: list[Heard] = []
        self.localizer = Localizer()
        self.ball = BallModel()
        self.teammates = PlayerTracker()
        self.opponents = PlayerTracker()
        #: time of the last See perceptor
        self.last_vision_time: float | None = None
        self._joints: dict[str, float] = {}
        self._transform_array: Array | None = None
        self._body_transforms: dict[str, Array] | None = None
        self._torso_height: float | None = None
        self._level = np.eye(3)

    # ------------------------------------------------------------------ the cycle
    def update(self, perception: Perception) -> None:
        """Take one perception message (already parsed)."""
        dt = self._advance_time(perception.time)
        self._read_game_state(perception)
        self.robot.update(perception, dt)
        # kinematics is computed when first needed in this cycle (vision, or a reader)
        self._joints = perception.joints
        self._transform_array = self._body_transforms = self._torso_height = None
        self._level = level_rotation(self.robot.up)
        gyro = self.robot.gyro_deg_s
        turn_rate = float(gyro @ self.robot.up)  # about the world's vertical
        self.localizer.predict(turn_rate, dt)
        self.heard = perception.heard
        if perception.vision is not None:
            self._see(perception.vision)
        self.ball.predict(self.time)

    def _advance_time(self, now: float) -> float:
        previous, self.time = self.time, now
        if previous is None:
            return CYCLE_SECONDS
        dt = now - previous
        return dt if 0.0 < dt <= MAX_CYCLE_GAP else CYCLE_SECONDS

    def _read_game_state(self, perception: Perception) -> None:
        gs = perception.game_state
        self.game_time = gs.game_time
        self.play_mode = gs.play_mode
        self.score_left, self.score_right = gs.score_left, gs.score_right
        if gs.unum is not None:
            self.unum = gs.unum
        if gs.team is not None and gs.team != self.side:
            self.side = gs.team
            self.localizer.set_side(gs.team)
            self.ball.reset()  # its positions were in the other frame
            self.teammates.forget()
            self.opponents.forget()

    @property
    def _transforms(self) -> Array:
        """This cycle's forward kinematics, (bodies, 4, 4) in spec order."""
        if self._transform_array is None:
            self._transform_array = self._kinematics.transforms(self._joints)
        return self._transform_array

    @property
    def torso_height(self) -> float:
        """Height of the torso centre above the ground (m): above the lowest sole corner,
        from this cycle's kinematics and tilt (so it assumes a foot is on the ground)."""
        if self._torso_height is None:
            self._torso_height = self._height_above_feet()
        return self._torso_height

    def _height_above_feet(self) -> float:
        """The torso's height above the lowest sole corner, measured along the vertical."""
        # only the vertical matters: the level frame's z row applied to each foot's transform
        vertical = self._level[2] @ self._transforms[self._feet, :3, :]  # (feet, 4)
        heights = np.einsum("fj,fcj->fc", vertical, self._sole_corners)
        return float(-heights.min())

    # ------------------------------------------------------------------ vision
    def _see(self, vision: Vision) -> None:
        self.last_vision_time = self.time
        names = list(vision.landmarks)
        polars = [(p.distance, p.phi, p.theta) for p in vision.landmarks.values()]
        ball_row = len(polars)
        if vision.ball is not None:
            b = vision.ball
            polars.append((b.distance, b.phi, b.theta))
        line_row = len(polars)
        for begin, end in vision.lines:
            polars.append((begin.distance, begin.phi, begin.theta))
            polars.append((end.distance, end.phi, end.theta))
        part_row = len(polars)
        for player in vision.players:
            polars.extend((p.distance, p.phi, p.theta) for p in player.parts.values())
        if not polars:
            return
        camera = self._transforms[self._head_index]
        torso_points = polar_to_camera(np.array(polars)) @ camera[:3, :3].T + camera[:3, 3]
        level = torso_points @ self._level.T
        ego = np.column_stack([level[:, 1], -level[:, 0], level[:, 2]])

        if not self.robot.is_fallen:
            landmarks = {name: (ego[i, 0], ego[i, 1]) for i, name in enumerate(names)}
            lines = ego[line_row:part_row, :2].reshape(-1, 2, 2)
            self.localizer.update(landmarks, lines, self.time)
        pose = self.localizer.pose
        if vision.players:
            self._see_players(vision, ego[part_row:], pose)
        if vision.ball is not None and pose is not None:
            self._see_ball(ego[ball_row], torso_points[ball_row], pose)

    def _see_ball(self, ego: Array, torso_point: Array, pose: Pose2D) -> None:
        position = self._ego_to_field(ego, pose)
        self.ball.relative = torso_point
        self.ball.height = float(position[2])
        self.ball.observe(
            (float(position[0]), float(position[1])),
            float(math.hypot(ego[0], ego[1])),
            self.time,
            pose.sigma_xy,
        )

    def _see_players(self, vision: Vision, ego: Array, pose: Pose2D | None) -> None:
        # one array operation for every part of every robot, then plain lists per robot
        ego_rows = ego.tolist()
        field_rows = self._ego_to_field(ego, pose).tolist() if pose is not None else None
        row = 0
        for player in vision.players:
            start, row = row, row + len(player.parts)
            if self._is_own_body(player.team, player.unum, ego_rows[start:row]):
                if self.team_name is None:
                    self.team_name = player.team  # the own arms carry the own team name
                continue
            if self.team_name is None or field_rows is None:
                continue
            parts = dict(zip(player.parts, map(tuple, field_rows[start:row]), strict=True))
            tracker = self.teammates if player.team == self.team_name else self.opponents
            tracker.observe(player.team, player.unum, parts, self.time)

    def _is_own_body(self, team: str, unum: int, ego: list[list[float]]) -> bool:
        """Vision reports the robot's own lower arms like another robot's parts: same number,
        (once known) same team, every part within arm's reach of the torso."""
        if unum != self.unum or (self.team_name is not None and team != self.team_name):
            return False
        return all(math.hypot(p[0], p[1]) < OWN_PARTS_DISTANCE for p in ego)

    def _ego_to_field(self, ego: Array, pose: Pose2D) -> Array:
        """Ego-frame point(s) (..., 3) -> team-frame point(s), z above the ground."""
        h = math.radians(pose.heading_deg)
        c, s = math.cos(h), math.sin(h)
        ego = np.asarray(ego, dtype=float)
        x = pose.x + c * ego[..., 0] - s * ego[..., 1]
        y = pose.y + s * ego[..., 0] + c * ego[..., 1]
        return np.stack([x, y, ego[..., 2] + self.torso_height], axis=-1)

    # ------------------------------------------------------------------ outputs
    @property
    def pose(self) -> Pose2D | None:
        """The robot's pose in the team frame, None before the first fix."""
        return self.localizer.pose

    @property
    def score_own(self) -> int:
        return self.score_right if self.side == "right" else self.score_left

    @property
    def score_opponent(self) -> int:
        return self.score_left if self.side == "right" else self.score_right

    @property
    def body_transforms(self) -> dict[str, Array]:
        """Body name -> 4x4 transform of its centre relative to the torso (this cycle)."""
        if self._body_transforms is None:
            self._body_transforms = dict(
                zip(self._kinematics.body_names, self._transforms, strict=True)
            )
        return self._body_transforms

    @property
    def camera_transform(self) -> Array:
        """4x4 transform of the camera (head centre) relative to the torso (this cycle)."""
        return self._transforms[self._head_index]

    @property
    def level_rotation(self) -> Array:
        """Rotation taking torso-frame vectors into the torso's level frame (this cycle)."""
        return self._level

    def to_ego(self, point_relative_to_torso: ArrayLike) -> Array:
        """A torso-frame point (native axes) in the ego frame (x forward, y left, z up)."""
        level = self._level @ np.asarray(point_relative_to_torso, dtype=float)
        return np.array([level[1], -level[0], level[2]])

    def to_field(self, point_relative_to_torso: ArrayLike) -> Array:
        """A torso-frame point (native axes, m) on the field: team frame (x, y, z above the
        ground). Raises ValueError before the robot knows where it is."""
        pose = self._require_pose()
        return self._ego_to_field(self.to_ego(point_relative_to_torso), pose)

    def to_relative(self, field_point: Sequence[float]) -> Array:
        """A team-frame point ((x, y) on the ground, or (x, y, z)) in the torso frame (native
        axes). Raises ValueError before the robot knows where it is."""
        pose = self._require_pose()
        x, y = float(field_point[0]), float(field_point[1])
        z = float(field_point[2]) if len(field_point) > 2 else 0.0
        h = math.radians(pose.heading_deg)
        c, s = math.cos(h), math.sin(h)
        dx, dy = x - pose.x, y - pose.y
        forward, left = c * dx + s * dy, -s * dx + c * dy
        level = np.array([-left, forward, z - self.torso_height])
        return self._level.T @ level

    def distance_to(self, field_point: Sequence[float]) -> float:
        """Distance along the ground from the torso to a team-frame point (m)."""
        pose = self._require_pose()
        return math.hypot(field_point[0] - pose.x, field_point[1] - pose.y)

    def bearing_to(self, field_point: Sequence[float]) -> float:
        """Direction of a team-frame point relative to the torso's heading (deg, + = left)."""
        pose = self._require_pose()
        angle = math.degrees(math.atan2(field_point[1] - pose.y, field_point[0] - pose.x))
        return (angle - pose.heading_deg + 180.0) % 360.0 - 180.0

    def _require_pose(self) -> Pose2D:
        pose = self.localizer.pose
        if pose is None:
            raise ValueError("the robot does not know where it is yet (no image with 2 landmarks)")
        return pose

    @property
    def ball_relative_ego(self) -> Array | None:
        """The ball estimate now in the ego frame (x forward, y left, z = its centre's height
        relative to the torso), or None if the ball or the pose is unknown."""
        position = self.ball.position
        pose = self.localizer.pose
        if position is None or pose is None:
            return None
        return self.to_ego(self.to_relative((position[0], position[1], BALL_RADIUS)))


def _bottom_corners(size: tuple[float, ...]) -> Array:
    """The four bottom corners of a box of ``size`` around its centre, homogeneous (4, 4)."""
    sx, sy, sz = size
    return np.array([[cx * sx / 2, cy * sy / 2, -sz / 2, 1.0] for cx in (-1, 1) for cy in (-1, 1)])
