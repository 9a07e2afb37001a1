"""The basic kick: walk to the ball, line the chosen foot up behind it, kick it a set distance.

``execute("basic_kick", target_x, target_y, distance)`` kicks the ball towards the team-frame
point ``(target_x, target_y)``; ``distance`` is metres (the short kick, controllable over the
calibrated range of ``kicks.yaml``, 3-9 m asked by the issue) or ``"long"`` (the strongest
kick). Everything comes from the world model (ball estimate, own pose, joint angles): the skill
never sees the simulator.

Phases:

1. ``approach``: the ``walk`` skill to the spot from which the chosen foot lies behind the
   ball on the line ball -> target, facing the target. The foot is the one whose spot is
   nearer, unless only the other foot's kick reaches the distance (:func:`choose_foot`),
   chosen anew until the robot is close to the ball. The spot is that of the motion the kick
   will play (:func:`motion_for`: the short one, or the long one beyond its table). Where the
   ball should lie ahead of the toe depends on the distance asked for when the kick is
   calibrated by its ball gap (:func:`ball_gap_for`): a shorter kick lines the ball up further
   ahead. An estimate that lies in view but is not seen (the ball moved while out of view) is
   searched for instead of walked to (:meth:`BasicKickSkill._searching`).
2. ``settle``: stand still (``walk_velocity`` 0, then the stand pose), then measure where the
   ball lies against where the kick expects it (``ball_gap_m``, ``ball_side_m`` of the kick,
   relative to the kicking foot in the stand pose) from the mean of the ball's torso-relative
   sights of the last standing cycles: within ``FINE_*`` (about 1 cm, facing the target within
   6 deg), kick; within ``SHUFFLE_REACH_M`` and ``SHUFFLE_TURN_MAX_DEG``, ``shuffle``; else
   ``back_off`` (walk to a spot behind) and approach again.
3. ``shuffle``: :class:`FootShuffle`, small IK-driven steps in place that turn the robot by the
   measured heading error and move it so that the ball lies on the spot in the turned frame
   (:func:`shuffle_move`), leaving the feet squared in the stand pose; then settle again (at
   most ``MAX_SHUFFLES`` times, after which a coarse ``READY_*`` alignment kicks anyway).
4. ``head_up``: the head level in the stand for at least ``HEAD_UP_CYCLES``, then until the
   torso has stopped swaying (:class:`CalmWatch`, at most ``CALM_MAX_CYCLES`` in all).
5. ``kick``: the ``kick`` skill with the strength that the kick's calibration table gives for
   the distance (full strength for a kick calibrated by its ball gap); beyond the table's
   reach, and for ``"long"``, the kick's long version where the file has one
   (:func:`wants_long`). Both are calibrated by strength (session 29): the short kick goes
   about 2.1-3.2 m, the long one 3.7-6.3 m, on either foot (the right foot plays the left
   motions mirrored).

Once the kick has started it plays to its end. The head
looks down while approaching: a ball at the toes lies about 65 deg below the horizon, outside a
level head's 120 deg view cone.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from types import MappingProxyType

import numpy as np

from behaviors.ik import leg_ik_for
from behaviors.joint_control import CYCLE_SECONDS, JointCommands
from behaviors.kick import FEET, KickMotion, kick_motion
from behaviors.poses import get_pose
from behaviors.skill import Skill, SkillContext
from world.field_geometry import BALL_RADIUS
from world.kinematics import body_transforms
from world.nao_model import robot_spec

#: Neck pitch (deg, negative = down) while approaching and settling.
HEAD_PITCH_DEG = -45.0
#: The kick starts once the robot stands still with the ball this close (m) to where the kick
#: expects it, along and across the foot, and facing the target within ``READY_HEADING_DEG``.
#: Why this loose: the walk cannot make steps much shorter than a few centimetres (slower
#: commands tread on the spot), so finer alignment by walking was measured to oscillate.
READY_ALONG_M = 0.04
READY_ACROSS_M = 0.025
READY_HEADING_DEG = 12.0
#: When the robot stopped too far off, it walks back this far (m) from the kicking spot and
#: approaches again (the walk counts a target within 4 cm as reached and would not move).
BACK_OFF_M = 0.15
#: How far (m) beyond the kicking spot the walk is sent (it stops up to 4 cm short of its
#: target, ``behaviors.walk.ARRIVE_DISTANCE``): measured 3-5 cm short without it, and with 3 cm
#: its last steps pushed the ball away at times. Even so the first settle measured the ball
#: 2-5.7 cm further ahead than wanted in 9 of 9 layouts (fifth round), so a shuffle follows in
#: almost every trial.
WALK_OVERSHOOT_M = 0.015
#: ... per robot type where it differs. Type 4's walk sets its soles 2.5 cm further back than
#: type 0's (``walk.yaml`` foot_forward -0.04 against -0.015), so when it takes the stand after
#: the walk the torso settles further back: with 0.015 its first settle measured the ball 6.1-6.8
#: cm further ahead than wanted (type 0: 0.2-5.3 cm), past the shuffle's reach, and it backed
#: off and walked in again in 8 of 20 trials (session 30, basic kicks asked 2.0 / 4.5 m, layout
#: seed 0). With 0.045: 2.4-3.9 cm in 8 of 8 layouts, no back-off (see runs/kick_abort/README.md).
TYPE_WALK_OVERSHOOT_M: Mapping[int, float] = MappingProxyType({4: 0.045})
#: Cycles in the stand pose between the walk's stop and the kick: the walk stands with other
#: angles, and the kick's weight shift from those tipped the robot over. Fifth round: ending
#: this settle early once the torso was steady (2 deg range over 12 cycles, after 15 cycles;
#: 0.5-0.9 s instead of 1.02) saved ~0.3 s a trial but the same 20 layouts fell 7 times
#: instead of 2, 6 of them in the kick.
SETTLE_CYCLES = 50
#: When the straight way to the kicking spot passes closer than this (m) to the ball, the robot
#: first walks round it, to a point ``DETOUR_BEHIND_M`` behind the ball and ``DETOUR_SIDE_M``
#: to the side it is on (the spot itself lies about 0.19 m from the ball).
DETOUR_CLEARANCE_M = 0.15
DETOUR_BEHIND_M = 0.3
DETOUR_SIDE_M = 0.45
#: Session 12, tried on the approach and not kept (python -m benchmarks.kick --strengths
#: --basic-trials 20 --basic-distance 3 --layout-seed L; before: time to kick 11.64 / 11.50 /
#: 12.08 / 11.97 / 12.50 s median on L = 0-4, 12.54 / 12.58 / 12.45 / 12.50 on 9-12 with
#: scripts/kick/sweep.py --verbose --layout-seeds 9 10 11 12): (1) a search for a stale ball
#: (an estimate straight ahead unseen for 0.5 s: the robot had last seen the ball before the
#: trainer moved it behind, walked to the old spot and found the real ball seconds later,
#: scripts/kick/approach_trace.py): standing and panning the head +-110 deg over 1.6 s, then
#: turning left: 11.97 / 12.38 / 11.86 / 11.97 / 12.37 and 13.40 / 12.58 / 12.52 / 12.22 s;
#: the slowest trials 17-21 s -> 13-15 s (mean over the trials both kicked 12.85 -> 12.49 s),
#: never kicked 5 -> 3 and 9 -> 5, falls 19 -> 19 and 19 -> 13, but the median not better
#: (turning left only: mean 12.87 -> 12.31 s, balls behind on the right 3-5 s slower). (2)
#: ending the approach once the ball's sight lay within 3 / 5 cm of the kick's spot (heading
#: within 8 deg, 3 cycles), the shuffle doing the rest: approach 0.3 s shorter, time to kick
#: 11.72 / 11.50 / 11.74 s on L = 0-2 (scripts/kick/sweep.py --layout-seeds 0 1 2), falls 11
#: -> 11, never kicked 5 -> 5; with 5 cm 12.74 / 10.78 / 12.64 s, falls 8, never kicked 7.
#: A ball estimate in view (within this many deg of the heading, and of this many metres) that
#: vision has not confirmed for this long (s) is stale: the approach turns on the spot at
#: SEARCH_TURN_DEG_S until it sees the ball (at most SEARCH_MAX_S), see
#: :meth:`BasicKickSkill._searching`.
STALE_VIEW_DEG = 45.0
STALE_VIEW_M = 3.0
#: ... and further than this (m): nearer, the ball may lie below the camera's view.
STALE_VIEW_MIN_M = 0.5
STALE_BALL_S = 0.25
SEARCH_TURN_DEG_S = 60.0
#: ... after standing for this long (s) with the head swept to this yaw (deg) left, then right
SEARCH_SWEEP_S = 1.2
SEARCH_HEAD_YAW_DEG = 115.0
SEARCH_MAX_S = 8.0
#: The kicking foot is chosen anew every cycle until the robot is this close (m) to the ball.
CHOOSE_FOOT_DISTANCE_M = 0.6
#: "long" asks for the strongest kick.
LONG = "long"
#: Metres of walking a foot's kicking spot may lie further than the other's and still be chosen
#: when only that foot's kick reaches the distance asked (for "long": reaches further). Why: on
#: the bounce contacts (session 20) the left long kick went about 6.5 m, the right one (a motion
#: of its own until session 29) about 4.3 m. With both feet playing the same motion mirrored
#: the reaches are equal and this never applies, but a kick file may again give a foot its own.
REACH_PREFERENCE_M = 1.0
#: Metres of walking a robot type's steadier foot for the long kick is credited when the foot
#: is chosen for a long kick (robot type -> (foot, metres)). Why: type 1's left long kick fell
#: in its swing, before the ball, far more often than its right (the mirrored motion; Bullet's
#: solver is not left-right symmetric): asked 5 m, layout seeds 2-9, left 7 falls of 82 trials
#: (5 before contact), right 1 of 78; with the credit 3 falls in 160 (session 34,
#: runs/kick_abort/README.md). Its short kick is left out: all right-footed it fell 3 times in
#: 60 asked 3 m, against 1 (a right kick) choosing by walking alone.
TYPE_LONG_KICK_FOOT_CREDIT_M: Mapping[int, tuple[str, float]] = MappingProxyType(
    {1: ("right", 0.5)}
)

#: Fine alignment: the robot moves by small steps of its own (:class:`FootShuffle`) until the
#: ball lies within these distances (m) of where the kick wants it. Why so tight: a stand kick
#: with the ball 2 cm across off the spot went 1.8-4.2 m instead of 3.6 m, and 3 cm too close
#: with 2 cm inwards fell (``/tmp`` study with benchmarks.kick.place_ball_in_front_of).
FINE_ALONG_M = 0.012
FINE_ACROSS_M = 0.01
#: ... and facing the target within this (deg): the shuffles turn the robot too (session 30).
FINE_HEADING_DEG = 6.0
#: A shuffle moves the robot at most this far (m) along and across; larger errors walk again.
SHUFFLE_REACH_M = 0.06
#: How far (m) the torso moves sideways over the support foot before the other foot lifts
#: (the stand's feet are about 0.11 m apart), and how high (m) the foot lifts.
SHUFFLE_WEIGHT_SHIFT_M = 0.045
#: ... for feet this far (m) from the middle (types 0-2, 4); see :func:`shuffle_weight_shift`.
SHUFFLE_REFERENCE_HALF_SPACING_M = 0.055
SHUFFLE_LIFT_M = 0.02
#: A shuffle that also turns leads with the foot on the side of the turn unless its sideways
#: move is longer than this (m): then the foot on the side of the move goes first, so that a
#: foot never steps towards the other by more than this. Why the turn side: from a stand,
#: asked 3 cm forward, 2 cm right and 10 deg left, the robot turned 2-5 deg (type 3: -2.7)
#: leading with the right foot and 7-10 deg leading with the left (session 30, every type).
SHUFFLE_SIDE_FIRST_M = 0.025
#: A shuffle turns the robot by the heading error it measured, up to this (deg), and only when
#: the error exceeds SHUFFLE_TURN_MIN_DEG (the pose's heading is noisier than that).
SHUFFLE_TURN_MAX_DEG = 15.0
SHUFFLE_TURN_MIN_DEG = 2.0
#: Seconds per shuffle stage: weight shift, lift, move, lower (each foot), then back to the
#: middle. 0.5 (was 0.4): the slower shift leaves the robot calmer for the kick. Session 5
#: (benchmarks/kick.py --strengths --basic-trials 20 --basic-distance 3 [--layout-seed 1]):
#: layout seed 0 9 -> 5 falls, 7 -> 2 no-kicks, 2.42 -> 2.68 m; seed 1 4 -> 5 falls,
#: 5 -> 6 no-kicks, 2.57 m both; 0.6 made test layout 5 fall after contact (single trial).
SHUFFLE_SHIFT_S = 0.5
SHUFFLE_LIFT_S = 0.12
SHUFFLE_MOVE_S = 0.16
SHUFFLE_LOWER_S = 0.12
#: Balance while shuffling (off): the support legs' ankle roll moves by this gain (deg per deg)
#: against the torso's roll, as the walk's ``ankle_roll_gain`` does; with
#: ``SHUFFLE_SINGLE_SUPPORT_ONLY`` only while the other foot is in the air. Session 25 traced
#: the shuffle's falls (3 % of basic trials) to the open-loop weight shift: on one foot the
#: torso drifts 6-9 deg over the foot's edge, and now and then the shift to the other foot swings
#: it past that foot's edge. 0.3 ended those falls (6 -> 0 in 200 trials, ``python
#: scripts/kick/fall_stages.py``) but long kicks then went off line more often (more than 15 deg
#: off in 10 of 53 kicks against 3 of 52; single support only: 14 of 103 against 6 of 103,
#: and a shuffle fall remained), so it stays off. Outputs: ``runs/kick_shuffle/``.
SHUFFLE_ANKLE_ROLL_GAIN = 0.0
SHUFFLE_SINGLE_SUPPORT_ONLY = False
#: Shuffles before the robot kicks anyway (within the coarse ``READY_*`` limits) or walks off
#: and approaches again.
MAX_SHUFFLES = 3
#: Cycles in the stand between a shuffle's end and the next measurement.
SHUFFLE_SETTLE_CYCLES = 15
#: Cycles in the stand with the head level between the decision to kick and the kick, at
#: least; then the kick waits until the torso is calm (:class:`CalmWatch`), at most
#: ``CALM_MAX_CYCLES`` in all. Why: the walk's stop and the shuffle leave the torso swaying a
#: few degrees for a second or more, and the right kicks that started 15 cycles after the
#: head-up into such a sway fell over the support foot (5 of 20, benchmarks/kick.py); the same
#: layouts kicked 60 cycles later did not fall. But over all 20 layouts a 60-cycle wait fell 5
#: times, not 2 (``benchmarks/kick.py --head-up-cycles 60``): the kick's falls depend on its
#: start in ways a longer wait does not cure.
HEAD_UP_CYCLES = 15
CALM_MAX_CYCLES = 90
#: Calm: the perceived torso roll and pitch each stayed within this range (deg) over the last
#: ``CALM_WINDOW_CYCLES`` cycles.
CALM_RANGE_DEG = 0.8
CALM_WINDOW_CYCLES = 12


@dataclass(frozen=True)
class Alignment:
    """Where the ball lies against where the kick wants it, in the robot frame (x forward,
    y left), and how far the robot's heading is off the line to the target (deg, + = turn
    left)."""

    along_m: float
    across_m: float
    heading_deg: float

    def within(
        self, along_m: float, across_m: float, heading_deg: float = READY_HEADING_DEG
    ) -> bool:
        """The ball within ``along_m``/``across_m`` of where the kick wants it and the heading
        within ``heading_deg``."""
        return (
            abs(self.along_m) < along_m
            and abs(self.across_m) < across_m
            and abs(self.heading_deg) < heading_deg
        )

    @property
    def fine(self) -> bool:
        """Lined up well enough for the kick's full distance and direction."""
        return self.within(FINE_ALONG_M, FINE_ACROSS_M, FINE_HEADING_DEG)

    @property
    def within_shuffle(self) -> bool:
        """Close enough for :class:`FootShuffle` steps (which also turn) to finish the
        alignment."""
        return self.within(SHUFFLE_REACH_M, SHUFFLE_REACH_M, SHUFFLE_TURN_MAX_DEG)

    @property
    def ready(self) -> bool:
        """Close enough to kick."""
        return self.within(READY_ALONG_M, READY_ACROSS_M)


def shuffle_move(alignment: Alignment, expected: tuple[float, float]) -> tuple[float, float, float]:
    """The (forward m, left m, turn rad) a shuffle makes so that the ball, seen ``alignment``
    off ``expected`` (where the kick wants it, ego x, y relative to the torso), lies there
    afterwards, the robot facing the target: a turn by the heading error (beyond
    :data:`SHUFFLE_TURN_MIN_DEG`, at most :data:`SHUFFLE_TURN_MAX_DEG`) about the torso, and
    the move that then puts the ball at ``expected`` (each axis at most
    :data:`SHUFFLE_REACH_M`; the next settle measures again)."""
    heading = alignment.heading_deg if abs(alignment.heading_deg) > SHUFFLE_TURN_MIN_DEG else 0.0
    turn = math.radians(max(-SHUFFLE_TURN_MAX_DEG, min(SHUFFLE_TURN_MAX_DEG, heading)))
    ball_x, ball_y = expected[0] + alignment.along_m, expected[1] + alignment.across_m
    c, s = math.cos(turn), math.sin(turn)
    forward = ball_x - (c * expected[0] - s * expected[1])
    left = ball_y - (s * expected[0] + c * expected[1])
    reach = SHUFFLE_REACH_M
    return max(-reach, min(reach, forward)), max(-reach, min(reach, left)), turn


def wants_long(motion: KickMotion, distance: float | str) -> bool:
    """Whether ``distance`` (m or "long") lies beyond what ``motion``'s table reaches, so that
    the kick's long version (``kick_motion(..., long=True)``) should play."""
    return distance == LONG or (
        not isinstance(distance, str) and distance > motion.distance_range_m[1]
    )


def strength_for(motion: KickMotion, distance: float | str) -> float:
    """The kick strength (0..1) for ``distance`` metres or ``"long"`` (full strength)."""
    if distance == LONG:
        return 1.0
    assert not isinstance(distance, str)
    return motion.strength_for(distance)


def motion_for(
    robot_type: int,
    motions: Mapping[str, KickMotion] | None,
    foot: str,
    distance: float | str,
) -> tuple[KickMotion, bool]:
    """The motion ``basic_kick`` lines the ball up for and plays after its alignment, and
    whether it is the long version: the long one where ``distance`` lies beyond the short
    motion's table (:func:`wants_long`). Why the approach needs to know: each motion has its own
    ball spot (``ball_gap_m``, ``ball_side_m``), and the long kicks searched under the bounce
    contacts (session 20) want the ball 1-1.5 cm further out than the short ones."""
    short = kick_motion(robot_type, motions, foot, aligned=True)
    if wants_long(short, distance):
        return kick_motion(robot_type, motions, foot, aligned=True, long=True), True
    return short, False


def choose_foot(
    walk_m: Mapping[str, float],
    reach_m: Mapping[str, float],
    distance: float | str,
    credit: tuple[str, float] | None = None,
) -> str:
    """The foot to kick with: the one whose spot is nearer (``walk_m``, metres to walk), unless
    only the other one's kick reaches ``distance`` (``reach_m``: the furthest each foot's kick
    goes; for "long", the further reach wins), which then wins within
    :data:`REACH_PREFERENCE_M` of extra walking. ``credit`` (foot, metres): that foot wins
    within so much extra walking too (a robot type's steadier foot for the long kick,
    :data:`TYPE_LONG_KICK_FOOT_CREDIT_M`; session 26's head start for the left long kick of
    every type went in session 27, docs/tuning-history.md)."""
    wanted = math.inf if distance == LONG else float(distance)
    best_reach = max(reach_m.values())

    def cost(foot: str) -> float:
        short_of = reach_m[foot] < min(wanted, best_reach)
        bonus = credit[1] if credit is not None and credit[0] == foot else 0.0
        return walk_m[foot] + (REACH_PREFERENCE_M if short_of else 0.0) - bonus

    return min(FEET, key=cost)


def ball_gap_for(motion: KickMotion, distance: float | str | None = None) -> float:
    """How far ahead of the toe (m) the ball should lie for a kick of ``distance`` (m or
    "long"; None: the motion's own ``ball_gap_m``): a motion calibrated by its ball gap
    (``gap_distances``) gives the gap for the distance, except for a long kick, which plays
    the long motion with its own gap."""
    if distance is None or wants_long(motion, distance):
        return motion.ball_gap_m
    assert not isinstance(distance, str)
    return motion.gap_for(distance)


def expected_ball_ego(
    robot_type: int, foot: str, motion: KickMotion, distance: float | str | None = None
) -> tuple[float, float]:
    """Where the kick wants the ball's centre relative to the torso when the robot stands in
    ``stand`` (ego frame: x forward, y left; m), for a kick of ``distance`` (see
    :func:`ball_gap_for`).

    Why the stand pose rather than this cycle's joint angles: while the robot steps the feet
    swing by centimetres, and the kick starts from the stand anyway."""
    gap = ball_gap_for(motion, distance)
    return _expected_ball_ego(robot_type, foot, gap, motion.ball_side_m)


@cache
def _expected_ball_ego(robot_type: int, foot: str, gap: float, side: float) -> tuple[float, float]:
    spec = robot_spec(robot_type)
    name = "lfoot" if foot == "left" else "rfoot"
    foot_pose = body_transforms(spec, get_pose("stand").joints)[name]
    forward_native = foot_pose[:3, 1]  # the foot's own y axis points forward
    outwards_native = foot_pose[:3, 0] * (-1.0 if foot == "left" else 1.0)  # its x: right
    reach = spec.body(name).size[1] / 2 + BALL_RADIUS + gap
    point = foot_pose[:3, 3] + forward_native * reach + outwards_native * side
    return (float(point[1]), float(-point[0]))  # native (x right, y forward) -> ego


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


def foot_aim_deg(motion: KickMotion, foot: str, distance: float | str) -> float:
    """The ball's direction off the facing (deg, + = left) when ``foot`` kicks ``motion`` for
    ``distance``: the motion's aim for its strength (:meth:`KickMotion.aim_for`, written for the
    left foot), mirrored for the right."""
    aim = motion.aim_for(strength_for(motion, distance))
    return aim if foot == "left" else -aim


def aimed_target(
    ball: tuple[float, float], target: tuple[float, float], aim_deg: float
) -> tuple[float, float]:
    """``target`` turned by ``-aim_deg`` about the ball: where to face so that a kick whose
    ball goes ``aim_deg`` to the left of the robot's facing (:attr:`KickMotion.aim_deg`) goes to
    ``target``."""
    angle = math.radians(-aim_deg)
    c, s = math.cos(angle), math.sin(angle)
    dx, dy = target[0] - ball[0], target[1] - ball[1]
    return (ball[0] + c * dx - s * dy, ball[1] + s * dx + c * dy)


def aimed_motion(
    robot_type: int,
    motions: Mapping[str, KickMotion] | None,
    foot: str,
    distance: float | str,
    ball: tuple[float, float],
    target: tuple[float, float],
) -> tuple[KickMotion, bool, tuple[float, float]]:
    """What ``foot`` kicks for ``distance`` towards ``target``: the motion and whether it is
    the long one (:func:`motion_for`), and the point to line up on, the target turned about
    ``ball`` by the foot's aim (:func:`foot_aim_deg`, :func:`aimed_target`). One function for
    the skill and the tools that trace it (``scripts/kick/approach_trace.py``), so that they
    walk to the same spot."""
    motion, long = motion_for(robot_type, motions, foot, distance)
    aimed = aimed_target(ball, target, foot_aim_deg(motion, foot, distance))
    return motion, long, aimed


def detour_point(
    ball: tuple[float, float],
    spot: tuple[float, float, float],
    robot: tuple[float, float],
) -> tuple[float, float] | None:
    """A point behind the ball and beside it, on the robot's side, to walk to first when the
    straight way from the robot to the kicking ``spot`` (x, y, heading deg) passes closer than
    :data:`DETOUR_CLEARANCE_M` to the ball; None when the way is clear."""
    if _distance_to_segment(ball, robot, spot[:2]) >= DETOUR_CLEARANCE_M:
        return None
    if math.dist(robot, ball) < DETOUR_CLEARANCE_M:
        return None  # already at the ball: a detour would not help
    c, s = math.cos(math.radians(spot[2])), math.sin(math.radians(spot[2]))
    across = -s * (robot[0] - ball[0]) + c * (robot[1] - ball[1])
    side = DETOUR_SIDE_M if across >= 0 else -DETOUR_SIDE_M
    return (ball[0] - c * DETOUR_BEHIND_M - s * side, ball[1] - s * DETOUR_BEHIND_M + c * side)


def _distance_to_segment(
    point: tuple[float, float], start: tuple[float, float], end: tuple[float, float]
) -> float:
    px, py = point[0] - start[0], point[1] - start[1]
    ex, ey = end[0] - start[0], end[1] - start[1]
    length2 = ex * ex + ey * ey
    t = 0.0 if length2 == 0 else min(max((px * ex + py * ey) / length2, 0.0), 1.0)
    return math.hypot(px - t * ex, py - t * ey)


class BasicKickSkill(Skill):
    """``execute("basic_kick", target_x, target_y, distance)``: walk, line up, kick towards the
    team-frame point; ``distance`` in metres or ``"long"``. Finished when the kick motion has
    ended (the robot stands again).

    ``head_up_cycles`` (default :data:`HEAD_UP_CYCLES`) is the least wait in the stand before
    the kick; benchmarks set it to measure how the kick's falls depend on its start."""

    name = "basic_kick"

    def __init__(self, head_up_cycles: int = HEAD_UP_CYCLES) -> None:
        self.head_up_cycles = head_up_cycles
        #: the kick motions to line up for (None: the packaged ones); benchmarks of candidate
        #: kicks set their own, as on the ``kick`` skill, so both agree on where the ball goes
        self.motions: Mapping[str, KickMotion] | None = None
        self.reset()

    def reset(self) -> None:
        self.phase = "approach"
        self.foot: str | None = None
        #: the distance asked for (m or "long"), which sets where the ball should lie
        self._request: float | str = LONG
        self._strength = 1.0
        self._long = False
        self._settled = 0
        self._shuffle: FootShuffle | None = None
        self._shuffles = 0
        self._seen: list[tuple[float, float]] = []
        self._seen_time: float | None = None
        self._head_up = 0
        self._calm = CalmWatch()
        #: cycles into a search for a ball not where it was last seen, None: no search
        self._search_cycles: int | None = None

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
        self._request = distance
        if self.phase == "head_up":
            robot = context.world.robot
            self._calm.add(robot.roll_deg, robot.pitch_deg)
            waiting = self._head_up < self.head_up_cycles or not self._calm.calm
            if waiting and self._head_up < max(CALM_MAX_CYCLES, self.head_up_cycles):
                # head level before the kick: it was tuned so (a head pitched down fell more)
                self._head_up += 1
                context.manager.execute_sub_behavior("pose", "stand")
                return False
            self.phase = "kick"  # from here on the kick plays to its end
        if self.phase == "kick":
            assert self.foot is not None
            return context.manager.execute_sub_behavior(
                "kick", self.foot, self._strength, True, self._long
            )
        world = context.world
        if world.pose is None or world.ball.position is None:
            context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, 0.0)
            self._look_down(context)
            return False
        if self.phase == "approach" and self._searching(world):
            self._search(context)
            return False
        if self.foot is None or (
            self.phase == "approach"
            and world.distance_to(world.ball.position) > CHOOSE_FOOT_DISTANCE_M
        ):
            self.foot = self._choose_foot(context, (target_x, target_y))
        motion, long, target = aimed_motion(
            world.robot.robot_type,
            self.motions,
            self.foot,
            distance,
            world.ball.position[:2],
            (target_x, target_y),
        )
        alignment = self._alignment(context, motion, target)
        if self.phase in ("approach", "back_off"):
            self._approach(context, motion, target)
        elif self.phase == "shuffle":
            self._step_shuffle(context)
        else:
            self._settle(context, alignment, motion, long, distance)
        self._look_down(context)
        return False

    def _searching(self, world) -> bool:
        """Whether the approach turns on the spot to find the ball instead of walking to its
        estimate: from the moment the estimate lies in view (:data:`STALE_VIEW_DEG`, within
        :data:`STALE_VIEW_M`) but vision has not reported the ball for :data:`STALE_BALL_S`,
        until the ball is seen again (or :data:`SEARCH_MAX_S` have passed).

        Why: a ball moved while out of view (the trainer's placement in the benchmark, a kick
        by someone else in a game) leaves the estimate where it was last seen, and the robot
        walked to that spot, stood on it and turned only when its walk happened to bring the
        real ball into view (``scripts/kick/approach_trace.py``: 4.6 s lost walking to a ball 1
        m ahead that lay 2.4 m behind)."""
        ball = world.ball
        if self._search_cycles is not None:
            self._search_cycles += 1
            seen_again = ball.time_since_seen < STALE_BALL_S and self._search_cycles > 1
            if seen_again or self._search_cycles * CYCLE_SECONDS > SEARCH_MAX_S:
                self._search_cycles = None
            return self._search_cycles is not None
        stale = ball.time_since_seen > STALE_BALL_S
        in_view = abs(world.bearing_to(ball.position)) < STALE_VIEW_DEG
        near = STALE_VIEW_MIN_M < world.distance_to(ball.position) < STALE_VIEW_M
        if stale and in_view and near:
            self._search_cycles = 0
            return True
        return False

    def _search(self, context: SkillContext) -> None:
        """Stand and sweep the head left, then right (its 120 deg view covers all round in
        :data:`SEARCH_SWEEP_S`), then turn on the spot while looking ahead."""
        assert self._search_cycles is not None
        sweep = self._search_cycles * CYCLE_SECONDS
        if sweep < SEARCH_SWEEP_S:
            context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, 0.0)
            yaw = SEARCH_HEAD_YAW_DEG if sweep < SEARCH_SWEEP_S / 3.0 else -SEARCH_HEAD_YAW_DEG
            context.commands.set_targets({"hj1": yaw, "hj2": HEAD_PITCH_DEG})
            return
        context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, SEARCH_TURN_DEG_S)
        self._look_down(context)

    # ------------------------------------------------------------------ phases
    def _approach(
        self,
        context: SkillContext,
        motion: KickMotion,
        target: tuple[float, float],
    ) -> None:
        assert self.foot is not None
        world = context.world
        ball, pose = world.ball.position, world.pose
        assert ball is not None and pose is not None
        offset = self._stand_offset(context, motion)
        x, y, heading = kick_spot(ball, target, offset)
        aim = math.radians(heading)
        detour = detour_point(ball, (x, y, heading), (pose.x, pose.y))
        if detour is not None:
            context.manager.execute_sub_behavior("walk", *detour, None)
            return
        overshoot = TYPE_WALK_OVERSHOOT_M.get(world.robot.robot_type, WALK_OVERSHOOT_M)
        beyond = -BACK_OFF_M if self.phase == "back_off" else overshoot
        x += beyond * math.cos(aim)
        y += beyond * math.sin(aim)
        if context.manager.execute_sub_behavior("walk", x, y, heading):
            self.phase = "approach" if self.phase == "back_off" else "settle"

    def _settle(
        self,
        context: SkillContext,
        alignment: Alignment,
        motion: KickMotion,
        long: bool,
        distance: float | str,
    ) -> None:
        """Stand still, take the stand pose, then kick (``motion``, the long version when
        ``long``) if the ball lies where the kick wants it, else walk again."""
        stopping = self._settled == 0
        if stopping and not context.manager.execute_sub_behavior("walk_velocity", 0.0, 0.0, 0.0):
            return
        if self._settled < SETTLE_CYCLES:
            self._settled += 1
            context.manager.execute_sub_behavior("pose", "stand")
            if self._settled > SETTLE_CYCLES - SHUFFLE_SETTLE_CYCLES:
                self._sample_ball(context)
            return
        self._settled = 0
        alignment = self._seen_alignment(alignment, context, motion)
        if alignment.fine or (alignment.ready and self._shuffles >= MAX_SHUFFLES):
            self.phase = "head_up"
            self._long = long
            self._strength = strength_for(motion, distance)
        elif alignment.within_shuffle and self._shuffles < MAX_SHUFFLES:
            self.phase = "shuffle"
            self._shuffles += 1
            robot_type = context.world.robot.robot_type
            assert self.foot is not None
            expected = expected_ball_ego(robot_type, self.foot, motion, self._request)
            self._shuffle = FootShuffle(robot_type, *shuffle_move(alignment, expected))
        else:
            self.phase = "back_off"
            self._shuffles = 0

    def _step_shuffle(self, context: SkillContext) -> None:
        """Play the fine-alignment steps in the stand pose, then settle briefly and measure
        again."""
        assert self._shuffle is not None
        context.manager.execute_sub_behavior("pose", "stand")  # arms, head base, then legs
        if self._shuffle.step(context.commands, context.world.robot.roll_deg):
            self._shuffle = None
            self.phase = "settle"
            self._settled = SETTLE_CYCLES - SHUFFLE_SETTLE_CYCLES

    # ------------------------------------------------------------------ measurements
    def _choose_foot(self, context: SkillContext, target: tuple[float, float]) -> str:
        """The foot whose kicking spot lies nearer the robot (less walking), or the one whose
        kick reaches the distance asked, or the robot type's steadier foot for a long kick
        (:func:`choose_foot`)."""
        world = context.world
        ball = world.ball.position
        assert ball is not None
        robot_type = world.robot.robot_type
        walk_m, reach_m, long = {}, {}, {}
        for foot in FEET:
            motion, long[foot] = motion_for(robot_type, self.motions, foot, self._request)
            ego = expected_ball_ego(robot_type, foot, motion, self._request)
            walk_m[foot] = world.distance_to(kick_spot(ball, target, ego)[:2])
            reach_m[foot] = motion.distance_range_m[1]
        credit = TYPE_LONG_KICK_FOOT_CREDIT_M.get(robot_type)
        if credit is not None and not long[credit[0]]:
            credit = None  # the credit is the long kick's
        return choose_foot(walk_m, reach_m, self._request, credit)

    def _stand_offset(self, context: SkillContext, motion: KickMotion) -> tuple[float, float]:
        """Where the ball should lie relative to the torso (ego x, y) when the robot stands
        ready to kick."""
        assert self.foot is not None
        return expected_ball_ego(context.world.robot.robot_type, self.foot, motion, self._request)

    def _alignment(
        self, context: SkillContext, motion: KickMotion, target: tuple[float, float]
    ) -> Alignment:
        assert self.foot is not None
        world = context.world
        ball_ego = world.ball_relative_ego
        ball = world.ball.position
        pose = world.pose
        assert ball_ego is not None and ball is not None and pose is not None
        expected = expected_ball_ego(world.robot.robot_type, self.foot, motion, self._request)
        error = ball_ego[:2] - np.asarray(expected)
        wanted = math.degrees(math.atan2(target[1] - ball[1], target[0] - ball[0]))
        heading = (wanted - pose.heading_deg + 180.0) % 360.0 - 180.0
        return Alignment(float(error[0]), float(error[1]), heading)

    def _sample_ball(self, context: SkillContext) -> None:
        """Keep each new sight of the ball relative to the torso (ego x, y) while standing."""
        world = context.world
        relative = world.ball.relative
        if relative is None or world.last_vision_time == self._seen_time:
            return
        self._seen_time = world.last_vision_time
        self._seen.append((float(relative[1]), float(-relative[0])))  # native -> ego

    def _seen_alignment(
        self, alignment: Alignment, context: SkillContext, motion: KickMotion
    ) -> Alignment:
        """The alignment from the mean of the ball's sights of the last standing cycles.

        Why not the ball estimate: it lives in the field frame through the localizer's pose,
        which lags the shuffle's few centimetres (it has no odometry for them), while a sight
        relative to the torso does not depend on the pose at all."""
        seen, self._seen = self._seen, []
        if not seen:
            return alignment
        assert self.foot is not None
        expected = expected_ball_ego(
            context.world.robot.robot_type, self.foot, motion, self._request
        )
        along = sum(x for x, _ in seen) / len(seen) - expected[0]
        across = sum(y for _, y in seen) / len(seen) - expected[1]
        return Alignment(along, across, alignment.heading_deg)

    @staticmethod
    def _look_down(context: SkillContext) -> None:
        context.commands.set_targets({"hj1": 0.0, "hj2": HEAD_PITCH_DEG})


class CalmWatch:
    """Whether the standing torso has stopped swaying: its perceived roll and pitch each
    stayed within :data:`CALM_RANGE_DEG` over the last :data:`CALM_WINDOW_CYCLES` cycles.

    Why the tilt estimate rather than the gyro: the gyro's single readings jump by several
    deg/s even while the robot stands still, while a sway of a degree shows in the tilt."""

    def __init__(self) -> None:
        self._tilts: deque[tuple[float, float]] = deque(maxlen=CALM_WINDOW_CYCLES)

    def add(self, roll_deg: float, pitch_deg: float) -> None:
        self._tilts.append((roll_deg, pitch_deg))

    def clear(self) -> None:
        self._tilts.clear()

    @property
    def calm(self) -> bool:
        if len(self._tilts) < CALM_WINDOW_CYCLES:
            return False
        rolls = [roll for roll, _ in self._tilts]
        pitches = [pitch for _, pitch in self._tilts]
        return (
            max(rolls) - min(rolls) < CALM_RANGE_DEG
            and max(pitches) - min(pitches) < CALM_RANGE_DEG
        )


# ---------------------------------------------------------------------- fine alignment
@dataclass(frozen=True)
class _ShuffleStage:
    """One waypoint of a shuffle: torso and feet displacements (ego x forward, y left; m) from
    where they stood when it began, each foot's lift (m), the seconds to get there, and the
    torso's and the feet's turn (rad, + = left) from where they faced."""

    seconds: float
    torso: tuple[float, float]
    left: tuple[float, float]
    right: tuple[float, float]
    left_lift: float = 0.0
    right_lift: float = 0.0
    torso_yaw: float = 0.0
    left_yaw: float = 0.0
    right_yaw: float = 0.0


def shuffle_stages(
    forward: float,
    left: float,
    weight_shift: float = SHUFFLE_WEIGHT_SHIFT_M,
    turn: float = 0.0,
    stand_feet: Mapping[str, tuple[float, float]] | None = None,
) -> tuple[_ShuffleStage, ...]:
    """The waypoints that move a robot standing in ``stand`` by (``forward``, ``left``) m and
    turn it by ``turn`` rad about its torso: the weight onto one foot (the torso
    ``weight_shift`` m sideways), the other lifted, moved and put down turned, the weight onto
    it, the first foot likewise, the torso back between the feet. The foot on the side of the
    move goes first (a step out, then closing up), so the feet never cross; with no sideways
    move, the foot on the side of the turn. ``stand_feet`` (ego x, y of each foot in ``stand``,
    relative to the torso) is needed for a turn: each foot goes to where the turned stand puts
    it."""
    d = (forward, left)
    zero = (0.0, 0.0)
    w = weight_shift
    offsets = {"left": d, "right": d}
    if turn:
        if stand_feet is None:
            raise ValueError("a turning shuffle needs the stand's foot places")
        c, s = math.cos(turn), math.sin(turn)
        for side, (x, y) in stand_feet.items():
            offsets[side] = (forward + c * x - s * y - x, left + s * x + c * y - y)
    sideways = left if abs(left) > SHUFFLE_SIDE_FIRST_M or not turn else turn
    first = "left" if sideways >= 0.0 else "right"
    second = "right" if first == "left" else "left"

    def over(foot: str, at: tuple[float, float]) -> tuple[float, float]:
        side = w if foot == "left" else -w
        return (at[0], at[1] + side)

    def stage(
        at: Mapping[str, tuple[float, float]],
        yaw: Mapping[str, float],
        lifted: str | None,
        seconds: float,
        torso: tuple[float, float],
        torso_yaw: float,
    ) -> _ShuffleStage:
        lift_l = SHUFFLE_LIFT_M if lifted == "left" else 0.0
        lift_r = SHUFFLE_LIFT_M if lifted == "right" else 0.0
        return _ShuffleStage(
            seconds, torso, at["left"], at["right"], lift_l, lift_r, torso_yaw, yaw["left"],
            yaw["right"],
        )  # fmt: skip

    start = {"left": zero, "right": zero}
    unturned = {"left": 0.0, "right": 0.0}
    one = {**start, first: offsets[first]}
    one_yaw = {**unturned, first: turn}
    both = {**one, second: offsets[second]}
    both_yaw = {"left": turn, "right": turn}
    t1, t2 = over(second, zero), over(first, offsets[first])
    half = turn / 2.0
    return (
        stage(start, unturned, None, SHUFFLE_SHIFT_S, t1, 0.0),
        stage(start, unturned, first, SHUFFLE_LIFT_S, t1, 0.0),
        stage(one, one_yaw, first, SHUFFLE_MOVE_S, t1, 0.0),
        stage(one, one_yaw, None, SHUFFLE_LOWER_S, t1, 0.0),
        stage(one, one_yaw, None, 2 * SHUFFLE_SHIFT_S, t2, half),
        stage(one, one_yaw, second, SHUFFLE_LIFT_S, t2, half),
        stage(both, both_yaw, second, SHUFFLE_MOVE_S, t2, half),
        stage(both, both_yaw, None, SHUFFLE_LOWER_S, t2, half),
        stage(both, both_yaw, None, SHUFFLE_SHIFT_S, d, turn),
    )


class FootShuffle:
    """Small steps in place, driven by leg inverse kinematics from the ``stand`` pose: moves
    the standing robot by a few centimetres and leaves both feet parallel in the stand pose.

    Why not the walk: it cannot make steps much shorter than 3-4 cm, so lining a foot up behind
    the ball to a centimetre by walking oscillated. Every stage is a straight, cosine-eased
    move of the torso and feet (relative to where they stood) that the joints follow through
    their angle targets; one foot moves only while the weight rests on the other.
    """

    def __init__(self, robot_type: int, forward: float, left: float, turn: float = 0.0) -> None:
        """Move by (``forward``, ``left``) m and turn by ``turn`` rad (+ = left) about the
        torso."""
        self._ik = leg_ik_for(robot_type)
        self._stand = _stand_feet(robot_type)
        #: each foot's stand place, ego x, y relative to the torso (native x is the robot's right)
        self._stand_ego = {
            side: (float(t[1, 3]), float(-t[0, 3])) for side, t in self._stand.items()
        }
        weight_shift = shuffle_weight_shift(robot_type)
        self._stages = shuffle_stages(forward, left, weight_shift, turn, self._stand_ego)
        self._elapsed = 0.0
        self._start = _ShuffleStage(0.0, (0.0, 0.0), (0.0, 0.0), (0.0, 0.0))

    @property
    def duration(self) -> float:
        return sum(stage.seconds for stage in self._stages)

    def step(self, commands: JointCommands, roll_deg: float = 0.0) -> bool:
        """Write this cycle's leg targets; True once the last stage has been reached.
        ``roll_deg`` (the torso's roll, + = leaning right) tilts the support ankles against it
        by ``SHUFFLE_ANKLE_ROLL_GAIN`` (off by default); a lifted foot is no support."""
        self._elapsed += CYCLE_SECONDS
        stage, share, before = self._stage_at(self._elapsed)
        blend = 0.5 - 0.5 * math.cos(math.pi * share)

        def mix(a: tuple[float, float], b: tuple[float, float]) -> tuple[float, float]:
            return (a[0] + (b[0] - a[0]) * blend, a[1] + (b[1] - a[1]) * blend)

        def between(a: float, b: float) -> float:
            return a + (b - a) * blend

        torso = mix(before.torso, stage.torso)
        torso_yaw = between(before.torso_yaw, stage.torso_yaw)
        lifts = {
            "left": between(before.left_lift, stage.left_lift),
            "right": between(before.right_lift, stage.right_lift),
        }
        yaws = {
            "left": between(before.left_yaw, stage.left_yaw),
            "right": between(before.right_yaw, stage.right_yaw),
        }
        feet = {"left": mix(before.left, stage.left), "right": mix(before.right, stage.right)}
        for side in FEET:
            transform = self._foot_transform(side, feet[side], yaws[side], torso, torso_yaw)
            transform[2, 3] += lifts[side]
            angles = dict(self._ik.solve(side, transform).angles_deg)
            other = "right" if side == "left" else "left"
            if lifts[side] <= 0.0 and (lifts[other] > 0.0 or not SHUFFLE_SINGLE_SUPPORT_ONLY):
                angles[f"{side[0]}lj6"] += SHUFFLE_ANKLE_ROLL_GAIN * roll_deg
            commands.set_targets(angles)
        return self._elapsed >= self.duration

    def _foot_transform(
        self,
        side: str,
        moved: tuple[float, float],
        yaw: float,
        torso: tuple[float, float],
        torso_yaw: float,
    ) -> np.ndarray:
        """The foot's transform relative to the torso (native frame, as the leg IK takes it)
        with the foot moved by ``moved`` and turned by ``yaw`` from its stand place, the torso
        by ``torso`` and ``torso_yaw`` (start frame, ego axes)."""
        stand_x, stand_y = self._stand_ego[side]
        x, y = stand_x + moved[0] - torso[0], stand_y + moved[1] - torso[1]
        c, s = math.cos(torso_yaw), math.sin(torso_yaw)
        ego_x, ego_y = c * x + s * y, -s * x + c * y
        transform = self._stand[side].copy()
        transform[0, 3] = -ego_y  # native x = the robot's right
        transform[1, 3] = ego_x  # native y = forward
        turn = yaw - torso_yaw
        if turn:
            c, s = math.cos(turn), math.sin(turn)
            yaw_rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
            transform[:3, :3] = yaw_rotation @ transform[:3, :3]
        return transform

    def _stage_at(self, elapsed: float) -> tuple[_ShuffleStage, float, _ShuffleStage]:
        """The stage being played, the share of it done (0..1) and the stage before it."""
        before = self._start
        for stage in self._stages:
            if elapsed < stage.seconds:
                return stage, elapsed / stage.seconds, before
            elapsed -= stage.seconds
            before = stage
        return before, 1.0, before


@cache
def shuffle_weight_shift(robot_type: int) -> float:
    """How far (m) a shuffle moves the torso sideways over its support foot: the share of half
    the stand's foot spacing that ``SHUFFLE_WEIGHT_SHIFT_M`` is on types 0-2 and 4 (feet 0.11 m
    apart). Why: type 3 stands on feet 0.146 m apart, and with the same 0.045 m its weight stayed
    partly on the lifted foot, whose moves then gave way: its shuffles moved the robot by about
    40 % of the distance asked (4.4 -> 3.9 -> 2.4 cm), it shuffled two or three times and ran
    out of time in 5-8 of 40 basic kicks (session 30)."""
    feet = _stand_feet(robot_type)
    half_spacing = abs(float(feet["left"][0, 3] - feet["right"][0, 3])) / 2.0
    return SHUFFLE_WEIGHT_SHIFT_M * half_spacing / SHUFFLE_REFERENCE_HALF_SPACING_M


@cache
def _stand_feet(robot_type: int) -> dict[str, np.ndarray]:
    """Both foot bodies' transforms relative to the torso (native frame) in ``stand``."""
    transforms = body_transforms(robot_spec(robot_type), get_pose("stand").joints)
    return {"left": transforms["lfoot"], "right": transforms["rfoot"]}
