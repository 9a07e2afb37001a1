"""The referee's rules, cycle by cycle, without physics: positions and touches are made up here."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from sim.referee import (
    DEFAULT_CONFIG_PATH,
    BallInfo,
    Event,
    EventKind,
    PlaceBall,
    PlayerInfo,
    Referee,
    RefereeAction,
    RefereeConfig,
    load_referee_config,
)
from world.field_geometry import (
    BALL_RADIUS,
    FIELD_WIDTH,
    GOAL_WIDTH,
    HALF_LENGTH,
    HALF_WIDTH,
    PENALTY_DEPTH,
    PENALTY_WIDTH,
)

DT = 0.02
R = BALL_RADIUS


def ball(x: float, y: float, z: float = R, v: tuple[float, float, float] = (0, 0, 0)) -> BallInfo:
    return BallInfo((x, y, z), v)


def player(team: str, unum: int, x: float, y: float, z: float = 0.35) -> PlayerInfo:
    return PlayerInfo(team, unum, (x, y, z))  # type: ignore[arg-type]


def run(
    referee: Referee,
    seconds: float,
    ball_info: BallInfo,
    players: Sequence[PlayerInfo] = (),
    touches: Iterable[tuple[str, int]] = (),
) -> list[RefereeAction]:
    """Step ``seconds`` of cycles with the same world; return every action."""
    actions: list[RefereeAction] = []
    for _ in range(round(seconds / DT)):
        actions += referee.step(DT, ball_info, players, list(touches))  # type: ignore[arg-type]
    return actions


def placements(actions: Sequence[RefereeAction]) -> list[tuple[float, float, float]]:
    return [a.position for a in actions if isinstance(a, PlaceBall)]


def events(actions: Sequence[RefereeAction], kind: EventKind) -> list[Event]:
    return [a for a in actions if isinstance(a, Event) and a.kind == kind]


def modes(actions: Sequence[RefereeAction]) -> list[str]:
    return [e.text.removeprefix("play mode ") for e in events(actions, EventKind.PLAY_MODE)]


def playing(config: RefereeConfig | None = None) -> Referee:
    """A referee in PlayOn with the clock started."""
    referee = Referee(config)
    referee.kick_off("left")
    referee.set_play_mode("PlayOn")
    referee.step(DT, ball(0, 0), [])
    return referee


def kick_out(referee: Referee, toucher: tuple[str, int], path: Sequence[tuple]) -> list:
    """``toucher`` touches the ball at the first position; it then moves along ``path``."""
    actions = referee.step(DT, ball(*path[0]), [], [toucher])  # type: ignore[list-item]
    for position in path[1:]:
        actions += referee.step(DT, ball(*position), [])
    return actions


# ---- configuration ---------------------------------------------------------------------------


def test_defaults_are_the_real_servers_settings() -> None:
    config = RefereeConfig()
    assert config.half_time == 300.0
    assert config.goal_pause_time == 3.0
    assert config.kick_in_pause_time == 1.0
    assert config.wait_before_kick_off == 30.0
    assert config.auto_kick_off is False
    assert config.free_kick_distance == 2.0
    assert config.ball_holding_rule is True
    assert (config.ball_hold_radius, config.ball_hold_max_time) == (0.12, 5.0)
    assert (config.ball_hold_goalie_max_time, config.ball_hold_reset_time) == (10.0, 0.5)
    assert (config.ball_hold_max_distance, config.ball_hold_opp_distance) == (1.0, 0.75)


def test_repository_yaml_holds_the_defaults() -> None:
    assert load_referee_config(DEFAULT_CONFIG_PATH) == RefereeConfig()


def test_yaml_overrides_and_keeps_the_rest(tmp_path: Path) -> None:
    path = tmp_path / "ref.yaml"
    path.write_text("half_time: 60\nauto_kick_off: true\nball_hold_opp_distance: -1\n")
    config = load_referee_config(path)
    assert (config.half_time, config.auto_kick_off, config.ball_hold_opp_distance) == (
        60,
        True,
        -1,
    )
    assert config.goal_pause_time == 3.0
    empty = tmp_path / "empty.yaml"
    empty.write_text("")
    assert load_referee_config(empty) == RefereeConfig()


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("half_tme: 300\n", ["half_tme", "unknown"]),
        ("goal_pause_time: soon\n", ["goal_pause_time", "number"]),
        ("auto_kick_off: 1\n", ["auto_kick_off", "true or false"]),
        ("kick_in_pause_time: true\n", ["kick_in_pause_time", "number"]),
        ("ball_hold_max_time: -5\n", ["ball_hold_max_time", "negative"]),
        ("half_time: 0\n", ["half_time", "positive"]),
        ("drop_ball_time: .nan\n", ["drop_ball_time", "finite"]),
        ("- half_time\n", ["mapping"]),
        ("half_time: [\n", ["YAML"]),
    ],
)
def test_yaml_errors_name_the_key_and_the_file(tmp_path: Path, text: str, words: list) -> None:
    path = tmp_path / "bad_referee.yaml"
    path.write_text(text)
    with pytest.raises(ValueError) as error:
        load_referee_config(path)
    message = str(error.value)
    assert "bad_referee.yaml" in message
    for word in words:
        assert word in message


def test_config_refuses_negative_times_directly() -> None:
    with pytest.raises(ValueError, match="goal_pause_time"):
        RefereeConfig(goal_pause_time=-1.0)


# ---- teams -----------------------------------------------------------------------------------


def test_first_two_teams_get_left_and_right_and_a_third_is_refused() -> None:
    referee = Referee()
    assert referee.team_names == (None, None)
    assert referee.register_team("Alpha") == "left"
    assert referee.register_team("Beta") == "right"
    assert referee.register_team("Alpha") == "left"
    assert referee.team_names == ("Alpha", "Beta")
    with pytest.raises(ValueError, match="invalid teamname 'Gamma'"):
        referee.register_team("Gamma")
    assert referee.team_names == ("Alpha", "Beta")


# ---- before kick-off and kick-off ------------------------------------------------------------


def test_clock_stands_still_before_kick_off_and_runs_after() -> None:
    referee = Referee()
    run(referee, 60.0, ball(0, 0), [player("left", 1, -5, 0)])
    assert referee.play_mode == "BeforeKickOff"  # no automatic kick-off by default
    assert referee.game_time == 0.0
    referee.kick_off(None)
    assert referee.play_mode == "KickOff_Left"
    run(referee, 1.0, ball(0, 0))
    assert referee.game_time == pytest.approx(1.0)


def test_before_kick_off_keeps_the_ball_on_the_centre_spot_once_robots_are_there() -> None:
    referee = Referee()
    assert placements(run(referee, 0.1, ball(3, 2))) == []  # nobody connected yet
    actions = referee.step(DT, ball(3, 2), [player("left", 1, -5, 0)])
    assert placements(actions) == [(0.0, 0.0, R)]
    assert placements(referee.step(DT, ball(0, 0), [player("left", 1, -5, 0)])) == []


def test_automatic_kick_off_waits_and_then_kicks_off_left() -> None:
    referee = Referee(RefereeConfig(auto_kick_off=True, wait_before_kick_off=1.0))
    run(referee, 0.9, ball(0, 0))
    assert referee.play_mode == "BeforeKickOff"
    run(referee, 0.2, ball(0, 0))
    assert referee.play_mode == "KickOff_Left"


def test_kick_off_places_the_ball_and_the_first_touch_starts_play() -> None:
    referee = Referee()
    referee.kick_off("right")
    actions = referee.step(DT, ball(0.3, 0.1), [])
    assert placements(actions) == [(0.0, 0.0, R)]
    assert [e.text for e in events(actions, EventKind.KICK_OFF)] == ["kick-off right"]
    assert referee.play_mode == "KickOff_Right"
    run(referee, 2.0, ball(0, 0))
    assert referee.play_mode == "KickOff_Right"
    referee.step(DT, ball(0, 0), [], [("right", 9)])
    assert referee.play_mode == "PlayOn"
    assert referee.last_touch == ("right", 9)


def test_kick_off_nobody_takes_becomes_a_drop_ball() -> None:
    referee = Referee()
    referee.kick_off("left")
    run(referee, 14.9, ball(0, 0))
    assert referee.play_mode == "KickOff_Left"
    actions = run(referee, 0.2, ball(0, 0))
    assert referee.play_mode == "PlayOn"
    assert len(events(actions, EventKind.DROP_BALL)) == 1


# ---- goals -----------------------------------------------------------------------------------


def test_ball_through_the_goal_scores_and_the_other_side_kicks_off_after_the_pause() -> None:
    referee = Referee()
    referee.register_team("Alpha")
    referee.kick_off("left")
    referee.step(DT, ball(0, 0), [], [("left", 9)])
    # a shot from (14.9, 0.3) into the right goal: the whole ball is past the line next cycle
    actions = kick_out(referee, ("left", 9), [(14.9, 0.3, 0.2), (HALF_LENGTH + 0.1, 0.35, 0.2)])
    assert referee.play_mode == "Goal_Left"
    assert (referee.score_left, referee.score_right) == (1, 0)
    assert "goal for left (Alpha)" in events(actions, EventKind.GOAL)[0].text
    assert referee.may_beam("left") and referee.may_beam("right")
    run(referee, 2.9, ball(15.3, 0.35))
    assert referee.play_mode == "Goal_Left"
    actions = run(referee, 0.2, ball(15.3, 0.35))
    assert referee.play_mode == "KickOff_Right"
    assert placements(actions) == [(0.0, 0.0, R)]
    assert not referee.may_beam("left")


def test_own_goal_counts_for_the_other_team() -> None:
    referee = playing()
    kick_out(referee, ("left", 3), [(-14.8, -0.5), (-HALF_LENGTH - 0.1, -0.6)])
    assert referee.play_mode == "Goal_Right"
    assert (referee.score_left, referee.score_right) == (0, 1)


def test_ball_partly_over_the_line_is_no_goal_yet() -> None:
    referee = playing()
    kick_out(referee, ("left", 9), [(14.9, 0.0), (HALF_LENGTH + R / 2, 0.0)])
    assert referee.play_mode == "PlayOn"
    assert referee.score_left == 0


def test_ball_over_the_bar_or_wide_of_the_post_is_no_goal() -> None:
    over_bar = playing()
    kick_out(over_bar, ("left", 9), [(14.8, 0.0, 0.9), (HALF_LENGTH + 0.2, 0.0, 0.95)])
    assert over_bar.play_mode == "goal_kick_right"
    wide = playing()
    y = GOAL_WIDTH / 2 + 0.1
    kick_out(wide, ("left", 9), [(14.8, y), (HALF_LENGTH + 0.2, y)])
    assert wide.play_mode == "goal_kick_right"
    assert over_bar.score_left == wide.score_left == 0


# ---- outs ------------------------------------------------------------------------------------


def test_ball_over_the_side_line_gives_a_kick_in_to_the_other_team_on_the_line() -> None:
    referee = playing()
    actions = kick_out(referee, ("left", 7), [(3.0, 9.9), (3.2, HALF_WIDTH + 0.1)])
    assert referee.play_mode == "KickIn_Right"
    assert len(events(actions, EventKind.KICK_IN)) == 1
    assert placements(actions) == []  # the ball is placed when the pause is over
    actions = run(referee, 0.98, ball(3.6, 10.6))
    assert placements(actions) == []
    actions = run(referee, 0.02, ball(3.6, 10.6))
    assert placements(actions) == [(3.0, HALF_WIDTH - R, R)]
    # the team that kicked it out cannot take the kick-in; the ball is kept on its spot
    actions = referee.step(DT, ball(3.1, 9.8, v=(0.5, 0, 0)), [], [("left", 7)])
    assert referee.play_mode == "KickIn_Right"
    assert placements(actions) == [(3.0, HALF_WIDTH - R, R)]
    referee.step(DT, ball(3.0, HALF_WIDTH - R), [], [("right", 4)])
    assert referee.play_mode == "PlayOn"


def test_kick_in_nobody_takes_becomes_a_drop_ball_on_the_spot() -> None:
    referee = playing()
    kick_out(referee, ("right", 2), [(-4.0, -9.9), (-4.0, -HALF_WIDTH - 0.1)])
    assert referee.play_mode == "KickIn_Left"
    actions = run(referee, 15.1, ball(-4.0, -HALF_WIDTH + R))
    assert referee.play_mode == "PlayOn"
    assert len(events(actions, EventKind.DROP_BALL)) == 1
    assert placements(actions)[-1] == (-4.0, -HALF_WIDTH + R, R)


def test_attackers_over_the_goal_line_give_a_goal_kick() -> None:
    referee = playing()
    actions = kick_out(referee, ("left", 9), [(14.9, 5.0), (HALF_LENGTH + 0.1, 5.0)])
    assert referee.play_mode == "goal_kick_right"
    actions += run(referee, 1.1, ball(15.5, 5.0))
    assert set(placements(actions)) == {(HALF_LENGTH - 1.0, 0.0, R)}


def test_defenders_over_their_own_goal_line_give_a_corner_kick() -> None:
    referee = playing()
    actions = kick_out(referee, ("left", 2), [(-14.9, 6.0), (-HALF_LENGTH - 0.1, 6.0)])
    assert referee.play_mode == "corner_kick_right"
    actions += run(referee, 1.1, ball(-15.5, 6.0))
    corner_y = (FIELD_WIDTH + GOAL_WIDTH) / 4 - R
    assert set(placements(actions)) == {(-HALF_LENGTH + R, corner_y, R)}
    other_side = playing()
    kick_out(other_side, ("right", 2), [(14.9, -6.0), (HALF_LENGTH + 0.1, -6.0)])
    assert other_side.play_mode == "corner_kick_left"


def test_goal_kick_plays_on_only_when_the_ball_leaves_the_penalty_area() -> None:
    referee = playing()
    kick_out(referee, ("right", 9), [(-14.9, 5.0), (-HALF_LENGTH - 0.1, 5.0)])
    assert referee.play_mode == "goal_kick_left"
    run(referee, 1.1, ball(-14.0, 0.0))
    referee.step(DT, ball(-14.0, 0.0), [], [("left", 1)])
    run(referee, 0.2, ball(-13.5, 0.0))
    assert referee.play_mode == "goal_kick_left"
    referee.step(DT, ball(-HALF_LENGTH + PENALTY_DEPTH + 0.1, 0.0), [])
    assert referee.play_mode == "PlayOn"


def test_ball_out_before_anybody_touched_it_is_dropped_back() -> None:
    referee = Referee()
    referee.set_play_mode("PlayOn")
    referee.step(DT, ball(5.0, 9.9), [])
    actions = referee.step(DT, ball(5.0, 10.2), [])
    assert referee.play_mode == "PlayOn"
    assert placements(actions) == [(5.0, 9.9, R)]


# ---- halves ----------------------------------------------------------------------------------


def test_half_time_at_300_seconds_then_second_half_kicked_off_by_the_other_side() -> None:
    referee = Referee()
    assert referee.kick_off(None) == "left"
    referee.set_play_mode("PlayOn")
    run(referee, 299.98, ball(0, 0))
    assert (referee.half, referee.play_mode) == (1, "PlayOn")
    actions = run(referee, DT, ball(0, 0))
    assert (referee.half, referee.play_mode) == (2, "BeforeKickOff")
    assert referee.game_time == pytest.approx(300.0)
    assert len(events(actions, EventKind.HALF_TIME)) == 1
    run(referee, 5.0, ball(0, 0))
    assert referee.game_time == pytest.approx(300.0)
    assert referee.kick_off(None) == "right"


def test_game_over_after_the_second_half_stops_the_clock() -> None:
    referee = Referee(RefereeConfig(half_time=2.0))
    referee.kick_off("right")
    referee.set_play_mode("PlayOn")
    run(referee, 2.0, ball(0, 0))
    assert referee.half == 2
    assert referee.kick_off(None) == "left"
    referee.set_play_mode("PlayOn")
    actions = run(referee, 2.0, ball(0, 0))
    assert referee.play_mode == "GameOver"
    assert len(events(actions, EventKind.GAME_OVER)) == 1
    run(referee, 1.0, ball(0, 0))
    assert referee.game_time == pytest.approx(4.0)
    with pytest.raises(RuntimeError):
        referee.kick_off(None)


def test_single_half_ends_the_game_at_half_time() -> None:
    referee = Referee(RefereeConfig(half_time=1.0, single_half=True))
    referee.kick_off("left")
    run(referee, 1.0, ball(0, 0))
    assert referee.play_mode == "GameOver"


# ---- ball holding ----------------------------------------------------------------------------

HOLDER = player("left", 7, 2.0, 0.0)
MARKER = player("right", 5, 2.6, 0.0)  # 0.5 m from the ball: near, but not closer
BALL_AT_FEET = ball(2.08, 0.0)


def test_holding_the_ball_past_5_s_with_an_opponent_near_is_a_free_kick_for_them() -> None:
    referee = playing()
    run(referee, 4.9, BALL_AT_FEET, [HOLDER, MARKER])
    assert referee.play_mode == "PlayOn"
    actions = run(referee, 0.2, BALL_AT_FEET, [HOLDER, MARKER])
    assert referee.play_mode == "free_kick_right"
    assert "ball holding by left 7" in events(actions, EventKind.FOUL)[0].text
    actions += run(referee, 1.0, BALL_AT_FEET, [HOLDER, MARKER])
    assert placements(actions) == [(2.08, 0.0, R)]  # the ball stays where it was


def test_holding_released_in_time_is_not_called() -> None:
    referee = playing()
    run(referee, 4.8, BALL_AT_FEET, [HOLDER, MARKER])
    run(referee, 0.6, ball(2.5, 1.0), [HOLDER, MARKER])  # 0.6 s away: the record restarts
    run(referee, 4.8, BALL_AT_FEET, [HOLDER, MARKER])
    assert referee.play_mode == "PlayOn"


def test_holding_time_is_not_reset_by_a_release_shorter_than_the_reset_time() -> None:
    referee = playing()
    run(referee, 4.0, BALL_AT_FEET, [HOLDER, MARKER])
    run(referee, 0.3, ball(2.5, 1.0), [HOLDER, MARKER])
    assert referee.ball_holding.held_time(("left", 7)) == pytest.approx(4.0)
    run(referee, 1.2, BALL_AT_FEET, [HOLDER, MARKER])
    assert referee.play_mode == "free_kick_right"


def test_a_nearer_opponent_means_the_player_is_not_holding() -> None:
    referee = playing()
    thief = player("right", 5, 2.12, 0.0)  # 0.04 m from the ball, the holder 0.08 m
    run(referee, 4.0, BALL_AT_FEET, [HOLDER, thief])
    assert referee.ball_holding.held_time(("left", 7)) == 0.0
    assert referee.ball_holding.held_time(("right", 5)) == pytest.approx(4.0)
    run(referee, 1.5, BALL_AT_FEET, [HOLDER, thief])
    assert referee.play_mode == "free_kick_left"  # the thief held it


def test_goalie_may_hold_longer_in_its_own_penalty_area_only() -> None:
    goalie_inside = player("left", 1, -14.0, 0.0)
    referee = playing()
    run(referee, 9.0, ball(-13.92, 0.0), [goalie_inside])
    assert referee.play_mode == "PlayOn"
    run(referee, 1.1, ball(-13.92, 0.0), [goalie_inside])
    assert referee.play_mode == "free_kick_right"
    goalie_outside = playing()
    run(goalie_outside, 5.1, ball(-9.92, 0.0), [player("left", 1, -10.0, 0.0)])
    assert goalie_outside.play_mode == "free_kick_right"


def test_dribbling_a_metre_with_an_opponent_near_is_called_and_without_is_not() -> None:
    def dribble(referee: Referee, marker_offset: float | None) -> None:
        for i in range(60):  # 1.2 m in 1.2 s, ball 8 cm ahead of the torso
            x = 2.0 + 0.02 * i
            players = [player("left", 7, x, 0.0)]
            if marker_offset is not None:
                players.append(player("right", 5, x + marker_offset, 0.0))
            referee.step(DT, ball(x + 0.08, 0.0), players)

    marked = playing()
    dribble(marked, 0.6)
    assert marked.play_mode == "free_kick_right"
    free = playing()
    dribble(free, None)
    assert free.play_mode == "PlayOn"
    regardless = playing(RefereeConfig(ball_hold_opp_distance=-1.0))
    dribble(regardless, None)
    assert regardless.play_mode == "free_kick_right"


def test_ball_holding_rule_can_be_switched_off() -> None:
    referee = playing(RefereeConfig(ball_holding_rule=False))
    run(referee, 8.0, BALL_AT_FEET, [HOLDER, MARKER])
    assert referee.play_mode == "PlayOn"


def test_free_kick_in_a_penalty_area_moves_to_the_area_corner() -> None:
    referee = playing()
    holder = player("right", 4, -14.0, -1.0)
    actions = run(referee, 6.1, ball(-13.92, -1.0), [holder])
    assert referee.play_mode == "free_kick_left"
    assert set(placements(actions)) == {(-HALF_LENGTH + PENALTY_DEPTH, -PENALTY_WIDTH / 2, R)}


# ---- beams and trainer commands --------------------------------------------------------------


def test_beam_is_allowed_before_kick_off_and_after_goals_only() -> None:
    referee = Referee()
    assert referee.may_beam("left")
    for mode, allowed in [
        ("KickOff_Left", False),
        ("PlayOn", False),
        ("Goal_Right", True),
        ("KickIn_Left", False),
        ("BeforeKickOff", True),
        ("GameOver", False),
    ]:
        referee.set_play_mode(mode)
        assert referee.may_beam("right") is allowed, mode


def test_beam_is_clamped_to_the_own_half_and_mirrored_for_the_right_team() -> None:
    referee = Referee()
    assert referee.clamp_beam("left", 3.0, 12.0, 0.0) == (0.0, HALF_WIDTH, 0.0)
    assert referee.clamp_beam("left", -20.0, -3.0, 90.0) == (-HALF_LENGTH, -3.0, 90.0)
    assert referee.clamp_beam("right", -5.0, 2.0, 0.0) == (5.0, -2.0, -180.0)
    assert referee.clamp_beam("right", 4.0, 0.0, 90.0) == (0.0, 0.0, -90.0)
    with pytest.raises(ValueError):
        referee.clamp_beam("left", math.nan, 0.0, 0.0)
    with pytest.raises(ValueError):
        referee.clamp_beam("middle", 0.0, 0.0, 0.0)  # type: ignore[arg-type]


@given(
    st.sampled_from(["left", "right"]),
    st.floats(-1e6, 1e6),
    st.floats(-1e6, 1e6),
    st.floats(-1e4, 1e4),
)
def test_clamped_beams_stay_in_the_own_half(team: str, x: float, y: float, deg: float) -> None:
    wx, wy, yaw = Referee().clamp_beam(team, x, y, deg)  # type: ignore[arg-type]
    assert (wx <= 0.0) if team == "left" else (wx >= 0.0)
    assert abs(wx) <= HALF_LENGTH and abs(wy) <= HALF_WIDTH
    assert -180.0 <= yaw < 180.0


def test_trainer_play_mode_validates_names_and_starts_the_clock() -> None:
    referee = Referee()
    with pytest.raises(ValueError, match="unknown play mode"):
        referee.set_play_mode("Halftime")
    referee.set_play_mode("PlayOn")
    run(referee, 1.0, ball(0, 0))
    assert referee.game_time == pytest.approx(1.0)


def test_trainer_free_kick_is_taken_where_the_ball_is() -> None:
    referee = playing()
    referee.step(DT, ball(4.0, -3.0), [])
    referee.set_play_mode("free_kick_left")
    actions = run(referee, 1.1, ball(4.5, -3.0))
    assert set(placements(actions)) == {(4.0, -3.0, R)}
    referee.step(DT, ball(4.0, -3.0), [], [("left", 6)])
    assert referee.play_mode == "PlayOn"


def test_drop_ball_puts_the_ball_down_where_it_is_and_plays_on() -> None:
    referee = Referee()
    referee.kick_off("left")
    referee.step(DT, ball(1.0, 2.0), [])
    referee.drop_ball()
    actions = referee.step(DT, ball(1.0, 2.0), [])
    assert referee.play_mode == "PlayOn"
    assert placements(actions)[-1] == (1.0, 2.0, R)
