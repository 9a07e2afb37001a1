"""The numpy policy file: round trip, the maths, and clear errors for files that do not fit."""

from __future__ import annotations

import numpy as np
import pytest

from behaviors.get_up import (
    RESIDUAL_ACTIONS,
    RESIDUAL_MAX_DEG,
    RESIDUAL_OBS_NAMES,
    PolicyResidual,
    residual_offsets,
)
from behaviors.policy import MlpPolicy, PolicyError


def _policy(n_obs: int = 4, hidden: int = 3, n_act: int = 2, seed: int = 0) -> MlpPolicy:
    rng = np.random.default_rng(seed)
    return MlpPolicy(
        weights=(rng.normal(size=(hidden, n_obs)), rng.normal(size=(n_act, hidden))),
        biases=(rng.normal(size=hidden), rng.normal(size=n_act)),
        activation="tanh",
        obs_mean=rng.normal(size=n_obs),
        obs_var=rng.uniform(0.5, 2.0, size=n_obs),
        obs_epsilon=1e-8,
        obs_clip=10.0,
        action_scale=np.arange(1.0, n_act + 1.0),
        obs_names=tuple(f"o{i}" for i in range(n_obs)),
        action_names=tuple(f"a{i}" for i in range(n_act)),
        config_text="ppo: {}\n",
        git_commit="abc",
    )


def test_round_trip_and_forward_pass(tmp_path):
    policy = _policy()
    path = tmp_path / "p.npz"
    policy.save(path)
    loaded = MlpPolicy.load(path, policy.obs_names, policy.action_names)
    obs = np.array([0.3, -1.0, 2.0, 0.1])
    x = (obs - policy.obs_mean) / np.sqrt(policy.obs_var + 1e-8)
    expected = policy.weights[1] @ np.tanh(policy.weights[0] @ x + policy.biases[0])
    expected = np.clip(expected + policy.biases[1], -1, 1) * policy.action_scale
    assert np.allclose(loaded.act(obs), expected)
    assert loaded.config_text == "ppo: {}\n" and loaded.git_commit == "abc"


def test_wrong_shapes_raise_a_clear_error(tmp_path):
    policy = _policy()
    path = tmp_path / "bad.npz"
    policy.save(path)
    with np.load(path) as data:
        entries = dict(data)
    entries["obs_mean"] = np.zeros(7)
    np.savez(path, **entries)
    with pytest.raises(PolicyError, match=r"obs_mean has shape \(7,\), the layers need \(4,\)"):
        MlpPolicy.load(path)
    entries["obs_mean"] = np.zeros(4)
    entries["w1"] = np.zeros((2, 5))
    np.savez(path, **entries)
    with pytest.raises(PolicyError, match="layer 1 takes 5 inputs, layer 0 gives 3"):
        MlpPolicy.load(path)


def test_missing_entries_and_other_names_raise(tmp_path):
    policy = _policy()
    path = tmp_path / "p.npz"
    policy.save(path)
    with pytest.raises(PolicyError, match=r"missing \['o9'\], unexpected \['o3'\]"):
        MlpPolicy.load(path, obs_names=("o0", "o1", "o2", "o9"))
    with pytest.raises(PolicyError, match="other order"):
        MlpPolicy.load(path, action_names=("a1", "a0"))
    with np.load(path) as data:
        entries = {k: v for k, v in data.items() if k != "obs_var"}
    np.savez(path, **entries)
    with pytest.raises(PolicyError, match=r"missing entries \['obs_var'\]"):
        MlpPolicy.load(path)
    with pytest.raises(PolicyError, match="not a readable policy file"):
        MlpPolicy.load(tmp_path / "absent.npz")


def test_observation_of_the_wrong_length_raises():
    with pytest.raises(PolicyError, match=r"takes \(4,\)"):
        _policy().act(np.zeros(5))


def test_get_up_residual_checks_its_names_and_scale(tmp_path):
    path = tmp_path / "wrong.npz"
    _policy().save(path)
    with pytest.raises(PolicyError, match="observation names differ"):
        PolicyResidual.load(path)
    n_obs, n_act = len(RESIDUAL_OBS_NAMES), len(RESIDUAL_ACTIONS)
    good = _policy(n_obs=n_obs, n_act=n_act)
    scale = np.array([RESIDUAL_MAX_DEG[a] for a in RESIDUAL_ACTIONS])
    fields = {**good.__dict__, "obs_names": RESIDUAL_OBS_NAMES,
              "action_names": tuple(RESIDUAL_ACTIONS), "action_scale": scale}  # fmt: skip
    MlpPolicy(**fields).save(path)
    residual = PolicyResidual.load(path)
    assert residual.residual_deg(np.zeros(n_obs)).shape == (n_act,)
    MlpPolicy(**{**fields, "action_scale": scale * 2}).save(path)
    with pytest.raises(ValueError, match="action scale"):
        PolicyResidual.load(path)


def test_residual_offsets_are_clipped_and_grouped():
    offsets = residual_offsets(np.array([100.0, -3.0, 0.0, 5.0, -100.0]))
    assert offsets["llj3"] == offsets["rlj3"] == RESIDUAL_MAX_DEG["hip_pitch"]
    assert offsets["llj4"] == offsets["rlj4"] == -3.0
    assert offsets["laj1"] == offsets["raj1"] == 5.0
    assert offsets["llj2"] == offsets["rlj2"] == -RESIDUAL_MAX_DEG["hip_roll"]
