"""Export a trained stable-baselines3 PPO actor to the numpy policy file a behaviour loads.

Why: a playing agent runs policies without torch (:mod:`behaviors.policy`). The export takes
the actor's layers (``mlp_extractor.policy_net`` then ``action_net``: the deterministic action
PPO's ``predict(..., deterministic=True)`` gives), the observation normalisation of the
``VecNormalize`` wrapper it was trained behind, and writes them with the names of the
observation and action entries, the action scale, the training config and the git commit.
"""

from __future__ import annotations

import argparse
import pickle
import subprocess
from collections.abc import Sequence
from pathlib import Path

import gymnasium as gym
import numpy as np
import yaml
from stable_baselines3 import PPO
from stable_baselines3.common.torch_layers import FlattenExtractor
from stable_baselines3.common.vec_env import VecNormalize
from torch import nn

import learning.envs  # noqa: F401  (registers the environments)
from behaviors.policy import MlpPolicy

_ACTIVATIONS = {nn.Tanh: "tanh", nn.ReLU: "relu"}


class ExportError(ValueError):
    """A model whose actor this exporter cannot turn into an :class:`MlpPolicy`."""


def git_commit(repo: Path | None = None) -> str:
    """The checkout's commit, with ``-dirty`` when tracked files differ from it; "unknown"
    outside git."""
    where = repo or Path(__file__).resolve().parents[1]
    try:
        commit = subprocess.run(
            ["git", "rev-parse", "HEAD"], cwd=where, capture_output=True, text=True, check=True
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=where,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return f"{commit}-dirty" if dirty else commit


def actor_layers(model: PPO) -> tuple[list[np.ndarray], list[np.ndarray], str]:
    """Weights, biases and hidden activation of the PPO actor (Linear/activation pairs)."""
    policy = model.policy
    if not isinstance(policy.features_extractor, FlattenExtractor):
        raise ExportError("only flat Box observations (FlattenExtractor) are supported")
    weights, biases, activation = [], [], None
    for module in policy.mlp_extractor.policy_net:
        if isinstance(module, nn.Linear):
            weights.append(module.weight.detach().cpu().numpy().astype(np.float64))
            biases.append(module.bias.detach().cpu().numpy().astype(np.float64))
        elif type(module) in _ACTIVATIONS:
            name = _ACTIVATIONS[type(module)]
            if activation not in (None, name):
                raise ExportError("the actor mixes activations")
            activation = name
        else:
            raise ExportError(f"cannot export actor layer {module!r}")
    head = policy.action_net
    if not isinstance(head, nn.Linear):
        raise ExportError(f"cannot export action head {head!r}")
    weights.append(head.weight.detach().cpu().numpy().astype(np.float64))
    biases.append(head.bias.detach().cpu().numpy().astype(np.float64))
    return weights, biases, activation or "tanh"


def export_policy(
    model: PPO,
    normalizer: VecNormalize | None,
    path: str | Path,
    obs_names: Sequence[str],
    action_names: Sequence[str],
    action_scale: Sequence[float] | np.ndarray,
    config_text: str = "",
    commit: str | None = None,
) -> MlpPolicy:
    """Write the actor of ``model`` to ``path`` (``.npz``) and return it as loaded back."""
    weights, biases, activation = actor_layers(model)
    n_obs = weights[0].shape[1]
    if normalizer is not None and normalizer.norm_obs:
        rms = normalizer.obs_rms
        mean, var = np.asarray(rms.mean, dtype=np.float64), np.asarray(rms.var, dtype=np.float64)
        epsilon, clip = float(normalizer.epsilon), float(normalizer.clip_obs)
    else:  # no normalisation: the identity (var 1 - epsilon, a clip nothing reaches)
        epsilon, clip = 1e-8, 1e9
        mean, var = np.zeros(n_obs), np.full(n_obs, 1.0 - epsilon)
    policy = MlpPolicy(
        weights=tuple(weights),
        biases=tuple(biases),
        activation=activation,
        obs_mean=mean,
        obs_var=var,
        obs_epsilon=epsilon,
        obs_clip=clip,
        action_scale=np.asarray(action_scale, dtype=np.float64),
        obs_names=tuple(obs_names),
        action_names=tuple(action_names),
        config_text=config_text,
        git_commit=git_commit() if commit is None else commit,
    )
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    policy.save(path)
    return MlpPolicy.load(path, obs_names, action_names)


def export_checkpoint(run: Path, step: int, out: Path | None = None) -> MlpPolicy:
    """Export checkpoint ``step`` of training run ``run`` (``checkpoints/model_STEP.zip`` and
    its normaliser) to ``out`` (default ``run/policy_STEP.npz``): to evaluate a run while it
    trains, or an earlier checkpoint than its end."""
    config = yaml.safe_load((run / "config.yaml").read_text())
    model = PPO.load(run / "checkpoints" / f"model_{step}.zip", device="cpu")
    with open(run / "checkpoints" / f"vecnormalize_{step}.pkl", "rb") as file:
        normalizer = pickle.load(file)  # the pickle holds no environment: only the statistics
    env = gym.make(config["env_id"], config=config.get("env")).unwrapped
    try:
        return export_policy(
            model,
            normalizer,
            out or run / f"policy_{step}.npz",
            env.observation_names,
            env.action_names,
            env.action_scale,
            yaml.safe_dump(config),
        )
    finally:
        env.close()


def main(argv: list[str] | None = None) -> None:
    """``python -m learning.export --run runs/X --step N [--out FILE]``."""
    parser = argparse.ArgumentParser(description=export_checkpoint.__doc__)
    parser.add_argument("--run", type=Path, required=True)
    parser.add_argument("--step", type=int, required=True)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    policy = export_checkpoint(args.run, args.step, args.out)
    print(f"exported step {args.step}: {policy.n_obs} observations -> {policy.n_actions} actions")


if __name__ == "__main__":
    main()
