"""The two "dribble long" gaits: DFDL (double-footed) and LFDL (left-footed).

``execute("dribble", kind, direction_deg, foot)`` walks the ball towards ``direction_deg`` (team
frame, counter-clockwise from the opponent goal's direction). Both gaits are the walk
(:class:`~behaviors.walk.WalkEngine`) steered so that the ball stays where the gait wants it,
relative to the torso (:class:`DribbleGait`):

* **DFDL** keeps the ball straight ahead, between the feet's paths: each swinging toe meets
  the ball's side as it lands, so both feet push it, one step after the other.
* **LFDL** keeps the ball in front of the left foot and further ahead: only the left toe
  reaches it, every second step, and pushes it further each time.

The controller (:func:`dribble_velocity`) is a plain feedback law on what the robot perceives
(ball and own pose from the world model, never the simulator): turn towards the direction,
step sideways to put the ball on the gait's line, and walk at the gait's speed while the ball
is within reach (:func:`ball_within_reach`), faster when it rolled ahead, slower when it lies
off the line. Turning, the robot steps sideways as it turns so that it orbits the ball instead
of leaving it behind ("walking around the ball's side"); for a sharp turn the ball's wanted
place turns with the new direction, so the robot circles the ball rather than crossing it.
A ball that slipped beside or behind the robot (not :func:`ball_in_front`) is walked round
(:func:`recovery_velocity`) before the dribble goes on.

Right-footed versions (``foot="right"``) are never written out: the left-footed controller runs
on mirrored inputs (ball, heading error, gyro, tilt, joint angles) and its joint speeds and
odometry are mirrored back (:mod:`behaviors.mirror`). DFDL is symmetric but takes ``foot`` too:
``"right"`` starts with the right leg.

Each gait has its own :class:`~behaviors.walk.WalkParameters` from ``behaviors/data/dribble.yaml``,
so tuning the plain walk does not change the dribbles. The phase (``t`` = 0..7 inside a step,
``left_active``) is :attr:`DribbleSkill.phase`; a caller hands over control at any of the 16
phases simply by not calling ``dribble`` again.

The 2023 ball-holding rule (the ball within 0.12 m of the torso for more than 5 s is a foul)
is met by design: both gaits keep the ball ahead of the toes, well beyond 0.12 m from the
torso centre; ``benchmarks/dribble.py`` measures it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from behaviors.joint_control import JointCommands
from behaviors.mirror import (
    mirror_accelerometer,
    mirror_gyro,
    mirror_joint_angles,
    mirror_vector_native,
)
from behaviors.skill import Skill, SkillContext
from behaviors.walk import WalkEngine, WalkParameters, _read_parameters, carry_on_gait
from world.field_geometry import BALL_RADIUS
from world.localization import wrap_deg
from world.nao_model import ROBOT_TYPES
from world.perception import ForceResistance
from world.robot_state import RobotState

__all__ = [
    "DRIBBLE_FILE",
    "DRIBBLE_KINDS",
    "FEET",
    "DribbleGait",
    "DribbleInputs",
    "DribbleSkill",
    "ball_in_front",
    "ball_within_reach",
    "dribble_gait",
    "dribble_velocity",
    "dribble_walk_parameters",
    "recovery_velocity",
    "still_turning",
    "touch_step_cap",
]

DRIBBLE_FILE = Path(__file__).resolve().parent / "data" / "dribble.yaml"
DRIBBLE_KINDS = ("dfdl", "lfdl")
FEET = ("left", "right")
#: the legs whose steps the touch planner may cap (DribbleGait.touch_legs)
TOUCH_LEGS = ("left", "both")
#: Neck pitch while dribbling (deg, negative = down): the ball at the toes lies about 65 deg
#: below the horizon, outside the 120 deg view cone of a level head; at -45 deg the cone
#: still reaches 9 deg above the horizon, enough for the flags that localise the robot.
HEAD_PITCH_DEG = -45.0


@dataclass(frozen=True)
class DribbleGait:
    """Where one gait keeps the ball and how it steers (metres, m/s, degrees; ego frame of the
    torso: x forward, y left). See ``behaviors/data/dribble.yaml`` for the tuned values."""

    #: where the ball should lie relative to the torso centre
    ball_ahead: float = 0.2
    ball_side: float = 0.0
    #: the ball counts as on the gait's line while it lies within this much of ``ball_side``
    #: either way (0: only on it). Why: DFDL's toes push the ball alternately from its sides,
    #: so it swings between the feet's lines; chasing it back to the middle with sidesteps
    #: (and slowing down for it) cost most of DFDL's speed, while either toe can push a ball
    #: that lies between the feet's lines
    ball_corridor: float = 0.0
    #: the ball is within reach (:func:`ball_within_reach`) while it lies this far ahead ...
    reach_min_ahead: float = 0.08
    reach_max_ahead: float = 0.35
    #: ... and no further than this from the gait's line sideways
    reach_side: float = 0.07
    #: forward speed while the ball is within reach and on the line
    speed: float = 0.4
    #: forward speed bounds: slowest (may be negative) and fastest, when catching up
    min_speed: float = 0.0
    max_speed: float = 0.6
    #: forward speed (m/s) while the ball lies beyond reach_max_ahead, before the catch-up
    #: terms (0: only they bring the robot back to a ball that rolled off)
    beyond_reach_speed: float = 0.0
    #: m/s of extra forward speed per metre the ball lies beyond ball_ahead (negative
    #: nearer) ...
    ahead_gain: float = 2.0
    #: ... or beyond this distance where set (None: ball_ahead). Why a distance of its own:
    #: under the bounce contacts LFDL slows as the ball comes nearer than 0.4 m, so that its
    #: toe meets the ball gently, while it still lines up and walks round a ball at ball_ahead
    catch_up_ahead: float | None = None
    #: share of the ball's own forward speed added (a kicked ball runs off: follow it at once)
    follow_gain: float = 0.0
    #: forward speed limit (m/s) through a sharp turn: from the time the heading error passes
    #: the placement dead band until it is back within turn_settled_deg (inf: off; the skill
    #: keeps the state, :attr:`DribbleInputs.turning`). Why: coming out of a sharp turn at
    #: DFDL's full speed (0.9 m/s) a foot met the ball beside it and the robot fell
    turning_max_speed: float = math.inf
    turn_settled_deg: float = 5.0
    #: m/s of sideways speed per metre the ball lies off the line
    side_gain: float = 3.0
    max_side_speed: float = 0.25
    #: deg/s of turn per degree of heading error, and the largest turn rate
    turn_gain: float = 2.0
    max_turn_deg: float = 60.0
    #: the ball's place turns with the direction to dribble once the heading error exceeds
    #: the dead band (small heading wobbles would rock the robot sideways), by the excess, up
    #: to max_placement_deg
    placement_deadband_deg: float = 20.0
    max_placement_deg: float = 75.0
    #: share of the catch-up speed kept while turning hard
    turning_catch_up_share: float = 0.3
    #: all commands shrink while the torso tilts beyond tilt_calm_deg, to calm_min_share of
    #: themselves tilt_calm_range_deg further
    tilt_calm_deg: float = 90.0
    tilt_calm_range_deg: float = 10.0
    calm_min_share: float = 0.3
    #: the forward speed shrinks to nothing as the ball lies this far off the line ...
    side_slowdown: float = 0.1
    #: ... or as the heading error reaches this many degrees
    heading_slowdown_deg: float = 60.0
    #: steering at a ball that lies off the line, ahead: the heading aims this share of the
    #: ball's bearing from the gait's line, at most pursuit_max_deg (0: off, the robot only
    #: steps sideways). Why: stepping sideways costs forward speed (the walk shares its step
    #: limits), while a few degrees of heading bring the robot back on the line as it walks
    pursuit_share: float = 0.0
    pursuit_max_deg: float = 0.0
    #: a ball nearer than reach_min_ahead (beside or behind the robot) is walked round
    #: (:func:`recovery_velocity`): the robot keeps this far from it sideways while passing ...
    recover_clearance: float = 0.2
    #: ... at this speed (m/s) at most, m/s per metre of way left, sideways at most this
    recover_speed: float = 0.3
    recover_gain: float = 2.0
    recover_side_speed: float = 0.2
    #: a way longer than recover_face_distance is walked facing it (turning first), fully so
    #: beyond twice that: sidestepping half a metre takes seconds
    recover_face_distance: float = 0.3
    #: a ball further than fetch_distance from the torso while the heading is off by more than
    #: the placement dead band is fetched (:func:`recovery_velocity`, walking to the gait's
    #: place behind it) rather than orbited: turning on the spot towards a new direction
    #: leaves a ball that rolled 0.8 m ahead where it is, and it drifts out of the front
    fetch_distance: float = math.inf
    #: the touch planner (:func:`touch_step_cap`; inf: off): where the touching toe lands,
    #: metres ahead of the torso at the end of its step, less half the step ...
    touch_reach: float = math.inf
    #: ... how far past the ball's back it may land (the push), and the shortest step the
    #: planner asks for
    touch_push: float = 0.0
    touch_min_step: float = 0.04
    #: which legs' steps the planner caps: ``"left"`` (LFDL: only the left toe touches) or
    #: ``"both"`` (DFDL: the toes take turns)
    touch_legs: str = "left"


@dataclass(frozen=True, slots=True)
class DribbleInputs:
    """What the controller needs, in the torso's ego frame (x forward, y left)."""

    #: ball position relative to the torso (m)
    ball_x: float
    ball_y: float
    #: ball velocity (m/s)
    ball_vx: float
    ball_vy: float
    #: direction to dribble minus own heading (deg, + = the direction lies to the left)
    heading_error_deg: float
    #: the torso's tilt from upright (deg; the same in the mirror)
    tilt_deg: float = 0.0
    #: coming out of a sharp turn: the heading error passed the placement dead band and has
    #: not been within ``turn_settled_deg`` since (:func:`still_turning`; the same in the mirror)
    turning: bool = False

    def mirrored(self) -> DribbleInputs:
        """The same situation seen in the mirror (the sagittal plane): lateral values negate."""
        return DribbleInputs(
            self.ball_x,
            -self.ball_y,
            self.ball_vx,
            -self.ball_vy,
            -self.heading_error_deg,
            self.tilt_deg,
            self.turning,
        )


def ball_within_reach(inputs: DribbleInputs, gait: DribbleGait) -> bool:
    """The ball is within reach when the gait's next steps can touch it: between
    ``reach_min_ahead`` and ``reach_max_ahead`` in front of the torso centre and no more than
    ``reach_side`` off the gait's line (``ball_side``) sideways. The robot only speeds up
    while this holds."""
    ahead_ok = gait.reach_min_ahead <= inputs.ball_x <= gait.reach_max_ahead
    return (
        ahead_ok and abs(_off_line(inputs.ball_y - gait.ball_side, inputs, gait)) <= gait.reach_side
    )


def ball_in_front(inputs: DribbleInputs, gait: DribbleGait) -> bool:
    """The ball lies in front of the robot, where the dribble's forward law can take it: at
    least ``reach_min_ahead`` ahead of the torso centre, and the further off the gait's line
    sideways (beyond ``reach_side``), the further ahead too (a ball 0.2 m to the side at the
    height of the toes is not walked at diagonally, it is walked round)."""
    off_line = max(
        0.0, abs(_off_line(inputs.ball_y - gait.ball_side, inputs, gait)) - gait.reach_side
    )
    return inputs.ball_x >= gait.reach_min_ahead + off_line


def touch_step_cap(inputs: DribbleInputs, gait: DribbleGait, step_seconds: float) -> float | None:
    """The longest forward step (m) the touching leg may take so that its toe would land at
    the ball's back, or None (planner off, turning, or the ball off the toe's line).

    Why: under the bounce contacts (restitution 0.8, as on the real server) a ball the toe
    meets mid-swing, where the swing foot moves at about twice the walking speed, leaves at
    2-3.7 m/s and rolls beyond reach (``scripts/dribble/touches.py``: LFDL's touches at t = 4-6
    of the left swing). The toe lands ``touch_reach + step / 2`` ahead of the torso's place at
    the end of the step, i.e. ``touch_reach + 1.5 step`` ahead of where the torso is now; the
    ball will lie ``ball_x + ball_vx * step_seconds`` ahead by then. The step that lands the toe
    ``touch_push`` past the ball's back is the cap (at least ``touch_min_step``); a longer
    planned step is shortened to it. Measured (session 21, ``dribble.yaml``): the toe still
    meets the ball mid-swing, but the shortened steps bring robot and toe to it slower, the
    ball leaves at 1.8-2.4 instead of 2.3-2.9 m/s, and the losses beyond 1 m fall from 166 to
    21 in 320 runs. Not while turning (:attr:`DribbleInputs.turning`, or the heading off by
    more than the placement dead band): short steps there tipped the robot."""
    if not math.isfinite(gait.touch_reach) or not ball_in_front(inputs, gait):
        return None
    if inputs.turning or abs(inputs.heading_error_deg) > gait.placement_deadband_deg:
        return None
    if abs(_off_line(inputs.ball_y - gait.ball_side, inputs, gait)) > gait.reach_side:
        return None
    ball_then = inputs.ball_x + max(inputs.ball_vx, 0.0) * step_seconds
    step = (ball_then - BALL_RADIUS + gait.touch_push - gait.touch_reach) / 1.5
    return max(gait.touch_min_step, step)


def dribble_velocity(inputs: DribbleInputs, gait: DribbleGait) -> tuple[float, float, float]:
    """The walk command (vx m/s, vy m/s, vturn deg/s) that keeps the ball on the gait's line.

    Turn: proportional to the heading error. Where the ball should lie: ``ball_ahead`` along
    the direction to dribble and ``ball_side`` to its left; the direction's angle counts only
    beyond a dead band and up to ``max_placement_deg``, so that for a sharp turn the robot
    circles the ball instead of walking through it. Sideways: proportional to the ball's side
    error, plus the orbit term ``-turn * ball_x`` (turning left swings a ball ahead to the
    right; stepping right by as much keeps it in front). Forward: the gait's speed while the
    ball is within reach, shrunk as the ball lies off the line (a toe would hit it on its side)
    or the heading is wrong, plus a catch-up term (a share of the ball's forward error and,
    once it lies beyond ``ball_ahead``, of its own forward speed).
    """
    if not ball_in_front(inputs, gait) or _fetch(inputs, gait):  # walk round it / to it first
        return recovery_velocity(inputs, gait)
    error = inputs.heading_error_deg
    turn_deg = _clip(gait.turn_gain * error, gait.max_turn_deg)
    pursuit_deg = _pursuit_deg(inputs, gait)
    beyond = max(0.0, abs(error) - gait.placement_deadband_deg)
    angle = math.radians(math.copysign(min(beyond, gait.max_placement_deg), error))
    ux, uy = math.cos(angle), math.sin(angle)
    ahead_error = inputs.ball_x - (gait.ball_ahead * ux - gait.ball_side * uy)
    side_error = _off_line(
        inputs.ball_y - (gait.ball_ahead * uy + gait.ball_side * ux), inputs, gait
    )
    orbit = -math.radians(turn_deg) * max(inputs.ball_x, 0.0)
    vy = _clip(gait.side_gain * side_error + orbit, gait.max_side_speed)
    turn_deg = _clip(turn_deg + gait.turn_gain * pursuit_deg, gait.max_turn_deg)
    aligned = max(0.0, 1.0 - abs(side_error) / gait.side_slowdown)
    facing = max(0.0, 1.0 - abs(error) / gait.heading_slowdown_deg)
    turning = inputs.turning or abs(error) > gait.placement_deadband_deg
    limit = min(gait.max_speed, gait.turning_max_speed) if turning else gait.max_speed
    if ball_within_reach(inputs, gait):
        base = min(gait.speed, limit) * aligned * facing
    elif inputs.ball_x > gait.reach_max_ahead:  # rolled off ahead: follow it
        base = gait.beyond_reach_speed * facing
    else:
        base = 0.0
    if gait.catch_up_ahead is not None:
        ahead_error += (gait.ball_ahead - gait.catch_up_ahead) * ux
    catch_up = gait.ahead_gain * ahead_error
    if ahead_error > 0.0:  # following a ball that is nearer than wanted would tread on it
        catch_up += gait.follow_gain * max(inputs.ball_vx, 0.0)
    catch_up *= max(facing, gait.turning_catch_up_share)
    vx = min(max(base + catch_up, gait.min_speed), limit)
    calm = _calm_share(inputs.tilt_deg, gait)
    return vx * calm, vy * calm, turn_deg * calm


def still_turning(was_turning: bool, inputs: DribbleInputs, gait: DribbleGait) -> bool:
    """Whether the robot is (still) coming out of a sharp turn: it starts one when the
    heading error passes the placement dead band and ends it once the error is within
    ``turn_settled_deg`` (hysteresis: the error swings by 10 deg while the robot settles)
    with the ball further ahead than ``ball_ahead`` (speeding up towards a near, slow ball
    overran it)."""
    error = abs(inputs.heading_error_deg)
    if error > gait.placement_deadband_deg:
        return True
    settled = error <= gait.turn_settled_deg and inputs.ball_x > gait.ball_ahead
    return was_turning and not settled


def _fetch(inputs: DribbleInputs, gait: DribbleGait) -> bool:
    """The ball lies far (beyond ``fetch_distance``) while the direction to dribble is well
    off the heading (beyond the placement dead band): walk to it rather than orbit it."""
    far = math.hypot(inputs.ball_x, inputs.ball_y) > gait.fetch_distance
    return far and abs(inputs.heading_error_deg) > gait.placement_deadband_deg


def _pursuit_deg(inputs: DribbleInputs, gait: DribbleGait) -> float:
    """Extra heading (deg, + = left) towards a ball ahead that lies off the gait's line: a
    share of its bearing from the line's point under the torso, capped; only while the
    heading is roughly right (turning to a new direction has its own law)."""
    if gait.pursuit_share <= 0.0 or abs(inputs.heading_error_deg) > gait.placement_deadband_deg:
        return 0.0
    off_line = _off_line(inputs.ball_y - gait.ball_side, inputs, gait)
    bearing = math.degrees(math.atan2(off_line, max(inputs.ball_x, 0.1)))
    return _clip(gait.pursuit_share * bearing, gait.pursuit_max_deg)


def _off_line(side: float, inputs: DribbleInputs, gait: DribbleGait) -> float:
    """How far a ball ``side`` metres to the left of the gait's line lies outside the
    corridor (``ball_corridor`` either way) where it counts as on the line. Turning (the
    heading error beyond the placement dead band) there is no corridor: coming out of a sharp
    turn at speed, a ball beside the line met the landing foot's side and tripped the robot."""
    if abs(inputs.heading_error_deg) > gait.placement_deadband_deg:
        return side
    return side - _clip(side, gait.ball_corridor)


def recovery_velocity(inputs: DribbleInputs, gait: DribbleGait) -> tuple[float, float, float]:
    """The walk command that brings a ball lying beside or behind the robot back in front
    (not :func:`ball_in_front`).

    Why: the dribble's law only ever walks forwards; a ball that slipped past a foot would
    be left behind for good (the dribble stalled). Here the robot heads for its dribbling
    place, ``ball_ahead`` behind the ball along the direction to dribble, while turning to
    that direction. If the straight way there passes the ball (the robot is not yet behind
    it), it first heads for a point ``recover_clearance`` beside the ball on its own side,
    so that it walks round the ball instead of through it. Speeds are capped at
    ``recover_speed`` forwards and backwards and ``recover_side_speed`` sideways: slow steps,
    since a foot meeting the ball sideways trips the robot. A way longer than
    ``recover_face_distance`` is walked facing it (turning towards it first): a ball kicked
    off half a metre to the side took LFDL 10 s of sidestepping.
    """
    error = math.radians(inputs.heading_error_deg)
    ux, uy = math.cos(error), math.sin(error)  # the direction to dribble, ego frame
    bx, by = inputs.ball_x, inputs.ball_y
    # where the robot stands along the direction, measured from the ball (negative: behind)
    behind = -(bx * ux + by * uy)
    # the robot's side of the line through the ball along the direction (+1: its left)
    side = 1.0 if (ux * -by - uy * -bx) >= 0.0 else -1.0
    offset = gait.ball_side  # the gait's line lies ball_side to the left of the ball's
    if behind < -0.5 * gait.ball_ahead:  # already behind the ball: straight to the place
        gx = bx - gait.ball_ahead * ux + offset * uy
        gy = by - gait.ball_ahead * uy - offset * ux
    else:  # beside it, half a place back: the ball stays clear of the feet
        gx = bx - 0.5 * gait.ball_ahead * ux - side * gait.recover_clearance * uy
        gy = by - 0.5 * gait.ball_ahead * uy + side * gait.recover_clearance * ux
    vx = _clip(gait.recover_gain * gx, gait.recover_speed)
    vy = _clip(gait.recover_gain * gy, gait.recover_side_speed)
    # far from the place: face the way there (the walk is fastest forwards), near it: face
    # the direction to dribble
    way = math.hypot(gx, gy)
    facing_way = min(max(way / gait.recover_face_distance - 1.0, 0.0), 1.0)
    bearing = math.degrees(math.atan2(gy, gx))
    aim = facing_way * bearing + (1.0 - facing_way) * inputs.heading_error_deg
    if facing_way > 0.0:  # walk on only once roughly facing the way: forward, no sidestep
        ahead = max(0.0, math.cos(math.radians(min(2.0 * abs(bearing), 90.0))))
        vx = (1.0 - facing_way) * vx + facing_way * gait.recover_speed * ahead
        vy = (1.0 - facing_way) * vy
    turn_deg = _clip(gait.turn_gain * aim, gait.max_turn_deg)
    calm = _calm_share(inputs.tilt_deg, gait)
    return vx * calm, vy * calm, turn_deg * calm


def _calm_share(tilt_deg: float, gait: DribbleGait) -> float:
    """How much of the command to keep while the torso tilts: all of it up to
    ``tilt_calm_deg``, down to ``calm_min_share`` at ``tilt_calm_deg + tilt_calm_range_deg``.
    Why: a robot rocking sideways while stepping sideways and turning spins on its support
    foot and falls (type 0: 1 run in 4 over 10 m before this); slower steps let it settle."""
    excess = (tilt_deg - gait.tilt_calm_deg) / gait.tilt_calm_range_deg
    return 1.0 - (1.0 - gait.calm_min_share) * min(max(excess, 0.0), 1.0)


def _clip(value: float, limit: float) -> float:
    return min(max(value, -limit), limit)


# --------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------


def _check_kind(kind: str) -> None:
    if kind not in DRIBBLE_KINDS:
        raise ValueError(f"dribble kind must be one of {DRIBBLE_KINDS}, got {kind!r}")


def _check_type(robot_type: int) -> None:
    if robot_type not in ROBOT_TYPES:
        raise ValueError(f"robot type must be one of {ROBOT_TYPES}, got {robot_type!r}")


@cache
def _load(path: Path) -> dict[str, Any]:
    return yaml.safe_load(path.read_text()) or {}


def _typed_block(data: dict[str, Any], robot_type: int) -> dict[str, Any]:
    """A mapping's ``default`` block overridden by its ``type<N>`` block (one level deep for
    a ``step`` sub-mapping)."""
    base = dict(data.get("default") or {})
    own = dict(data.get(f"type{robot_type}") or {})
    merged = {**base, **own}
    if "step" in base or "step" in own:
        merged["step"] = {**(base.get("step") or {}), **(own.get("step") or {})}
    return merged


@cache
def dribble_gait(kind: str, robot_type: int, path: Path = DRIBBLE_FILE) -> DribbleGait:
    """The controller settings of gait ``kind`` for ``robot_type`` (``<kind>.controller``)."""
    _check_kind(kind)
    _check_type(robot_type)
    block = (_load(path).get(kind) or {}).get("controller") or {}
    values = _typed_block(block, robot_type)
    known = {f.name for f in fields(DribbleGait)}
    unknown = set(values) - known
    if unknown:
        raise ValueError(f"{path} ({kind}, type{robot_type}): unknown setting(s) {sorted(unknown)}")
    if values.get("touch_legs", "left") not in TOUCH_LEGS:
        raise ValueError(
            f"{path} ({kind}, type{robot_type}): touch_legs must be one of {TOUCH_LEGS}, "
            f"got {values['touch_legs']!r}"
        )
    return DribbleGait(**{k: v if k == "touch_legs" else float(v) for k, v in values.items()})


@cache
def dribble_walk_parameters(
    kind: str, robot_type: int, path: Path = DRIBBLE_FILE
) -> WalkParameters:
    """The walk of gait ``kind`` for ``robot_type``: the file's shared ``walk`` block, then the
    gait's own ``walk`` block on top (each with ``default`` and ``type<N>`` parts)."""
    _check_kind(kind)
    _check_type(robot_type)
    data = _load(path)
    shared = _typed_block(data.get("walk") or {}, robot_type)
    own = _typed_block((data.get(kind) or {}).get("walk") or {}, robot_type)
    merged = {**shared, **own}
    merged["step"] = {**(shared.get("step") or {}), **(own.get("step") or {})}
    return _read_parameters(merged, f"{path} ({kind}, type{robot_type})")


# --------------------------------------------------------------------------------------------
# Mirroring the walk's inputs and outputs
# --------------------------------------------------------------------------------------------


class _MirroredOdometry:
    """Passes the mirrored walk's odometry to the real localiser, mirrored back."""

    def __init__(self, localizer: Any) -> None:
        self._localizer = localizer

    def add_odometry(self, forward: float, left: float, turn_deg: float) -> None:
        self._localizer.add_odometry(forward, -left, -turn_deg)


@dataclass
class _MirroredWorld:
    """The part of a world model the walk engine reads, as the mirrored robot would see it."""

    robot: RobotState
    localizer: _MirroredOdometry | None


def _mirrored_robot(robot: RobotState) -> RobotState:
    """The robot's body readings reflected about its sagittal plane."""
    mirrored = RobotState(robot.robot_type)
    mirrored.joints_deg = mirror_joint_angles(robot.joints_deg)
    mirrored.gyro_deg_s = mirror_gyro(robot.gyro_deg_s)
    mirrored.accelerometer = mirror_accelerometer(robot.accelerometer)
    mirrored.up = mirror_vector_native(robot.up)
    mirrored.foot_pressure = {
        _swap_side(name): ForceResistance(
            _swap_side(name),
            tuple(mirror_vector_native(fr.contact)),
            tuple(mirror_vector_native(fr.force)),
        )
        for name, fr in robot.foot_pressure.items()
    }
    return mirrored


def _swap_side(name: str) -> str:
    return {"l": "r", "r": "l"}[name[0]] + name[1:]


# --------------------------------------------------------------------------------------------
# The skill
# --------------------------------------------------------------------------------------------


class DribbleSkill(Skill):
    """Dribble the ball towards ``direction_deg`` (team frame) with gait ``kind`` (``"dfdl"``
    or ``"lfdl"``) on the ``foot`` side (``"left"``, or ``"right"``: the mirror image). Never
    finishes: the caller decides when to stop (at any phase, see :attr:`phase`)."""

    name = "dribble"

    def __init__(self) -> None:
        self._engine: WalkEngine | None = None
        self._key: tuple[str, int, Path] | None = None
        self._mirror = False
        #: where the gaits' settings come from (a benchmark trying other settings points it
        #: at its own copy; the settings are read once per file, robot type and kind)
        self.data_file: Path = DRIBBLE_FILE
        #: the last inputs and command, for benchmarks and debugging (gait's own frame)
        self.last_inputs: DribbleInputs | None = None
        self.last_command: tuple[float, float, float] = (0.0, 0.0, 0.0)
        #: coming out of a sharp turn (see :func:`still_turning`)
        self._turning = False

    def reset(self) -> None:
        if self._engine is not None:
            self._engine.reset()
        self.last_inputs = None
        self.last_command = (0.0, 0.0, 0.0)
        self._turning = False

    @property
    def gait_engine(self) -> WalkEngine | None:
        """The engine of the left-footed gait (None for a right-footed dribble, whose engine
        walks in the mirrored frame): a walk taking over carries on its steps."""
        return None if self._mirror else self._engine

    def validate(self, kind: str, direction_deg: float, foot: str = "left") -> None:
        _check_kind(kind)
        if foot not in FEET:
            raise ValueError(f"foot must be one of {FEET}, got {foot!r}")
        if not math.isfinite(direction_deg):
            raise ValueError("direction_deg must be finite")

    # ------------------------------------------------------------------ state
    @property
    def phase(self) -> tuple[int, bool]:
        """(t, left_active) of the real robot: t = 0..7 inside the step, left_active True
        while the LEFT leg swings; (-1, False) before the first step."""
        t, left_active = self.gait_phase
        if t < 0 or not self._mirror:
            return t, left_active
        return t, not left_active

    @property
    def gait_phase(self) -> tuple[int, bool]:
        """The phase in the gait's own (left-footed) frame: ``left_active`` is True while the
        leg playing the left-footed gait's left leg swings (the right leg, for a right-footed
        dribble). A mirrored policy trained on the left foot reads this one."""
        if self._engine is None:
            return (-1, False)
        return self._engine.phase

    def engine_for(self, kind: str, robot_type: int) -> WalkEngine:
        """The walk engine of ``kind`` (a new one when the kind or the robot type changes)."""
        key = (kind, robot_type, self.data_file)
        if self._engine is None or self._key != key:
            parameters = dribble_walk_parameters(kind, robot_type, self.data_file)
            self._engine = WalkEngine(robot_type, parameters)
            self._key = key
        return self._engine

    # ------------------------------------------------------------------ one cycle
    def step(
        self, context: SkillContext, kind: str, direction_deg: float, foot: str = "left"
    ) -> bool:
        robot_type = context.world.robot.robot_type
        engine = self.engine_for(kind, robot_type)
        mirror = foot == "right"
        if mirror != self._mirror:  # the engine's feet are in the other side's frame
            engine.reset()
            self._mirror = mirror
        if not mirror:  # the mirrored gait's engine walks in the other side's frame
            carry_on_gait(context, self.name, engine)
        gait = dribble_gait(kind, robot_type, self.data_file)
        inputs = _perceived_inputs(context, direction_deg)
        if inputs is None:  # lost the ball or the own pose: tread on the spot until seen
            command = (0.0, 0.0, 0.0)
        else:
            self._turning = still_turning(self._turning, inputs, gait)
            inputs = replace(inputs, turning=self._turning)
            own = inputs.mirrored() if self._mirror else inputs
            command = dribble_velocity(own, gait)
            self.last_inputs = own
        self.last_command = command
        if inputs is not None:
            self._plan_touch(engine, gait, own)
        if self._mirror:
            self._step_mirrored(context, engine, command)
        else:
            engine.step(context, *command)
        context.commands.set_targets({"hj1": 0.0, "hj2": HEAD_PITCH_DEG})
        return False

    def _plan_touch(self, engine: WalkEngine, gait: DribbleGait, inputs: DribbleInputs) -> None:
        """Before a step of a touching leg starts (the gait's left, or either with
        ``touch_legs: both``), cap its length (:func:`touch_step_cap`)."""
        t, left_active = engine.phase
        if t < 0 or not engine.generator.at_step_end:
            return
        if left_active and gait.touch_legs != "both":  # the next step is the right leg's
            return
        engine.next_step_forward_cap = touch_step_cap(inputs, gait, engine.step_seconds)

    def _step_mirrored(
        self, context: SkillContext, engine: WalkEngine, command: tuple[float, float, float]
    ) -> None:
        """One walk cycle of the mirror image: mirrored body readings in, speeds mirrored out."""
        world = context.world
        localizer = getattr(world, "localizer", None)
        mirrored_world = _MirroredWorld(
            _mirrored_robot(world.robot),
            None if localizer is None else _MirroredOdometry(localizer),
        )
        scratch = JointCommands(world.robot.robot_type)
        engine.step(replace(context, world=mirrored_world, commands=scratch), *command)
        context.commands.set_speeds(mirror_joint_angles(scratch.speeds()))


def _perceived_inputs(context: SkillContext, direction_deg: float) -> DribbleInputs | None:
    """Ball position and velocity in the ego frame and the heading error, from the world
    model; None while the ball or the robot's own pose is unknown."""
    world = context.world
    pose = world.pose
    ball = world.ball_relative_ego
    if pose is None or ball is None:
        return None
    h = math.radians(pose.heading_deg)
    vx, vy = world.ball.velocity
    c, s = math.cos(h), math.sin(h)
    velocity = np.array([c * vx + s * vy, -s * vx + c * vy])
    return DribbleInputs(
        float(ball[0]),
        float(ball[1]),
        float(velocity[0]),
        float(velocity[1]),
        wrap_deg(direction_deg - pose.heading_deg),
        world.robot.tilt_deg,
    )
