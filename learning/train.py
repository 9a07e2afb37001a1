"""Train a policy with stable-baselines3 PPO from a YAML config, and export it for numpy.

Run::

    nice -n 5 .venv/bin/python -m learning.train --config config/train/get_up.yaml \\
        --out runs/get_up_X [--max-minutes 60] [--total-timesteps N] [--resume runs/get_up_W]

The config (validated; every error names its key) has three blocks: ``env_id`` and ``env``
(the gymnasium id and its config mapping), ``ppo`` (PPO's settings) and ``train`` (seed,
steps, checkpoints, observation/reward normalisation, log interval). The run directory gets:
``config.yaml`` (the config as used, overrides included) and ``meta.json`` (git commit, seed,
command line) at the start; ``checkpoints/`` every ``checkpoint_every`` steps (model and
normaliser); at the end ``model.zip``, ``vecnormalize.pkl`` and ``policy.npz``, the actor
exported by :mod:`learning.export` with the config and the commit inside. Progress is one log
line every ``log_every`` steps (steps, steps/s, episodes, success rate and return of the
recent episodes, over every environment). Runs are reproducible for a given seed on one
machine (one thread: ``torch.set_num_threads(1)``). ``train.n_envs`` > 1 steps that many
environments in worker processes (a core each); ``ppo.use_sde`` explores with gSDE.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import sys
import time
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from functools import partial
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch
import yaml
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.utils import set_random_seed
from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv, VecNormalize
from torch import nn

import learning.envs  # noqa: F401  (registers the environments)
from learning.export import export_policy, git_commit
from world.yaml_config import ConfigError, config_from_mapping


class TrainConfigError(ValueError):
    """A training config that cannot be used; the message names the key."""


@dataclass(frozen=True)
class PpoConfig:
    """PPO's settings (stable-baselines3 names)."""

    n_steps: int = 2048
    batch_size: int = 256
    n_epochs: int = 10
    learning_rate: float = 3e-4
    gamma: float = 0.99
    gae_lambda: float = 0.95
    clip_range: float = 0.2
    ent_coef: float = 0.0
    vf_coef: float = 0.5
    max_grad_norm: float = 0.5
    net_arch: tuple[int, ...] = (64, 64)
    activation: str = "tanh"
    #: initial log standard deviation of the actions (-1: std 0.37 of the [-1, 1] range)
    log_std_init: float = -1.0
    #: generalised state-dependent exploration (gSDE): the exploration noise is a function
    #: of the observation, redrawn every ``sde_sample_freq`` steps (-1: once per rollout),
    #: so it is smooth in time; iid noise on joint targets every 20 ms shakes a robot that
    #: the keyframes alone would stand up (docs/tuning-history.md, learned residuals)
    use_sde: bool = False
    sde_sample_freq: int = -1

    def __post_init__(self) -> None:
        _check_non_negative_ints(self, allowed_negative=("sde_sample_freq",))
        if not all(width > 0 for width in self.net_arch):
            raise TrainConfigError(f"net_arch must list positive integers, got {self.net_arch}")


@dataclass(frozen=True)
class RunConfig:
    """How long and how reproducibly to train."""

    seed: int = 0
    #: environments stepped in parallel, each in a process of its own (1: in this process);
    #: PPO's ``n_steps`` is per environment, so a rollout holds n_envs * n_steps steps
    n_envs: int = 1
    total_timesteps: int = 200_000
    checkpoint_every: int = 50_000
    log_every: int = 10_000
    norm_obs: bool = True
    norm_reward: bool = True
    clip_obs: float = 10.0

    def __post_init__(self) -> None:
        _check_non_negative_ints(self)


@dataclass(frozen=True)
class TrainConfig:
    env_id: str
    env: Mapping[str, Any] = field(default_factory=dict)
    ppo: PpoConfig = field(default_factory=PpoConfig)
    train: RunConfig = field(default_factory=RunConfig)


_ACTIVATIONS = {"tanh": nn.Tanh, "relu": nn.ReLU}
#: What the exported policy file takes from the environment.
_EXPORTED_ENV_ATTRIBUTES = ("observation_names", "action_names", "action_scale")


def _make_env(env_id: str, env_config: dict[str, Any]) -> gym.Env:
    """One environment; a module-level function so that a worker process can build it
    (unpickling it imports this module, whose imports register the project's environments)."""
    return gym.make(env_id, config=env_config)


def _start_method() -> str:
    """How worker environments start: a fork server where the platform has one (workers do
    not inherit this process's torch threads or open simulators), else a fresh interpreter."""
    return "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"


def _section(cls: type, data: Any, where: str) -> Any:
    """One block of the config as its dataclass, through the project's YAML validation
    (:func:`world.yaml_config.config_from_mapping`: unknown keys, types), as a
    :class:`TrainConfigError` naming the block."""
    if data is None:
        return cls()
    try:
        return config_from_mapping(cls, data, source=where)
    except ConfigError as error:
        raise TrainConfigError(str(error)) from None


def _check_non_negative_ints(config: Any, allowed_negative: tuple[str, ...] = ()) -> None:
    """Counts, sizes and seeds are integers >= 0 (the types are checked on reading)."""
    for item in fields(config):
        value = getattr(config, item.name)
        if item.name in allowed_negative:
            continue
        if isinstance(value, int) and not isinstance(value, bool) and value < 0:
            raise TrainConfigError(f"{item.name} must be an integer >= 0, got {value!r}")


def parse_config(data: Any, where: str = "config") -> TrainConfig:
    """Validate a training config mapping (as read from YAML)."""
    if not isinstance(data, Mapping):
        raise TrainConfigError(f"{where} must be a mapping with env_id, env, ppo, train")
    unknown = sorted(set(data) - {"env_id", "env", "ppo", "train"})
    if unknown:
        raise TrainConfigError(f"{where}: unknown keys {unknown}; known: env_id, env, ppo, train")
    env_id = data.get("env_id")
    if not isinstance(env_id, str) or env_id not in gym.registry:
        known = sorted(k for k in gym.registry if k.startswith("naosoccer/"))
        raise TrainConfigError(f"{where}.env_id must be one of {known}, got {env_id!r}")
    env = data.get("env") or {}
    if not isinstance(env, Mapping):
        raise TrainConfigError(f"{where}.env must be a mapping, got {env!r}")
    ppo = _section(PpoConfig, data.get("ppo"), f"{where}.ppo")
    if ppo.activation not in _ACTIVATIONS:
        raise TrainConfigError(f"{where}.ppo.activation must be one of {sorted(_ACTIVATIONS)}")
    if ppo.batch_size < 2 or ppo.n_steps < ppo.batch_size:
        raise TrainConfigError(f"{where}.ppo: need 2 <= batch_size <= n_steps")
    run = _section(RunConfig, data.get("train"), f"{where}.train")
    if run.total_timesteps < 1 or run.log_every < 1 or run.n_envs < 1:
        raise TrainConfigError(f"{where}.train: total_timesteps, log_every and n_envs must be >= 1")
    return TrainConfig(env_id, dict(env), ppo, run)


def load_config(path: str | Path) -> tuple[TrainConfig, dict[str, Any]]:
    """The validated config and the raw mapping (saved beside the model)."""
    path = Path(path)
    try:
        raw = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as error:
        raise TrainConfigError(f"{path}: cannot read ({error})") from error
    return parse_config(raw, str(path)), raw


class ProgressLog(BaseCallback):
    """One line every ``every`` steps; stops training after ``max_seconds`` (None: never)."""

    def __init__(self, every: int, max_seconds: float | None = None, window: int = 200) -> None:
        super().__init__()
        self.every = every
        self.max_seconds = max_seconds
        self.returns: deque[float] = deque(maxlen=window)
        self.successes: deque[float] = deque(maxlen=window)
        self.lengths: deque[int] = deque(maxlen=window)
        self.episodes = 0
        #: per environment: the return and length of the episode under way (rewards as the
        #: algorithm sees them, i.e. normalised where norm_reward is on)
        self._running = np.zeros(0)
        self._steps_in_episode = np.zeros(0, dtype=int)
        self._start = time.monotonic()
        self._next = every

    def _on_step(self) -> bool:
        rewards, dones, infos = self.locals["rewards"], self.locals["dones"], self.locals["infos"]
        if len(self._running) != len(rewards):
            self._running = np.zeros(len(rewards))
            self._steps_in_episode = np.zeros(len(rewards), dtype=int)
        self._running += rewards
        self._steps_in_episode += 1
        for i in np.flatnonzero(dones):
            self.episodes += 1
            self.returns.append(float(self._running[i]))
            self.lengths.append(int(self._steps_in_episode[i]))
            self.successes.append(float(infos[i].get("success", False)))
            self._running[i] = 0.0
            self._steps_in_episode[i] = 0
        if self.num_timesteps >= self._next:
            self._next += self.every
            print(self.summary(), flush=True)
        elapsed = time.monotonic() - self._start
        return self.max_seconds is None or elapsed < self.max_seconds

    def summary(self) -> str:
        elapsed = time.monotonic() - self._start
        success = np.mean(self.successes) if self.successes else float("nan")
        ret = np.mean(self.returns) if self.returns else float("nan")
        length = np.mean(self.lengths) if self.lengths else float("nan")
        return (
            f"steps {self.num_timesteps} ({self.num_timesteps / max(elapsed, 1e-9):.0f}/s), "
            f"episodes {self.episodes}, last {len(self.successes)}: success {success:.3f}, "
            f"return {ret:.2f}, length {length:.0f} steps, {elapsed / 60:.1f} min"
        )


class Checkpoints(BaseCallback):
    """Model and normaliser every ``every`` steps, under ``out/checkpoints``."""

    def __init__(self, out: Path, every: int) -> None:
        super().__init__()
        self.out = out
        self.every = every
        self._next = every

    def _on_step(self) -> bool:
        if self.every and self.num_timesteps >= self._next:
            self._next += self.every
            self.out.mkdir(parents=True, exist_ok=True)
            self.model.save(self.out / f"model_{self.num_timesteps}.zip")
            normalizer = self.model.get_vec_normalize_env()
            if normalizer is not None:
                normalizer.save(str(self.out / f"vecnormalize_{self.num_timesteps}.pkl"))
        return True


def make_model(config: TrainConfig, resume: Path | None = None) -> tuple[PPO, VecNormalize]:
    """The vectorised, normalised environment (one env, this process) and its PPO model;
    ``resume`` (a run directory) continues that run's ``model.zip`` and normaliser."""
    run, ppo = config.train, config.ppo
    set_random_seed(run.seed)
    makers = [partial(_make_env, config.env_id, dict(config.env)) for _ in range(run.n_envs)]
    venv = DummyVecEnv(makers) if run.n_envs == 1 else SubprocVecEnv(makers, _start_method())
    venv.seed(run.seed)
    if resume is not None:
        env = VecNormalize.load(str(resume / "vecnormalize.pkl"), venv)
        return PPO.load(resume / "model.zip", env=env, device="cpu", seed=run.seed), env
    env = VecNormalize(
        venv, norm_obs=run.norm_obs, norm_reward=run.norm_reward, clip_obs=run.clip_obs,
        gamma=ppo.gamma,
    )  # fmt: skip
    model = PPO(
        "MlpPolicy",
        env,
        n_steps=ppo.n_steps,
        batch_size=ppo.batch_size,
        n_epochs=ppo.n_epochs,
        learning_rate=ppo.learning_rate,
        gamma=ppo.gamma,
        gae_lambda=ppo.gae_lambda,
        clip_range=ppo.clip_range,
        ent_coef=ppo.ent_coef,
        vf_coef=ppo.vf_coef,
        max_grad_norm=ppo.max_grad_norm,
        use_sde=ppo.use_sde,
        sde_sample_freq=ppo.sde_sample_freq,
        policy_kwargs={
            "net_arch": {"pi": list(ppo.net_arch), "vf": list(ppo.net_arch)},
            "activation_fn": _ACTIVATIONS[ppo.activation],
            "log_std_init": ppo.log_std_init,
        },
        seed=run.seed,
        device="cpu",
        verbose=0,
    )
    return model, env


def train(
    config: TrainConfig,
    raw: Mapping[str, Any],
    out: Path,
    max_minutes: float | None = None,
    resume: Path | None = None,
) -> Path:
    """Train, checkpoint and export; returns the path of the exported ``policy.npz``."""
    torch.set_num_threads(1)
    out.mkdir(parents=True, exist_ok=True)
    config_text = yaml.safe_dump(dict(raw), sort_keys=False)
    (out / "config.yaml").write_text(config_text)
    commit = git_commit()
    meta = {
        "git_commit": commit,
        "seed": config.train.seed,
        "argv": sys.argv,
        "resumed_from": None if resume is None else str(resume),
    }
    (out / "meta.json").write_text(json.dumps(meta, indent=2) + "\n")
    model, env = make_model(config, resume)
    progress = ProgressLog(
        config.train.log_every, None if max_minutes is None else max_minutes * 60
    )
    callbacks = [progress, Checkpoints(out / "checkpoints", config.train.checkpoint_every)]
    try:
        model.learn(total_timesteps=config.train.total_timesteps, callback=callbacks)
        print(progress.summary(), flush=True)
        model.save(out / "model.zip")
        env.save(str(out / "vecnormalize.pkl"))
        names = {key: env.get_attr(key, indices=0)[0] for key in _EXPORTED_ENV_ATTRIBUTES}
        export_policy(
            model, env, out / "policy.npz", names["observation_names"], names["action_names"],
            names["action_scale"], config_text, commit,
        )  # fmt: skip
    finally:
        env.close()
    return out / "policy.npz"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--config", type=Path, required=True, help="training config (YAML)")
    parser.add_argument("--out", type=Path, required=True, help="run directory (created)")
    parser.add_argument("--max-minutes", type=float, help="stop (and export) after this long")
    parser.add_argument("--total-timesteps", type=int, help="override train.total_timesteps")
    parser.add_argument("--seed", type=int, help="override train.seed")
    parser.add_argument(
        "--resume",
        type=Path,
        help="continue the model and normaliser of this finished run directory (the config's "
        "env and train blocks apply; its ppo block is the resumed model's)",
    )
    args = parser.parse_args(argv)
    try:
        _, raw = load_config(args.config)
        raw = dict(raw)
        overrides = {"total_timesteps": args.total_timesteps, "seed": args.seed}
        train_block = dict(raw.get("train") or {})
        train_block.update({k: v for k, v in overrides.items() if v is not None})
        raw["train"] = train_block
        config = parse_config(raw, str(args.config))
    except TrainConfigError as error:
        parser.error(str(error))
    path = train(config, raw, args.out, args.max_minutes, args.resume)
    print(f"exported {path}")


if __name__ == "__main__":
    main()
