"""The robots the referee moves, as rcssserver3d's soccerruleaspect.cpp does: kick-offs, set
pieces and drop balls cleared, robots lying too long or crowding their own penalty area taken
off. Pure referee logic with made-up positions, and one session test with real robots."""

from __future__ import annotations

import math
from collections.abc import Sequence

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim.referee import (
    BallInfo,
    MovePlayer,
    PlayerInfo,
    Referee,
    RefereeAction,
    RefereeConfig,
)
from sim.referee_players import PLAYER_HALF_EXTENT, footprint, penalty_box
from world.field_geometry import BALL_RADIUS, HALF_LENGTH, HALF_WIDTH, PENALTY_DEPTH

DT = 0.02
R = BALL_RADIUS
STANDING = 0.36
LYING = 0.1
MOVE = RefereeConfig().free_kick_move_distance


def ball(x: float, y: float) -> BallInfo:
    return BallInfo((x, y, R))


def player(team: str, unum: int, x: float, y: float, z: float = STANDING) -> PlayerInfo:
    return PlayerInfo(team, unum, (x, y, z))  # type: ignore[arg-type]


def moves(actions: Sequence[RefereeAction]) -> dict[tuple[str, int], MovePlayer]:
    """The last move of each robot in ``actions``."""
    return {a.key: a for a in actions if isinstance(a, MovePlayer)}


class World:
    """Made-up robots that go where the referee moves them, cycle after cycle."""

    def __init__(self, referee: Referee, ball_info: BallInfo, players: Sequence[PlayerInfo]):
        self.referee = referee
        self.ball = ball_info
        self.players = {p.key: p for p in players}

    def run(self, seconds: float) -> list[RefereeAction]:
        actions: list[RefereeAction] = []
        for _ in range(round(seconds / DT)):
            step = self.referee.step(DT, self.ball, list(self.players.values()))
            for move in moves(step).values():
                self.players[move.key] = PlayerInfo(move.team, move.unum, move.position)
            actions += step
        return actions

    def at(self, team: str, unum: int) -> tuple[float, float, float]:
        return self.players[(team, unum)].position  # type: ignore[index]


def in_mode(mode: str, ball_xy: tuple[float, float], config: RefereeConfig | None = None):
    """A referee in PlayOn that has seen the ball at ``ball_xy``, then switched to ``mode``."""
    referee = Referee(config, seed=4)
    referee.kick_off("left")
    referee.set_play_mode("PlayOn")
    referee.step(DT, ball(*ball_xy), [])
    referee.set_play_mode(mode)
    return referee


# ---- set pieces ------------------------------------------------------------------------------


def test_free_kick_clears_defenders_from_the_circle_after_the_pause_only() -> None:
    referee = in_mode("free_kick_left", (3.0, 1.0))
    world = World(
        referee, ball(3.0, 1.0), [player("right", 5, 3.5, 1.2), player("left", 9, 2.0, 1)]
    )
    assert moves(world.run(0.96)) == {}  # RuleKickInPauseTime: nothing happens yet
    moved = moves(world.run(0.06))
    assert set(moved) == {("right", 5)}
    x, y, z = world.at("right", 5)
    assert MOVE <= x - 3.0 <= MOVE + 2.0  # towards its own goal (+x), y and height kept
    assert (y, z) == (1.2, STANDING)
    assert moves(world.run(1.0)) == {}  # out of the circle: left alone
    assert world.at("left", 9) == (2.0, 1, STANDING)  # the kicking team stays


def test_kick_in_clears_the_circle_around_the_spot_on_the_side_line() -> None:
    referee = in_mode("KickIn_Right", (-4.0, 9.9))
    world = World(referee, ball(-4.0, HALF_WIDTH - R), [player("left", 7, -3.0, 9.0)])
    world.run(1.1)
    x, y, _ = world.at("left", 7)
    assert -4.0 - MOVE - 2.0 <= x <= -4.0 - MOVE
    assert y == 9.0


def test_defender_near_its_own_goal_line_steps_aside_instead_of_behind_the_line() -> None:
    referee = in_mode("corner_kick_right", (-14.9, 5.0))
    world = World(referee, ball(-14.9, 5.0), [player("left", 2, -14.2, 4.5)])
    world.run(1.1)
    x, y, _ = world.at("left", 2)
    assert x == -14.2  # x kept, moved along y towards the middle
    spot_y = y + 0  # the corner spot's y is the server's (FieldWidth + GoalWidth) / 4 - r
    assert spot_y < 5.0 - MOVE + 1.0
    corner_y = (20.0 + 2.1) / 4 - R
    assert math.hypot(x + HALF_LENGTH - R, y - corner_y) >= 2.0 + PLAYER_HALF_EXTENT


def test_goal_kick_clears_attackers_from_the_penalty_area_not_from_a_circle() -> None:
    referee = in_mode("goal_kick_left", (-14.0, 0.0))
    inside = player("right", 9, -14.0, 2.0)
    near_but_outside = player("right", 10, -12.8, 0.5)  # 1.4 m from the spot, out of the area
    world = World(referee, ball(-HALF_LENGTH + 1.0, 0.0), [inside, near_but_outside])
    world.run(1.1)
    x, y, _ = world.at("right", 9)
    front = -HALF_LENGTH + PENALTY_DEPTH
    assert front + MOVE <= x <= front + 2 * MOVE
    assert y == 2.0
    assert world.at("right", 10) == (-12.8, 0.5, STANDING)


def test_ball_put_on_its_spot_repels_the_kicking_teams_robot_standing_on_it() -> None:
    referee = in_mode("free_kick_left", (3.0, 1.0))
    world = World(referee, ball(3.0, 1.0), [player("left", 9, 3.1, 1.0)])
    world.run(1.1)
    x, y, _ = world.at("left", 9)
    assert (x, y) == pytest.approx((3.5, 1.0))


def test_set_piece_clearing_can_be_switched_off() -> None:
    config = RefereeConfig(clear_set_pieces=False, kick_repel_distance=0.0)
    referee = in_mode("free_kick_left", (3.0, 1.0), config)
    world = World(
        referee, ball(3.0, 1.0), [player("right", 5, 3.5, 1.2), player("left", 9, 3.1, 1)]
    )
    assert moves(world.run(2.0)) == {}


def test_drop_ball_clears_both_teams_from_the_circle() -> None:
    referee = Referee(seed=1)
    referee.set_play_mode("PlayOn")
    referee.step(DT, ball(1.0, 2.0), [])
    referee.drop_ball()
    near = [player("left", 3, 1.5, 2.0), player("right", 4, 0.5, 2.5)]
    moved = moves(referee.step(DT, ball(1.0, 2.0), near))
    assert set(moved) == {("left", 3), ("right", 4)}
    assert moved[("left", 3)].position[0] <= 1.0 - MOVE
    assert moved[("right", 4)].position[0] >= 1.0 + MOVE


@settings(max_examples=60, deadline=None)
@given(
    st.sampled_from(["KickIn_Left", "KickIn_Right", "free_kick_left", "free_kick_right"]),
    st.floats(-14.9, 14.9),
    st.floats(-9.9, 9.9),
    st.lists(st.tuples(st.floats(-2.5, 2.5), st.floats(-2.5, 2.5)), min_size=1, max_size=6),
)
def test_after_clearing_no_defender_reaches_into_the_free_kick_circle(
    mode: str, bx: float, by: float, offsets: list[tuple[float, float]]
) -> None:
    referee = in_mode(mode, (bx, by))
    kicker = "left" if mode.lower().endswith("left") else "right"
    defender = "right" if kicker == "left" else "left"
    defenders = [player(defender, k + 2, bx + dx, by + dy) for k, (dx, dy) in enumerate(offsets)]
    world = World(referee, ball(bx, by), defenders)
    world.run(1.02)
    spot = referee.set_piece_spot
    for p in world.players.values():
        assert not footprint(p.position).intersects_circle(spot[0], spot[1], 2.0), p


# ---- kick-off ----------------------------------------------------------------------------------


def test_before_kick_off_each_team_is_kept_in_its_own_half() -> None:
    world = World(
        Referee(seed=2), ball(0, 0), [player("left", 4, 3.0, 2.0), player("right", 4, 5, 0)]
    )
    world.run(DT)
    x, y, _ = world.at("left", 4)
    assert -2 * MOVE <= x <= -MOVE and y == 2.0
    assert world.at("right", 4) == (5, 0, STANDING)


def test_start_any_field_position_keeps_robots_where_they_are() -> None:
    referee = Referee(RefereeConfig(start_any_field_position=True))
    world = World(referee, ball(0, 0), [player("left", 4, 3.0, 2.0)])
    world.run(0.1)
    referee.kick_off("right")
    world.run(0.1)
    assert world.at("left", 4) == (3.0, 2.0, STANDING)


def test_kick_off_clears_the_centre_circle_of_the_other_team_only() -> None:
    referee = Referee(seed=3)
    referee.kick_off("left")
    kicker = player("left", 9, 0.6, 0.3)  # in the opponents' half, but inside the circle
    kicker_far = player("left", 10, 4.0, 3.0)  # in the opponents' half, outside the circle
    defender = player("right", 9, 1.2, -0.5)  # in its own half, inside the circle
    world = World(referee, ball(0, 0), [kicker, kicker_far, defender])
    world.run(DT)
    assert world.at("left", 9) == (0.6, 0.3, STANDING)
    assert -2 * MOVE <= world.at("left", 10)[0] <= -MOVE
    x, y, _ = world.at("right", 9)
    assert MOVE <= x <= MOVE + 2.0 and y == -0.5


def test_goal_pause_clears_for_the_coming_kick_off() -> None:
    referee = Referee(seed=5)
    referee.set_play_mode("Goal_Left")  # the right team kicks off next
    world = World(referee, ball(15.3, 0), [player("left", 9, -0.5, 0.0), player("right", 9, -3, 1)])
    world.run(DT)
    assert world.at("left", 9)[0] <= -MOVE  # out of the circle, towards its own goal
    assert world.at("right", 9)[0] >= MOVE  # the kick-off team's robot back in its half


# ---- positional fouls --------------------------------------------------------------------------


def test_field_player_on_the_ground_too_long_is_held_up_then_put_outside() -> None:
    referee = in_mode("PlayOn", (2.0, 3.0))
    world = World(referee, ball(2.0, 3.0), [player("left", 5, 1.0, 1.0, LYING)])
    assert moves(world.run(15.0)) == {}  # GroundMaxTime 15 s
    held = moves(world.run(0.04))[("left", 5)]
    assert held.position[:2] == (1.0, 1.0) and held.position[2] >= 1.0
    assert "incapable" in held.reason
    world.run(0.5)  # FoulHoldTime
    assert world.at("left", 5) == pytest.approx((-0.6 * (7 - 5), -(HALF_WIDTH + 0.5), 0.4))
    assert moves(world.run(1.0)) == {}  # outside the field: counted no more


def test_goalie_may_lie_longer_and_sitting_counts_only_after_30_s() -> None:
    referee = in_mode("PlayOn", (2.0, 3.0))
    goalie = player("right", 1, 14.0, 0.0, LYING)
    sitter = player("right", 6, 5.0, 0.0, 0.2)  # below 0.25 m, above 0.15 m
    world = World(referee, ball(2.0, 3.0), [goalie, sitter])
    assert moves(world.run(29.9)) == {}
    assert set(moves(world.run(0.2))) == {("right", 1), ("right", 6)}  # 30 s each


def test_standing_up_in_time_resets_the_count_and_pauses_reset_everything() -> None:
    referee = in_mode("PlayOn", (2.0, 3.0))
    world = World(referee, ball(2.0, 3.0), [player("left", 5, 1.0, 1.0, LYING)])
    world.run(14.0)
    world.players[("left", 5)] = player("left", 5, 1.0, 1.0, STANDING)
    world.run(0.1)
    world.players[("left", 5)] = player("left", 5, 1.0, 1.0, LYING)
    assert moves(world.run(14.0)) == {}
    referee.set_play_mode("BeforeKickOff")
    world.run(5.0)
    referee.set_play_mode("PlayOn")
    assert moves(world.run(14.0)) == {}


def test_incapable_rule_can_be_switched_off() -> None:
    referee = in_mode("PlayOn", (2.0, 3.0), RefereeConfig(incapable_rule=False))
    world = World(referee, ball(2.0, 3.0), [player("left", 5, 1.0, 1.0, LYING)])
    assert moves(world.run(40.0)) == {}


def test_fourth_defender_entering_the_own_penalty_area_is_taken_off() -> None:
    referee = in_mode("PlayOn", (0.0, 0.0))
    area = penalty_box("left")
    defenders = [player("left", n, -14.0, -2.0 + n) for n in (1, 2, 3)]
    world = World(referee, ball(0, 0), [*defenders, player("left", 4, -12.0, 0.0)])
    assert moves(world.run(0.5)) == {}  # three inside: allowed
    world.players[("left", 4)] = player("left", 4, -13.5, 0.0)
    assert set(moves(world.run(DT))) == {("left", 4)}
    world.run(0.6)
    x, y, _ = world.at("left", 4)
    assert not area.contains(x, y) and abs(y) > HALF_WIDTH


def test_crowding_is_off_by_default_and_calls_the_second_nearest_when_on() -> None:
    crowd = [player("left", 7, 0.2, 0.0), player("left", 8, -0.2, 0.1), player("right", 5, 0.5, 0)]
    off = World(in_mode("PlayOn", (0.0, 0.0)), ball(0, 0), crowd)
    assert moves(off.run(1.0)) == {}
    on = World(in_mode("PlayOn", (0.0, 0.0), RefereeConfig(crowding_rule=True)), ball(0, 0), crowd)
    assert set(moves(on.run(DT))) == {("left", 8)}  # tie at 0.2 m: the higher unum is nearer


def test_new_config_keys_are_the_real_servers_settings() -> None:
    config = RefereeConfig()
    assert (config.free_kick_move_distance, config.kick_repel_distance) == (2.2, 0.5)
    assert (config.ground_max_time, config.goalie_ground_max_time) == (15.0, 30.0)
    assert (config.not_standing_max_time, config.goalie_not_standing_max_time) == (30.0, 60.0)
    assert (config.max_players_inside_own_area, config.foul_hold_time) == (3, 0.5)
    assert config.crowding_rule is False and config.start_any_field_position is False
    with pytest.raises(ValueError, match="max_players_inside_own_area"):
        RefereeConfig(max_players_inside_own_area=2.5)  # type: ignore[arg-type]


# ---- in the session ----------------------------------------------------------------------------


def test_session_free_kick_moves_a_real_opponent_out_of_the_radius() -> None:
    from sim.session import Session, SessionConfig

    session = Session(SessionConfig(seed=7, beam_noise=False))
    try:
        session.join("Alpha", 9, beam=(-8.0, 0.0, 0.0))
        opponent = session.join("Beta", 5, beam=(-8.0, 0.0, 0.0), settle_cycles=20)
        robot = session.agents[opponent].robot
        session.trainer("(playMode PlayOn)(ball (pos -3 0 0.042) (vel 0 0 0))")
        session.trainer(f"(agent (unum 5) (team Right) (move -2.5 0.6 {STANDING + 0.02} -90))")
        session.step()
        session.trainer("(playMode free_kick_left)")
        session.step()
        before = robot.torso_position()
        assert math.hypot(before[0] + 3.0, before[1]) < 1.0
        for _ in range(round(1.1 / DT)):
            session.step()
        x, y, _ = robot.torso_position()
        assert math.hypot(x + 3.0, y) > 2.0  # out of FreeKickDistance around the spot
        assert x > before[0] + 1.5  # moved towards its own goal (+x), not along y
        assert abs(y - before[1]) < 0.3
        assert session.referee.play_mode == "free_kick_left"
    finally:
        session.close()
