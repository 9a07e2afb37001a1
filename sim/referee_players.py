"""How the referee moves robots, as rcssserver3d does (``soccerruleaspect.cpp``).

The real server keeps set pieces and kick-offs clear and takes robots that break positional
rules off the field by moving them, the way the trainer's ``move`` does: every body of the robot
is shifted by the same offset and stopped (``SoccerBase::MoveAgent``); orientation and joint
angles are kept. This module decides those moves as :class:`MovePlayer` values; it is pure logic
on positions (no physics), and :class:`sim.referee.Referee` calls it every cycle.

What the real server does, and this module reproduces:

- ``ClearPlayers(pos, radius)``: a robot of the cleared team whose body's bounding rectangle
  reaches into the circle is put ``d`` from the centre towards its own goal (x only, its y kept),
  ``d`` drawn uniformly from [FreeKickMoveDist, FreeKickMoveDist + 2]; where that would be
  behind its goal line, it is moved ``d`` in y towards the field's middle instead.
- ``ClearPlayers(box)``: a robot whose rectangle overlaps the box is put in front of the box's
  edge on its own side, ``d`` from [FreeKickMoveDist, 2 FreeKickMoveDist] away.
- Before kick-off both teams are kept in their own halves (a robot counts as in the other half
  as soon as any part of its footprint is past the centre line). At a kick-off, and in the goal
  pause before it, the non-kicking team is kept out of the kicker's half and the centre circle,
  and the kicking team out of the opponents' half except for robots wholly inside the circle.
- Kick-ins, corners and free kicks clear the defending team from the free-kick circle around
  the ball; a goal kick clears the attackers from the defenders' penalty area; a drop ball
  clears both teams from the circle. When the ball is first put on its spot, robots of the
  kicking team closer than KickRepelDist are pushed out to that distance.
- :class:`PositionalFoulMonitor`: the "incapable" rule (lying or sitting too long), illegal
  defence (too many defenders in the own penalty area) and crowding (too many team mates near
  the ball). A robot called for one of these is lifted into the air for FoulHoldTime and then
  put outside the field on the side line away from the ball.

Simplifications, said so: a robot's bounding rectangle is taken as a square of
:data:`PLAYER_HALF_EXTENT` around its torso (the real server uses the union of its colliders'
boxes); robots are visited in a seeded random order (the real server shuffles too, unseeded);
the real server's "safe reposition", which nudges a moved robot off another robot it would land
on, is not reproduced.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal, TypeAlias

from world.field_geometry import HALF_LENGTH, HALF_WIDTH, PENALTY_DEPTH, PENALTY_WIDTH

if TYPE_CHECKING:  # the referee's config; imported only for type checkers (no import cycle)
    from sim.referee import RefereeConfig

Team: TypeAlias = Literal["left", "right"]
Vec3: TypeAlias = tuple[float, float, float]
PlayerKey: TypeAlias = tuple[Team, int]

#: Half-size (m) of the square taken as a robot's bounding rectangle on the ground: a standing
#: NAO's colliders span about 0.2 m front to back and, arms down, 0.3 m across.
PLAYER_HALF_EXTENT = 0.1
#: The real server's half-field boxes reach this far past the side and goal lines, "so that no
#: opponents sneak up from behind".
HALF_BOX_OVERSIZE = 10.0
#: ProcessAgentState: below this torso height a robot is "not standing", below the next "on the
#: ground" (m). Counted only for robots within this margin of the side lines.
NOT_STANDING_HEIGHT = 0.25
GROUND_HEIGHT = 0.15
_SIDE_LINE_MARGIN = 0.1
#: A robot standing longer than this (s) has its not-standing time reset.
STANDING_RESET_TIME = 0.5
#: After a reset a robot counts as having stood this long (s), as on the real server.
_RESET_STANDING_TIME = 5.0
#: A fouling robot is held this high (m) and rises this fast (m/s) during FoulHoldTime.
FOUL_HOLD_HEIGHT = 1.0
FOUL_HOLD_RISE_SPEED = 0.5
#: Where a fouling robot is put (RepositionOutsidePos): x = -+0.6 (7 - unum), 0.5 m outside the
#: side line away from the ball, torso at AgentRadius (or at FOUL_HOLD_HEIGHT with no hold).
_OUTSIDE_X_FACTOR = 0.6
_OUTSIDE_X_OFFSET = 7
_OUTSIDE_Y_MARGIN = 0.5
AGENT_RADIUS = 0.4
#: Slack on distance comparisons, as the real crowding test has (m).
_CROWDING_SLACK = 0.01
_TIME_SLACK = 1e-9


class FoulKind:
    """Names of the positional fouls (the real server's EFoulType, as words)."""

    CROWDING = "crowding"
    ILLEGAL_DEFENCE = "illegal defence"
    INCAPABLE = "incapable"


@dataclass(frozen=True, slots=True)
class MovePlayer:
    """Put robot ``(team, unum)``'s torso at ``position`` (world, m), shifting every body of the
    robot by the same offset and stopping it; orientation and joint angles stay. The real
    server's ``SoccerBase::MoveAgent``, which its referee uses to clear set pieces and remove
    fouling robots. ``reason`` says which rule moved it, for the log."""

    team: Team
    unum: int
    position: Vec3
    reason: str

    @property
    def key(self) -> PlayerKey:
        return (self.team, self.unum)


# --------------------------------------------------------------------------------------------
# Geometry
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Rect:
    """An axis-aligned rectangle on the ground (world, m)."""

    x_min: float
    y_min: float
    x_max: float
    y_max: float

    def intersects(self, other: Rect) -> bool:
        return (
            self.x_min <= other.x_max
            and other.x_min <= self.x_max
            and self.y_min <= other.y_max
            and other.y_min <= self.y_max
        )

    def intersects_circle(self, cx: float, cy: float, radius: float) -> bool:
        """Whether the circle reaches the rectangle (its nearest point is within ``radius``)."""
        nearest_x = min(max(cx, self.x_min), self.x_max)
        nearest_y = min(max(cy, self.y_min), self.y_max)
        return math.hypot(nearest_x - cx, nearest_y - cy) <= radius

    def inside_circle(self, cx: float, cy: float, radius: float) -> bool:
        """Whether all four corners lie strictly inside the circle."""
        corners = (
            (self.x_min, self.y_min),
            (self.x_min, self.y_max),
            (self.x_max, self.y_min),
            (self.x_max, self.y_max),
        )
        return all(math.hypot(x - cx, y - cy) < radius for x, y in corners)

    def contains(self, x: float, y: float) -> bool:
        return self.x_min <= x <= self.x_max and self.y_min <= y <= self.y_max


def footprint(position: Sequence[float]) -> Rect:
    """The bounding rectangle the referee takes for a robot whose torso is at ``position``."""
    x, y = position[0], position[1]
    h = PLAYER_HALF_EXTENT
    return Rect(x - h, y - h, x + h, y + h)


def half_box(team: Team) -> Rect:
    """``team``'s own half, oversized past the side and goal lines as on the real server."""
    far_x = HALF_LENGTH + HALF_BOX_OVERSIZE
    far_y = HALF_WIDTH + HALF_BOX_OVERSIZE
    if team == "left":
        return Rect(-far_x, -far_y, 0.0, far_y)
    return Rect(0.0, -far_y, far_x, far_y)


def penalty_box(team: Team) -> Rect:
    """``team``'s own penalty area, exact (goal line to the front line, 6 m wide)."""
    if team == "left":
        return Rect(
            -HALF_LENGTH, -PENALTY_WIDTH / 2, -HALF_LENGTH + PENALTY_DEPTH, PENALTY_WIDTH / 2
        )
    return Rect(HALF_LENGTH - PENALTY_DEPTH, -PENALTY_WIDTH / 2, HALF_LENGTH, PENALTY_WIDTH / 2)


def _other(team: Team) -> Team:
    return "right" if team == "left" else "left"


def _distance_xy(a: Sequence[float], b: Sequence[float]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


# --------------------------------------------------------------------------------------------
# Clearing set pieces and kick-offs
# --------------------------------------------------------------------------------------------


class PlayerMover:
    """The robots' positions during one referee cycle and the moves decided so far.

    Each clearing rule reads the positions as earlier moves of the same cycle left them, as on
    the real server, where a moved robot is already elsewhere when the next rule looks.
    ``move_distance`` is FreeKickMoveDist.
    """

    def __init__(
        self, positions: Mapping[PlayerKey, Vec3], rng: random.Random, move_distance: float
    ) -> None:
        self._positions: dict[PlayerKey, Vec3] = dict(positions)
        self._rng = rng
        self._move_distance = move_distance
        self.moves: list[MovePlayer] = []

    @property
    def positions(self) -> Mapping[PlayerKey, Vec3]:
        """Every robot's torso position after the moves so far."""
        return self._positions

    def move(self, key: PlayerKey, position: Vec3, reason: str) -> None:
        """Record a move and let later rules of this cycle see the robot at its new place."""
        self._positions[key] = position
        self.moves.append(MovePlayer(key[0], key[1], position, reason))

    def _team(self, team: Team) -> list[PlayerKey]:
        """``team``'s robots in a random order (the real server shuffles before clearing, so no
        uniform number is always moved first)."""
        keys = sorted(key for key in self._positions if key[0] == team)
        self._rng.shuffle(keys)
        return keys

    def clear_circle(self, team: Team, centre: Sequence[float], radius: float, reason: str) -> None:
        """ClearPlayers(pos, radius): ``team``'s robots reaching into the circle step back."""
        cx, cy = centre[0], centre[1]
        for key in self._team(team):
            x, y, z = self._positions[key]
            if not footprint((x, y)).intersects_circle(cx, cy, radius):
                continue
            d = self._rng.uniform(self._move_distance, self._move_distance + 2.0)
            target_x = cx - d if team == "left" else cx + d
            if abs(target_x) > HALF_LENGTH:  # behind the own goal line: step aside instead
                y = cy + d if cy < 0 else cy - d
            else:
                x = target_x
            self.move(key, (x, y, z), reason)

    def clear_box(self, team: Team, box: Rect, reason: str) -> None:
        """ClearPlayers(box): ``team``'s robots overlapping the box go out of its own-side edge."""
        for key in self._team(team):
            x, y, z = self._positions[key]
            if not footprint((x, y)).intersects(box):
                continue
            d = self._rng.uniform(self._move_distance, 2.0 * self._move_distance)
            x = box.x_min - d if team == "left" else box.x_max + d
            self.move(key, (x, y, z), reason)

    def clear_for_kick_off(self, kicker: Team, circle_radius: float) -> None:
        """ClearPlayersBeforeKickOff: the other team out of the kicker's half and the centre
        circle; the kicker's robots out of the other half unless wholly inside the circle."""
        defender = _other(kicker)
        self.clear_box(defender, half_box(kicker), "kick-off: own half")
        self.clear_circle(defender, (0.0, 0.0), circle_radius, "kick-off: centre circle")
        opponents_half = half_box(defender)
        for key in self._team(kicker):
            x, y, z = self._positions[key]
            rect = footprint((x, y))
            if not rect.intersects(opponents_half) or rect.inside_circle(0.0, 0.0, circle_radius):
                continue
            d = self._rng.uniform(self._move_distance, 2.0 * self._move_distance)
            x = opponents_half.x_min - d if kicker == "left" else opponents_half.x_max + d
            self.move(key, (x, y, z), "kick-off: own half")

    def keep_in_halves(self) -> None:
        """UpdateBeforeKickOff: each team is kept out of the other's half.

        As on the real server, a robot is in the other half as soon as any part of its
        footprint is past the centre line, so a robot standing on the line is moved too."""
        teams: list[Team] = ["left", "right"]
        self._rng.shuffle(teams)
        for team in teams:
            for key in self._team(team):
                x, y, z = self._positions[key]
                if (
                    (x + PLAYER_HALF_EXTENT > 0.0)
                    if team == "left"
                    else (x - PLAYER_HALF_EXTENT < 0.0)
                ):
                    d = self._rng.uniform(self._move_distance, 2.0 * self._move_distance)
                    self.move(key, (-d if team == "left" else d, y, z), "before kick-off: own half")

    def repel(self, team: Team, centre: Sequence[float], radius: float) -> None:
        """RepelPlayers: ``team``'s robots closer than ``radius`` to the ball's spot are pushed
        straight away from it to ``radius`` (towards the own goal when exactly on the spot)."""
        cx, cy = centre[0], centre[1]
        for key in self._team(team):
            x, y, z = self._positions[key]
            distance = math.hypot(x - cx, y - cy)
            if distance >= radius:
                continue
            if distance > 0.0:
                ux, uy = (x - cx) / distance, (y - cy) / distance
            else:
                ux, uy = (-1.0 if team == "left" else 1.0), 0.0
            self.move(key, (cx + ux * radius, cy + uy * radius, z), "set piece: repel kicker")


# --------------------------------------------------------------------------------------------
# Positional fouls
# --------------------------------------------------------------------------------------------


@dataclass
class _PlayerRecord:
    """One robot's counters (seconds), as ProcessAgentState keeps them."""

    ground: float = 0.0
    not_standing: float = 0.0
    standing: float = _RESET_STANDING_TIME
    inside_area: bool = False
    previously_inside_area: bool = False
    #: seconds since the foul was called; None: no foul pending
    foul_time: float | None = None
    foul: str = ""


class PositionalFoulMonitor:
    """The real server's automatic referee for positional fouls, cycle by cycle.

    Rules, each switched in :class:`~sim.referee.RefereeConfig`:

    - incapable (``incapable_rule``): a field player whose torso is below 0.15 m for longer than
      GroundMaxTime, or below 0.25 m for longer than NotStandingMaxTime (the goalie, unum 1:
      the Goalie... times); standing 0.5 s resets the not-standing time.
    - illegal defence (``illegal_defence_rule``): more than MaxPlayersInsideOwnArea robots of a
      team in their own penalty area; the field player who entered last is called (if the
      goalie entered last, the one ranking MaxPlayersInsideOwnArea + 1 by distance to the own
      goal, the goalie in its area ranking first).
    - crowding (``crowding_rule``): while an opponent is within MinOppDistance of the ball, a
      field player that is its team's second (third) nearest to the ball and within
      Min2PlDistance (Min3PlDistance) of it; not checked for the kicking team at its kick-off.

    A called robot is held at 1 m and rising for FoulHoldTime and then put outside the field.
    Robots are judged only while the game runs: in BeforeKickOff and the goal pauses the
    referee calls :meth:`reset`, as the real server does when the game is paused.
    """

    def __init__(self, config: RefereeConfig) -> None:
        self._config = config
        self._records: dict[PlayerKey, _PlayerRecord] = {}

    def reset(self) -> None:
        """Forget every counter and pending foul."""
        self._records.clear()

    def record(self, key: PlayerKey) -> _PlayerRecord | None:
        """The counters of one robot (for tests and logs)."""
        return self._records.get(key)

    def update(
        self, dt: float, ball: Sequence[float], mover: PlayerMover, kick_off_team: Team | None
    ) -> None:
        """Advance one cycle: update the counters, call new fouls, and add the moves of pending
        fouls to ``mover``. ``kick_off_team`` is the side taking a kick-off now, if any."""
        positions = mover.positions
        for gone in set(self._records) - set(positions):
            del self._records[gone]
        for key, position in positions.items():
            self._observe(self._records.setdefault(key, _PlayerRecord()), position, dt)
        for team in ("left", "right"):
            self._call_fouls(team, ball, positions, kick_off_team)
        for key in sorted(positions):
            record = self._records[key]
            if record.foul_time is not None:
                self._enforce(key, record, dt, ball, mover)

    # ---- counters ------------------------------------------------------------------------

    def _observe(self, record: _PlayerRecord, position: Sequence[float], dt: float) -> None:
        """ProcessAgentState: time low, time on the ground, time standing; and the penalty
        area flags (set by :meth:`_call_fouls`)."""
        z = position[2]
        on_field = abs(position[1]) < HALF_WIDTH + _SIDE_LINE_MARGIN
        if z < NOT_STANDING_HEIGHT and on_field:
            record.not_standing += dt
            record.standing = 0.0
        if z < GROUND_HEIGHT and on_field:
            record.ground += dt
        if z >= NOT_STANDING_HEIGHT:
            record.standing += dt
            record.ground = 0.0
        if record.standing > STANDING_RESET_TIME + _TIME_SLACK:
            record.not_standing = 0.0

    def _call_fouls(
        self,
        team: Team,
        ball: Sequence[float],
        positions: Mapping[PlayerKey, Vec3],
        kick_off_team: Team | None,
    ) -> None:
        """AnalyseFouls for one team (robots already called are left alone)."""
        mine = {key: pos for key, pos in positions.items() if key[0] == team}
        free = [key for key in mine if self._records[key].foul_time is None]
        area = penalty_box(team)
        for key, pos in mine.items():
            record = self._records[key]
            record.previously_inside_area = record.inside_area
            record.inside_area = key in free and area.contains(pos[0], pos[1])
        inside = sum(self._records[key].inside_area for key in free)
        ball_rank = _ranks({key: _distance_xy(mine[key], ball) for key in free})
        goal_x = -HALF_LENGTH if team == "left" else HALF_LENGTH
        goal_distance = {key: math.hypot(mine[key][0] - goal_x, mine[key][1]) for key in free}
        goalie = (team, 1)
        if goalie in goal_distance and self._records[goalie].inside_area:
            goal_distance[goalie] = 0.0
        goal_rank = _ranks(goal_distance)
        opponents = [pos for key, pos in positions.items() if key[0] != team]
        nearest_opponent = min((_distance_xy(p, ball) for p in opponents), default=math.inf)
        crowding = self._config.crowding_rule and kick_off_team != team
        for key in sorted(free):
            distance = _distance_xy(mine[key], ball)
            foul = self._foul_of(
                key,
                crowding and nearest_opponent < self._config.min_opp_distance,
                distance,
                ball_rank[key],
                inside,
                goal_rank[key],
            )
            if foul == FoulKind.ILLEGAL_DEFENCE:
                inside -= 1
            if foul:
                self._records[key].foul_time = 0.0
                self._records[key].foul = foul

    def _foul_of(
        self,
        key: PlayerKey,
        check_crowding: bool,
        ball_distance: float,
        ball_rank: int,
        inside: int,
        goal_rank: int,
    ) -> str:
        """The foul ``key`` commits now, in the real server's order of tests, or ''."""
        config = self._config
        record = self._records[key]
        field_player = key[1] != 1
        if check_crowding and field_player:
            if ball_rank == 3 and ball_distance <= config.min_3pl_distance + _CROWDING_SLACK:
                return FoulKind.CROWDING
            if ball_rank == 2 and ball_distance <= config.min_2pl_distance + _CROWDING_SLACK:
                return FoulKind.CROWDING
        if config.illegal_defence_rule and self._illegal_defence(key, record, inside, goal_rank):
            return FoulKind.ILLEGAL_DEFENCE
        if config.incapable_rule:
            ground_limit = config.ground_max_time if field_player else config.goalie_ground_max_time
            low_limit = (
                config.not_standing_max_time
                if field_player
                else config.goalie_not_standing_max_time
            )
            if record.ground > ground_limit + _TIME_SLACK:
                return FoulKind.INCAPABLE
            if record.not_standing > low_limit + _TIME_SLACK:
                return FoulKind.INCAPABLE
        return ""

    def _illegal_defence(
        self, key: PlayerKey, record: _PlayerRecord, inside: int, goal_rank: int
    ) -> bool:
        limit = self._config.max_players_inside_own_area
        if inside <= limit or key[1] == 1 or not record.inside_area:
            return False
        if not record.previously_inside_area:
            return True
        goalie = self._records.get((key[0], 1))
        goalie_entered = (
            goalie is not None and goalie.inside_area and not goalie.previously_inside_area
        )
        return goalie_entered and goal_rank == limit + 1

    # ---- enforcement ---------------------------------------------------------------------

    def _enforce(
        self,
        key: PlayerKey,
        record: _PlayerRecord,
        dt: float,
        ball: Sequence[float],
        mover: PlayerMover,
    ) -> None:
        """ClearPlayersAutomatic: hold the robot up for FoulHoldTime, then put it outside."""
        assert record.foul_time is not None
        hold = self._config.foul_hold_time
        x, y, _ = mover.positions[key]
        if record.foul_time < hold - _TIME_SLACK:
            record.foul_time += dt
            z = FOUL_HOLD_HEIGHT + FOUL_HOLD_RISE_SPEED * record.foul_time
            mover.move(key, (x, y, z), f"{record.foul}: held")
            return
        mover.move(key, outside_position(key, ball, hold > 0), f"{record.foul}: taken off")
        self._records[key] = _PlayerRecord()


def outside_position(key: PlayerKey, ball: Sequence[float], held: bool) -> Vec3:
    """RepositionOutsidePos: beside the side line away from the ball, spread by uniform number,
    on the team's own side of the centre for low numbers."""
    team, unum = key
    x_factor = -_OUTSIDE_X_FACTOR if team == "left" else _OUTSIDE_X_FACTOR
    y_side = 1.0 if ball[1] < 0 else -1.0
    z = AGENT_RADIUS if held else FOUL_HOLD_HEIGHT
    return (x_factor * (_OUTSIDE_X_OFFSET - unum), (HALF_WIDTH + _OUTSIDE_Y_MARGIN) * y_side, z)


def _ranks(distances: Mapping[PlayerKey, float]) -> dict[PlayerKey, int]:
    """1 for the nearest, 2 for the next...; on a tie the higher uniform number ranks first (the
    real server's SimpleOrder)."""
    order = sorted(distances, key=lambda key: (distances[key], -key[1]))
    return {key: rank for rank, key in enumerate(order, start=1)}
