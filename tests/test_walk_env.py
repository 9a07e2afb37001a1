"""The learned walk's residual and its training environment: the residual's zero is the walk
engine itself, the right leg's half-cycles are the mirror image of the left's, episodes
reproduce for a seed, and a tiny PPO run gives a policy file ``learned_walk`` loads."""

from __future__ import annotations

from types import SimpleNamespace

import gymnasium as gym
import numpy as np
import pytest
import yaml
from gymnasium.utils.env_checker import check_env

from agent.cli import main as cli_main
from behaviors.get_up import PolicyResidual
from behaviors.learned_walk import (
    ACTION_SCALE,
    LEG_JOINTS,
    OBS_LAYOUT,
    OBS_NAMES,
    LearnedWalkSkill,
    PolicyWalkResidual,
    real_frame_residual,
    walk_observation,
)
from behaviors.mirror import mirror_joint_angles, mirror_observation
from behaviors.policy import PolicyError
from learning.envs import WALK_RESIDUAL_ID, WalkEnvConfig, WalkResidualEnv
from learning.envs.walk import EnvConfigError, measure_speed
from learning.export import export_checkpoint
from learning.local_agent import LocalAgent
from learning.walk_eval import evaluate
from sim.session import Session, SessionConfig
from tests.env_rollout import rollout
from world.robot_state import RobotState

SMALL = {"robot_types": [0], "episode_s": 1.0, "command_every_s": 0.5}


@pytest.fixture(scope="module")
def env():
    environment = WalkResidualEnv(SMALL)
    yield environment
    environment.close()


def test_check_env_passes(env):
    check_env(env, skip_render_check=True)


def test_registered_with_gymnasium():
    made = gym.make(WALK_RESIDUAL_ID, config=SMALL)
    try:
        assert isinstance(made.unwrapped, WalkResidualEnv)
    finally:
        made.close()


def test_reset_with_a_seed_is_reproducible_and_commands_change(env):
    actions = np.random.default_rng(3).uniform(-0.3, 0.3, size=(60, 12)).astype(np.float32)
    first = rollout(env, 11, actions)
    assert len(first) == 51  # 1 s: truncated after 50 cycles
    assert rollout(env, 11, actions) == first
    env.reset(seed=11)
    commands = {env._episode.command}
    for _ in range(30):
        env.step(np.zeros(12, dtype=np.float32))
        commands.add(env._episode.command)
    assert len(commands) == 2  # a new command after command_every_s


def _torso_path(skill_name: str, cycles: int, residual=None) -> list[tuple[float, ...]]:
    session = Session(SessionConfig(seed=2, beam_noise=False))
    try:
        agent = LocalAgent.join(session, "Walkers", 1, 0, beam=(-12.0, 0.0, 0.0))
        agent.trainer("(playMode PlayOn)")
        agent.rise_to_stand()
        if residual is not None:
            agent.behavior.skill("learned_walk").residual = residual
        path = []
        for _ in range(cycles):
            agent.run(skill_name, 0.6, 0.0, 10.0)
            path.append(tuple(agent.robot.torso_position()))
        return path
    finally:
        session.close()


def test_without_a_residual_the_learned_walk_is_the_engine():
    zero = SimpleNamespace(residual_deg=lambda obs: np.zeros(12))
    plain = _torso_path("walk_velocity", 80)
    assert plain[-1][0] - plain[0][0] > 0.2  # it walked
    assert _torso_path("learned_walk", 80) == plain
    assert _torso_path("learned_walk", 80, zero) == plain
    knees = SimpleNamespace(residual_deg=lambda obs: ACTION_SCALE * (np.arange(12) % 6 == 3))
    assert _torso_path("learned_walk", 80, knees) != plain


def _fake_engine(t: int, left_active: bool) -> SimpleNamespace:
    return SimpleNamespace(
        phase=(t, left_active),
        velocity=(0.5, 0.1, 0.3),
        params=SimpleNamespace(step=SimpleNamespace(step_cycles=8)),
    )


def test_the_right_legs_half_cycle_is_seen_and_answered_in_the_mirror():
    rng = np.random.default_rng(0)
    state = RobotState(robot_type=0)
    state.joints_deg = {name: float(rng.uniform(-30, 30)) for name in LEG_JOINTS}
    state.gyro_deg_s = rng.uniform(-50, 50, 3)
    state.accelerometer = np.array([0.3, -0.5, 9.7])
    command = (0.7, 0.1, 20.0)
    left = walk_observation(state, _fake_engine(3, True), command)
    right = walk_observation(state, _fake_engine(3, False), command)
    assert left.shape == (len(OBS_NAMES),)
    np.testing.assert_allclose(right, mirror_observation(left, OBS_LAYOUT), atol=1e-5)
    residual = rng.uniform(-1, 1, 12) * ACTION_SCALE
    mirrored = dict(zip(LEG_JOINTS, real_frame_residual(residual, mirrored=True)))
    plain = dict(zip(LEG_JOINTS, real_frame_residual(residual, mirrored=False)))
    assert mirrored == pytest.approx(mirror_joint_angles(plain))
    assert mirrored != pytest.approx(plain)
    # the applied offsets are observed in the canonical frame too
    applied = rng.uniform(-5, 5, 12)
    left = walk_observation(state, _fake_engine(3, True), command, applied)
    right = walk_observation(state, _fake_engine(3, False), command, applied)
    np.testing.assert_allclose(right, mirror_observation(left, OBS_LAYOUT), atol=1e-5)
    # not stepping yet: no mirror, no phase
    still = walk_observation(state, None, command)
    assert list(still[OBS_NAMES.index("phase_sin") :][:3]) == [0.0, 0.0, 0.0]


def test_offsets_are_clipped_to_the_residual_bounds_and_smoothed():
    offsets = dict(zip(LEG_JOINTS, real_frame_residual(np.full(12, 100.0), mirrored=False)))
    assert offsets["llj3"] == 15.0 and offsets["llj1"] == 5.0 and offsets["rlj6"] == 8.0
    constant = SimpleNamespace(residual_deg=lambda obs: np.full(12, 4.0))
    session = Session(SessionConfig(seed=2, beam_noise=False))
    try:
        agent = LocalAgent.join(session, "Walkers", 1, 0, beam=(-12.0, 0.0, 0.0))
        skill = agent.behavior.skill("learned_walk")
        skill.residual = constant
        applied = []
        for _ in range(3):
            agent.run("learned_walk", 0.0, 0.0, 0.0)
            applied.append(skill.offsets_deg["llj3"])
        assert applied == pytest.approx([1.0, 1.75, 2.3125])  # a quarter of the gap a cycle
    finally:
        session.close()


def test_config_errors_name_the_key():
    with pytest.raises(EnvConfigError, match=r"unknown key\(s\) max_speed"):
        WalkEnvConfig.from_mapping({"max_speed": 1.0})
    with pytest.raises(EnvConfigError, match="min_forward <= max_forward"):
        WalkEnvConfig.from_mapping({"min_forward": 1.0, "max_forward": 0.5})
    with pytest.raises(EnvConfigError, match="episode_s must be > 0"):
        WalkEnvConfig.from_mapping({"episode_s": 0.0})


def test_speed_measurement_runs_episodes():
    result = measure_speed(WalkEnvConfig(robot_types=(0,), episode_s=0.2), seconds=0.5)
    assert result["steps_per_s"] > 0 and result["episodes"] >= 1


def test_a_tiny_training_run_gives_a_policy_the_skill_runs(tmp_path):
    config = {
        "env_id": WALK_RESIDUAL_ID,
        "env": {**SMALL, "episode_s": 0.5},
        "ppo": {"n_steps": 64, "batch_size": 32, "n_epochs": 1, "net_arch": [8]},
        "train": {"seed": 1, "total_timesteps": 64, "checkpoint_every": 64, "log_every": 64},
    }
    path = tmp_path / "walk.yaml"
    path.write_text(yaml.safe_dump(config))
    assert cli_main(["train", "--config", str(path), "--out", str(tmp_path / "run")]) == 0
    residual = PolicyWalkResidual(tmp_path / "run" / "policy.npz")
    assert residual.policy.n_obs == len(OBS_NAMES)
    skill = LearnedWalkSkill(residual)
    assert skill.residual is residual
    assert len(_torso_path("learned_walk", 20, residual)) == 20  # it runs in an agent
    # a checkpoint exports to a file the skill loads (taken before the run's last update)
    export_checkpoint(tmp_path / "run", 64, tmp_path / "checkpoint.npz")
    checkpoint = PolicyWalkResidual(tmp_path / "checkpoint.npz").policy
    assert [w.shape for w in checkpoint.weights] == [w.shape for w in residual.policy.weights]
    assert not np.allclose(checkpoint.weights[-1], residual.policy.weights[-1])
    with pytest.raises(PolicyError, match="observation"):  # not a get-up residual
        PolicyResidual.load(tmp_path / "run" / "policy.npz")


def test_the_evaluation_reports_every_figure_per_type():
    figures = evaluate(None, [0], episodes=1, seconds=1.5, seed=0)
    assert set(figures) == {
        "walk_full_mps[type0]",
        "walk_full_falls[type0]",
        "walk_tracking[type0]",
        "walk_random_falls[type0]",
    }
    assert 0.2 < figures["walk_full_mps[type0]"] < 1.2 and figures["walk_full_falls[type0]"] == 0
