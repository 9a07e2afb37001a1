"""The behaviour manager: lazy skills, restarts, sub-behaviours, durations, argument errors, the
registry, and the agent loop against the simulator."""

from __future__ import annotations

import subprocess
import sys
from types import SimpleNamespace
from typing import Literal

import numpy as np
import pytest

import behaviors
from behaviors import Behavior, BehaviorRun, Skill, SkillContext
from behaviors.joint_control import DEFAULT_GAIN
from sim.session import Session, SessionConfig
from world.effectors import EffectorMessage, write_effectors
from world.perception import parse_perception
from world.robot_state import RobotState

# --------------------------------------------------------------------------------------------
# Skills defined for these tests (names start with "test_" to stay out of real skill lists)
# --------------------------------------------------------------------------------------------


class Counting(Skill):
    """Counts its resets and steps; finished after ``length`` steps since the last reset."""

    name = "test_counting"

    def __init__(self) -> None:
        self.resets = 0
        self.steps = 0

    def reset(self) -> None:
        self.resets += 1
        self.steps = 0

    def step(self, context: SkillContext, length: int = 3) -> bool:
        self.steps += 1
        return self.steps >= length


class Other(Counting):
    """A second counting skill, to switch to."""

    name = "test_other"


class Parent(Skill):
    """Runs the sub-skill it is told to, as skills made of skills do."""

    name = "test_parent"

    def __init__(self) -> None:
        self.resets = 0

    def reset(self) -> None:
        self.resets += 1

    def step(self, context: SkillContext, sub: str) -> bool:
        return context.manager.execute_sub_behavior(sub)


class StackReader(Skill):
    """Records the manager's stack of running skills as it sees it while stepping."""

    name = "test_stack_reader"

    def __init__(self) -> None:
        self.seen: tuple[str, ...] = ()

    def step(self, context: SkillContext) -> bool:
        self.seen = context.manager.running
        return True


class Typed(Skill):
    """Takes a distance and an optional label."""

    name = "test_typed"

    def validate(self, distance: float, label: str | None = None) -> None:
        if distance < 0:
            raise ValueError(f"distance must be >= 0, got {distance}")

    def step(self, context: SkillContext, distance: float, label: str | None = None) -> bool:
        return True


class Sided(Skill):
    """Takes a foot by name: its annotation checks values, not only types."""

    name = "test_sided"

    def step(self, context: SkillContext, foot: Literal["left", "right"]) -> bool:
        return True


class Careless(Skill):
    """Forgets to return whether it has finished."""

    name = "test_careless"

    def step(self, context: SkillContext):
        pass


class Meddler(Skill):
    """Calls ``execute`` from inside a skill, which is not allowed."""

    name = "test_meddler"

    def step(self, context: SkillContext) -> bool:
        return context.manager.execute("zero")


def _world(joints: dict[str, float] | None = None) -> SimpleNamespace:
    """The part of the world model the manager and the basic skills use: ``robot``."""
    robot = RobotState()
    robot.joints_deg = dict.fromkeys(robot.spec.perceptor_names, 0.0) | (joints or {})
    return SimpleNamespace(robot=robot)


@pytest.fixture
def manager() -> Behavior:
    return Behavior(_world())


def _cycle(manager: Behavior, name: str, *args) -> bool:
    manager.begin_cycle()
    return manager.execute(name, *args)


# --------------------------------------------------------------------------------------------
# Instances, restarts and durations
# --------------------------------------------------------------------------------------------


def test_one_lazy_instance_per_skill_and_manager(manager):
    assert manager.current is None and manager.previous is None
    _cycle(manager, "test_counting")
    first = manager.skill("test_counting")
    _cycle(manager, "test_counting")
    assert manager.skill("test_counting") is first and isinstance(first, Counting)
    assert Behavior(_world()).skill("test_counting") is not first


def test_skill_restarts_only_after_another_ran(manager):
    results = [_cycle(manager, "test_counting", 3) for _ in range(4)]
    assert results == [False, False, True, True]
    counting = manager.skill("test_counting")
    assert counting.resets == 1
    _cycle(manager, "test_other")
    _cycle(manager, "test_counting")
    assert counting.resets == 2 and counting.steps == 1


def test_skill_restarts_after_a_cycle_without_it(manager):
    _cycle(manager, "test_counting")
    manager.begin_cycle()  # a cycle in which no behaviour ran
    _cycle(manager, "test_counting")
    assert manager.skill("test_counting").resets == 2


def test_current_and_previous_with_durations(manager):
    for _ in range(3):
        _cycle(manager, "test_counting")
    for _ in range(2):
        _cycle(manager, "test_other")
    assert manager.current == BehaviorRun("test_other", 2)
    assert manager.previous == BehaviorRun("test_counting", 3)
    assert manager.current.seconds == pytest.approx(0.04)
    assert manager.previous.seconds == pytest.approx(0.06)


# --------------------------------------------------------------------------------------------
# Sub-behaviours
# --------------------------------------------------------------------------------------------


def test_sub_behaviour_keeps_top_level_and_restarts_on_switch(manager):
    for _ in range(2):
        _cycle(manager, "test_parent", "test_counting")
    counting = manager.skill("test_counting")
    assert (counting.resets, counting.steps) == (1, 2)
    assert manager.current == BehaviorRun("test_parent", 2)
    _cycle(manager, "test_parent", "test_other")
    _cycle(manager, "test_parent", "test_counting")
    assert (counting.resets, counting.steps) == (2, 1), "parent switched sub-skills"
    assert manager.current == BehaviorRun("test_parent", 4)
    assert manager.skill("test_parent").resets == 1


def test_running_names_the_stack_of_skills_stepping_now(manager):
    reader = manager.skill("test_stack_reader")
    _cycle(manager, "test_stack_reader")
    assert reader.seen == ("test_stack_reader",)
    _cycle(manager, "test_parent", "test_stack_reader")
    assert reader.seen == ("test_parent", "test_stack_reader")
    assert manager.running == (), "nothing runs between steps"


def test_restarted_parent_restarts_its_sub_behaviour(manager):
    _cycle(manager, "test_parent", "test_counting")
    _cycle(manager, "test_other")
    _cycle(manager, "test_parent", "test_counting")
    assert manager.skill("test_counting").resets == 2
    assert manager.skill("test_parent").resets == 2


def test_sub_behaviour_result_is_the_parents(manager):
    assert [_cycle(manager, "test_parent", "test_counting") for _ in range(3)] == [
        False,
        False,
        True,
    ]


def test_misuse_of_execute_and_sub_behaviours(manager):
    with pytest.raises(RuntimeError, match="outside a skill"):
        manager.execute_sub_behavior("zero")
    with pytest.raises(RuntimeError, match="execute_sub_behavior"):
        _cycle(manager, "test_meddler")
    with pytest.raises(RuntimeError, match="itself"):
        _cycle(manager, "test_parent", "test_parent")
    _cycle(manager, "zero")  # the manager is still usable after the errors
    assert manager.current.name == "zero"


# --------------------------------------------------------------------------------------------
# Errors that teach
# --------------------------------------------------------------------------------------------


def test_unknown_skill_lists_every_registered_skill(manager):
    with pytest.raises(KeyError) as error:
        manager.execute("kick_the_moon")
    message = str(error.value)
    for name in Skill.registry:
        assert name in message
    assert set(manager.skill_names) == set(Skill.registry)
    assert "test_typed(distance: float, label: str | None = None)" in message


def test_wrong_argument_count_names_skill_and_signature(manager):
    with pytest.raises(TypeError) as error:
        manager.execute("zero", 5)
    assert "zero()" in str(error.value) and "test_counting" in str(error.value)
    with pytest.raises(TypeError, match=r"test_typed\(distance: float"):
        manager.execute("test_typed")


def test_wrong_argument_type_names_the_parameter(manager):
    with pytest.raises(TypeError, match="'distance' must be float, got 'far'"):
        manager.execute("test_typed", "far")
    with pytest.raises(TypeError, match="'distance'"):
        manager.execute("test_typed", True)
    with pytest.raises(TypeError, match="'label'"):
        manager.execute("test_typed", 1.0, 3)
    assert manager.execute("test_typed", 2) is True, "an int is a float"
    assert manager.execute("test_typed", 2.0, None) is True
    assert manager.execute("test_typed", 2.0, "x") is True


def test_accepted_argument_types_are_remembered_but_other_calls_still_checked(manager):
    """The check is cached per tuple of argument types; a new combination is checked again,
    and values are still validated on every call."""
    assert manager.execute("test_typed", 2.0, "x") is True
    assert manager.execute("test_typed", 3.0, "y") is True
    with pytest.raises(TypeError, match="'label'"):
        manager.execute("test_typed", 1.0, 3)
    with pytest.raises(TypeError, match="'distance'"):
        manager.execute("test_typed", "far", "x")
    with pytest.raises(ValueError, match="distance must be >= 0"):
        manager.execute("test_typed", -1.0, "x")


def test_literal_arguments_are_checked_on_every_call(manager):
    """A ``Literal`` check depends on the value, so an accepted call does not excuse the next."""
    assert manager.execute("test_sided", "left") is True
    with pytest.raises(TypeError, match="'foot'"):
        manager.execute("test_sided", "middle")


def test_bad_argument_value_is_a_value_error_with_the_signature(manager):
    with pytest.raises(ValueError, match=r"test_typed\(distance.*distance must be >= 0"):
        manager.execute("test_typed", -1.0)


def test_step_must_say_whether_it_finished(manager):
    with pytest.raises(TypeError, match=r"test_careless.*returned None"):
        manager.execute("test_careless")


def test_duplicate_skill_names_are_refused():
    with pytest.raises(TypeError, match="taken"):
        type("Again", (Skill,), {"name": "zero", "step": lambda self, context: True})


def test_importing_behaviors_registers_the_builtin_skills():
    code = "import behaviors, behaviors.skill as s; print(' '.join(sorted(s.Skill.registry)))"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert {"zero", "hold", "pose", "keyframe", "get_up"} <= set(result.stdout.split())
    assert "behaviors.basic" in behaviors.BUILTIN_SKILL_MODULES


# --------------------------------------------------------------------------------------------
# Joint commands through the manager
# --------------------------------------------------------------------------------------------


def test_zero_and_effector_speeds_follow_the_world_joints():
    world = _world({"hj1": 10.0, "raj1": -20.0})
    manager = Behavior(world)
    manager.begin_cycle()
    assert manager.execute("zero") is False
    speeds = manager.effector_speeds()
    assert speeds["he1"] == pytest.approx(-DEFAULT_GAIN * np.radians(10.0) / 0.02)
    assert speeds["rae1"] > 0 and speeds["lae1"] == 0.0
    world.robot.joints_deg = dict.fromkeys(world.robot.joints_deg, 0.4)
    manager.begin_cycle()
    assert manager.execute("zero") is True


def test_begin_cycle_clears_last_cycles_commands():
    manager = Behavior(_world({"hj1": 10.0}))
    manager.begin_cycle()
    manager.execute("zero")
    manager.begin_cycle()
    assert manager.commands.targets() == {}
    assert all(speed == 0.0 for speed in manager.effector_speeds().values())


def test_hold_keeps_the_pose_it_started_with():
    world = _world({"hj1": 20.0, "rlj3": 30.0})
    manager = Behavior(world)
    assert _cycle(manager, "hold") is True
    world.robot.joints_deg = world.robot.joints_deg | {"hj1": 25.0}
    assert _cycle(manager, "hold") is False
    assert manager.commands.targets()["hj1"] == 20.0
    assert manager.effector_speeds()["he1"] < 0
    _cycle(manager, "zero")
    _cycle(manager, "hold")  # a restart captures the new pose
    assert manager.commands.targets()["hj1"] == 25.0


def test_agent_loop_drives_a_simulated_robot_to_zero_and_holds_it():
    """The whole path: perception bytes -> RobotState -> manager -> effector bytes."""
    session = Session(SessionConfig(seed=2, beam_noise=False, vision_noise=False))
    try:
        agent = session.join("Alpha", 1, beam=(-2.0, 0.0, 0.0), settle_cycles=1)
        session.handle_message(agent, b"(he1 -3.0)(rae1 3.0)(lae2 2.0)(syn)")  # leave zero
        for _ in range(20):
            session.step()
        world = SimpleNamespace(robot=RobotState())
        manager = Behavior(world)
        finished_at = None
        for cycle in range(60):
            session.step()
            world.robot.update(parse_perception(session.perception(agent)))
            manager.begin_cycle()
            done = manager.execute("zero" if finished_at is None else "hold")
            if finished_at is None and done:
                finished_at = cycle
            speeds = manager.effector_speeds()
            session.handle_message(agent, write_effectors(EffectorMessage(joint_speeds=speeds)))
        assert finished_at is not None, world.robot.joints_deg
        assert manager.previous.name == "zero" and manager.current.name == "hold"
        for name in ("hj1", "raj1", "laj2"):
            assert abs(world.robot.joints_deg[name]) < 1.0, (name, world.robot.joints_deg)
    finally:
        session.close()
