"""The strategy's choices, on stand-in world models (no simulator): who goes for the ball and
which skill it picks where, and the claims players say to settle who goes."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from types import SimpleNamespace

import pytest

from agent.attack_keeper import detour_point, free_heading, open_side
from agent.roles import ClaimBoard, claim_message, is_closest, my_turn_to_speak, parse_claim
from agent.strategy import (
    SEARCH_TURN_DEG_S,
    HoldWatch,
    Strategy,
    approach_point,
    dodge_heading,
    head_yaw_for,
    search_turn_deg_s,
)
from agent.strategy_config import (
    AdvanceConfig,
    AttackConfig,
    KeeperConfig,
    StrategyConfig,
    SupportConfig,
)
from behaviors.joint_control import JointCommands
from behaviors.manager import BehaviorRun
from world.perception import Heard


class RecordingBehavior:
    """Records ``execute`` calls; offers the given skill names."""

    def __init__(self, *skills: str) -> None:
        self.skill_names = ("pose", "keyframe", *skills)
        self.calls: list[tuple] = []
        self.commands = JointCommands(0)

    def execute(self, name: str, *args: object) -> bool:
        self.calls.append((name, *args))
        return False

    @property
    def current(self) -> BehaviorRun | None:
        return BehaviorRun(self.calls[-1][0], 1) if self.calls else None

    def skill(self, name: str) -> SimpleNamespace:
        """The skill's state as the strategy reads it: ``kick_phase`` for ``basic_kick``."""
        return SimpleNamespace(phase=self.kick_phase)

    kick_phase = "approach"


class Seen:
    """A stand-in player tracker holding the given observations."""

    def __init__(self, players=()) -> None:
        self.players = list(players)

    def recent(self, time, memory):
        return list(self.players)

    def nearest(self, point, time, memory):
        return min(self.players, key=lambda p: math.dist(p.position, point), default=None)


def world(ball, pose, teammates=(), play_mode="PlayOn", unum=9, heard=(), opponents=()):
    def bearing_to(point):  # as WorldModel.bearing_to
        angle = math.degrees(math.atan2(point[1] - pose[1], point[0] - pose[0]))
        return (angle - pose[2] + 180.0) % 360.0 - 180.0

    return SimpleNamespace(
        bearing_to=bearing_to,
        play_mode=play_mode,
        side="left",
        unum=unum,
        team_name="Us",
        time=10.0,
        robot=SimpleNamespace(is_fallen=False),
        ball=SimpleNamespace(position=ball),
        pose=SimpleNamespace(x=pose[0], y=pose[1], heading_deg=pose[2]),
        teammates=Seen(teammates),
        opponents=Seen(opponents),
        heard=list(heard),
    )


def said(unum: int, claim_m: float, team: str = "Us") -> Heard:
    return Heard(team, 10.0, 30.0, claim_message(unum, claim_m))


def test_active_player_approaches_behind_the_ball_facing_the_goal():
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    Strategy().decide(world(ball=(0.0, 3.0), pose=(-4.0, 0.0, 0.0)), behavior)
    name, x, y, heading = behavior.calls[-1]
    to_goal = math.atan2(-3.0, 15.0)
    assert name == "walk"
    assert (x, y) == pytest.approx((-0.3 * math.cos(to_goal), 3.0 - 0.3 * math.sin(to_goal)))
    assert heading == pytest.approx(math.degrees(to_goal))


def test_behind_the_ball_and_facing_the_goal_it_dribbles_and_keeps_dribbling():
    strategy = Strategy(StrategyConfig(attack=AttackConfig(dribble_kind="dfdl")))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    strategy.decide(world(ball=(0.0, 0.0), pose=(-0.3, 0.0, 5.0)), behavior)
    assert behavior.calls[-1] == ("dribble", "dfdl", pytest.approx(0.0), "left")
    # the ball ran a little ahead and the robot turned: still its dribble, not a new approach
    strategy.decide(world(ball=(0.5, 0.0), pose=(0.0, 0.1, 40.0)), behavior)
    assert behavior.calls[-1][0] == "dribble"
    # once the ball is lost, it walks back behind it
    strategy.decide(world(ball=(3.0, 0.0), pose=(0.0, 0.1, 0.0)), behavior)
    assert behavior.calls[-1][0] == "walk"


def test_a_ball_a_stride_pushed_a_metre_ahead_is_followed_by_the_dribble_not_a_walk():
    # LFDL strides push the ball up to about 1.3 m ahead; the dribble follows it faster than
    # a walk back to the approach point (benchmarks/match.py: 0 goals in 16 matches at 0.7)
    strategy, behavior = Strategy(), RecordingBehavior("walk", "dribble")
    strategy.decide(world(ball=(0.0, 0.0), pose=(-0.3, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    strategy.decide(world(ball=(1.1, 0.05), pose=(0.0, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    short = Strategy(StrategyConfig(attack=AttackConfig(dribble_keep_m=0.7)))
    short.decide(world(ball=(0.0, 0.0), pose=(-0.3, 0.0, 0.0)), behavior)
    short.decide(world(ball=(1.1, 0.05), pose=(0.0, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][0] == "walk"


def test_without_a_dribble_skill_it_kicks_anywhere():
    behavior = RecordingBehavior("walk", "basic_kick")
    Strategy().decide(world(ball=(0.0, 0.0), pose=(-0.3, 0.0, 0.0)), behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")


def test_it_shoots_within_the_kick_range_and_dribbles_outside_it_or_without_one():
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    Strategy().decide(world(ball=(8.0, 0.5), pose=(7.7, 0.5, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")  # 7 m out: beyond the default 6 m
    Strategy().decide(world(ball=(10.0, 0.5), pose=(9.7, 0.5, 0.0)), behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")
    # closer than dribble_in_m it walks the ball in even with a kick range
    Strategy().decide(world(ball=(13.0, 0.5), pose=(12.7, 0.5, -5.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    dribbler = StrategyConfig(attack=AttackConfig(kick_range_m=0.0))
    Strategy(dribbler).decide(world(ball=(10.0, 0.5), pose=(9.7, 0.5, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")


def test_a_shot_under_way_goes_on_at_the_edge_of_the_kick_range():
    # the ball's estimate jitters: a shot started 5.9 m out goes on at 6.1 m (kick_range_hold_m)
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    strategy = Strategy()
    strategy.decide(world(ball=(9.1, 0.5), pose=(8.8, 0.5, 0.0)), behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")
    strategy.decide(world(ball=(8.9, 0.5), pose=(8.8, 0.5, 0.0)), behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")
    # ... but not once the ball is beyond the hold (the dribble takes it on)
    strategy.decide(world(ball=(7.8, 0.5), pose=(7.5, 0.5, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    # a fresh start at 6.1 m dribbles: the hold is for a shot under way only
    strategy.decide(world(ball=(8.9, 0.5), pose=(8.6, 0.5, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    no_hold = Strategy(StrategyConfig(attack=AttackConfig(kick_range_hold_m=0.0)))
    no_hold.decide(world(ball=(9.1, 0.5), pose=(8.8, 0.5, 0.0)), behavior)
    no_hold.decide(world(ball=(8.9, 0.5), pose=(8.6, 0.5, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")


def test_an_opponent_at_the_ball_stops_a_range_shot_until_its_kick_is_committed():
    rival = SimpleNamespace(unum=4, position=(9.5, 0.9))  # 0.7 m from the ball
    contest = Strategy(StrategyConfig(attack=AttackConfig(shot_contest_m=1.0)))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    scene = world(ball=(9.1, 0.5), pose=(8.8, 0.5, 0.0), opponents=[rival])
    contest.decide(scene, behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    # with the rival 1.2 m off the shot starts ...
    far = SimpleNamespace(unum=4, position=(9.5, 1.65))
    contest.decide(world(ball=(9.1, 0.5), pose=(8.8, 0.5, 0.0), opponents=[far]), behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")
    # ... ends while lining up when the rival comes to the ball ...
    contest.decide(scene, behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")
    # ... but a kick past its head-up plays on
    contest.decide(world(ball=(9.1, 0.5), pose=(8.8, 0.5, 0.0), opponents=[far]), behavior)
    behavior.kick_phase = "head_up"
    contest.decide(scene, behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")
    # off by default: the default strategy shoots whoever is at the ball
    default = RecordingBehavior("walk", "dribble", "basic_kick")
    Strategy().decide(scene, default)
    assert default.calls[-1] == ("basic_kick", 15.0, 0.0, "long")


def test_a_player_with_a_closer_teammate_holds_its_formation_place_facing_the_ball():
    mate = SimpleNamespace(unum=10, position=(0.5, 0.0))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    strategy = Strategy()
    strategy.decide(world(ball=(0.0, 0.0), pose=(-3.0, -4.5, 0.0), teammates=[mate]), behavior)
    # facing the ball (56 deg) in steps of 30 deg
    assert behavior.calls[-1] == ("walk", *strategy.home(9), 60.0)


def test_a_lower_claim_heard_from_a_teammate_keeps_the_player_back():
    behavior = RecordingBehavior("walk", "dribble")
    strategy = Strategy()
    # nobody seen, but teammates 7 and 8 say they are 1.0 and 1.5 m from the ball: this player
    # (2.0 m, third) holds its place
    claims = [said(7, 1.0), said(8, 1.5)]
    decision = strategy.decide(world((0.0, 0.0), (-2.0, 0.0, 0.0), heard=claims), behavior)
    assert behavior.calls[-1][:3] == ("walk", *strategy.home(9))
    assert parse_claim(decision.say) == (9, 2.0)
    # the other team's claims do not count
    strategy = Strategy()
    claim = said(7, 1.0, team="Them")
    strategy.decide(world((0.0, 0.0), (-2.0, 0.0, 0.0), heard=[claim]), behavior)
    assert behavior.calls[-1][0] == "walk"
    assert behavior.calls[-1][1:3] != strategy.home(9)


def test_claims_round_trip_and_ties_go_to_the_lower_number():
    assert parse_claim(claim_message(7, 4.23)) == (7, 4.2)
    assert parse_claim("hello") is None
    assert len(claim_message(11, 1e6)) <= 20
    board = ClaimBoard()
    board.hear(world((0, 0), (0, 0, 0), unum=9, heard=[said(7, 4.2), said(8, 5.0)]))
    assert not is_closest(board, 9, 4.21, now=10.0)  # 4.2 vs 4.2: player 7 has the lower number
    assert is_closest(board, 6, 4.21, now=10.0)
    assert is_closest(board, 9, 4.1, now=10.0)
    assert is_closest(board, 9, 9.0, now=20.0)  # claims older than a second are forgotten


def test_the_goalkeeper_guards_its_line_and_clears_a_ball_near_its_goal():
    behavior = RecordingBehavior("walk", "dribble")
    keeper = Strategy()
    decision = keeper.decide(world((0.0, 3.0), (-14.0, 0.0, 0.0), unum=1), behavior)
    name, x, y, _ = behavior.calls[-1]
    assert (name, x) == ("walk", pytest.approx(-14.3)) and 0.0 < y <= 0.8
    assert decision.say is None  # no claim: field players must not wait for the keeper
    keeper.decide(world((-13.0, 0.5), (-14.0, 0.0, 0.0), unum=1), behavior)
    assert behavior.calls[-1][0] == "walk"
    assert behavior.calls[-1][1] > -13.5  # towards the ball, not back to its line


def test_the_goalkeeper_keeps_its_place_while_a_far_ball_moves_a_little_if_told_so():
    def keeper_walk(ball: tuple[float, float], keeper: KeeperConfig) -> tuple:
        behavior = RecordingBehavior("walk", "dribble")
        Strategy(StrategyConfig(keeper=keeper)).decide(
            world(ball, (-14.3, 0.0, 0.0), unum=1), behavior
        )
        return behavior.calls[-1]

    stepped = [keeper_walk((0.0, y), KeeperConfig(side_step_m=0.2)) for y in (0.65, 0.7, 0.75)]
    assert stepped[0] == stepped[1] == stepped[2]  # one place and heading
    name, _, y, heading = stepped[0]
    assert name == "walk" and y == pytest.approx(0.2) and heading % 30.0 == 0.0
    smooth = [keeper_walk((0.0, y), KeeperConfig()) for y in (0.65, 0.7, 0.75)]
    assert len({call[2] for call in smooth}) == 3  # every move of the ball moves the place


def test_a_player_in_front_of_the_ball_goes_round_it():
    ball, aim = (0.0, 0.0), (15.0, 0.0)
    x, y = approach_point((1.0, 0.1), ball, aim, behind_m=0.3, round_m=0.5)
    assert x < 0.0 and y == pytest.approx(0.5)  # beside and behind, on its own side
    assert approach_point((-2.0, 0.1), ball, aim, 0.3, 0.5) == pytest.approx((-0.3, 0.0))


def test_it_aims_away_from_a_goalkeeper_it_sees():
    keeper = SimpleNamespace(unum=1, position=(14.3, 0.3))
    behavior = RecordingBehavior("walk", "dribble")
    strategy = Strategy()
    scene = world(ball=(10.0, 0.0), pose=(8.0, 0.0, 0.0), opponents=[keeper])
    assert strategy.aim(scene) == pytest.approx((15.0, -0.6))
    strategy.decide(scene, behavior)
    assert behavior.calls[-1][3] == pytest.approx(math.degrees(math.atan2(-0.6, 5.0)))


def test_it_aims_inside_the_post_the_keeper_leaves_open_as_seen_from_the_ball():
    # from a ball out on the left, a keeper just left of the goal centre covers the far
    # (right) side best: the near post is the open one, though the keeper stands at y > 0
    assert open_side((12.0, 2.0), (14.3, 0.3), margin_m=0.3, current=None, switch_deg=0.0) == 1
    assert open_side((12.0, 0.0), (14.3, 0.3), 0.3, None, 0.0) == -1
    keeper = SimpleNamespace(unum=1, position=(14.3, 0.3))
    strategy = Strategy(StrategyConfig(attack=AttackConfig(aim_post_margin_m=0.3)))
    scene = world(ball=(12.0, 2.0), pose=(11.0, 2.0, 0.0), opponents=[keeper])
    assert strategy.aim(scene) == pytest.approx((15.0, 0.75))


def test_the_aimed_side_is_kept_until_the_other_side_is_clearly_more_open():
    # from straight in front, a keeper 0.1 m right of the middle leaves the left side a
    # little more open: not enough to turn the dribble from the right side over
    ball, keeper = (11.0, 0.0), (14.3, -0.1)
    assert open_side(ball, keeper, 0.3, current=None, switch_deg=10.0) == 1
    assert open_side(ball, keeper, 0.3, current=-1.0, switch_deg=10.0) == -1
    assert open_side(ball, (14.3, -0.6), 0.3, current=-1.0, switch_deg=10.0) == 1


def test_a_keeper_in_the_way_is_passed_beside_it_on_its_open_side():
    ball, aim = (12.0, 0.0), (15.0, 0.0)
    # keeper 1 m ahead, 0.2 m left of the line: pass 0.9 m from it on the right
    assert detour_point(ball, aim, (13.0, 0.2), clear_m=0.9, ahead_m=2.0) == pytest.approx(
        (13.0, -0.7)
    )
    # behind the ball, too far ahead or clear of the line: no detour
    for keeper in [(11.5, 0.0), (14.5, 0.0), (13.0, 1.0)]:
        assert detour_point(ball, aim, keeper, 0.9, 2.0) is None
    # in the strategy: an opponent in the way out in the field (the aim is the goal centre)
    attack = AttackConfig(detour_clear_m=0.9, detour_ahead_m=2.0)
    strategy = Strategy(StrategyConfig(attack=attack))
    behavior = RecordingBehavior("walk", "dribble")
    rival = SimpleNamespace(unum=4, position=(9.0, 0.2))
    strategy.decide(world((8.0, 0.0), (7.75, 0.17, -30.0), opponents=[rival]), behavior)
    expected = math.degrees(math.atan2(-0.7, 1.0))
    assert behavior.calls[-1][:3] == ("dribble", "lfdl", pytest.approx(expected))


def test_the_dribble_turns_into_free_space_by_the_fewest_steps_if_told_so():
    def free(ball, opponents, heading=0.0):
        return free_heading(ball, heading, opponents, 60.0, 15.0, 2.0, 0.8)

    assert free((0.0, 0.0), []) == 0.0
    assert free((0.0, 0.0), [(-0.5, 0.1), (3.0, 0.0)]) == 0.0  # behind the ball, beyond the path
    # 1 m straight ahead: 15-45 deg pass it within 0.8 m, 60 deg does not
    assert abs(free((0.0, 0.0), [(1.0, 0.0)])) == 60.0
    # a little to the left of the path: away from it to the right, 30 deg is enough
    assert free((0.0, 0.0), [(1.2, 0.3)]) == -30.0
    # ... but with a second one there, left round the first
    assert free((0.0, 0.0), [(1.2, 0.3), (1.2, -1.2)]) == 60.0
    # 0.3 m to the right near the touch line: the paths to the left end beyond it (30 deg
    # would do off it), so right round the opponent
    assert free((0.0, 9.0), [(1.2, 8.7)]) == -60.0
    assert free((0.0, 0.0), [(1.2, -0.3)]) == 30.0
    # none free: the widest passage
    wall = [(1.0, y) for y in (-1.2, -0.6, 0.0, 0.6, 1.2)]
    assert abs(free((0.0, 0.0), wall)) == 60.0
    # in the strategy: instead of the 35 deg dodge away from the nearest opponent
    attack = AttackConfig(free_space_deg=60.0)
    behavior = RecordingBehavior("walk", "dribble")
    rival = SimpleNamespace(unum=10, position=(1.2, 0.3))
    Strategy(StrategyConfig(attack=attack)).decide(
        world((0.0, 0.0), (-0.3, 0.0, 0.0), opponents=[rival]), behavior
    )
    assert behavior.calls[-1][:3] == ("dribble", "lfdl", pytest.approx(-30.0))
    with pytest.raises(ValueError, match="free_space_step_deg"):
        AttackConfig(free_space_deg=60.0, free_space_step_deg=0.0)
    # only in a team as large as asked for: a 3 v 3 team keeps the dodge
    from agent.team import TeamConfig
    from benchmarks.match import small_team

    gated = StrategyConfig(attack=attack, free_space_min_players=11)
    base = TeamConfig("Us", strategy=gated)
    assert small_team("Us", 11, base).strategy.free_space_deg == 60.0
    assert small_team("Us", 3, base).strategy.free_space_deg == 0.0
    Strategy(small_team("Us", 3, base).strategy).decide(
        world((0.0, 0.0), (-0.3, 0.0, 0.0), opponents=[rival], unum=3), behavior
    )
    assert behavior.calls[-1][:3] == ("dribble", "lfdl", pytest.approx(-35.0))
    with pytest.raises(ValueError, match="free_space_min_players"):
        StrategyConfig(free_space_min_players=12)


def test_a_ball_an_opponent_holds_from_the_far_side_is_stood_off_for_a_while_if_told_so():
    attack = AttackConfig(yield_opponent_m=0.5, yield_reach_m=0.6, yield_s=2.0)
    strategy = Strategy(StrategyConfig(attack=attack))
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble")
    keeper = SimpleNamespace(unum=1, position=(13.3, 0.0))  # at the ball, beyond it
    scene = world((13.0, 0.0), (12.7, 0.0, 0.0), opponents=[keeper])
    skills = []
    for k in range(150):  # 3 s
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
        skills.append(behavior.calls[-1][0])
    assert behavior.calls[0] == ("walk_velocity", 0.0, 0.0, 0.0)
    assert skills[:100] == ["walk_velocity"] * 100  # stood off 2 s ...
    assert skills[100:] == ["dribble"] * 50  # ... then plays on, not standing off at once
    # an opponent behind this player, or this player too far from the ball: no standing off
    behind = SimpleNamespace(unum=1, position=(12.5, 0.0))
    for opponent, pose in [(behind, (12.7, 0.0, 0.0)), (keeper, (12.0, 0.0, 0.0))]:
        fresh = Strategy(StrategyConfig(attack=attack))
        fresh.decide(world((13.0, 0.0), pose, opponents=[opponent]), behavior)
        assert behavior.calls[-1][0] != "walk_velocity"


def test_near_the_goal_a_dribble_starts_with_the_near_goal_gait_and_keeps_it_if_told_so():
    attack = AttackConfig(near_goal_dribble_kind="dfdl", near_goal_dribble_m=5.0)
    strategy, behavior = (
        Strategy(StrategyConfig(attack=attack)),
        RecordingBehavior("walk", "dribble"),
    )
    strategy.decide(world((9.0, 0.0), (8.7, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")  # 6 m out: the usual gait ...
    strategy.decide(world((10.3, 0.0), (10.0, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "lfdl")  # ... kept while this dribble lasts
    strategy.decide(world((13.0, 0.0), (10.0, 0.0, 0.0)), behavior)  # the ball got away
    strategy.decide(world((13.0, 0.0), (12.7, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "dfdl")  # a new dribble 2 m out


def test_only_a_stand_when_walking_does_not_exist():
    behavior = RecordingBehavior()
    Strategy().decide(world(ball=(0.0, 0.0), pose=(-1.0, 0.0, 0.0)), behavior)
    assert behavior.calls[-1] == ("pose", "stand")


def test_a_started_get_up_runs_until_it_reports_standing():
    class GetUpBehavior(RecordingBehavior):
        def __init__(self) -> None:
            super().__init__("walk", "get_up")
            self.get_up_cycles = 0

        def execute(self, name: str, *args: object) -> bool:
            super().execute(name, *args)
            if name == "get_up":
                self.get_up_cycles += 1
                return self.get_up_cycles >= 3
            return False

    strategy, behavior = Strategy(), GetUpBehavior()
    lying = world(ball=(0.0, 0.0), pose=(-1.0, 0.0, 0.0))
    lying.robot.is_fallen = True
    strategy.decide(lying, behavior)
    sitting = world(ball=(0.0, 0.0), pose=(-1.0, 0.0, 0.0))  # halfway up: no longer "fallen"
    strategy.decide(sitting, behavior)
    strategy.decide(sitting, behavior)
    assert [call[0] for call in behavior.calls] == ["get_up"] * 3
    strategy.decide(sitting, behavior)
    assert behavior.calls[-1][0] == "walk"


def test_the_dribble_turns_away_from_an_opponent_in_the_way_without_free_space():
    attack = AttackConfig(free_space_deg=0.0)
    assert dodge_heading((0.0, 0.0), 0.0, [(1.0, 0.2)], attack) == pytest.approx(-35.0)
    assert dodge_heading((0.0, 0.0), 0.0, [(1.0, -0.2)], attack) == pytest.approx(35.0)
    # behind the ball, far ahead or well to the side: no dodge
    assert dodge_heading((0.0, 0.0), 0.0, [(-0.5, 0.0), (3.0, 0.0), (1.0, 1.5)], attack) == 0.0
    strategy = Strategy(StrategyConfig(attack=attack))
    behavior = RecordingBehavior("walk", "dribble")
    rival = SimpleNamespace(unum=10, position=(1.2, 0.3))
    strategy.decide(world((0.0, 0.0), (-0.3, 0.0, 0.0), opponents=[rival]), behavior)
    assert behavior.calls[-1][:3] == ("dribble", "lfdl", pytest.approx(-35.0))


def test_a_player_that_lost_the_ball_turns_to_find_it_and_claims_nothing():
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble")
    lost = world((0.0, 0.0), (-1.0, 0.0, 0.0))
    lost.ball.time_since_seen = 5.0
    decision = Strategy().decide(lost, behavior)
    assert behavior.calls[-1][0] == "walk_velocity" and behavior.calls[-1][3] > 0.0
    assert decision.say is None


def test_a_ball_pushed_against_an_opponent_for_seconds_is_taken_off_sideways():
    strategy = Strategy(StrategyConfig(attack=AttackConfig(free_space_deg=0.0)))
    behavior = RecordingBehavior("walk", "dribble")
    rival = SimpleNamespace(unum=3, position=(0.4, 0.3))  # ahead, a little to the left
    scene = world((0.0, 0.0), (-0.3, 0.0, 0.0), opponents=[rival])
    headings = []
    for k in range(260):  # 5.2 s at the ball, which does not move
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
        headings.append(behavior.calls[-1][-2] if behavior.calls[-1][0] == "dribble" else None)
    assert headings[0] == pytest.approx(-35.0)  # the dodge first
    assert min(h for h in headings if h is not None) < -60.0  # then away to the right


def test_walking_up_to_a_still_ball_is_no_stall():
    strategy, behavior = Strategy(), RecordingBehavior("walk", "dribble")
    scene = world((0.0, 0.0), (-5.0, 0.0, 0.0))
    for k in range(300):
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
    assert behavior.calls[-1] == ("walk", pytest.approx(-0.3), pytest.approx(0.0), 0.0)


def test_walking_round_a_still_ball_near_the_goal_starts_no_stall_shot_if_told_so():
    def last_skill_after_walking_round(attack: AttackConfig) -> str:
        strategy, behavior = (
            Strategy(StrategyConfig(attack=attack)),
            RecordingBehavior("walk", "dribble", "basic_kick"),
        )
        # in front of the ball near the goal, within dribble_keep_m of it: going round it
        scene = world((12.5, 0.0), (12.9, 0.1, 180.0))
        for k in range(260):
            scene.time = 10.0 + 0.02 * k
            strategy.decide(scene, behavior)
        return behavior.calls[-1][0]

    # no range shot (kick_range_m 0): the stall decides
    any_still_ball = AttackConfig(stall_opponent_m=0.0, kick_range_m=0.0)
    assert last_skill_after_walking_round(any_still_ball) == "basic_kick"
    only_dribbling = replace(any_still_ball, stall_only_dribbling=True)
    assert last_skill_after_walking_round(only_dribbling) == "walk"


def test_a_still_ball_with_no_opponent_near_starts_no_stall_shot():
    def last_skill_at_a_still_ball(attack: AttackConfig, rival_at: tuple[float, float]) -> str:
        strategy, behavior = (
            Strategy(StrategyConfig(attack=attack)),
            RecordingBehavior("walk", "dribble", "basic_kick"),
        )
        rival = SimpleNamespace(unum=1, position=rival_at)
        scene = world((12.5, 0.0), (12.2, 0.0, 0.0), opponents=[rival])
        for k in range(260):  # 5.2 s at a ball that does not move
            scene.time = 10.0 + 0.02 * k
            strategy.decide(scene, behavior)
        return behavior.calls[-1][0]

    far, near = (14.5, 0.0), (12.9, 0.2)
    no_range = AttackConfig(kick_range_m=0.0)  # no range shot: the stall decides
    any_ball = replace(no_range, stall_opponent_m=0.0)
    assert last_skill_at_a_still_ball(any_ball, far) == "basic_kick"
    assert last_skill_at_a_still_ball(no_range, far) == "dribble"
    assert last_skill_at_a_still_ball(no_range, near) == "basic_kick"


@pytest.mark.parametrize(
    ("ball", "finishing"),
    [((14.8, -0.8), True), ((14.8, 1.0), False), ((13.0, -0.8), False), ((15.1, 0.0), False)],
)
def test_a_ball_just_before_the_goal_mouth_is_aimed_straight_over_the_line(ball, finishing):
    keeper = SimpleNamespace(unum=1, position=(14.9, -0.3))
    scene = world(ball, (ball[0] - 0.3, ball[1], 0.0), opponents=[keeper])
    on_the_line = Strategy(StrategyConfig(attack=AttackConfig(finish_m=0.0))).aim(scene)
    aim = Strategy().aim(scene)
    assert on_the_line[0] == pytest.approx(15.0)
    if finishing:
        assert aim == pytest.approx((16.0, ball[1]))
    else:
        assert aim == pytest.approx(on_the_line)


def test_a_dribbler_that_ends_up_over_the_ball_steps_off_it():
    strategy, behavior = Strategy(), RecordingBehavior("walk", "dribble")
    strategy.decide(world((0.0, 0.0), (-0.3, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][0] == "dribble"
    strategy.decide(world((0.0, 0.0), (-0.05, 0.02, 0.0)), behavior)
    name, _, y, _ = behavior.calls[-1]
    assert name == "walk" and abs(y) == pytest.approx(0.5)  # round the ball, not over it


def test_a_stall_near_the_goal_is_answered_with_a_shot_that_runs_to_its_end():
    strategy, behavior = Strategy(), RecordingBehavior("walk", "dribble", "basic_kick")
    keeper = SimpleNamespace(unum=1, position=(13.0, 0.3))  # at the ball, blocking it
    scene = world((12.5, 0.0), (12.2, 0.0, 0.0), opponents=[keeper])
    for k in range(260):
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
    assert behavior.calls[-1][0] == "basic_kick"
    scene.ball.position = (12.9, 0.1)  # the ball moved while the kick lines up: still kicking
    strategy.decide(scene, behavior)
    assert behavior.calls[-1][0] == "basic_kick"


def test_a_range_shot_lining_up_at_a_still_ball_starts_no_escape():
    # 5 m out (beyond stall_shot_m), an opponent beside the ball: the ball lies still while the
    # kick lines up, which is no stall to escape from (the escape turned the aim 70 deg away)
    strategy, behavior = Strategy(), RecordingBehavior("walk", "dribble", "basic_kick")
    defender = SimpleNamespace(unum=5, position=(10.3, 0.9))
    scene = world((10.0, 0.5), (9.7, 0.5, 0.0), opponents=[defender])
    for k in range(260):  # 5.2 s: a stall after 4 s
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
    assert {call for call in behavior.calls} == {("basic_kick", 15.0, 0.0, "long")}


def test_the_kick_off_taker_aims_away_from_the_opponent_waiting_ahead():
    turning = Strategy(StrategyConfig(attack=AttackConfig(kickoff_turn_deg=45.0)))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    forward = SimpleNamespace(unum=10, position=(2.1, 0.4))  # outside the circle, left of centre
    scene = world((0.0, 0.0), (-0.6, 0.0, 0.0), play_mode="KickOff_Left", opponents=[forward])
    turning.decide(scene, behavior)
    assert behavior.calls[-1][0] == "walk"
    assert behavior.calls[-1][3] == pytest.approx(-45.0)  # to the right, away from it
    # ... on for kickoff_turn_s after the kick-off, then straight at the goal again
    scene.play_mode, scene.time = "PlayOn", 13.9
    turning.decide(scene, behavior)
    assert behavior.calls[-1][3] == pytest.approx(-45.0)
    scene.time = 14.1
    turning.decide(scene, behavior)
    assert behavior.calls[-1][3] == pytest.approx(0.0)
    # off by default
    Strategy().decide(world((0.0, 0.0), (-0.6, 0.0, 0.0), play_mode="KickOff_Left"), behavior)
    assert behavior.calls[-1][3] == pytest.approx(0.0)


def test_a_stall_in_the_finishing_zone_is_pushed_over_the_line_if_told_so():
    def skills_at_a_blocked_ball(attack: AttackConfig, ball: tuple[float, float]) -> list[str]:
        strategy, behavior = (
            Strategy(StrategyConfig(attack=attack)),
            RecordingBehavior("walk", "dribble", "basic_kick"),
        )
        keeper = SimpleNamespace(unum=1, position=(ball[0] + 0.4, ball[1] + 0.3))
        scene = world(ball, (ball[0] - 0.3, ball[1], 0.0), opponents=[keeper])
        for k in range(260):  # 5.2 s at a ball that does not move: a stall after 4 s
            scene.time = 10.0 + 0.02 * k
            strategy.decide(scene, behavior)
        return [call[0] for call in behavior.calls]

    in_the_mouth, further_out = (14.0, -0.4), (12.5, 0.0)
    assert skills_at_a_blocked_ball(AttackConfig(), in_the_mouth)[-1] == "basic_kick"
    pushing = AttackConfig(finish_no_shot=True)
    assert "basic_kick" not in skills_at_a_blocked_ball(pushing, in_the_mouth)
    assert skills_at_a_blocked_ball(pushing, further_out)[-1] == "basic_kick"


def test_a_stall_shot_ends_once_the_ball_reaches_the_finishing_zone_if_told_so():
    strategy = Strategy(StrategyConfig(attack=AttackConfig(finish_no_shot=True)))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    keeper = SimpleNamespace(unum=1, position=(13.0, 0.3))
    scene = world((12.5, 0.0), (12.2, 0.0, 0.0), opponents=[keeper])
    for k in range(260):
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
    assert behavior.calls[-1][0] == "basic_kick"
    scene.ball.position = (14.0, -0.4)  # pushed on towards the line while the kick lined up
    strategy.decide(scene, behavior)
    assert behavior.calls[-1][0] != "basic_kick"


def test_a_stall_beside_the_goal_is_escaped_to_its_front_if_told_so():
    def calls_after_a_stall_beside_the_goal(attack: AttackConfig) -> list[tuple]:
        strategy, behavior = (
            Strategy(StrategyConfig(attack=attack)),
            RecordingBehavior("walk", "dribble", "basic_kick"),
        )
        # 2 m before the end line, outside the post (|y| 1.05): no angle for a shot
        scene = world((13.0, 1.8), (12.7, 1.8, 0.0))
        for k in range(260):  # 5.2 s at a ball that does not move: a stall after 4 s
            scene.time = 10.0 + 0.02 * k
            strategy.decide(scene, behavior)
        return behavior.calls

    # no range shot (kick_range_m 0): the stall decides
    any_still_ball = AttackConfig(stall_opponent_m=0.0, kick_range_m=0.0)
    assert calls_after_a_stall_beside_the_goal(any_still_ball)[-1][0] == "basic_kick"
    calls = calls_after_a_stall_beside_the_goal(replace(any_still_ball, stall_shot_max_y_m=1.0))
    assert all(call[0] != "basic_kick" for call in calls)
    name, *args = calls[-1]
    heading = args[1] if name == "dribble" else args[2]
    assert heading == pytest.approx(-90.0)  # towards (13, 0), in front of the goal centre
    # inside the posts' line the stall shot is still taken
    inside = replace(any_still_ball, stall_shot_max_y_m=2.0)
    assert calls_after_a_stall_beside_the_goal(inside)[-1][0] == "basic_kick"


def test_the_second_closest_field_player_waits_ahead_of_the_ball_beside_the_line():
    behavior = RecordingBehavior("walk", "dribble")
    support = SupportConfig(ahead_m=2.0, side_m=1.5, from_x_m=-15.0)
    strategy = Strategy(StrategyConfig(support=support))
    # teammate 7 is closer (active); this player is second: it supports
    strategy.decide(world((0.0, 2.0), (-2.0, 0.0, 0.0), heard=[said(7, 1.0)]), behavior)
    name, x, y, heading = behavior.calls[-1]
    to_goal = math.atan2(-2.0, 15.0)
    ahead = (x - 0.0) * math.cos(to_goal) + (y - 2.0) * math.sin(to_goal)
    across = -(x - 0.0) * math.sin(to_goal) + (y - 2.0) * math.cos(to_goal)
    assert name == "walk" and ahead == pytest.approx(2.0) and across == pytest.approx(-1.5)
    assert abs(heading) > 90.0  # facing back towards the ball
    # near the goal and a touch line it stays inside the field
    x, y = strategy.support_point((14.5, -8.5))
    assert x <= 14.0 and y >= -9.0
    # support switched off (0 and 0): it holds its formation place
    off = Strategy(StrategyConfig(support=SupportConfig(ahead_m=0.0, side_m=0.0)))
    off.decide(world((0.0, 2.0), (-2.0, 0.0, 0.0), heard=[said(7, 1.0)]), behavior)
    assert behavior.calls[-1][1:3] == off.home(9)
    # only from the given x on: short of it, it holds its place too
    late = Strategy(StrategyConfig(support=SupportConfig(ahead_m=2.0, side_m=1.5, from_x_m=5.0)))
    late.decide(world((0.0, 2.0), (-2.0, 0.0, 0.0), heard=[said(7, 1.0)]), behavior)
    assert behavior.calls[-1][1:3] == late.home(9)
    late.decide(world((6.0, 2.0), (-2.0, 0.0, 0.0), heard=[said(7, 1.0)]), behavior)
    assert behavior.calls[-1][1:3] == pytest.approx(late.support_point((6.0, 2.0)))


def test_a_supporter_steps_in_place_while_an_opponent_stands_in_its_way_if_told_so():
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble")
    support = SupportConfig(ahead_m=2.0, side_m=1.5, avoid_m=1.0)
    strategy = Strategy(StrategyConfig(support=support))
    heard = [said(7, 1.0)]
    in_way = SimpleNamespace(unum=3, position=(-1.3, 0.2))  # 0.7 m ahead, towards the point
    behind = SimpleNamespace(unum=4, position=(-2.7, 0.0))  # as close, but behind it
    strategy.decide(world((6.0, 2.0), (-2.0, 0.0, 0.0), heard=heard, opponents=[in_way]), behavior)
    assert behavior.calls[-1] == ("walk_velocity", 0.0, 0.0, 0.0)
    strategy.decide(world((6.0, 2.0), (-2.0, 0.0, 0.0), heard=heard, opponents=[behind]), behavior)
    assert behavior.calls[-1][0] == "walk"
    # with avoid_m 0 it walks on
    plain = Strategy(StrategyConfig(support=SupportConfig(ahead_m=2.0, side_m=1.5, avoid_m=0.0)))
    plain.decide(world((6.0, 2.0), (-2.0, 0.0, 0.0), heard=heard, opponents=[in_way]), behavior)
    assert behavior.calls[-1][0] == "walk"


def test_an_advancing_winger_waits_behind_the_ball_clear_of_it_and_only_if_told_so():
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble")
    advance = AdvanceConfig(unums=(9, 11), from_x_m=2.0, behind_m=1.0, y_m=2.5)
    strategy = Strategy(StrategyConfig(advance=advance))
    heard = [said(10, 0.5)]  # teammate 10 goes for the ball
    # ball at (9.4, 0.3): winger 9 (home -3, -4.5) waits at x 8 (9.4 - 1 in 1 m steps), y -2.5
    strategy.decide(world((9.4, 0.3), (0.0, -4.0, 0.0), heard=heard), behavior)
    assert behavior.calls[-1][:3] == ("walk", 8.0, -2.5)
    # a ball in its lane: its place keeps clear_m from the ball
    x, y = strategy.place(world((9.4, -2.4), (0.0, -4.0, 0.0), heard=heard))
    assert math.dist((x, y), (9.4, -2.4)) == pytest.approx(1.5)
    # short of from_x_m, for a player not listed, or switched off: the formation place
    assert strategy.place(world((1.0, 0.3), (0.0, -4.0, 0.0))) == strategy.home(9)
    assert strategy.place(world((9.4, 0.3), (0.0, -4.0, 0.0), unum=7)) == strategy.home(7)
    assert Strategy().place(world((9.4, 0.3), (0.0, -4.0, 0.0))) == Strategy().home(9)
    # an opponent in its way: it steps in place
    in_way = SimpleNamespace(unum=3, position=(0.7, -3.8))
    strategy.decide(world((9.4, 0.3), (0.0, -4.0, 0.0), heard=heard, opponents=[in_way]), behavior)
    assert behavior.calls[-1] == ("walk_velocity", 0.0, 0.0, 0.0)


def test_a_place_in_play_is_held_instead_of_the_formation_place_which_stays_the_beam_place():
    behavior = RecordingBehavior("walk", "dribble")
    strategy = Strategy(StrategyConfig(play_places={10: (-2.5, 0.0)}))
    heard = [said(7, 0.5)]  # teammate 7 goes for the ball
    strategy.decide(world((-8.0, 3.0), (0.0, 0.0, 0.0), heard=heard, unum=10), behavior)
    assert behavior.calls[-1][:3] == ("walk", -2.5, 0.0)
    beam = strategy.decide(
        world((0.0, 0.0), (0.0, 0.0, 0.0), play_mode="BeforeKickOff", unum=10), behavior
    ).beam
    assert beam == (*strategy.home(10), 0.0) and strategy.home(10) == (-0.6, 0.0)
    # a player without a place in play holds its formation place
    strategy.decide(world((-8.0, 3.0), (0.0, 0.0, 0.0), heard=heard, unum=9), behavior)
    assert behavior.calls[-1][1:3] == strategy.home(9)


def test_a_player_holding_its_place_keeps_clear_of_the_ball_if_told_so():
    behavior = RecordingBehavior("walk", "dribble")
    heard = [said(7, 0.3)]  # teammate 7 goes for the ball
    home = Strategy().home(4)  # (-11.5, -1.5)
    ball = (home[0] + 0.5, home[1])  # a duel half a metre in front of the place
    Strategy().decide(world(ball, (-12.0, -1.0, 0.0), heard=heard, unum=4), behavior)
    assert behavior.calls[-1][1:3] == home  # off: it walks into the duel
    strategy = Strategy(StrategyConfig(hold_clear_m=1.5))
    strategy.decide(world(ball, (-12.0, -1.0, 0.0), heard=heard, unum=4), behavior)
    assert behavior.calls[-1][1:3] == pytest.approx((ball[0] - 1.5, home[1]))
    # a place farther than that from the ball stays where it is
    far = (home[0] + 3.0, home[1])
    strategy.decide(world(far, (-12.0, -1.0, 0.0), heard=heard, unum=4), behavior)
    assert behavior.calls[-1][1:3] == home


def test_keeping_clear_of_the_ball_applies_only_to_a_team_of_the_size_asked_for():
    from agent.team import TeamConfig
    from benchmarks.match import small_team
    from world.yaml_config import ConfigError, config_from_mapping

    base = TeamConfig("Us", strategy=StrategyConfig(hold_clear_m=1.5, hold_clear_min_players=11))
    assert base.strategy.hold_clear == 1.5
    assert small_team("Us", 11, base).strategy.hold_clear == 1.5
    assert small_team("Us", 10, base).strategy.hold_clear == 0.0
    assert small_team("Us", 3, base).strategy.hold_clear == 0.0
    # a 3 v 3 player holding its place walks into the duel as with the option off
    behavior = RecordingBehavior("walk", "dribble")
    heard = [said(3, 0.3)]  # teammate 3 (the forward) goes for the ball
    small = Strategy(small_team("Us", 3, base).strategy)
    home = small.home(2)
    ball = (home[0] + 0.5, home[1])
    small.decide(world(ball, (home[0] - 0.5, home[1], 0.0), heard=heard, unum=2), behavior)
    assert behavior.calls[-1][1:3] == home
    full = Strategy(base.strategy)
    home = full.home(7)
    ball = (home[0] + 0.5, home[1])
    full.decide(world(ball, (home[0] - 0.5, home[1], 0.0), heard=heard, unum=7), behavior)
    assert behavior.calls[-1][1:3] == pytest.approx((ball[0] - 1.5, home[1]))
    for bad in ({"hold_clear_min_players": 12}, {"hold_clear_m": -1.0}):
        with pytest.raises(ConfigError, match=next(iter(bad))):
            config_from_mapping(StrategyConfig, bad)


def test_a_smaller_team_keeps_the_advancing_players_it_fields_under_their_new_numbers():
    from agent.team import TeamConfig
    from benchmarks.match import small_team

    base = TeamConfig("Us")
    base = replace(base, strategy=replace(base.strategy, advance=AdvanceConfig(unums=(9, 11))))
    assert small_team("Us", 3, base).strategy.advance.unums == ()  # unums 1, 7, 10
    assert small_team("Us", 5, base).strategy.advance.unums == (3, 5)  # 1, 7, 9, 10, 11
    assert small_team("Us", 11, base).strategy.advance.unums == (9, 11)
    base = replace(base, strategy=replace(base.strategy, play_places={10: (-2.5, 0.0)}))
    assert small_team("Us", 3, base).strategy.play_places == {3: (-2.5, 0.0)}


def test_a_ball_held_at_the_feet_for_seconds_makes_the_player_step_back():
    strategy, behavior = Strategy(), RecordingBehavior("walk", "walk_velocity", "dribble")
    rival = SimpleNamespace(unum=3, position=(0.25, 0.0))  # pushing the ball against it
    scene = world((0.1, 0.0), (0.0, 0.0, 0.0), opponents=[rival])
    names = []
    for k in range(200):  # 4 s with the ball 0.1 m from the torso
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
        names.append(behavior.calls[-1][0])
    first = names.index("walk_velocity")
    assert 140 <= first <= 155  # after about 3 s, well before the referee's 5 s
    assert behavior.calls[-1] == ("walk_velocity", -0.3, 0.0, 0.0)
    # short gaps (under the referee's 0.5 s reset) do not restart the count
    watch = HoldWatch()
    watch.update(0.0, True)
    watch.update(1.0, True)
    watch.update(1.3, False)
    assert watch.update(2.0, True) == pytest.approx(1.7)
    watch.update(2.1, False)
    assert watch.update(2.7, False) == 0.0


def test_a_stall_shot_that_cannot_finish_is_given_up_for_an_escape():
    no_range = StrategyConfig(attack=AttackConfig(kick_range_m=0.0))  # the stall shot only
    strategy, behavior = Strategy(no_range), RecordingBehavior("walk", "dribble", "basic_kick")
    keeper = SimpleNamespace(unum=1, position=(12.8, 0.2))  # at the ball, never lets it go
    scene = world((12.5, 0.0), (12.2, 0.0, 0.0), opponents=[keeper])
    names = []
    for k in range(800):  # 16 s: 4 s stall, 8 s of shot, then the escape
        scene.time = 10.0 + 0.02 * k
        strategy.decide(scene, behavior)
        names.append(behavior.calls[-1][0])
    assert "basic_kick" in names
    last_kick = len(names) - 1 - names[::-1].index("basic_kick")
    assert 560 <= last_kick <= 610  # about 4 s + 8 s after the start
    assert names[-1] != "basic_kick"


def test_a_ball_lost_under_the_robot_makes_it_step_back_not_turn_over_it():
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble")
    under = world((0.1, 0.0), (0.0, 0.0, 0.0))
    under.ball.time_since_seen = 4.0
    Strategy().decide(under, behavior)
    assert behavior.calls[-1] == ("walk_velocity", -0.3, 0.0, 0.0)


def test_holding_time_counts_while_getting_up_on_the_ball():
    class GetUpBehavior(RecordingBehavior):
        def execute(self, name: str, *args: object) -> bool:
            super().execute(name, *args)
            return name == "get_up" and len(self.calls) >= 150  # up after 3 s

    strategy, behavior = Strategy(), GetUpBehavior("walk", "walk_velocity", "dribble", "get_up")
    scene = world((0.05, 0.0), (0.0, 0.0, 0.0))
    scene.robot.is_fallen = True
    for k in range(155):
        scene.time = 10.0 + 0.02 * k
        scene.robot.is_fallen = k < 100
        strategy.decide(scene, behavior)
    # up and over the ball after 3 s: it steps back at once instead of walking round it
    assert behavior.calls[-1] == ("walk_velocity", -0.3, 0.0, 0.0)


def _snap_world(ball, pose, time=10.0):
    """A world with the robot type the snap shot reads the kick spot for."""
    w = world(ball=ball, pose=pose)
    w.robot = SimpleNamespace(is_fallen=False, robot_type=0)
    w.time = time
    return w


def test_a_ball_at_the_left_kick_spot_near_the_goal_stops_the_player_then_it_kicks_to_the_end():
    from behaviors.basic_kick import expected_ball_ego
    from behaviors.kick import kick_motion

    ahead, left = expected_ball_ego(0, "left", kick_motion(0))
    snapper = Strategy(StrategyConfig(attack=AttackConfig(snap_range_m=3.5)))
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble", "basic_kick", "kick")
    pose, ball = (12.5, 0.0, 0.0), (12.5 + ahead + 0.05, left)
    snapper.decide(_snap_world(ball, pose, 10.0), behavior)
    assert behavior.calls[-1] == ("walk_velocity", 0.0, 0.0, 0.0)
    snapper.decide(_snap_world(ball, pose, 10.6), behavior)
    assert behavior.calls[-1] == ("pose", "stand")
    snapper.decide(_snap_world(ball, pose, 11.0), behavior)
    assert behavior.calls[-1] == ("kick", "left", 1.0)
    # the kick plays on although the ball has gone (kicked) and the player is no longer at it
    snapper.decide(_snap_world((14.0, 0.0), pose, 11.1), behavior)
    assert behavior.calls[-1] == ("kick", "left", 1.0)


def test_a_snap_shot_whose_ball_rolled_off_the_spot_while_stopping_is_given_up():
    from behaviors.basic_kick import expected_ball_ego
    from behaviors.kick import kick_motion

    ahead, left = expected_ball_ego(0, "left", kick_motion(0))
    snapper = Strategy(StrategyConfig(attack=AttackConfig(snap_range_m=3.5)))
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble", "basic_kick", "kick")
    pose = (12.5, 0.0, 0.0)
    snapper.decide(_snap_world((12.5 + ahead, left), pose, 10.0), behavior)
    snapper.decide(_snap_world((13.2, 0.0), pose, 11.0), behavior)
    assert behavior.calls[-1] == ("pose", "stand")
    snapper.decide(_snap_world((13.2, 0.0), pose, 11.1), behavior)
    assert behavior.calls[-1][0] in ("walk", "dribble")
    # back at the spot within snap_retry_s: no new stop, it plays on
    snapper.decide(_snap_world((12.5 + ahead, left), pose, 12.0), behavior)
    assert behavior.calls[-1][0] in ("walk", "dribble")
    snapper.decide(_snap_world((12.5 + ahead, left), pose, 14.5), behavior)
    assert behavior.calls[-1] == ("walk_velocity", 0.0, 0.0, 0.0)


def test_no_snap_shot_off_the_spot_facing_past_the_post_far_from_goal_or_by_default():
    from behaviors.basic_kick import expected_ball_ego
    from behaviors.kick import kick_motion

    ahead, left = expected_ball_ego(0, "right", kick_motion(0))
    snapper = Strategy(StrategyConfig(attack=AttackConfig(snap_range_m=3.5)))
    at_spot = (12.5 + ahead, left)
    assert snapper.snap_foot(_snap_world(at_spot, (12.5, 0.0, 0.0))) == "right"
    assert Strategy().snap_foot(_snap_world(at_spot, (12.5, 0.0, 0.0))) is None
    # 8 cm to the side of the spot: between the feet's spots, no foot meets it
    assert snapper.snap_foot(_snap_world((12.5 + ahead, 0.0), (12.5, 0.0, 0.0))) is None
    # facing 30 deg to the left from 2.5 m: the line passes 1.4 m off the centre, wide
    turned = (12.5, 0.0, 30.0)
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    ball = (12.5 + ahead * c - left * s, ahead * s + left * c)
    assert snapper.snap_foot(_snap_world(ball, turned)) is None
    # 6 m from goal: too far for the stand kick's 1.7-2.7 m
    assert snapper.snap_foot(_snap_world((9.0 + ahead, left), (9.0, 0.0, 0.0))) is None


def test_players_take_turns_to_speak_so_every_claim_is_heard():
    # the real server's hearing (sim.hearing): one teammate message per cycle reaches a
    # listener, then it is deaf to its team for a cycle
    speakers = []
    for cycle in range(1000, 1044):
        speaking = [u for u in range(1, 12) if my_turn_to_speak(u, cycle * 0.02)]
        assert len(speaking) <= 1
        speakers.append(speaking[0] if speaking else None)
    assert all(a is None or b is None for a, b in itertools.pairwise(speakers))
    assert sorted(s for s in speakers if s is not None) == sorted(list(range(1, 12)) * 2)
    # the strategy says its claim in its turn only
    strategy, behavior = Strategy(), RecordingBehavior("walk", "dribble")
    said_at = []
    for cycle in range(1000, 1022):
        now = world((0.0, 0.0), (-2.0, 0.0, 0.0))
        now.time = cycle * 0.02
        decision = strategy.decide(now, behavior)
        if decision.say is not None:
            said_at.append(cycle)
    assert len(said_at) == 1 and my_turn_to_speak(9, said_at[0] * 0.02)


@pytest.mark.parametrize(
    ("ball", "heading_deg", "sign"),
    [
        ((-5.0, -0.5), 0.0, -1.0),  # behind, over the right shoulder: turn right
        ((-5.0, 0.5), 0.0, 1.0),  # behind, over the left shoulder: turn left
        ((0.0, 3.0), 0.0, 1.0),  # on the left
        ((-2.0, -3.0), 90.0, 1.0),  # facing +y, the ball behind, a little to the left
        ((3.0, -3.0), 90.0, -1.0),  # facing +y, the ball to the right
        (None, 0.0, 1.0),  # never seen: left by default
    ],
)
def test_a_lost_ball_is_searched_for_turning_towards_its_last_place(ball, heading_deg, sign):
    """The shorter way round to the side the lost ball was last placed on."""
    turn = search_turn_deg_s(world(ball=ball, pose=(-1.0, 0.0, heading_deg)))
    assert turn == sign * SEARCH_TURN_DEG_S


@pytest.mark.parametrize(
    ("bearing", "yaw"),
    [(0.0, 0.0), (25.0, 0.0), (-30.0, 0.0), (60.0, 30.0), (-100.0, -70.0), (170.0, 90.0)],
)
def test_the_head_turns_by_the_bearing_beyond_the_still_zone_up_to_its_limit(bearing, yaw):
    assert head_yaw_for(bearing) == pytest.approx(yaw)


@pytest.mark.parametrize(("skills", "turned"), [(("walk",), True), (("walk", "dribble"), False)])
def test_the_head_follows_a_ball_behind_only_while_a_walk_moves_the_body(skills, turned):
    """Holding its place with the ball behind on the right, a player walks there and turns its
    head right; a skill that sets the head itself (the dribble, once at the ball) is left alone."""
    behavior = RecordingBehavior(*skills)
    ball, pose = ((-3.0, -1.0), (0.0, 0.0, 0.0)) if turned else ((0.25, 0.0), (0.0, 0.0, 0.0))
    Strategy().decide(world(ball=ball, pose=pose, unum=10), behavior)
    targets = behavior.commands.targets()
    if turned:
        assert behavior.calls[-1][0] == "walk"
        assert targets["hj1"] == pytest.approx(
            head_yaw_for(-180.0 + math.degrees(math.atan2(1.0, 3.0)))
        )
        assert targets["hj1"] < -60.0
    else:
        assert behavior.calls[-1][0] != "walk"
        assert "hj1" not in targets


def test_a_search_keeps_the_turn_it_started_with_until_the_ball_is_seen():
    """A stale estimate drifting across the heading must not flip the turn every cycle (the
    robot then turns to and fro on the spot and never finds the ball)."""
    strategy, behavior = Strategy(), RecordingBehavior("walk", "walk_velocity")

    def turn_with(ball, since_seen):
        w = world(ball=ball, pose=(0.0, 0.0, 0.0))
        w.ball.time_since_seen = since_seen
        strategy.decide(w, behavior)
        return behavior.calls[-1]

    assert turn_with((3.0, -0.5), 5.0) == ("walk_velocity", 0.0, 0.0, -SEARCH_TURN_DEG_S)
    assert turn_with((3.0, 0.5), 5.1) == ("walk_velocity", 0.0, 0.0, -SEARCH_TURN_DEG_S)
    assert turn_with((3.0, 0.5), 0.0)[0] != "walk_velocity"  # seen: the search is over
    assert turn_with((3.0, 0.5), 5.0) == ("walk_velocity", 0.0, 0.0, SEARCH_TURN_DEG_S)


def test_a_far_approach_point_ahead_is_sprinted_to_and_walked_to_near_it_if_told_so():
    attack = AttackConfig(sprint_m=2.0)
    strategy = Strategy(StrategyConfig(attack=attack))
    behavior = RecordingBehavior("walk", "walk_velocity", "dribble")
    # ball 6 m ahead, 5 deg left of the heading: sprint, steering left within the cap
    strategy.decide(world(ball=(0.0, 0.5), pose=(-6.0, 0.0, 0.0)), behavior)
    name, vx, vy, turn = behavior.calls[-1]
    assert (name, vx, vy) == ("walk_velocity", attack.sprint_speed_m_s, 0.0)
    assert 0.0 < turn <= attack.sprint_max_turn_deg_s
    # 30 deg off: a started sprint goes on (stop at 45) ...
    strategy.decide(world(ball=(0.0, 3.5), pose=(-6.0, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][0] == "walk_velocity"
    assert behavior.calls[-1][3] == pytest.approx(attack.sprint_max_turn_deg_s)
    # ... but none starts (start within 10): a new player walks
    fresh = RecordingBehavior("walk", "walk_velocity", "dribble")
    Strategy(StrategyConfig(attack=attack)).decide(
        world(ball=(0.0, 3.5), pose=(-6.0, 0.0, 0.0)), fresh
    )
    assert fresh.calls[-1][0] == "walk"
    # within sprint_m of the approach point it walks there to face the goal
    strategy.decide(world(ball=(0.0, 0.0), pose=(-1.5, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][0] == "walk"
    # off by default
    default = RecordingBehavior("walk", "walk_velocity", "dribble")
    Strategy().decide(world(ball=(0.0, 0.5), pose=(-6.0, 0.0, 0.0)), default)
    assert default.calls[-1][0] == "walk"


def test_walking_to_the_ball_goes_round_a_robot_in_the_way():
    ball, pose = (0.0, 3.0), (-4.0, 0.0, 0.0)
    rival = SimpleNamespace(unum=2, position=(-2.0, 1.9))  # on the way, a little to its left
    plain = RecordingBehavior("walk", "dribble")
    straight_through = StrategyConfig(attack=AttackConfig(avoid_clear_m=0.0))
    Strategy(straight_through).decide(world(ball, pose, opponents=[rival]), plain)
    assert plain.calls[-1][0] == "walk"
    straight = plain.calls[-1][1:3]
    avoid = AttackConfig(avoid_clear_m=0.8, avoid_target_zone_m=0.6, avoid_beyond_m=0.3)
    behavior = RecordingBehavior("walk", "dribble")
    Strategy(StrategyConfig(attack=avoid)).decide(world(ball, pose, opponents=[rival]), behavior)
    name, x, y, heading = behavior.calls[-1]
    assert name == "walk" and (x, y) != pytest.approx(straight)
    assert math.dist((x, y), rival.position) == pytest.approx(math.hypot(0.8, 0.3))
    # the waypoint lies right of the way (the rival is left of it), heading on to the ball
    way = math.atan2(straight[1] - pose[1], straight[0] - pose[0])
    across = -(x - pose[0]) * math.sin(way) + (y - pose[1]) * math.cos(way)
    rival_across = -(-2.0 - pose[0]) * math.sin(way) + (1.9 - pose[1]) * math.cos(way)
    assert rival_across > 0.0 > across
    assert heading == pytest.approx(math.degrees(math.atan2(straight[1] - y, straight[0] - x)))
