"""The referee of the stand-in server: play modes, game clock, score, restarts and fouls.

The referee is pure logic on positions and time: it never touches physics, so it can be tested
without PyBullet. Each cycle the session hands it the ball, the players and the players whose
bodies touched the ball, and gets back what it must do (:class:`PlaceBall`, the referee's explicit
ball placement) and what to log (:class:`Event`).

The rules follow rcssserver3d 0.7.2 (``soccerruleaspect.cpp``, ``gamestateaspect.cpp``,
``beameffector.cpp``, ``naosoccersim.rb``) and add, as an option on by default, the 2023
ball-holding rule, which 0.7.2 does not have. Where this referee differs from the real server it
is on purpose, and said so:

- The real server's referee also moves robots; so does this one (``sim.referee_players``):
  kick-offs, set pieces and drop balls are cleared, and robots lying too long or crowding their
  own penalty area are taken off, with the real parameters, each rule switchable. Differences
  there: a robot's extent is a fixed square around its torso, not its colliders' box; a moved
  robot is not nudged off another robot it lands on ("safe reposition"); the touching and
  charging fouls, which need robot-robot contacts, are not implemented. A moved robot is
  stopped, every body part, as on the real server (``SimRobot.translate``).
- Only the kicking team's touch ends a set piece; the real server accepts any touch, as it has
  cleared the opponents away (here too, unless the clearing is switched off).
- ``kick_off(None)`` within a half, after that half's first kick-off, gives the kick-off to the
  side that did not take the last one; the real server tosses a coin there.
- A ball that leaves the field before anybody touched it is dropped back where it left; the real
  server leaves it outside and does nothing.
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, field, fields
from enum import Enum
from pathlib import Path
from typing import TypeAlias

from sim.referee_players import (
    MovePlayer,
    PlayerKey,
    PlayerMover,
    PositionalFoulMonitor,
    Team,
    Vec3,
    penalty_box,
)
from world.field_geometry import (
    BALL_RADIUS,
    FIELD_WIDTH,
    GOAL_DEPTH,
    GOAL_HEIGHT,
    GOAL_WIDTH,
    HALF_LENGTH,
    HALF_WIDTH,
    PENALTY_DEPTH,
    PENALTY_WIDTH,
)
from world.play_modes import play_mode_index
from world.yaml_config import load_yaml_config

TEAMS: tuple[Team, Team] = ("left", "right")

#: The repository's default parameter file (the real server's settings).
DEFAULT_CONFIG_PATH = Path(__file__).resolve().parents[1] / "config" / "referee.yaml"

CENTRE_SPOT: Vec3 = (0.0, 0.0, BALL_RADIUS)

#: Play modes in which the beam effector works (beameffector.cpp).
BEAM_MODES = frozenset({"BeforeKickOff", "Goal_Left", "Goal_Right"})

#: The real server's tolerance of its on-field test (ballstateaspect.cpp), metres.
_ON_FIELD_EPSILON = 0.001
#: The ball counts as resting on its spot within these bounds (m, m/s); beyond them it is put back.
_SPOT_TOLERANCE = 0.005
_SPOT_SPEED_TOLERANCE = 0.01
#: Slack on clock comparisons so that 15000 cycles of 0.02 s end the half at 300 s, not 300.02 s.
_CLOCK_SLACK = 1e-9

_SET_PIECE_PREFIXES = (
    "KickIn_",
    "corner_kick_",
    "goal_kick_",
    "free_kick_",
    "direct_free_kick_",
    "offside_",
)


# --------------------------------------------------------------------------------------------
# Configuration
# --------------------------------------------------------------------------------------------

_POSITIVE = "positive"
_NON_NEGATIVE = "non_negative"
_SIGNED = "signed"
_FLAG = "flag"
_COUNT = "count"


def _param(default: float | bool, kind: str) -> float | bool:
    """A config field whose ``kind`` tells the validator what values it accepts."""
    return field(default=default, metadata={"kind": kind})


@dataclass(frozen=True)
class RefereeConfig:
    """The referee's parameters. Defaults are the real server's (naosoccersim.rb, 0.7.2) and the
    2023 ball-holding rule's; times are seconds, distances metres."""

    #: RuleHalfTime: length of one half of game time.
    half_time: float = _param(300.0, _POSITIVE)
    #: RuleGoalPauseTime: Goal_Left/Goal_Right lasts this long before the kick-off.
    goal_pause_time: float = _param(3.0, _NON_NEGATIVE)
    #: RuleKickInPauseTime: a set piece ignores touches and leaves the ball alone this long.
    kick_in_pause_time: float = _param(1.0, _NON_NEGATIVE)
    #: RuleDropBallTime: a kick-off or set piece nobody takes becomes a drop ball (0: never).
    drop_ball_time: float = _param(15.0, _NON_NEGATIVE)
    #: AutomaticKickOff: off on the real server; the trainer or a match script kicks off.
    auto_kick_off: bool = _param(False, _FLAG)
    #: WaitBeforeKickOff: with ``auto_kick_off``, BeforeKickOff lasts this long.
    wait_before_kick_off: float = _param(30.0, _NON_NEGATIVE)
    #: SingleHalfTime: the game ends after the first half.
    single_half: bool = _param(False, _FLAG)
    #: FreeKickDistance: radius opponents must keep at set pieces (and the centre circle).
    free_kick_distance: float = _param(2.0, _NON_NEGATIVE)
    #: FreeKickMoveDist: a cleared robot is put at least this far from the ball (or the edge of
    #: the half or penalty area it must leave); the real server adds up to 2 m (or as much
    #: again, for boxes) at random.
    free_kick_move_distance: float = _param(2.2, _NON_NEGATIVE)
    #: StartAnyFieldPosition: when true, nobody is kept in their half before and at kick-off.
    start_any_field_position: bool = _param(False, _FLAG)
    #: Clear the defending team from the free-kick circle (the penalty area at a goal kick) at
    #: set pieces and both teams at drop balls. Always on in the real server; a switch here.
    clear_set_pieces: bool = _param(True, _FLAG)
    #: KickRepelDist: kicking-team robots closer to the ball's spot are pushed out to this
    #: distance when the ball is put there (0: never).
    kick_repel_distance: float = _param(0.5, _NON_NEGATIVE)
    #: The "incapable" rule: robots lying or sitting too long are taken off the field.
    incapable_rule: bool = _param(True, _FLAG)
    #: NotStandingMaxTime: a field player's torso below 0.25 m this long is a foul.
    not_standing_max_time: float = _param(30.0, _NON_NEGATIVE)
    #: GoalieNotStandingMaxTime: the same for unum 1.
    goalie_not_standing_max_time: float = _param(60.0, _NON_NEGATIVE)
    #: GroundMaxTime: a field player's torso below 0.15 m this long is a foul.
    ground_max_time: float = _param(15.0, _NON_NEGATIVE)
    #: GoalieGroundMaxTime: the same for unum 1.
    goalie_ground_max_time: float = _param(30.0, _NON_NEGATIVE)
    #: Illegal defence: more than MaxPlayersInsideOwnArea robots in the own penalty area.
    illegal_defence_rule: bool = _param(True, _FLAG)
    #: MaxPlayersInsideOwnArea.
    max_players_inside_own_area: int = _param(3, _COUNT)
    #: Crowding: off in the real server since 2017 (its distances are 0 there). Switched on, the
    #: distances below are the real server's until 2016 (kept commented in naosoccersim.rb).
    crowding_rule: bool = _param(False, _FLAG)
    #: MinOppDistance: crowding is judged only while an opponent is this close to the ball.
    min_opp_distance: float = _param(0.8, _NON_NEGATIVE)
    #: Min2PlDistance: a team's second-nearest field player may not be this close to the ball.
    min_2pl_distance: float = _param(0.4, _NON_NEGATIVE)
    #: Min3PlDistance: nor its third-nearest this close.
    min_3pl_distance: float = _param(1.0, _NON_NEGATIVE)
    #: FoulHoldTime: a robot called for a positional foul is held in the air this long before
    #: it is put outside the field.
    foul_hold_time: float = _param(0.5, _NON_NEGATIVE)
    #: GoalKickDist: a goal kick is taken this far in front of the goal line.
    goal_kick_distance: float = _param(1.0, _NON_NEGATIVE)
    #: The 2023 ball-holding rule, on by default (not in rcssserver3d 0.7.2).
    ball_holding_rule: bool = _param(True, _FLAG)
    #: BallHoldRadius: the ball is held while this close to a player's torso (x, y).
    ball_hold_radius: float = _param(0.12, _NON_NEGATIVE)
    #: BallHoldMaxTime: holding longer than this is a foul.
    ball_hold_max_time: float = _param(5.0, _NON_NEGATIVE)
    #: BallHoldGoalieMaxTime: the limit for unum 1 inside its own penalty area.
    ball_hold_goalie_max_time: float = _param(10.0, _NON_NEGATIVE)
    #: BallHoldResetTime: the holding time restarts after this long without holding.
    ball_hold_reset_time: float = _param(0.5, _NON_NEGATIVE)
    #: BallHoldMaxDistance: holding while the ball travels this far with an opponent near is a foul.
    ball_hold_max_distance: float = _param(1.0, _NON_NEGATIVE)
    #: BallHoldOppDistance: an opponent this close to the ball is "near"; negative: always near.
    ball_hold_opp_distance: float = _param(0.75, _SIGNED)

    def __post_init__(self) -> None:
        problems = _config_problems(asdict(self))
        if problems:
            raise ValueError("invalid referee config: " + "; ".join(problems))


def _config_kinds() -> dict[str, str]:
    return {f.name: f.metadata["kind"] for f in fields(RefereeConfig)}


def _value_problem(key: str, value: object, kind: str) -> str | None:
    """Why ``value`` is not acceptable for parameter ``key``, or None when it is."""
    if kind == _FLAG:
        if not isinstance(value, bool):
            return f"{key!r} must be true or false, got {value!r}"
        return None
    if kind == _COUNT:
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            return f"{key!r} must be a whole number >= 0, got {value!r}"
        return None
    if isinstance(value, bool) or not isinstance(value, int | float):
        return f"{key!r} must be a number, got {type(value).__name__} {value!r}"
    if not math.isfinite(value):
        return f"{key!r} must be finite, got {value!r}"
    if kind == _POSITIVE and value <= 0:
        return f"{key!r} must be positive, got {value!r}"
    if kind == _NON_NEGATIVE and value < 0:
        return f"{key!r} must not be negative, got {value!r}"
    return None


def _config_problems(values: Mapping[str, object]) -> list[str]:
    """Every problem with a mapping of parameter values: unknown keys, wrong types, bad ranges."""
    kinds = _config_kinds()
    problems = [
        f"unknown key {key!r} (known: {', '.join(sorted(kinds))})"
        for key in values
        if key not in kinds
    ]
    for key, value in values.items():
        if key in kinds:
            problem = _value_problem(key, value, kinds[key])
            if problem:
                problems.append(problem)
    return problems


def load_referee_config(path: str | Path = DEFAULT_CONFIG_PATH) -> RefereeConfig:
    """Read a YAML mapping of parameters; keys left out keep the real server's defaults.

    Raises ValueError (``world.yaml_config.ConfigError``) naming the file and the offending key
    for unknown keys, wrong types, negative times or distances, or a file that is not a mapping.
    """
    return load_yaml_config(RefereeConfig, path)


# --------------------------------------------------------------------------------------------
# Inputs and outputs
# --------------------------------------------------------------------------------------------


def _check_team(team: object) -> Team:
    if team not in TEAMS:
        raise ValueError(f"team must be 'left' or 'right', got {team!r}")
    return team  # type: ignore[return-value]


def other_team(team: Team) -> Team:
    """The opponent of ``team``."""
    return "right" if _check_team(team) == "left" else "left"


@dataclass(frozen=True, slots=True)
class PlayerInfo:
    """One robot as the referee needs it: team, uniform number, torso position (world, m)."""

    team: Team
    unum: int
    position: Vec3
    fallen: bool = False

    def __post_init__(self) -> None:
        _check_team(self.team)
        if isinstance(self.unum, bool) or not isinstance(self.unum, int) or self.unum < 1:
            raise ValueError(f"unum must be a positive int, got {self.unum!r}")

    @property
    def key(self) -> PlayerKey:
        return (self.team, self.unum)


@dataclass(frozen=True, slots=True)
class BallInfo:
    """The ball's centre (world, m) and linear velocity (m/s)."""

    position: Vec3
    velocity: Vec3 = (0.0, 0.0, 0.0)


class EventKind(str, Enum):
    """What an :class:`Event` is about."""

    PLAY_MODE = "play_mode"
    KICK_OFF = "kick_off"
    GOAL = "goal"
    KICK_IN = "kick_in"
    CORNER_KICK = "corner_kick"
    GOAL_KICK = "goal_kick"
    FREE_KICK = "free_kick"
    FOUL = "foul"
    DROP_BALL = "drop_ball"
    HALF_TIME = "half_time"
    GAME_OVER = "game_over"


@dataclass(frozen=True, slots=True)
class PlaceBall:
    """Put the ball at ``position`` with zero linear and angular velocity, as the real server's
    MoveBall does for kick-offs, outs, goals and set pieces."""

    position: Vec3


@dataclass(frozen=True, slots=True)
class Event:
    """Something for the log: a goal, a restart, a foul, a change of play mode."""

    kind: EventKind
    text: str


RefereeAction: TypeAlias = PlaceBall | MovePlayer | Event


# --------------------------------------------------------------------------------------------
# Field helpers
# --------------------------------------------------------------------------------------------


def _distance_xy(a: Sequence[float], b: Sequence[float]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def _ball_on_field(position: Vec3) -> bool:
    """True until the whole ball is past a line (the real server's BallStateAspect test)."""
    x_limit = HALF_LENGTH + BALL_RADIUS + _ON_FIELD_EPSILON
    y_limit = HALF_WIDTH + BALL_RADIUS + _ON_FIELD_EPSILON
    return abs(position[0]) < x_limit and abs(position[1]) < y_limit


def in_penalty_area(team: Team, x: float, y: float) -> bool:
    """Whether (x, y) is in ``team``'s own penalty area, extended behind the goal line as the
    real server does for its goalie."""
    if abs(y) > PENALTY_WIDTH / 2:
        return False
    if team == "left":
        return x <= -HALF_LENGTH + PENALTY_DEPTH
    return x >= HALF_LENGTH - PENALTY_DEPTH


def _out_of_penalty_areas(x: float, y: float) -> tuple[float, float]:
    """Free kicks and drop balls are never taken inside a penalty area: the real server moves
    the ball to the area's front corner on the ball's side."""
    corner_y = -PENALTY_WIDTH / 2 if y < 0 else PENALTY_WIDTH / 2
    if abs(y) <= PENALTY_WIDTH / 2 and -HALF_LENGTH <= x <= -HALF_LENGTH + PENALTY_DEPTH:
        return -HALF_LENGTH + PENALTY_DEPTH, corner_y
    if abs(y) <= PENALTY_WIDTH / 2 and HALF_LENGTH - PENALTY_DEPTH <= x <= HALF_LENGTH:
        return HALF_LENGTH - PENALTY_DEPTH, corner_y
    return x, y


def free_kick_spot(position: Sequence[float]) -> Vec3:
    """Where a free kick for a foul at ``position`` is taken: there, on the ground, outside the
    penalty areas."""
    x, y = _out_of_penalty_areas(position[0], position[1])
    return (x, y, BALL_RADIUS)


def drop_ball_spot(position: Sequence[float]) -> Vec3:
    """Where the ball is dropped: ``position`` moved out of the penalty areas and into the
    field."""
    x = min(max(position[0], -HALF_LENGTH + BALL_RADIUS), HALF_LENGTH - BALL_RADIUS)
    y = min(max(position[1], -HALF_WIDTH + BALL_RADIUS), HALF_WIDTH - BALL_RADIUS)
    x, y = _out_of_penalty_areas(x, y)
    return (x, y, BALL_RADIUS)


def kick_in_spot(last_on_field: Sequence[float]) -> Vec3:
    """A kick-in is taken on the side line where the ball left (just inside it)."""
    x = min(max(last_on_field[0], -HALF_LENGTH), HALF_LENGTH)
    y = HALF_WIDTH - BALL_RADIUS if last_on_field[1] > 0 else -HALF_WIDTH + BALL_RADIUS
    return (x, y, BALL_RADIUS)


def corner_kick_spot(team: Team, ball_y: float) -> Vec3:
    """The real server's corner spot for ``team``: on the opponents' goal line, on the ball's
    side, halfway between goal post and corner ((FieldWidth + GoalWidth) / 4, a value it has
    kept since 2012 instead of the corner itself)."""
    x = HALF_LENGTH - BALL_RADIUS if team == "left" else -HALF_LENGTH + BALL_RADIUS
    y = (FIELD_WIDTH + GOAL_WIDTH) / 4 - BALL_RADIUS
    return (x, y if ball_y > 0 else -y, BALL_RADIUS)


def goal_kick_spot(team: Team, distance: float) -> Vec3:
    """A goal kick is taken on the x axis, ``distance`` in front of ``team``'s goal line."""
    x = -HALF_LENGTH + distance if team == "left" else HALF_LENGTH - distance
    return (x, 0.0, BALL_RADIUS)


def _mode_team(mode: str) -> Team:
    return "left" if mode.lower().endswith("left") else "right"


def _is_set_piece(mode: str) -> bool:
    return mode.startswith(_SET_PIECE_PREFIXES)


# --------------------------------------------------------------------------------------------
# The ball-holding rule
# --------------------------------------------------------------------------------------------


@dataclass
class _HoldState:
    """One player's holding record."""

    held: float = 0.0  # seconds held, counted until a reset
    free: float = 0.0  # seconds not holding since the last holding cycle
    marked_path: float = 0.0  # metres the ball travelled while held with an opponent near


@dataclass(frozen=True, slots=True)
class HoldingFoul:
    """A player called for holding the ball, and why."""

    player: PlayerKey
    reason: str


class BallHoldingMonitor:
    """The 2023 ball-holding rule, cycle by cycle.

    A player holds the ball while the ball is within BallHoldRadius of its torso (x, y) and no
    opponent is closer to the ball: the holder is the player nearest the ball, if within the
    radius. Holding is a foul when it lasts longer than BallHoldMaxTime (BallHoldGoalieMaxTime
    for unum 1 in its own penalty area), or while the ball travels BallHoldMaxDistance in cycles
    with an opponent within BallHoldOppDistance of the ball (always, when that is negative).
    A player's record restarts after BallHoldResetTime of not holding. Fallen robots count too:
    lying on the ball is holding it.
    """

    def __init__(self, config: RefereeConfig) -> None:
        self._config = config
        self._states: dict[PlayerKey, _HoldState] = {}
        self._last_holder: PlayerKey | None = None

    def reset(self) -> None:
        """Forget every record (the game stopped; the real server resets its foul counters)."""
        self._states.clear()
        self._last_holder = None

    def held_time(self, player: PlayerKey) -> float:
        """Seconds ``player`` has held the ball in its current record."""
        state = self._states.get(player)
        return state.held if state else 0.0

    def update(
        self,
        dt: float,
        ball_xy: Sequence[float],
        previous_ball_xy: Sequence[float] | None,
        players: Sequence[PlayerInfo],
    ) -> HoldingFoul | None:
        """Advance one cycle; return the foul if the holder just committed one."""
        holder = self._holder(ball_xy, players)
        held_before, self._last_holder = self._last_holder, None if holder is None else holder.key
        self._age_free_players(dt, self._last_holder)
        if holder is None:
            return None
        state = self._states.setdefault(holder.key, _HoldState())
        state.held += dt
        state.free = 0.0
        # the ball's path counts from one holding cycle to the next only, so that a ball placed
        # or first seen at a player's feet has not "travelled" from where it was before
        carried = held_before == holder.key and previous_ball_xy is not None
        if carried and self._opponent_near(holder.team, ball_xy, players):
            state.marked_path += _distance_xy(ball_xy, previous_ball_xy)
        return self._foul(holder, state)

    def _holder(self, ball_xy: Sequence[float], players: Sequence[PlayerInfo]) -> PlayerInfo | None:
        if not players:
            return None
        nearest = min(players, key=lambda p: _distance_xy(p.position, ball_xy))
        if _distance_xy(nearest.position, ball_xy) > self._config.ball_hold_radius:
            return None
        return nearest

    def _age_free_players(self, dt: float, holder: PlayerKey | None) -> None:
        for key, state in self._states.items():
            if key == holder:
                continue
            state.free += dt
            if state.free >= self._config.ball_hold_reset_time - _CLOCK_SLACK:
                state.held = 0.0
                state.marked_path = 0.0

    def _opponent_near(
        self, team: Team, ball_xy: Sequence[float], players: Sequence[PlayerInfo]
    ) -> bool:
        limit = self._config.ball_hold_opp_distance
        if limit < 0:
            return True
        return any(p.team != team and _distance_xy(p.position, ball_xy) <= limit for p in players)

    def _time_limit(self, holder: PlayerInfo) -> float:
        x, y = holder.position[0], holder.position[1]
        if holder.unum == 1 and in_penalty_area(holder.team, x, y):
            return self._config.ball_hold_goalie_max_time
        return self._config.ball_hold_max_time

    def _foul(self, holder: PlayerInfo, state: _HoldState) -> HoldingFoul | None:
        limit = self._time_limit(holder)
        if state.held > limit + _CLOCK_SLACK:
            return HoldingFoul(holder.key, f"held the ball {state.held:.2f} s (limit {limit} s)")
        max_path = self._config.ball_hold_max_distance
        if state.marked_path >= max_path - _CLOCK_SLACK:
            return HoldingFoul(
                holder.key,
                f"held the ball over {state.marked_path:.2f} m with an opponent near "
                f"(limit {max_path} m)",
            )
        return None


# --------------------------------------------------------------------------------------------
# The referee
# --------------------------------------------------------------------------------------------


class Referee:
    """Play modes, game clock, score and restarts of one game, as rcssserver3d runs them.

    Call :meth:`step` once per server cycle, after physics, with the ball, the players and the
    ``(team, unum)`` of every robot whose body touched the ball in that cycle (in the order the
    contacts were found: the first counts as the last toucher, as on the real server). Commands
    (:meth:`kick_off`, :meth:`set_play_mode`, :meth:`drop_ball`) may come between cycles; their
    actions are returned by the next :meth:`step`.

    ``seed`` seeds the random choices the real server makes when it moves robots (how far a
    cleared robot goes, which robot is looked at first), so that a game can be replayed.
    """

    def __init__(self, config: RefereeConfig | None = None, seed: int = 0) -> None:
        self._config = config if config is not None else RefereeConfig()
        self._rng = random.Random(seed)
        self._fouls = PositionalFoulMonitor(self._config)
        self._mover = PlayerMover({}, self._rng, self._config.free_kick_move_distance)
        self._drop_to_clear: Vec3 | None = None
        self._play_mode = "BeforeKickOff"
        self._mode_time = 0.0
        self._game_time = 0.0
        self._half = 1
        self._scores: dict[Team, int] = {"left": 0, "right": 0}
        self._team_names: dict[Team, str | None] = {"left": None, "right": None}
        self._outbox: list[RefereeAction] = []
        self._cycle = 0
        self._mode_cycle = 0
        self._ball_position: Vec3 = CENTRE_SPOT
        self._previous_ball: Vec3 | None = None
        self._last_on_field: Vec3 = CENTRE_SPOT
        self._last_touch: PlayerKey | None = None
        self._spot: Vec3 = CENTRE_SPOT
        self._spot_placed = False
        self._goal_kick_taken = False
        self._first_kick_off: dict[int, Team] = {}
        self._last_kick_off: Team | None = None
        self._holding = BallHoldingMonitor(self._config)

    # ---- state -------------------------------------------------------------------------------

    @property
    def config(self) -> RefereeConfig:
        return self._config

    @property
    def play_mode(self) -> str:
        """The current play mode, one of ``world.play_modes.PLAY_MODES``."""
        return self._play_mode

    @property
    def game_time(self) -> float:
        """Game time in seconds, the ``GS t`` value: it stands still in BeforeKickOff and
        GameOver and runs in every other mode (goal pauses and set pieces included)."""
        return self._game_time

    @property
    def mode_time(self) -> float:
        """Seconds since the play mode last changed."""
        return self._mode_time

    @property
    def half(self) -> int:
        """1 or 2."""
        return self._half

    @property
    def score_left(self) -> int:
        return self._scores["left"]

    @property
    def score_right(self) -> int:
        return self._scores["right"]

    @property
    def team_names(self) -> tuple[str | None, str | None]:
        """(left, right) team names; None until a team has registered."""
        return self._team_names["left"], self._team_names["right"]

    @property
    def last_touch(self) -> PlayerKey | None:
        """The robot that touched the ball last, as the referee knows it."""
        return self._last_touch

    @property
    def ball_holding(self) -> BallHoldingMonitor:
        """The ball-holding records (read them; the referee updates them)."""
        return self._holding

    @property
    def set_piece_spot(self) -> Vec3:
        """Where the current (or last) set piece is taken: the ball's spot."""
        return self._spot

    @property
    def positional_fouls(self) -> PositionalFoulMonitor:
        """The incapable / illegal defence / crowding records (read them; the referee updates
        them)."""
        return self._fouls

    # ---- commands ----------------------------------------------------------------------------

    def register_team(self, name: str) -> Team:
        """The side of team ``name``: the first name to connect plays left, the second right;
        a known name gets its side again. A third name is refused, as the real server refuses it
        ("invalid teamname")."""
        if not isinstance(name, str) or not name.strip():
            raise ValueError(f"team name must be a non-empty string, got {name!r}")
        for side in TEAMS:
            if self._team_names[side] == name:
                return side
        for side in TEAMS:
            if self._team_names[side] is None:
                self._team_names[side] = name
                return side
        left, right = self.team_names
        raise ValueError(
            f"invalid teamname {name!r}: this game already has teams {left!r} (left) "
            f"and {right!r} (right)"
        )

    def kick_off(self, side: Team | None = None) -> Team:
        """Start play with a kick-off: the ball goes to the centre spot and the clock runs.

        ``side`` None means the side whose turn it is: the first kick-off of the first half goes
        to the left team (the real server with CoinTossForKickOff off), the first of the second
        half to the other team; later ones to the side that did not take the last kick-off.
        Returns the side that kicks off.
        """
        if self._play_mode == "GameOver":
            raise RuntimeError("the game is over: no kick-off")
        kicker = self._kick_off_side(side)
        self._first_kick_off.setdefault(self._half, kicker)
        self._last_kick_off = kicker
        self._place_ball(CENTRE_SPOT)
        self._emit(EventKind.KICK_OFF, f"kick-off {self._describe(kicker)}")
        self._set_mode("KickOff_Left" if kicker == "left" else "KickOff_Right")
        return kicker

    def set_play_mode(self, name: str) -> None:
        """The trainer's ``(playMode NAME)``: switch modes without scoring or moving robots.

        Set pieces get their spot from where the ball is now, by the same rules as when they are
        awarded; kick-off modes count as that side's kick-off.
        """
        play_mode_index(name)  # ValueError listing the valid names
        if name == self._play_mode:
            return
        if name.startswith("KickOff_"):
            kicker = _mode_team(name)
            self._first_kick_off.setdefault(self._half, kicker)
            self._last_kick_off = kicker
        if _is_set_piece(name):
            self._prepare_set_piece(self._trainer_spot(name))
        self._set_mode(name)

    def drop_ball(self) -> None:
        """Drop the ball where it is (out of the penalty areas) and play on."""
        self._drop_ball_at(self._ball_position)

    def may_beam(self, team: Team) -> bool:
        """Whether ``team``'s robots may beam now: in BeforeKickOff and after a goal only."""
        _check_team(team)
        return self._play_mode in BEAM_MODES

    def clamp_beam(self, team: Team, x: float, y: float, deg: float) -> Vec3:
        """Turn a ``(beam x y deg)`` request into the world pose the robot is placed at.

        The request is in the team's own frame (own goal at -x, ``deg`` 0 faces the opponents'
        goal). As the real server does, x is clamped to the own half [-15, 0] and y to the field
        [-10, 10]; the right team's request is then mirrored through the centre. Returns world
        (x, y, yaw in degrees from world +x, in [-180, 180)). The session adds the beam noise.
        Raises ValueError for a non-finite value (the real server ignores such a beam).
        """
        _check_team(team)
        if not all(math.isfinite(v) for v in (x, y, deg)):
            raise ValueError(f"beam needs finite numbers, got ({x}, {y}, {deg})")
        x = min(max(x, -HALF_LENGTH), 0.0)
        y = min(max(y, -HALF_WIDTH), HALF_WIDTH)
        if team == "right":
            x, y, deg = -x, -y, deg + 180.0
        yaw = (deg + 180.0) % 360.0 - 180.0
        if yaw >= 180.0:  # a tiny negative angle wraps to 360.0 in floating point
            yaw -= 360.0
        return (x + 0.0, y + 0.0, yaw)  # + 0.0 turns a mirrored -0.0 into 0.0

    # ---- the cycle ---------------------------------------------------------------------------

    def step(
        self,
        dt: float,
        ball: BallInfo,
        players: Sequence[PlayerInfo],
        touches: Iterable[PlayerKey] = (),
    ) -> list[RefereeAction]:
        """Advance one cycle of ``dt`` seconds and return what the session must do, in order."""
        if not math.isfinite(dt) or dt < 0:
            raise ValueError(f"dt must be a finite non-negative number, got {dt!r}")
        self._cycle += 1
        touched = [(_check_team(team), unum) for team, unum in touches]
        positions = {p.key: tuple(float(v) for v in p.position) for p in players}
        self._mover = PlayerMover(positions, self._rng, self._config.free_kick_move_distance)
        self._advance_clocks(dt)
        self._observe_ball(ball, touched)
        self._check_time()
        self._update_mode(dt, ball, players, touched)
        self._clear_for_drop_ball()
        self._judge_positions(dt)
        self._previous_ball = self._ball_position
        actions, self._outbox = self._outbox, []
        return actions + self._mover.moves

    def _judge_positions(self, dt: float) -> None:
        """The real server's automatic referee: positional fouls are judged while the game runs
        and forgotten while it is paused (before kick-off and in the goal pauses)."""
        if self._play_mode in BEAM_MODES:
            self._fouls.reset()
            return
        kick_off_team = (
            _mode_team(self._play_mode) if self._play_mode.startswith("KickOff_") else None
        )
        self._fouls.update(dt, self._ball_position, self._mover, kick_off_team)

    def _advance_clocks(self, dt: float) -> None:
        self._mode_time += dt
        if self._play_mode not in ("BeforeKickOff", "GameOver"):
            self._game_time += dt

    def _observe_ball(self, ball: BallInfo, touched: Sequence[PlayerKey]) -> None:
        self._ball_position = tuple(float(v) for v in ball.position)  # type: ignore[assignment]
        if _ball_on_field(self._ball_position):
            self._last_on_field = self._ball_position
        if touched:
            self._last_touch = touched[0]

    def _check_time(self) -> None:
        """End the half or the game when the clock says so (the real server's CheckTime)."""
        if self._play_mode == "GameOver":
            return
        half_time = self._config.half_time
        if self._half == 1 and self._game_time >= half_time - _CLOCK_SLACK:
            if self._config.single_half:
                self._end_game()
                return
            self._half = 2
            self._emit(EventKind.HALF_TIME, f"half time, {self._score_text()}")
            self._set_mode("BeforeKickOff")
        elif self._half == 2 and self._game_time >= 2 * half_time - _CLOCK_SLACK:
            self._end_game()

    def _update_mode(
        self,
        dt: float,
        ball: BallInfo,
        players: Sequence[PlayerInfo],
        touched: Sequence[PlayerKey],
    ) -> None:
        mode = self._play_mode
        if mode == "BeforeKickOff":
            self._update_before_kick_off(ball, players)
        elif mode.startswith("KickOff_"):
            self._clear_for_kick_off(_mode_team(mode))
            self._update_kick_off(touched)
        elif mode in ("PlayOn", "pass_left", "pass_right"):
            self._update_play_on(dt, ball, players)
        elif _is_set_piece(mode):
            self._update_set_piece(_mode_team(mode), ball, touched)
        elif mode.startswith("Goal_"):
            self._clear_for_kick_off(other_team(_mode_team(mode)))
            self._update_goal(_mode_team(mode))

    # ---- play modes --------------------------------------------------------------------------

    def _update_before_kick_off(self, ball: BallInfo, players: Sequence[PlayerInfo]) -> None:
        """Hold the ball on the centre spot while robots are on the field; kick off
        automatically only when configured to."""
        if players:
            self._hold_ball_on(CENTRE_SPOT, ball)
            if not self._config.start_any_field_position:
                self._mover.keep_in_halves()
        if self._config.auto_kick_off and self._mode_time > self._config.wait_before_kick_off:
            self.kick_off(None)

    def _update_kick_off(self, touched: Sequence[PlayerKey]) -> None:
        """The first touch after the kick-off was given starts play; nobody touching for
        RuleDropBallTime makes a drop ball."""
        drop_time = self._config.drop_ball_time
        if drop_time > 0 and self._mode_time > drop_time:
            self._drop_ball_at(self._ball_position)
            return
        if touched and self._mode_cycle < self._cycle:
            self._set_mode("PlayOn")

    def _update_play_on(self, dt: float, ball: BallInfo, players: Sequence[PlayerInfo]) -> None:
        if self._check_goal(ball.position):
            return
        if self._check_ball_left_field(ball.position):
            return
        if self._config.ball_holding_rule:
            self._check_ball_holding(dt, players)

    def _update_set_piece(self, kicker: Team, ball: BallInfo, touched: Sequence[PlayerKey]) -> None:
        """Kick-ins, corners, goal kicks and free kicks, as the real server runs them: nothing
        happens during RuleKickInPauseTime; then the ball is put on its spot and kept there until
        the kicking team touches it (a goal kick further waits for the ball to leave the penalty
        area); after RuleDropBallTime untaken, the ball is dropped."""
        if self._mode_time < self._config.kick_in_pause_time - _CLOCK_SLACK:
            return
        is_goal_kick = self._play_mode.startswith("goal_kick_")
        self._clear_for_set_piece(kicker, is_goal_kick)
        drop_time = self._config.drop_ball_time
        if drop_time > 0 and self._mode_time > drop_time:
            self._drop_ball_at(self._spot)
            return
        taken_now = self._spot_placed and any(team == kicker for team, _ in touched)
        if is_goal_kick and (self._goal_kick_taken or taken_now):
            self._goal_kick_taken = True
            x, y, _ = ball.position
            if not in_penalty_area(kicker, x, y) or not _ball_on_field(ball.position):
                self._set_mode("PlayOn")
            return
        if taken_now:
            self._set_mode("PlayOn")
            return
        if not self._spot_placed and self._config.kick_repel_distance > 0:
            self._mover.repel(kicker, self._spot, self._config.kick_repel_distance)
        self._hold_ball_on(self._spot, ball, force=not self._spot_placed)
        self._spot_placed = True

    def _update_goal(self, scorer: Team) -> None:
        """After the goal pause the ball goes to the centre and the other side kicks off."""
        if self._mode_time < self._config.goal_pause_time - _CLOCK_SLACK:
            return
        self.kick_off(other_team(scorer))

    # ---- rules in play -----------------------------------------------------------------------

    def _check_goal(self, position: Vec3) -> bool:
        """A goal: the whole ball past the goal line, having crossed it between the posts and
        under the bar."""
        goal_of = self._goal_entered(position)
        if goal_of is None:
            return False
        scorer = other_team(goal_of)
        self._scores[scorer] += 1
        self._emit(EventKind.GOAL, f"goal for {self._describe(scorer)}, {self._score_text()}")
        self._set_mode("Goal_Left" if scorer == "left" else "Goal_Right")
        return True

    def _goal_entered(self, position: Vec3) -> Team | None:
        """The team whose goal the ball is in, or None."""
        line = HALF_LENGTH + BALL_RADIUS
        if abs(position[0]) < line:
            return None
        crossing = self._goal_line_crossing(position, line)
        if crossing is None:
            return None
        y, z = crossing
        if abs(y) < GOAL_WIDTH / 2 and z < GOAL_HEIGHT:
            return "right" if position[0] > 0 else "left"
        return None

    def _goal_line_crossing(self, position: Vec3, line: float) -> tuple[float, float] | None:
        """(y, z) where the ball's centre crossed x = +-line, interpolated between the last
        cycle and this one; a ball already past the line counts only inside the goal."""
        previous = self._previous_ball
        x = abs(position[0])
        if previous is not None and abs(previous[0]) < line and previous[0] * position[0] > 0:
            t = (line - abs(previous[0])) / (x - abs(previous[0]))
            return (
                previous[1] + t * (position[1] - previous[1]),
                previous[2] + t * (position[2] - previous[2]),
            )
        if x <= HALF_LENGTH + GOAL_DEPTH:
            return position[1], position[2]
        return None

    def _check_ball_left_field(self, position: Vec3) -> bool:
        """Over a side line: kick-in for the team that did not touch the ball last. Over a goal
        line: goal kick for the defenders if the attackers touched it last, else a corner kick
        for the attackers."""
        if _ball_on_field(position):
            return False
        if self._last_touch is None:
            self._drop_ball_at(self._last_on_field)
            return True
        toucher = self._last_touch[0]
        x, y, _ = position
        if abs(x) >= HALF_LENGTH:
            line_owner: Team = "left" if x < 0 else "right"
            if toucher == line_owner:
                self._award_corner_kick(other_team(line_owner), y)
            else:
                self._award_goal_kick(line_owner)
        elif abs(y) >= HALF_WIDTH:
            self._award_kick_in(other_team(toucher))
        else:  # cannot happen with the tests above; keep the ball rather than lose it
            self._place_ball(self._last_on_field)
            return False
        return True

    def _check_ball_holding(self, dt: float, players: Sequence[PlayerInfo]) -> None:
        """The 2023 ball-holding rule. The foul gives the other team an indirect free kick
        (``free_kick_<side>``) where the ball is (moved out of a penalty area, as the real server
        does for every free kick). Indirect, because it is the real server's mode for the one
        foul it punishes with a free kick (a kicker touching the ball twice), and because
        holding is a non-contact offence, which football punishes with an indirect free kick;
        it also keeps the foul from turning into a free shot at goal."""
        foul = self._holding.update(dt, self._ball_position, self._previous_ball, players)
        if foul is None:
            return
        team, unum = foul.player
        self._emit(EventKind.FOUL, f"ball holding by {team} {unum}: {foul.reason}")
        self._award_free_kick(other_team(team), self._ball_position)

    # ---- awards ------------------------------------------------------------------------------

    def _award_kick_in(self, team: Team) -> None:
        spot = kick_in_spot(self._last_on_field)
        self._prepare_set_piece(spot)
        self._emit(EventKind.KICK_IN, f"kick-in {self._describe(team)} at {_fmt(spot)}")
        self._set_mode("KickIn_Left" if team == "left" else "KickIn_Right")

    def _award_corner_kick(self, team: Team, ball_y: float) -> None:
        spot = corner_kick_spot(team, ball_y)
        self._prepare_set_piece(spot)
        self._emit(EventKind.CORNER_KICK, f"corner kick {self._describe(team)} at {_fmt(spot)}")
        self._set_mode(f"corner_kick_{team}")

    def _award_goal_kick(self, team: Team) -> None:
        spot = goal_kick_spot(team, self._config.goal_kick_distance)
        self._prepare_set_piece(spot)
        self._emit(EventKind.GOAL_KICK, f"goal kick {self._describe(team)} at {_fmt(spot)}")
        self._set_mode(f"goal_kick_{team}")

    def _award_free_kick(self, team: Team, position: Sequence[float]) -> None:
        spot = free_kick_spot(position)
        self._prepare_set_piece(spot)
        self._emit(EventKind.FREE_KICK, f"free kick {self._describe(team)} at {_fmt(spot)}")
        self._set_mode(f"free_kick_{team}")

    def _prepare_set_piece(self, spot: Vec3) -> None:
        self._spot = spot
        self._spot_placed = False
        self._goal_kick_taken = False

    def _trainer_spot(self, mode: str) -> Vec3:
        """The spot of a set piece the trainer switched to, from where the ball is."""
        team = _mode_team(mode)
        if mode.startswith("KickIn_"):
            return kick_in_spot(self._ball_position)
        if mode.startswith("corner_kick_"):
            return corner_kick_spot(team, self._ball_position[1])
        if mode.startswith("goal_kick_"):
            return goal_kick_spot(team, self._config.goal_kick_distance)
        return free_kick_spot(self._ball_position)

    def _drop_ball_at(self, position: Sequence[float]) -> None:
        """DropBall: the ball goes down out of the penalty areas, both teams are cleared from
        around it (in a random order) and play goes on."""
        spot = drop_ball_spot(position)
        self._place_ball(spot)
        self._drop_to_clear = spot
        self._emit(EventKind.DROP_BALL, f"drop ball at {_fmt(spot)}")
        self._set_mode("PlayOn")

    def _end_game(self) -> None:
        self._emit(EventKind.GAME_OVER, f"game over, {self._score_text()}")
        self._set_mode("GameOver")

    # ---- moving robots -----------------------------------------------------------------------

    def _clear_for_drop_ball(self) -> None:
        """After a drop ball (this cycle or commanded since the last) both teams are cleared
        from the free-kick circle around it, in a random order."""
        spot, self._drop_to_clear = self._drop_to_clear, None
        if spot is None or not self._config.clear_set_pieces:
            return
        teams: list[Team] = list(TEAMS)
        self._rng.shuffle(teams)
        for team in teams:
            self._mover.clear_circle(
                team, spot, self._config.free_kick_distance, "drop ball: free-kick circle"
            )

    def _clear_for_kick_off(self, kicker: Team) -> None:
        """ClearPlayersBeforeKickOff, which the real server runs every cycle of a kick-off and of
        the goal pause before it."""
        if not self._config.start_any_field_position:
            self._mover.clear_for_kick_off(kicker, self._config.free_kick_distance)

    def _clear_for_set_piece(self, kicker: Team, is_goal_kick: bool) -> None:
        """The defenders keep the free-kick distance from the spot; at a goal kick the attackers
        keep out of the kicking team's penalty area instead (the real server's rules)."""
        if not self._config.clear_set_pieces:
            return
        defender = other_team(kicker)
        if is_goal_kick:
            self._mover.clear_box(defender, penalty_box(kicker), "goal kick: penalty area")
        else:
            self._mover.clear_circle(
                defender, self._spot, self._config.free_kick_distance, "set piece: free-kick circle"
            )

    # ---- helpers -----------------------------------------------------------------------------

    def _kick_off_side(self, side: Team | None) -> Team:
        if side is not None:
            return _check_team(side)
        if self._half not in self._first_kick_off:
            if self._half == 1:
                return "left"
            return other_team(self._first_kick_off.get(1, "right"))
        return other_team(self._last_kick_off or "right")

    def _set_mode(self, mode: str) -> None:
        if mode == self._play_mode:
            return
        self._play_mode = mode
        self._mode_time = 0.0
        self._mode_cycle = self._cycle
        self._holding.reset()
        self._emit(EventKind.PLAY_MODE, f"play mode {mode}")

    def _hold_ball_on(self, spot: Vec3, ball: BallInfo, *, force: bool = False) -> None:
        """Put the ball on ``spot`` unless it already rests there. The real server moves it there
        every cycle; telling the session only when the ball has moved off is the same."""
        resting = (
            math.dist(ball.position, spot) <= _SPOT_TOLERANCE
            and math.hypot(*ball.velocity) <= _SPOT_SPEED_TOLERANCE
        )
        if force or not resting:
            self._place_ball(spot)

    def _place_ball(self, position: Vec3) -> None:
        self._outbox.append(PlaceBall(position))
        self._ball_position = position
        self._previous_ball = None

    def _emit(self, kind: EventKind, text: str) -> None:
        self._outbox.append(Event(kind, text))

    def _describe(self, team: Team) -> str:
        name = self._team_names[team]
        return f"{team} ({name})" if name else team

    def _score_text(self) -> str:
        return f"score {self._scores['left']}:{self._scores['right']}"


def _fmt(position: Sequence[float]) -> str:
    return "(" + ", ".join(f"{v:.3f}" for v in position[:3]) + ")"
