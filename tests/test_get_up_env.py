"""The get-up residual environment: gymnasium's checks, reproducible resets, exact restores,
and the residual hook's zero being the keyframes themselves."""

from __future__ import annotations

import copy

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from learning.envs import GET_UP_RESIDUAL_ID, GetUpEnvConfig, GetUpResidualEnv
from learning.envs.get_up import EnvConfigError, measure_speed
from learning.falls import join_at_random_spot, knock_over
from learning.local_agent import LocalAgent
from sim.session import Session, SessionConfig
from tests.env_rollout import rollout

SMALL = {"robot_types": [1], "falls_per_type": 3, "bank_seed": 7}


@pytest.fixture(scope="module")
def env():
    environment = GetUpResidualEnv(SMALL)
    yield environment
    environment.close()


def test_check_env_passes(env):
    check_env(env, skip_render_check=True)


def test_registered_with_gymnasium():
    made = gym.make(GET_UP_RESIDUAL_ID, config={**SMALL, "falls_per_type": 1})
    try:
        assert isinstance(made.unwrapped, GetUpResidualEnv)
    finally:
        made.close()


def test_reset_with_a_seed_is_reproducible(env):
    actions = np.random.default_rng(3).uniform(-1, 1, size=(40, 5)).astype(np.float32)
    first = rollout(env, 11, actions)
    assert len(first) > 5
    assert rollout(env, 11, actions) == first
    other = GetUpResidualEnv(SMALL)
    try:
        assert rollout(other, 11, actions) == first  # a fresh env builds the same bank
    finally:
        other.close()


def test_a_restored_fall_continues_exactly():
    """Save at the end of a fall, run get_up on; restore, run again: the same numbers."""
    rng = np.random.default_rng(5)
    session = Session(SessionConfig(seed=5, beam_noise=False))
    try:
        driver = join_at_random_spot(session, 2, rng)
        assert knock_over(driver, "back", rng)
        driver.perceive()
        snapshot, world = session.save_state(), copy.deepcopy(driver.world)

        def continue_from_snapshot() -> list[tuple[float, ...]]:
            agent = LocalAgent.from_snapshot(session, driver.agent, 2, "Fallers", snapshot, world)
            path = []
            for _ in range(60):
                agent.run("get_up")
                path.append(tuple(agent.robot.torso_position()))
            return path

        original = []
        for _ in range(60):  # the original session, never restored
            driver.run("get_up")
            original.append(tuple(driver.robot.torso_position()))
        assert continue_from_snapshot() == original
        assert continue_from_snapshot() == original
        assert original[0] != original[-1]  # it did move
    finally:
        session.close()


def test_zero_residual_is_the_keyframes(env):
    """An episode of zero actions is the plain skill (no residual) from the same fall."""
    env.reset(options={"robot_type": 1, "fall": 0})
    path = []
    for _ in range(60):
        env.step(np.zeros(5, dtype=np.float32))
        episode = env._episode
        if episode is None:
            break
        path.append(tuple(episode.agent.robot.torso_position()))
    agent, skill = env.bank(1).restore(0)
    assert skill.residual is None
    plain = []
    while not skill.residual_active:  # the cycles the environment runs inside reset
        agent.run("get_up")
    for _ in range(len(path)):
        agent.run("get_up")
        while not skill.residual_active:  # a new attempt: the environment's step runs on
            agent.run("get_up")  # until the residual acts again (type 1 retries here)
        plain.append(tuple(agent.robot.torso_position()))
    assert len(path) > 20 and plain == path


def test_a_residual_changes_the_motion(env):
    def end_height(action: float) -> float:
        env.reset(options={"robot_type": 1, "fall": 0})
        for _ in range(30):
            env.step(np.full(5, action, dtype=np.float32))
        return float(env._episode.agent.robot.torso_position()[2])

    assert end_height(0.0) != end_height(1.0)


def test_config_errors_name_the_key():
    unknown = r"env: unknown key\(s\) robot_type for GetUpEnvConfig"
    with pytest.raises(EnvConfigError, match=unknown):
        GetUpEnvConfig.from_mapping({"robot_type": [1]})
    wrong_type = r"GetUpEnvConfig\.falls_per_type: expected int, got 2\.5"
    with pytest.raises(EnvConfigError, match=wrong_type):
        GetUpEnvConfig.from_mapping({"falls_per_type": 2.5})
    with pytest.raises(EnvConfigError, match="type_weights must give one weight"):
        GetUpEnvConfig.from_mapping({"robot_types": [0, 1], "type_weights": [1.0]})
    with pytest.raises(EnvConfigError, match="directions must be taken from"):
        GetUpEnvConfig.from_mapping({"directions": ["up"]})


def test_speed_measurement_runs_episodes():
    result = measure_speed(GetUpEnvConfig(robot_types=(0,), falls_per_type=1), seconds=0.5)
    assert result["steps_per_s"] > 0 and 0.0 <= result["success"] <= 1.0


def test_a_residual_for_other_robot_types_leaves_the_keyframes_alone(env):
    """A residual with ``robot_types`` acts only for those: on a type-1 robot a source made
    for type 3 is the keyframes alone, one made for type 1 moves it."""
    from types import SimpleNamespace

    def end_height(robot_types: frozenset[int] | None) -> float:
        agent, skill = env.bank(1).restore(0)
        if robot_types is not None:
            skill.residual = SimpleNamespace(
                residual_deg=lambda obs: np.full(5, 15.0), robot_types=robot_types
            )
        for _ in range(80):
            agent.run("get_up")
        return float(agent.robot.torso_position()[2])

    plain = end_height(None)
    assert end_height(frozenset({3})) == plain
    assert end_height(frozenset({1})) != plain
