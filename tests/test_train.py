"""PPO training from a YAML config: a tiny run exports a policy that numpy runs exactly as
the torch actor does; bad configs fail with the key in the message."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import DummyVecEnv, VecNormalize

from agent.cli import main as cli_main
from behaviors.get_up import RESIDUAL_ACTIONS, RESIDUAL_OBS_NAMES, PolicyResidual
from behaviors.policy import MlpPolicy
from learning.train import TrainConfigError, load_config, parse_config

TINY = {
    "env_id": "naosoccer/GetUpResidual-v0",
    "env": {"robot_types": [0], "falls_per_type": 2},
    "ppo": {"n_steps": 128, "batch_size": 64, "n_epochs": 1, "net_arch": [16, 16]},
    "train": {"seed": 3, "total_timesteps": 256, "checkpoint_every": 128, "log_every": 128},
}


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """A tiny run through the command line (``naosoccer train``)."""
    out = tmp_path_factory.mktemp("run")
    config = out / "tiny.yaml"
    config.write_text(yaml.safe_dump(TINY))
    assert cli_main(["train", "--config", str(config), "--out", str(out)]) == 0
    return out, out / "policy.npz"


def test_tiny_run_writes_a_loadable_policy(run):
    out, path = run
    policy = MlpPolicy.load(path, RESIDUAL_OBS_NAMES, tuple(RESIDUAL_ACTIONS))
    assert [w.shape for w in policy.weights] == [(16, 41), (16, 16), (5, 16)]
    assert yaml.safe_load(policy.config_text) == TINY
    assert policy.git_commit and (out / "config.yaml").exists() and (out / "meta.json").exists()
    assert sorted(p.name for p in (out / "checkpoints").iterdir()) == [
        "model_128.zip", "model_256.zip", "vecnormalize_128.pkl", "vecnormalize_256.pkl",
    ]  # fmt: skip
    residual = PolicyResidual.load(path)
    assert residual.policy.n_obs == len(RESIDUAL_OBS_NAMES)
    assert residual.robot_types == {0}  # trained on type 0 alone: it acts for type 0 alone


def test_numpy_policy_equals_the_torch_actor(run):
    out, path = run
    model = PPO.load(out / "model.zip", device="cpu")
    venv = DummyVecEnv([lambda: _box_env(len(RESIDUAL_OBS_NAMES))])
    normalizer = VecNormalize.load(str(out / "vecnormalize.pkl"), venv)
    policy = MlpPolicy.load(path)
    rng = np.random.default_rng(0)
    for _ in range(20):
        obs = rng.normal(0, 30, size=len(RESIDUAL_OBS_NAMES)).astype(np.float32)
        torch_action, _ = model.predict(normalizer.normalize_obs(obs), deterministic=True)
        assert np.allclose(policy.raw_action(obs), torch_action, atol=1e-5)
    assert not np.allclose(policy.normalise(np.zeros(41)), 0.0)  # the stats did travel


def _box_env(n: int):
    import gymnasium as gym

    class Box(gym.Env):
        observation_space = gym.spaces.Box(-1e4, 1e4, (n,), np.float32)
        action_space = gym.spaces.Box(-1, 1, (5,), np.float32)

    return Box()


def test_config_errors_name_the_key(tmp_path):
    unknown = r"config\.ppo: unknown key\(s\) n_step for PpoConfig"
    with pytest.raises(TrainConfigError, match=unknown):
        parse_config({**TINY, "ppo": {"n_step": 5}})
    message = r"config\.train: RunConfig\.total_timesteps: expected int, got 'many'"
    with pytest.raises(TrainConfigError, match=message):
        parse_config({**TINY, "train": {"total_timesteps": "many"}})
    with pytest.raises(TrainConfigError, match="env_id must be one of"):
        parse_config({**TINY, "env_id": "Nope-v0"})
    with pytest.raises(TrainConfigError, match="batch_size <= n_steps"):
        parse_config({**TINY, "ppo": {"n_steps": 64, "batch_size": 128}})
    path = tmp_path / "c.yaml"
    path.write_text("env_id: [")
    with pytest.raises(TrainConfigError, match="cannot read"):
        load_config(path)


@pytest.mark.parametrize(
    ("name", "env_id"),
    [("get_up", "naosoccer/GetUpResidual-v0"), ("walk", "naosoccer/WalkResidual-v0")],
)
def test_packaged_configs_are_valid(name, env_id):
    config, _ = load_config(Path(__file__).resolve().parents[1] / f"config/train/{name}.yaml")
    assert config.env_id == env_id


def test_parallel_environments_with_gsde_train_and_export(tmp_path):
    """Two worker processes (train.n_envs) and gSDE exploration: the run counts the steps of
    both environments, and the exported numpy policy is the deterministic torch actor."""
    tiny = {
        **TINY,
        "ppo": {**TINY["ppo"], "n_steps": 64, "use_sde": True, "sde_sample_freq": 4},
        "train": {**TINY["train"], "n_envs": 2, "checkpoint_every": 0},
    }
    config = tmp_path / "parallel.yaml"
    config.write_text(yaml.safe_dump(tiny))
    out = tmp_path / "run"
    assert cli_main(["train", "--config", str(config), "--out", str(out)]) == 0
    model = PPO.load(out / "model.zip", device="cpu")
    assert model.num_timesteps == 256 and model.n_envs == 2 and model.use_sde
    policy = MlpPolicy.load(out / "policy.npz", RESIDUAL_OBS_NAMES, tuple(RESIDUAL_ACTIONS))
    obs = np.random.default_rng(1).normal(0, 1, size=len(RESIDUAL_OBS_NAMES)).astype(np.float32)
    torch_action, _ = model.predict(policy.normalise(obs), deterministic=True)
    assert np.allclose(policy.raw_action(obs), torch_action, atol=1e-5)


def test_n_envs_must_be_positive():
    with pytest.raises(TrainConfigError, match="n_envs"):
        parse_config({**TINY, "train": {**TINY["train"], "n_envs": 0}})
