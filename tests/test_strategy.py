"""The strategy's choices, on stand-in world models (no simulator): who goes for the ball and
which skill it picks where."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from agent.strategy import AttackConfig, Strategy, StrategyConfig


class RecordingBehavior:
    """Records ``execute`` calls; offers the given skill names."""

    def __init__(self, *skills: str) -> None:
        self.skill_names = ("pose", "keyframe", *skills)
        self.calls: list[tuple] = []

    def execute(self, name: str, *args: object) -> bool:
        self.calls.append((name, *args))
        return False


def world(ball, pose, teammates=(), play_mode="PlayOn", unum=9):
    return SimpleNamespace(
        play_mode=play_mode,
        side="left",
        unum=unum,
        time=10.0,
        robot=SimpleNamespace(is_fallen=False),
        ball=SimpleNamespace(position=ball),
        pose=SimpleNamespace(x=pose[0], y=pose[1], heading_deg=pose[2]),
        teammates=SimpleNamespace(recent=lambda time, memory: list(teammates)),
    )


def test_active_player_approaches_behind_the_ball_facing_the_goal():
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    Strategy().decide(world(ball=(0.0, 3.0), pose=(-4.0, 0.0, 0.0)), behavior)
    name, x, y, heading = behavior.calls[-1]
    to_goal = math.atan2(-3.0, 15.0)
    assert name == "walk"
    assert (x, y) == pytest.approx((-0.3 * math.cos(to_goal), 3.0 - 0.3 * math.sin(to_goal)))
    assert heading == pytest.approx(math.degrees(to_goal))


def test_behind_the_ball_and_facing_the_goal_it_dribbles_and_keeps_dribbling():
    strategy = Strategy(StrategyConfig(attack=AttackConfig(dribble_kind="lfdl")))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    strategy.decide(world(ball=(0.0, 0.0), pose=(-0.3, 0.0, 5.0)), behavior)
    assert behavior.calls[-1] == ("dribble", "lfdl", pytest.approx(0.0), "left")
    # the ball ran a little ahead and the robot turned: still its dribble, not a new approach
    strategy.decide(world(ball=(0.5, 0.0), pose=(0.0, 0.1, 40.0)), behavior)
    assert behavior.calls[-1][0] == "dribble"
    # once the ball is lost, it walks back behind it
    strategy.decide(world(ball=(3.0, 0.0), pose=(0.0, 0.1, 0.0)), behavior)
    assert behavior.calls[-1][0] == "walk"


def test_without_a_dribble_skill_it_walks_and_in_range_it_shoots():
    behavior = RecordingBehavior("walk", "basic_kick")
    Strategy().decide(world(ball=(0.0, 0.0), pose=(-0.3, 0.0, 0.0)), behavior)
    assert behavior.calls[-1][0] == "walk"
    Strategy().decide(world(ball=(10.0, 1.0), pose=(8.0, 0.0, 0.0)), behavior)
    assert behavior.calls[-1] == ("basic_kick", 15.0, 0.0, "long")


def test_close_to_the_goal_it_walks_the_ball_in_rather_than_kicking():
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    Strategy().decide(world(ball=(13.0, 0.5), pose=(12.7, 0.5, -5.0)), behavior)
    assert behavior.calls[-1][:2] == ("dribble", "dfdl")
    Strategy().decide(world(ball=(10.0, 0.5), pose=(9.7, 0.5, 0.0)), behavior)
    assert behavior.calls[-1][0] == "basic_kick"


def test_a_player_with_a_closer_teammate_holds_its_formation_place():
    mate = SimpleNamespace(unum=10, position=(0.5, 0.0))
    behavior = RecordingBehavior("walk", "dribble", "basic_kick")
    strategy = Strategy()
    strategy.decide(world(ball=(0.0, 0.0), pose=(-3.0, -4.5, 0.0), teammates=[mate]), behavior)
    assert behavior.calls[-1] == ("walk", *strategy.home(9), 0.0)


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
