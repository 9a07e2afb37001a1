"""The basic kick: walk to the ball, line the chosen foot up behind it, kick it a set distance.

``execute("basic_kick", target_x, target_y, distance)`` kicks the ball towards the team-frame
point ``(target_x, target_y)``; ``distance`` is metres (the short kick, controllable over the
calibrated range of ``kicks.yaml``, 3-9 m asked by the issue) or ``"long"`` (the strongest
kick). Everything comes from the world model (ball estimate, own pose, joint angles): the skill
never sees the simulator.

Phases, one per cycle:

1. ``approach``: the ``walk`` skill to the spot from which the chosen foot lies behind the
   ball on the line ball -> target, facing the target. The foot is chosen once, at the start:
   the one on the side where the ball lies, so the robot steps less across.
2. ``align``: small ``walk_velocity`` corrections from the measured error between the ball and
   where the kick expects it relative to the foot (``ball_gap_m``, ``ball_side_m`` of the kick),
   both measured in the robot's own frame from this cycle's joint angles, so that the walk's
   stopping error (a few cm) does not decide where the foot meets the ball. Then it stands
   still.
3. ``kick``: the ``kick`` skill with the strength that the kick's calibration table gives for
   the distance.

If the ball moves away (more than :data:`LOST_DISTANCE_M` from where it should lie) before the
kick starts, the skill walks again. Once the kick has started it plays to its end. The head
looks down while approaching: a ball at the toes lies about 65 deg below the horizon, outside a
level head's 120 deg view cone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from behaviors.kick import FEET, KickMotion, kick_motion
from behaviors.skill import Skill, SkillContext
from world.field_geometry import BALL_RADIUS

#: Neck pitch (deg, negative = down) while approaching and aligning.
HEAD_PITCH_DEG = -45.0
#: The kick starts once the ball lies this close (m) to where the kick expects it, along and
#: across the foot, and the robot faces the target within ``ALIGNED_HEADING_DEG``.
ALIGNED_ALONG_M = 0.02
ALIGNED_ACROSS_M = 0.015
ALIGNED_HEADING_DEG = 5.0
#: Fine alignment: walk speed (m/s, deg/s) per metre / degree of error, and its caps.
ALIGN_GAIN = 1.5
ALIGN_TURN_GAIN = 1.5
ALIGN_MAX_SPEED = 0.12
ALIGN_MAX_TURN_DEG = 20.0
#: Beyond this error (m) or heading error (deg) alignment gives way to walking again.
LOST_DISTANCE_M = 0.2
LOST_HEADING_DEG = 25.0
#: Fine alignment rounds (correct, stand still, measure) before kicking with what there is.
MAX_ALIGN_ROUNDS = 4
#: "long" asks for the strongest kick.
LONG = "long"


@dataclass(frozen=True)
class Alignment:
    """Where the ball lies against where the kick wants it, in the robot frame (x forward,
    y left), and how far the robot's heading is off the line to the target (deg, + = turn
    left)."""

    along_m: float
    across_m: float
    heading_deg: float

    @property
    def aligned(self) -> bool:
        return (
            abs(self.along_m) < ALIGNED_ALONG_M
            and abs(self.across_m) < ALIGNED_ACROSS_M
            and abs(self.heading_deg) < ALIGNED_HEADING_DEG
        )

    @property
    def lost(self) -> bool:
        return (
            math.hypot(self.along_m, self.across_m) > LOST_DISTANCE_M
            or abs(self.heading_deg) > LOST_HEADING_DEG
        )


def strength_for(motion: KickMotion, distance: float | str) -> float:
    """The kick strength (0..1) for ``distance`` metres or ``"long"`` (full strength)."""
    if distance == LONG:
        return 1.0
    assert not isinstance(distance, str)
    return motion.strength_for(distance)


def expected_ball_ego(context: SkillContext, foot: str, motion: KickMotion) -> np.ndarray:
    """Where the kick wants the ball's centre now, ego frame (x forward, y left; m), from the
    kicking foot's pose that this cycle's joint angles give."""
    world = context.world
    name = "lfoot" if foot == "left" else "rfoot"
    foot_pose = world.body_transforms[name]
    size = world.robot.spec.body(name).size
    forward_native = foot_pose[:3, 1]  # the foot's own y axis points forward
    outwards_native = foot_pose[:3, 0] * (-1.0 if foot == "left" else 1.0)  # its x: right
    reach = size[1] / 2 + BALL_RADIUS + motion.ball_gap_m
    point = foot_pose[:3, 3] + forward_native * reach + outwards_native * motion.ball_side_m
    return world.to_ego(point)[:2]


def kick_spot(
    ball: tuple[float, float],
    target: tuple[float, float],
    offset_ego: tuple[float, float],
) -> tuple[float, float, float]:
    """Team-frame torso position and heading (deg) from which the ball lies at ``offset_ego``
    (x forward, y left, relative to the torso) with the robot facing from the ball to the
    target."""
    heading = math.atan2(target[1] - ball[1], target[0] - ball[0])
    c, s = math.cos(heading), math.sin(heading)
    fx, fy = offset_ego
    return (ball[0] - c * fx + s * fy, ball[1] - s * fx - c * fy, math.degrees(heading))


class BasicKickSkill(Skill):
    """``execute("basic_kick", target_x, target_y, distance)``: walk, align, kick towards the
    team-frame point; ``distance`` in metres or ``"long"``. Finished when the kick motion has
    ended (the robot stands again)."""

    name = "basic_kick"

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self.phase = "approach"
        self.foot: str | None = None
        self._rounds = 0
        self._strength = 1.0

    def validate(self, target_x: float, target_y: float, distance: float | str = LONG) -> None:
        if not (math.isfinite(target_x) and math.isfinite(target_y)):
            raise ValueError("target coordinates must be finite")
        if isinstance(distance, str):
            if distance != LONG:
                raise ValueError(f"distance must be metres or {LONG!r}, got {distance!r}")
        elif not (math.isfinite(distance) and distance > 0):
            raise ValueError(f"distance must be a positive number of metres, got {distance!r}")

    def step(
        self, context: SkillContext, target_x: float, target_y: float, distance: float | str = LONG
    ) -> bool:
        if self.phase == "kick":
            assert self.foot is not None
            return context.manager.execute_sub_behavior("kick", self.foot, self._strength)
        world = context.world
        if world.pose is None or world.ball.position is None:
            context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, 0.0)
            self._look_down(context)
            return False
        motion = kick_motion(world.robot.robot_type)
        if self.foot is None:
            self.foot = self._choose_foot(context)
        alignment = self._alignment(context, motion, (target_x, target_y))
        if self.phase == "approach":
            self._approach(context, motion, (target_x, target_y), alignment)
        else:
            self._align(context, alignment, motion, distance)
        self._look_down(context)
        return False

    # ------------------------------------------------------------------ phases
    def _approach(
        self,
        context: SkillContext,
        motion: KickMotion,
        target: tuple[float, float],
        alignment: Alignment,
    ) -> None:
        assert self.foot is not None
        world = context.world
        ball = world.ball.position
        assert ball is not None
        offset = self._stand_offset(context, motion)
        x, y, heading = kick_spot(ball, target, offset)
        if context.manager.execute_sub_behavior("walk", x, y, heading) or (
            alignment.aligned and self._rounds == 0
        ):
            self.phase = "align"
            self._rounds = 0

    def _align(
        self,
        context: SkillContext,
        alignment: Alignment,
        motion: KickMotion,
        distance: float | str,
    ) -> None:
        assert self.foot is not None
        if alignment.lost:
            self.phase = "approach"
            context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, 0.0)
            return
        if alignment.aligned or self._rounds >= MAX_ALIGN_ROUNDS:
            stopped = context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, 0.0)
            if stopped:
                if alignment.aligned or self._rounds >= MAX_ALIGN_ROUNDS:
                    self.phase = "kick"
                    self._strength = strength_for(motion, distance)
                self._rounds += 1
            return
        vx = _clip(ALIGN_GAIN * alignment.along_m, ALIGN_MAX_SPEED)
        vy = _clip(ALIGN_GAIN * alignment.across_m, ALIGN_MAX_SPEED)
        vturn = _clip(ALIGN_TURN_GAIN * alignment.heading_deg, ALIGN_MAX_TURN_DEG)
        context.manager.execute_sub_behavior("walk_velocity", vx, vy, vturn)

    # ------------------------------------------------------------------ measurements
    def _choose_foot(self, context: SkillContext) -> str:
        """The foot on the side the ball lies (ego y > 0: left)."""
        ball = context.world.ball_relative_ego
        return FEET[0] if ball is None or ball[1] >= 0 else FEET[1]

    def _stand_offset(self, context: SkillContext, motion: KickMotion) -> tuple[float, float]:
        """Where the ball should lie relative to the torso (ego x, y) when the robot stands
        ready to kick."""
        assert self.foot is not None
        x, y = expected_ball_ego(context, self.foot, motion)
        return float(x), float(y)

    def _alignment(
        self, context: SkillContext, motion: KickMotion, target: tuple[float, float]
    ) -> Alignment:
        assert self.foot is not None
        world = context.world
        ball_ego = world.ball_relative_ego
        ball = world.ball.position
        pose = world.pose
        assert ball_ego is not None and ball is not None and pose is not None
        error = ball_ego[:2] - expected_ball_ego(context, self.foot, motion)
        wanted = math.degrees(math.atan2(target[1] - ball[1], target[0] - ball[0]))
        heading = (wanted - pose.heading_deg + 180.0) % 360.0 - 180.0
        return Alignment(float(error[0]), float(error[1]), heading)

    @staticmethod
    def _look_down(context: SkillContext) -> None:
        context.commands.set_targets({"hj1": 0.0, "hj2": HEAD_PITCH_DEG})


def _clip(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))
