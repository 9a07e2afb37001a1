"""The strategy layer: formation, beam before kick-off, roles, and which behaviour runs when.

Kept deliberately small: it decides, behaviours act. Each cycle :meth:`Strategy.decide` reads
the world model (perception-fed only) and calls ``Behavior.execute`` with the chosen skill.
Positions are in the team frame: x towards the opponent goal, own goal at x = -15.

Roles (:mod:`agent.roles`): every player says how far it is from the ball (a short ``say``
message, :func:`~agent.roles.claim_message`) and listens to its teammates' claims; the field
player with the lowest claim is *active* and goes for the ball, and nobody else does, so a
team does not converge on the ball in a crowd that knocks itself over. Without claims (a
teammate that says nothing), the teammates it has seen count. The goalkeeper guards its goal
line and goes for the ball only when the ball is in front of its goal and it is the closest.
The field player with the next-lowest claim supports: it waits ahead of and beside the ball
for a loose ball (:class:`~agent.strategy_config.SupportConfig`). The others hold their
formation places, facing the ball so they keep seeing it. A player that has not seen the ball
for a few seconds turns on the spot until it sees it again. The settings of all this live in
:mod:`agent.strategy_config` (read from ``config/team.yaml``).

The active player walks to a point behind the ball on the line to its aim in the opponent goal
(the middle, or the side away from a goalkeeper it sees), going round the ball first when it
stands in front of it, dribbles towards the aim once there and facing it, and shoots with
``basic_kick`` when the ball is within kicking range of the goal (``AttackConfig``);
optionally (``snap_range_m``, off) it stops and kicks at once with the stand kick when near
the goal the ball lies at a foot's kick spot with the robot facing into the goal mouth. A
skill that is not registered is skipped (the player walks or stands instead), so the strategy
runs with whatever skills exist.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from agent.attack_keeper import aim_point, contested, detour_point, free_heading, open_side
from agent.avoidance import avoidance_waypoint
from agent.roles import ClaimBoard, claim_message, is_closest, my_turn_to_speak, parse_claim
from agent.strategy_config import AttackConfig, StrategyConfig
from behaviors.basic_kick import expected_ball_ego
from behaviors.kick import FEET, kick_motion
from world.field_geometry import GOAL_WIDTH, HALF_LENGTH, HALF_WIDTH
from world.localization import wrap_deg

#: Play modes in which the rules allow beaming.
BEAM_MODES = ("BeforeKickOff", "Goal_Left", "Goal_Right")
#: A teammate whose estimate is older than this (s) is not counted in role assignment.
TEAMMATE_MEMORY_S = 3.0
#: An opponent seen this recently (s) can be the goalkeeper to shoot past.
OPPONENT_MEMORY_S = 2.0
#: A ball not seen for this long (s) is lost: the player stops trusting the estimate (it may
#: have been kicked away unseen) and turns on the spot until it sees the ball again.
BALL_LOST_S = 3.0
#: Turning speed (deg/s) while searching for the ball.
SEARCH_TURN_DEG_S = 40.0
#: A ball lost while last seen this close (m) to the torso lies under the robot, below its
#: view: the player steps back (at ``STEP_BACK_M_S``) to see it instead of turning on the
#: spot over it, which the referee calls ball holding after 5 s.
LOST_AT_FEET_M = 0.3
STEP_BACK_M_S = 0.3
#: A player that gets up with the ball estimated this close (m) steps back first. Wider than
#: LOST_AT_FEET_M: the estimates made while lying are poor (measured: 0.34 m estimated, 0.02 m
#: true, for a robot that had lain 4 s on the ball and was called for holding 2.6 s later).
GOT_UP_NEAR_BALL_M = 0.5
#: Players holding their place face the ball to the nearest multiple of this angle (deg).
HOLD_HEADING_STEP_DEG = 30.0
#: Skills that leave the head alone, so the strategy turns it towards the ball
#: (:func:`head_yaw_for`): within HEAD_STILL_DEG of the torso's heading the head looks ahead,
#: and it turns at most HEAD_YAW_MAX_DEG (the neck allows 120).
HEAD_FREE_SKILLS = ("walk", "walk_velocity")
HEAD_STILL_DEG = 30.0
HEAD_YAW_MAX_DEG = 90.0
#: basic_kick phases from which its kick plays on whoever comes to the ball
#: (:meth:`Strategy._shot_contested`)
COMMITTED_KICK_PHASES = ("head_up", "kick")
#: a finishing aim (:attr:`AttackConfig.finish_m`) lies this far beyond the goal line (m)
FINISH_AHEAD_M = 1.0


@dataclass(frozen=True)
class Decision:
    """What the strategy wants sent besides joint speeds this cycle."""

    beam: tuple[float, float, float] | None = None
    say: str | None = None


def opponents_restart(play_mode: str, side: str | None) -> bool:
    """Whether the opponents are taking a kick-off or set piece: then the rules keep our
    players away from the ball (outside the centre circle, or the free-kick distance)."""
    lower = play_mode.lower()
    if side is None or lower == "playon" or not lower.endswith(("_left", "_right")):
        return False
    return not lower.endswith("_" + side)


def _turned_aim(
    ball: tuple[float, float], aim: tuple[float, float], side: float, turn_deg: float
) -> tuple[float, float]:
    """A point 5 m from ``ball`` on the line to ``aim`` turned ``turn_deg`` to the ``side``
    (+1 left, -1 right): where the escape from a stall and the kick-off's turn aim."""
    heading = math.atan2(aim[1] - ball[1], aim[0] - ball[0])
    heading += side * math.radians(turn_deg)
    return (ball[0] + 5.0 * math.cos(heading), ball[1] + 5.0 * math.sin(heading))


def ball_lost(world) -> bool:
    """Whether the ball has gone unseen for :data:`BALL_LOST_S` or was never seen."""
    ball = world.ball
    return ball.position is None or getattr(ball, "time_since_seen", 0.0) > BALL_LOST_S


def dodge_heading(
    ball: tuple[float, float],
    heading_deg: float,
    opponents: list[tuple[float, float]],
    attack: AttackConfig,
) -> float:
    """The dribble heading (deg): ``heading_deg``, turned ``attack.dodge_deg`` away from the
    nearest opponent standing in the way ahead of the ball (dribbling into a robot loses the
    ball or knocks both over)."""
    h = math.radians(heading_deg)
    ux, uy = math.cos(h), math.sin(h)
    nearest: tuple[float, float] | None = None
    for ox, oy in opponents:
        rx, ry = ox - ball[0], oy - ball[1]
        along, across = rx * ux + ry * uy, -rx * uy + ry * ux
        in_way = 0.0 < along < attack.dodge_ahead_m and abs(across) < attack.dodge_across_m
        if in_way and (nearest is None or along < nearest[0]):
            nearest = (along, across)
    if nearest is None:
        return heading_deg
    return heading_deg - math.copysign(attack.dodge_deg, nearest[1] if nearest[1] else 1.0)


def approach_point(
    robot: tuple[float, float],
    ball: tuple[float, float],
    aim: tuple[float, float],
    behind_m: float,
    round_m: float,
) -> tuple[float, float]:
    """Where to walk to get behind the ball on the line ball -> aim.

    A robot that is not behind the ball (level with it or in front, and less than ``round_m``
    to its side) first walks to a point beside and a little behind it, on its own side: the
    straight way to the point behind would walk through the ball and knock it back.
    """
    bx, by = ball
    heading = math.atan2(aim[1] - by, aim[0] - bx)
    ux, uy = math.cos(heading), math.sin(heading)
    rx, ry = robot[0] - bx, robot[1] - by
    along, across = rx * ux + ry * uy, -rx * uy + ry * ux
    if along > -0.5 * behind_m and abs(across) < round_m:
        side = 1.0 if across >= 0.0 else -1.0
        return (
            bx - behind_m * ux - side * round_m * uy,
            by - behind_m * uy + side * round_m * ux,
        )
    return (bx - behind_m * ux, by - behind_m * uy)


class StallWatch:
    """Notices when the ball stays put while the player goes for it: both sides then push it
    against each other, and the referee's ball-holding rule does not end it."""

    def __init__(self) -> None:
        self._since: float | None = None
        self._where: tuple[float, float] | None = None

    def reset(self) -> None:
        self._since = self._where = None

    def stalled(
        self, now: float, ball: tuple[float, float], window_s: float, still_m: float
    ) -> bool:
        """Record the ball at ``now``; True once it has stayed within ``still_m`` of where it
        was ``window_s`` or more ago (then the watch starts over)."""
        if self._where is None or math.dist(ball, self._where) > still_m:
            self._since, self._where = now, ball
            return False
        if now - self._since >= window_s:
            self.reset()
            return True
        return False


class HoldWatch:
    """Counts how long the ball has stayed close to the torso, forgiving short gaps the way
    the referee's ball-holding rule does (its record restarts only after 0.5 s without
    holding), so the player can let go before the referee calls the foul."""

    #: a gap at least this long (s) restarts the count, as BallHoldResetTime does
    RESET_S = 0.5

    def __init__(self) -> None:
        self._held_s = 0.0
        self._free_s = 0.0
        self._last: float | None = None

    def reset(self) -> None:
        self._held_s = self._free_s = 0.0
        self._last = None

    def update(self, now: float, holding: bool) -> float:
        """Record whether the ball is held at ``now``; return the seconds held so far."""
        dt = 0.0 if self._last is None else max(0.0, now - self._last)
        self._last = now
        if holding:
            self._held_s += dt
            self._free_s = 0.0
        else:
            self._free_s += dt
            if self._free_s >= self.RESET_S:
                self._held_s = 0.0
        return self._held_s


class Strategy:
    """Formation, beaming and role assignment for one agent."""

    def __init__(self, config: StrategyConfig | None = None) -> None:
        self.config = config or StrategyConfig()
        self._beamed_in_mode: str | None = None
        self._dribbling = False
        self._getting_up = False
        self._was_active = False
        self._claims = ClaimBoard()
        self._stall = StallWatch()
        #: until when (world time) and which way (+1 left, -1 right) the ball is taken off
        #: the line to the aim to get out of a stall
        self._escape: tuple[float, float] | None = None
        #: a stall shot has started: basic_kick runs to its end while this player is active
        self._shooting = False
        #: when (world time) the stall shot started
        self._shot_since = 0.0
        self._hold = HoldWatch()
        #: until when (world time) the player steps back off a ball it has held too long
        self._back_off_until: float | None = None
        #: the foot of a snap shot's kick under way (it plays to its end), else None
        self._snap_foot: str | None = None
        #: a snap shot stopping to kick: when (world time) the stop began
        self._snap_stop_since: float | None = None
        #: no new snap shot before this world time (one was just given up)
        self._snap_not_before = 0.0
        #: the goal side aimed at past a keeper (+1 / -1), None before a keeper was seen
        self._aim_side: float | None = None
        #: the dribble gait of the dribble under way (chosen as it starts)
        self._gait: str | None = None
        #: yielding a contested ball: when (world time) it began, None while not yielding
        self._yield_since: float | None = None
        #: no new yield before this world time
        self._yield_not_before = 0.0
        #: the turn (deg/s) of the search for a lost ball under way, None while not searching
        self._search_turn: float | None = None
        #: sprinting to the approach point (see :attr:`AttackConfig.sprint_m`)
        self._sprinting = False
        #: until when (world time) and which way (+1 left, -1 right) the aim turns after the
        #: team's kick-off (see :attr:`AttackConfig.kickoff_turn_deg`)
        self._kickoff_turn: tuple[float, float] | None = None
        #: last cycle this player shot from within the kick range (see
        #: :attr:`AttackConfig.kick_range_hold_m`)
        self._range_shot = False

    def decide(self, world, behavior) -> Decision:
        """Pick this cycle's behaviour (through ``behavior.execute``), any beam and the claim
        to say."""
        beam = self._beam(world)
        self._claims.hear(world)
        claim = self.claim(world)
        active = self.is_active(world, claim)
        if not self._was_active:
            self._stall.reset()
        if not active:
            self._shooting = self._sprinting = self._range_shot = False
            self._snap_stop_since = None
        self._was_active = False
        if not ball_lost(world):
            self._search_turn = None
        held_s = self._count_holding(world)
        if world.robot.is_fallen:
            self._snap_foot = self._snap_stop_since = None
        if self._snap_stop_since is not None:
            self._was_active = True
            self._snap_stop(world, behavior)
        elif self._snap_foot is not None:
            # a started kick plays to its end: stopping it halfway leaves the robot on one leg
            if behavior.execute("kick", self._snap_foot, 1.0):
                self._snap_foot = None
        elif "get_up" in behavior.skill_names and (world.robot.is_fallen or self._getting_up):
            # once started, the get-up runs until it reports the robot standing: halfway up
            # (sitting, torso 50 deg from vertical) the robot no longer counts as fallen, and
            # walking off from there drops it again
            self._getting_up = not behavior.execute("get_up")
            if not self._getting_up and _ball_within(world, GOT_UP_NEAR_BALL_M):
                # up over the ball: the referee has counted the time lying on it as holding,
                # and the own estimates were wrong while lying (see _count_holding)
                self._back_off_until = (world.time or 0.0) + self.config.attack.back_off_s
        elif world.play_mode in BEAM_MODES or world.play_mode == "GameOver":
            behavior.execute("pose", "stand")
        elif world.pose is not None and self._backing_off(world, held_s):
            self._backing_off_step(world, world.ball.position, behavior)
        elif ball_lost(world) and "walk_velocity" in behavior.skill_names:
            self._dribbling = False
            if _last_seen_at_feet(world):
                behavior.execute("walk_velocity", -STEP_BACK_M_S, 0.0, 0.0)
            else:
                if self._search_turn is None:  # chosen once per search: see search_turn_deg_s
                    self._search_turn = search_turn_deg_s(world)
                behavior.execute("walk_velocity", 0.0, 0.0, self._search_turn)
        elif active and not opponents_restart(world.play_mode, world.side):
            self._was_active = True
            self._go_for_ball(world, behavior)
        elif self.is_goalie(world):
            self._guard_goal(world, behavior)
        elif self.is_support(world, claim) and not opponents_restart(world.play_mode, world.side):
            self._support(world, behavior)
        else:
            self._hold_position(world, behavior)
        _look_towards_ball(world, behavior)
        return Decision(beam=beam, say=self._say(world, claim))

    @staticmethod
    def _say(world, claim: float | None) -> str | None:
        """The claim, said in this player's turn only (see :mod:`agent.roles`)."""
        if claim is None or world.unum is None or world.time is None:
            return None
        if not my_turn_to_speak(world.unum, world.time):
            return None
        return claim_message(world.unum, claim)

    # ------------------------------------------------------------------ roles
    def home(self, unum: int | None) -> tuple[float, float]:
        return self.config.formation.get(unum or 0, (-5.0, 0.0))

    def play_home(self, unum: int | None) -> tuple[float, float]:
        """The place held during play (:attr:`StrategyConfig.play_places`, else the
        formation's)."""
        return self.config.play_places.get(unum or 0, self.home(unum))

    def is_goalie(self, world) -> bool:
        return world.unum is not None and world.unum == self.config.goalie_unum

    def claim(self, world) -> float | None:
        """This player's claim on the ball (lower wins): its distance to the ball, less a
        little while it is already the active player (so two players at nearly the same
        distance do not swap every cycle), more while it lies on the ground. None: no claim
        (ball or own pose unknown, or a goalkeeper whose goal is not threatened)."""
        ball = world.ball.position
        if ball is None or world.pose is None or ball_lost(world):
            return None
        if self.is_goalie(world) and not self._ball_threatens_goal(ball):
            return None
        distance = math.dist((world.pose.x, world.pose.y), ball)
        if world.robot.is_fallen or self._getting_up:
            distance += 2.0
        if self._was_active:
            distance -= 0.3
        return max(distance, 0.0)

    def is_active(self, world, claim: float | None = None) -> bool:
        """Whether this player goes for the ball: it has the lowest claim among its
        teammates' recent claims, and is no farther than any teammate it has seen."""
        if claim is None:
            claim = self.claim(world)
        ball = world.ball.position
        if claim is None or ball is None or world.time is None or world.unum is None:
            return False
        seen_closer = any(
            math.dist(mate.position, ball) < claim - 0.3
            for mate in world.teammates.recent(world.time, TEAMMATE_MEMORY_S)
            if mate.unum != world.unum
            and not self._claims.has(mate.unum, world.time)
            and mate.unum != self.config.goalie_unum
        )
        return not seen_closer and is_closest(self._claims, world.unum, claim, world.time)

    def is_support(self, world, claim: float | None = None) -> bool:
        """Whether this player supports the attack: it is not active, and exactly one
        teammate claims the ball more strongly (lower claim, ties to the lower unum)."""
        if claim is None or world.time is None or world.unum is None:
            return False
        support = self.config.support
        if support.ahead_m <= 0.0 and support.side_m <= 0.0:
            return False
        ball = world.ball.position
        if ball is None or ball[0] < support.from_x_m:
            return False
        mine = parse_claim(claim_message(world.unum, claim))
        own = claim if mine is None else mine[1]
        stronger = [
            unum
            for unum, other in self._claims.recent(world.time).items()
            if unum != world.unum and (other, unum) < (own, world.unum)
        ]
        return len(stronger) == 1

    def support_point(self, ball: tuple[float, float]) -> tuple[float, float]:
        """Where the supporting player waits: ahead of the ball towards the opponent goal,
        beside the line, on the side nearer the middle of the field, inside the field."""
        support = self.config.support
        heading = math.atan2(-ball[1], HALF_LENGTH - ball[0])
        ux, uy = math.cos(heading), math.sin(heading)
        side = -1.0 if ball[1] > 0.0 else 1.0
        x = ball[0] + support.ahead_m * ux - side * support.side_m * uy
        y = ball[1] + support.ahead_m * uy + side * support.side_m * ux
        x = min(x, HALF_LENGTH - support.margin_m)
        y_limit = HALF_WIDTH - support.margin_m
        return x, max(-y_limit, min(y_limit, y))

    def _ball_threatens_goal(self, ball: tuple[float, float]) -> bool:
        own_goal = (-HALF_LENGTH, 0.0)
        return math.dist(ball, own_goal) < self.config.keeper.clear_range_m

    # ------------------------------------------------------------------ actions
    def _beam(self, world) -> tuple[float, float, float] | None:
        """Beam once each time a beam-allowed mode starts, to the formation place."""
        if world.play_mode not in BEAM_MODES or world.side is None:
            self._beamed_in_mode = None
            return None
        if self._beamed_in_mode == world.play_mode:
            return None
        self._beamed_in_mode = world.play_mode
        x, y = self.home(world.unum)
        return (x, y, 0.0)

    def aim(self, world) -> tuple[float, float]:
        """The point in the opponent goal to play the ball to: the centre, or the side away
        from an opponent standing near the goal centre (its goalkeeper); straight over the
        line from a ball right in front of the goal mouth (:attr:`AttackConfig.finish_m`)."""
        attack = self.config.attack
        ball = world.ball.position
        if ball is not None and _in_front_of_goal_mouth(ball, attack):
            return (HALF_LENGTH + FINISH_AHEAD_M, ball[1])
        goal = (HALF_LENGTH, 0.0)
        opponents = getattr(world, "opponents", None)
        if opponents is None or world.time is None or attack.aim_side_m <= 0.0:
            return goal
        keeper = opponents.nearest(goal, world.time, OPPONENT_MEMORY_S)
        if keeper is None or math.dist(keeper.position, goal) > attack.keeper_near_m:
            return goal
        ball = world.ball.position
        if attack.aim_post_margin_m > 0.0 and ball is not None:
            self._aim_side = open_side(
                ball,
                keeper.position[:2],
                attack.aim_post_margin_m,
                self._aim_side,
                attack.aim_switch_deg,
            )
            return aim_point(self._aim_side, attack.aim_post_margin_m)
        side = -1.0 if keeper.position[1] >= 0.0 else 1.0
        return (HALF_LENGTH, side * min(attack.aim_side_m, GOAL_WIDTH / 2 - 0.2))

    def _go_for_ball(self, world, behavior) -> None:
        """Shoot when in range, dribble when behind the ball facing the aim, else approach."""
        skills = behavior.skill_names
        if "walk" not in skills or world.pose is None:
            behavior.execute("pose", "stand")
            return
        attack = self.config.attack
        bx, by = world.ball.position
        range_shot = self._range_shot  # a shot from within the range under way
        range_m = attack.kick_range_m + (attack.kick_range_hold_m if range_shot else 0.0)
        self._range_shot = False
        if self._yielding(world) and "walk_velocity" in skills:
            self._dribbling = False
            behavior.execute("walk_velocity", 0.0, 0.0, 0.0)
            return
        snap_allowed = "kick" in skills and (world.time or 0.0) >= self._snap_not_before
        if snap_allowed and self.snap_foot(world) is not None:
            self._dribbling = self._shooting = False
            self._snap_stop_since = world.time or 0.0
            self._snap_stop(world, behavior)
            return
        if self._shooting:
            self._end_overdue_shot(world, (bx, by))
        if _no_stall_shot_at((bx, by), attack):
            self._shooting = False
        goal_x, goal_y = self._escape_aim(world, (bx, by), self.aim(world), range_shot)
        goal_x, goal_y = self._kickoff_aim(world, (bx, by), (goal_x, goal_y))
        detour = self._detour(world, (bx, by), (goal_x, goal_y))
        if detour is not None:
            goal_x, goal_y = detour
        to_goal = math.atan2(goal_y - by, goal_x - bx)
        to_goal_m = math.dist((bx, by), (HALF_LENGTH, 0.0))
        can_dribble = "dribble" in skills
        in_range = to_goal_m < range_m and to_goal_m >= attack.dribble_in_m
        if in_range and self._shot_contested(world, (bx, by), behavior):
            in_range = False
        if "basic_kick" in skills and (in_range or not can_dribble or self._shooting):
            self._dribbling = False
            self._range_shot = in_range
            finished = behavior.execute("basic_kick", goal_x, goal_y, "long")
            self._shooting = self._shooting and not finished
            return
        pose = world.pose
        approach = approach_point(
            (pose.x, pose.y), (bx, by), (goal_x, goal_y), attack.behind_ball_m, attack.round_ball_m
        )
        behind = (
            bx - attack.behind_ball_m * math.cos(to_goal),
            by - attack.behind_ball_m * math.sin(to_goal),
        )
        facing = abs(wrap_deg(pose.heading_deg - math.degrees(to_goal)))
        if can_dribble:
            gap = math.dist((pose.x, pose.y), (bx, by))
            near_ball = attack.dribble_min_m < gap < attack.dribble_keep_m
            ready = (
                math.dist((pose.x, pose.y), behind) < attack.dribble_start_m
                and facing < attack.dribble_align_deg
            )
            starting = not self._dribbling
            self._dribbling = ready or (self._dribbling and near_ball)
            if self._dribbling:
                if starting or self._gait is None:
                    # the gait is chosen as a dribble starts: a walk engine changed mid-stride
                    # starts from its first step, under a robot that is in its last one
                    self._gait = self._dribble_kind((bx, by))
                heading = math.degrees(to_goal)
                if attack.detour_clear_m <= 0.0:  # a detour passes opponents itself
                    heading = self._dribble_heading(world, (bx, by), heading)
                behavior.execute("dribble", self._gait, heading, "left")
                return
        waypoint = self._round_robots(world, approach)
        if waypoint is not None:
            self._walk_to(world, behavior, waypoint, _heading_to(waypoint, approach))
            return
        self._walk_to(world, behavior, approach, math.degrees(to_goal))

    def _shot_contested(self, world, ball: tuple[float, float], behavior) -> bool:
        """Whether an opponent within :attr:`AttackConfig.shot_contest_m` of the ball stops a
        range shot: none starts, and one still walking up or lining up ends (the dribble takes
        the ball on). A kick past its head-up (its last wait before the swing) plays on."""
        radius = self.config.attack.shot_contest_m
        if radius <= 0.0:
            return False
        current = behavior.current
        kicking = current is not None and current.name == "basic_kick"
        if kicking and behavior.skill("basic_kick").phase in COMMITTED_KICK_PHASES:
            return False
        return any(math.dist(p, ball) < radius for p in self._opponent_positions(world))

    def _round_robots(self, world, target: tuple[float, float]) -> tuple[float, float] | None:
        """A waypoint beside a robot in the way to ``target`` (see
        :attr:`AttackConfig.avoid_clear_m`), or None."""
        attack = self.config.attack
        if attack.avoid_clear_m <= 0.0:
            return None
        robots = _recent_positions(world, "opponents") + _recent_positions(world, "teammates")
        pose = world.pose
        return avoidance_waypoint(
            (pose.x, pose.y),
            target,
            robots,
            attack.avoid_clear_m,
            attack.avoid_target_zone_m,
            attack.avoid_beyond_m,
        )

    def _dribble_heading(self, world, ball: tuple[float, float], heading_deg: float) -> float:
        """The dribble's heading past the opponents in its way: into free space
        (:attr:`AttackConfig.free_space_deg`), else the fixed dodge."""
        attack = self.config.attack
        opponents = self._opponent_positions(world)
        if self.config.free_space_deg <= 0.0:
            return dodge_heading(ball, heading_deg, opponents, attack)
        return free_heading(
            ball,
            heading_deg,
            opponents,
            self.config.free_space_deg,
            attack.free_space_step_deg,
            attack.free_space_ahead_m,
            attack.free_space_clear_m,
        )

    def _walk_to(self, world, behavior, target: tuple[float, float], heading_deg: float) -> None:
        """Walk to ``target`` facing ``heading_deg`` there, sprinting on the way while it is
        far (:attr:`AttackConfig.sprint_m`)."""
        command = self._sprint_command(world, behavior, target)
        if command is None:
            behavior.execute("walk", target[0], target[1], heading_deg)
        else:
            behavior.execute("walk_velocity", *command)

    def _sprint_command(
        self, world, behavior, target: tuple[float, float]
    ) -> tuple[float, float, float] | None:
        """The ``walk_velocity`` command (forward m/s, 0, turn deg/s) of a sprint towards
        ``target``, or None to walk there: the sprint starts with the target farther than
        ``sprint_m`` and within ``sprint_start_deg`` of the heading, and goes on until it is
        closer or more than ``sprint_stop_deg`` off."""
        attack = self.config.attack
        pose = world.pose
        if attack.sprint_m <= 0.0 or "walk_velocity" not in behavior.skill_names:
            self._sprinting = False
            return None
        error = wrap_deg(_heading_to((pose.x, pose.y), target) - pose.heading_deg)
        far = math.dist((pose.x, pose.y), target) > attack.sprint_m
        limit = attack.sprint_stop_deg if self._sprinting else attack.sprint_start_deg
        self._sprinting = far and abs(error) < limit
        if not self._sprinting:
            return None
        turn = attack.sprint_turn_gain * error
        cap = attack.sprint_max_turn_deg_s
        return attack.sprint_speed_m_s, 0.0, max(-cap, min(cap, turn))

    def _dribble_kind(self, ball: tuple[float, float]) -> str:
        """The dribble gait for a ball here (:attr:`AttackConfig.near_goal_dribble_kind`)."""
        attack = self.config.attack
        near = math.dist(ball, (HALF_LENGTH, 0.0)) < attack.near_goal_dribble_m
        return (
            attack.near_goal_dribble_kind
            if near and attack.near_goal_dribble_kind
            else attack.dribble_kind
        )

    def _yielding(self, world) -> bool:
        """Whether to stand off a contested ball this cycle (:attr:`AttackConfig.yield_opponent_m`):
        yes from the moment it is contested, for at most ``yield_s`` or until it is no longer
        contested; then not again for ``yield_s``."""
        attack = self.config.attack
        now = world.time or 0.0
        if attack.yield_opponent_m <= 0.0 or world.pose is None:
            return False
        is_contested = contested(
            (world.pose.x, world.pose.y),
            world.ball.position,
            self._opponent_positions(world),
            attack.yield_opponent_m,
            attack.yield_reach_m,
        )
        if self._yield_since is not None:
            if is_contested and now - self._yield_since < attack.yield_s:
                return True
            self._yield_since = None
            self._yield_not_before = now + attack.yield_s
            return False
        if is_contested and now >= self._yield_not_before:
            self._yield_since = now
            return True
        return False

    def _detour(
        self, world, ball: tuple[float, float], aim: tuple[float, float]
    ) -> tuple[float, float] | None:
        """The point beside the nearest opponent in the way to take the ball to instead of
        ``aim`` (:attr:`AttackConfig.detour_clear_m`), or None."""
        attack = self.config.attack
        if attack.detour_clear_m <= 0.0:
            return None
        points = [
            detour_point(ball, aim, opponent, attack.detour_clear_m, attack.detour_ahead_m)
            for opponent in sorted(
                self._opponent_positions(world), key=lambda p: math.dist(p, ball)
            )
        ]
        return next((point for point in points if point is not None), None)

    def snap_foot(self, world) -> str | None:
        """The foot for a snap shot now (see :attr:`AttackConfig.snap_range_m`), or None: the
        ball is near the goal, at a foot's kick spot, and the robot faces into the goal."""
        attack = self.config.attack
        ball, pose = world.ball.position, world.pose
        if attack.snap_range_m <= 0.0 or ball is None or pose is None:
            return None
        if math.dist(ball, (HALF_LENGTH, 0.0)) > attack.snap_range_m or ball[0] >= HALF_LENGTH:
            return None
        heading = math.radians(pose.heading_deg)
        if math.cos(heading) <= 0.1:
            return None
        cross_y = ball[1] + (HALF_LENGTH - ball[0]) * math.tan(heading)
        if abs(cross_y) > GOAL_WIDTH / 2 - attack.snap_post_margin_m:
            return None
        rx, ry = ball[0] - pose.x, ball[1] - pose.y
        ahead = rx * math.cos(heading) + ry * math.sin(heading)
        left = -rx * math.sin(heading) + ry * math.cos(heading)
        robot_type = getattr(world.robot, "robot_type", 0)
        for foot in FEET:
            spot_ahead, spot_left = expected_ball_ego(robot_type, foot, kick_motion(robot_type))
            if (
                abs(ahead - spot_ahead) < attack.snap_along_m
                and abs(left - spot_left) < attack.snap_across_m
            ):
                return foot
        return None

    def _snap_stop(self, world, behavior) -> None:
        """One cycle of a snap shot's stop: step to a halt, stand, then kick with the foot the
        ball lies at, or give up (the ball has moved off the spot) and play on."""
        attack = self.config.attack
        elapsed = (world.time or 0.0) - (self._snap_stop_since or 0.0)
        if elapsed < attack.snap_stop_s and "walk_velocity" in behavior.skill_names:
            behavior.execute("walk_velocity", 0.0, 0.0, 0.0)
            return
        if elapsed < attack.snap_stop_s + attack.snap_stand_s:
            behavior.execute("pose", "stand")
            return
        self._snap_stop_since = None
        self._snap_foot = self.snap_foot(world)
        if self._snap_foot is None:
            self._snap_not_before = (world.time or 0.0) + attack.snap_retry_s
            behavior.execute("pose", "stand")
        elif behavior.execute("kick", self._snap_foot, 1.0):
            self._snap_foot = None

    def _count_holding(self, world) -> float:
        """Seconds this player has had the ball within :attr:`AttackConfig.hold_guard_m` of
        its torso, by its own estimates. Counted every cycle, whatever the player does: the
        referee counts a robot getting up on the ball too (a dribbler that fell over the ball
        lay on it for 4 s, stood up over it and was called 2 s later)."""
        holding = _ball_within(world, self.config.attack.hold_guard_m)
        return self._hold.update(world.time or 0.0, holding)

    def _backing_off(self, world, held_s: float) -> bool:
        """Whether to step back off the ball this cycle: the ball has been held
        :attr:`AttackConfig.hold_guard_s` (then for :attr:`AttackConfig.back_off_s`)."""
        attack = self.config.attack
        now = world.time or 0.0
        if self._back_off_until is not None and now < self._back_off_until:
            return True
        self._back_off_until = None
        if attack.hold_guard_s <= 0.0 or held_s < attack.hold_guard_s:
            return False
        self._hold.reset()
        self._dribbling = False
        self._back_off_until = now + attack.back_off_s
        return True

    def _backing_off_step(self, world, ball: tuple[float, float] | None, behavior) -> None:
        """One cycle of stepping away from the ball: backwards in the robot frame, or with
        only ``walk``, to a point 0.6 m from the ball on the far side from it."""
        if "walk_velocity" in behavior.skill_names:
            behavior.execute("walk_velocity", -STEP_BACK_M_S, 0.0, 0.0)
            return
        pose = world.pose
        if ball is None:
            behavior.execute("pose", "stand")
            return
        away = math.atan2(pose.y - ball[1], pose.x - ball[0])
        behavior.execute(
            "walk",
            ball[0] + 0.6 * math.cos(away),
            ball[1] + 0.6 * math.sin(away),
            pose.heading_deg,
        )

    def _escape_aim(
        self, world, ball: tuple[float, float], aim: tuple[float, float], range_shot: bool
    ) -> tuple[float, float]:
        """``aim``, or while escaping a stall a point 5 m from the ball ``escape_deg`` off the
        line to ``aim`` (from beside the goal: the point in front of it, see
        :attr:`AttackConfig.stall_shot_max_y_m`). A stall counts only while the player is at
        the ball. A stall during a shot from within the kick range (``range_shot``) starts no
        escape: its ball lies still while the kick lines up, and an escape turned the shot's
        aim 70 deg away and sent the robot round the ball again (session 32,
        ``scripts/attack/match_probe.py --seed 2 --window 50 80``: 16 s of approach, settle
        and back-off before the kick)."""
        attack = self.config.attack
        now = world.time or 0.0
        at_ball = math.dist((world.pose.x, world.pose.y), ball) < attack.dribble_keep_m
        if attack.stall_only_dribbling and not self._dribbling:
            at_ball = False
        if at_ball and attack.stall_opponent_m > 0.0:
            at_ball = any(
                math.dist(p, ball) < attack.stall_opponent_m
                for p in self._opponent_positions(world)
            )
        if not at_ball or attack.stall_s <= 0.0:
            self._stall.reset()  # walking up to a ball that lies still is no stall
        elif (
            self._escape is None
            and not self._shooting
            and self._stall.stalled(now, ball, attack.stall_s, attack.stall_m)
        ):
            near_goal = math.dist(ball, (HALF_LENGTH, 0.0)) < attack.stall_shot_m
            wide = 0.0 < attack.stall_shot_max_y_m < abs(ball[1])
            if near_goal and wide:
                self._escape = (now + attack.escape_s, 0.0)  # side 0: to the goal's front
            elif near_goal and _no_stall_shot_at(ball, attack):
                self._stall.reset()  # in the finishing zone: keep pushing it over the line
            elif near_goal:
                self._shooting, self._shot_since = True, now
            elif range_shot:
                self._stall.reset()  # the shot lines up: no escape
            else:
                self._escape = (now + attack.escape_s, self._escape_side(world, ball))
        if self._escape is None:
            return aim
        until, side = self._escape
        if now >= until:
            self._escape = None
            return aim
        if side == 0.0:
            return (HALF_LENGTH - attack.stall_centre_back_m, 0.0)
        return _turned_aim(ball, aim, side, attack.escape_deg)

    def _end_overdue_shot(self, world, ball: tuple[float, float]) -> None:
        """End a stall shot running longer than :attr:`AttackConfig.shot_max_s` and start an
        escape instead (which :meth:`_escape_aim` then steers)."""
        attack = self.config.attack
        now = world.time or 0.0
        if attack.shot_max_s <= 0.0 or now - self._shot_since < attack.shot_max_s:
            return
        self._shooting = False
        self._escape = (now + attack.escape_s, self._escape_side(world, ball))

    def _kickoff_aim(
        self, world, ball: tuple[float, float], aim: tuple[float, float]
    ) -> tuple[float, float]:
        """``aim``, or during and for :attr:`AttackConfig.kickoff_turn_s` after the team's own
        kick-off a point 5 m from the ball ``kickoff_turn_deg`` off the line to ``aim``, on the
        side with fewer opponents near the ball (chosen once per kick-off)."""
        attack = self.config.attack
        if attack.kickoff_turn_deg <= 0.0:
            return aim
        now = world.time or 0.0
        if world.play_mode.lower() == f"kickoff_{world.side}":
            side = self._kickoff_turn[1] if self._kickoff_turn else self._kickoff_side(world, ball)
            self._kickoff_turn = (now + attack.kickoff_turn_s, side)
        if self._kickoff_turn is None or now >= self._kickoff_turn[0]:
            self._kickoff_turn = None
            return aim
        return _turned_aim(ball, aim, self._kickoff_turn[1], attack.kickoff_turn_deg)

    def _kickoff_side(self, world, ball: tuple[float, float]) -> float:
        """+1 (to the left, team frame y up) or -1: away from the opponents within
        :attr:`AttackConfig.kickoff_clear_m` of the ball, to the left when there are none."""
        side = self._side_away(world, ball, self.config.attack.kickoff_clear_m)
        return 1.0 if side is None else side

    def _escape_side(self, world, ball: tuple[float, float]) -> float:
        """+1 (to the left, team frame y up) or -1: away from the opponents near the ball,
        else towards the middle of the field."""
        side = self._side_away(world, ball, 1.5)
        if side is not None:
            return side
        return -1.0 if ball[1] > 0.0 else 1.0

    def _side_away(self, world, ball: tuple[float, float], radius_m: float) -> float | None:
        """+1 (to the left, team frame y up) or -1: away from the mean place across of the
        opponents within ``radius_m`` of the ball (to the left when it is level with the
        ball); None when there are none."""
        near = [p for p in self._opponent_positions(world) if math.dist(p, ball) < radius_m]
        if not near:
            return None
        mean_y = sum(p[1] for p in near) / len(near)
        return -1.0 if mean_y > ball[1] else 1.0

    def _opponent_positions(self, world) -> list[tuple[float, float]]:
        return _recent_positions(world, "opponents")

    def _guard_goal(self, world, behavior) -> None:
        """Stand in front of the own goal, shifted towards the ball's side, facing the ball."""
        if "walk" not in behavior.skill_names:
            behavior.execute("pose", "stand")
            return
        keeper = self.config.keeper
        x = -HALF_LENGTH + keeper.line_offset_m
        ball = world.ball.position
        if ball is None:
            behavior.execute("walk", x, 0.0, 0.0)
            return
        y = max(-keeper.max_side_m, min(keeper.max_side_m, keeper.follow_fraction * ball[1]))
        if keeper.side_step_m > 0.0:
            y = keeper.side_step_m * round(y / keeper.side_step_m)
            _walk_facing_ball(world, behavior, (x, y))
        else:
            behavior.execute("walk", x, y, _heading_to((x, y), ball))

    def _support(self, world, behavior) -> None:
        """Wait ahead of and beside the ball for a loose ball, facing the ball."""
        if "walk" not in behavior.skill_names:
            behavior.execute("pose", "stand")
            return
        target = self.support_point(world.ball.position)
        self._walk_round_opponents(world, behavior, target, self.config.support.avoid_m)

    def _hold_position(self, world, behavior) -> None:
        """Walk to the place to wait at (:meth:`place`) and face the ball there (to keep seeing
        it); an advancing player steps in place while an opponent stands in its way."""
        if "walk" not in behavior.skill_names:
            behavior.execute("pose", "stand")
            return
        target, advancing = self._waiting_place(world)
        avoid_m = self.config.advance.avoid_m if advancing else 0.0
        self._walk_round_opponents(world, behavior, target, avoid_m)

    def _walk_round_opponents(
        self, world, behavior, target: tuple[float, float], avoid_m: float
    ) -> None:
        """Walk to ``target`` facing the ball, but step in place while an opponent stands
        within ``avoid_m`` in the way (0: never): walking into a robot knocks both over."""
        pose = world.pose
        if (
            pose is not None
            and "walk_velocity" in behavior.skill_names
            and _opponent_in_the_way(
                (pose.x, pose.y), target, self._opponent_positions(world), avoid_m
            )
        ):
            behavior.execute("walk_velocity", 0.0, 0.0, 0.0)
            return
        _walk_facing_ball(world, behavior, target)

    def place(self, world) -> tuple[float, float]:
        """Where this player waits while it does not go for the ball (:meth:`_waiting_place`)."""
        return self._waiting_place(world)[0]

    def _waiting_place(self, world) -> tuple[tuple[float, float], bool]:
        """Where this player waits while it does not go for the ball, and whether it has
        moved up with the ball: its place in play (:meth:`play_home`), moved up for an
        advancing player (``AdvanceConfig``), kept :attr:`StrategyConfig.hold_clear` (an
        advancing player: ``advance.clear_m``) from the ball."""
        home = self.play_home(world.unum)
        advance = self.config.advance
        ball = world.ball.position
        if ball is None:
            return home, False
        if (
            world.unum not in advance.unums
            or ball[0] < advance.from_x_m
            or opponents_restart(world.play_mode, world.side)
        ):
            return _clear_of(home, ball, self.config.hold_clear), False
        x = min(advance.max_x_m, ball[0] - advance.behind_m)
        if advance.step_m > 0.0:
            x = advance.step_m * math.floor(x / advance.step_m)
        x = max(home[0], x)
        y = math.copysign(advance.y_m, home[1]) if home[1] else 0.0
        return _clear_of((x, y), ball, advance.clear_m), True


def _recent_positions(world, tracker_name: str) -> list[tuple[float, float]]:
    """Where vision last saw the players of ``world.<tracker_name>`` (``opponents`` or
    ``teammates``) within :data:`OPPONENT_MEMORY_S`; none without a tracker or a clock."""
    tracker = getattr(world, tracker_name, None)
    if tracker is None or world.time is None:
        return []
    return [p.position[:2] for p in tracker.recent(world.time, OPPONENT_MEMORY_S)]


def _clear_of(
    place: tuple[float, float], ball: tuple[float, float], clear_m: float
) -> tuple[float, float]:
    """``place``, or where the line from the ball through it is ``clear_m`` from the ball
    when it lies closer (a place on the ball: ``clear_m`` behind it; 0: ``place``)."""
    gap = math.dist(place, ball)
    if clear_m <= 0.0 or gap >= clear_m:
        return place
    if gap < 1e-6:
        return ball[0] - clear_m, ball[1]
    scale = clear_m / gap
    return ball[0] + (place[0] - ball[0]) * scale, ball[1] + (place[1] - ball[1]) * scale


def _in_front_of_goal_mouth(ball: tuple[float, float], attack: AttackConfig) -> bool:
    """Whether the ball lies within ``finish_m`` of the opponent goal line, short of it, and
    ``finish_post_margin_m`` inside the posts."""
    return (
        0.0 < HALF_LENGTH - ball[0] < attack.finish_m
        and abs(ball[1]) < GOAL_WIDTH / 2 - attack.finish_post_margin_m
    )


def _no_stall_shot_at(ball: tuple[float, float], attack: AttackConfig) -> bool:
    """Whether :attr:`AttackConfig.finish_no_shot` keeps stall shots away from a ball lying
    here (the finishing zone, where the dribble pushes it over the line instead)."""
    return attack.finish_no_shot and _in_front_of_goal_mouth(ball, attack)


def _walk_facing_ball(world, behavior, place: tuple[float, float]) -> None:
    """Walk to ``place`` and face the ball there (heading 0 while the ball is unknown), in
    steps of :data:`HOLD_HEADING_STEP_DEG`: a heading that followed every move of the ball
    would keep the walk turning on the spot."""
    ball = world.ball.position
    heading = 0.0 if ball is None else _heading_to(place, ball)
    step = HOLD_HEADING_STEP_DEG
    behavior.execute("walk", place[0], place[1], step * round(heading / step))


def _opponent_in_the_way(
    origin: tuple[float, float],
    target: tuple[float, float],
    opponents: list[tuple[float, float]],
    within_m: float,
) -> bool:
    """Whether an opponent stands within ``within_m`` of ``origin`` and within 60 deg of the
    direction to ``target`` (never once ``target`` is reached or ``within_m`` is 0)."""
    if within_m <= 0.0 or math.dist(origin, target) < within_m:
        return False
    to_target = _heading_to(origin, target)
    return any(
        math.dist(origin, p) < within_m and abs(wrap_deg(_heading_to(origin, p) - to_target)) < 60.0
        for p in opponents
    )


def head_yaw_for(bearing_deg: float) -> float:
    """The neck yaw (deg) that keeps a ball at ``bearing_deg`` from the torso in view: none
    within :data:`HEAD_STILL_DEG` (the camera looks ahead, as the skills expect), beyond it the
    head turns by the excess, up to :data:`HEAD_YAW_MAX_DEG` (the view cone's half-width is 60
    deg, so the ball stays in view up to about 150 deg off the torso's heading)."""
    excess = max(0.0, abs(bearing_deg) - HEAD_STILL_DEG)
    return math.copysign(min(excess, HEAD_YAW_MAX_DEG), bearing_deg)


def _look_towards_ball(world, behavior) -> None:
    """Turn the head towards the ball while a walking skill, which leaves the head alone, moves
    the body. Why: walking to a place facing the way of travel, players lost sight of a ball
    behind them for seconds (and made no claims meanwhile). The dribbles, kicks, poses and the
    get-up set the head themselves."""
    current = behavior.current
    ball, pose = world.ball.position, world.pose
    if current is None or current.name not in HEAD_FREE_SKILLS or ball is None or pose is None:
        return
    behavior.commands.set_targets({"hj1": head_yaw_for(world.bearing_to(ball))})


def search_turn_deg_s(world) -> float:
    """The turn (deg/s) that starts a search for a lost ball: towards the side where it was
    last placed, the shorter way round. Why: always turning left, a player whose ball was lost
    behind its right shoulder (walking to its place facing the way, the ball behind) turned
    270 deg, 7 s, before it saw the ball again (``scripts/attack/match_probe.py --seed 1``).
    The strategy keeps the direction for the whole search: re-chosen every cycle, a stale
    estimate straight ahead (the ball long gone from there) flipped it from side to side and
    the robot stood turning to and fro for 25 s (3 v 3 seed 2, the right team's forward)."""
    ball, pose = world.ball.position, world.pose
    if ball is None or pose is None:
        return SEARCH_TURN_DEG_S
    return -SEARCH_TURN_DEG_S if world.bearing_to(ball) < 0.0 else SEARCH_TURN_DEG_S


def _last_seen_at_feet(world) -> bool:
    """Whether the (lost) ball was last placed within :data:`LOST_AT_FEET_M` of the torso."""
    return _ball_within(world, LOST_AT_FEET_M)


def _ball_within(world, radius_m: float) -> bool:
    """Whether the ball estimate lies within ``radius_m`` of the torso estimate."""
    ball, pose = world.ball.position, world.pose
    return ball is not None and pose is not None and math.dist((pose.x, pose.y), ball) < radius_m


def _heading_to(origin: tuple[float, float], point: tuple[float, float]) -> float:
    """Heading (deg) from ``origin`` towards ``point``."""
    return math.degrees(math.atan2(point[1] - origin[1], point[0] - origin[0]))
