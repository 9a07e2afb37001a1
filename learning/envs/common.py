"""What the residual-learning environments share: their configs' robot types (with weights),
errors and reading from a training config's ``env:`` block; the residual the policy's action
hands to the skill; and timing an environment."""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from typing import Any, TypeVar

import numpy as np

from world.nao_model import ROBOT_TYPES
from world.yaml_config import ConfigError, config_from_mapping

Config = TypeVar("Config")


class EnvConfigError(ValueError):
    """An environment setting that cannot be used; the message names the key."""


def check_robot_types(robot_types: Sequence[int], type_weights: Sequence[float] | None) -> None:
    """Robot types must be known and non-empty; weights (None: equal) one per type, >= 0,
    not all 0."""
    unknown = [t for t in robot_types if t not in ROBOT_TYPES]
    if not robot_types or unknown:
        raise EnvConfigError(f"robot_types must be a non-empty list of {list(ROBOT_TYPES)}")
    if type_weights is not None and (
        len(type_weights) != len(robot_types) or min(type_weights) < 0 or sum(type_weights) <= 0
    ):
        raise EnvConfigError(
            "type_weights must give one weight >= 0 per robot type (not all 0), "
            f"got {type_weights} for {robot_types}"
        )


def episode_robot_type(
    rng: np.random.Generator,
    options: Mapping[str, Any],
    robot_types: Sequence[int],
    type_weights: Sequence[float] | None,
) -> int:
    """The robot type of an episode: ``options['robot_type']`` where ``reset`` was given one,
    else drawn by ``type_weights`` (equal where None)."""
    chosen = options.get("robot_type")
    if chosen is not None:
        return int(chosen)
    weights = np.array(type_weights or [1.0] * len(robot_types))
    return int(robot_types[int(rng.choice(len(robot_types), p=weights / weights.sum()))])


def env_config_from_mapping(
    cls: type[Config], data: Mapping[str, Any] | None, where: str
) -> Config:
    """Build an environment config dataclass from a YAML mapping through the project's YAML
    validation (:func:`world.yaml_config.config_from_mapping`): unknown keys, wrong types and
    the class's own checks raise an :class:`EnvConfigError` naming the key."""
    try:
        return config_from_mapping(cls, dict(data or {}), source=where)
    except ConfigError as error:
        raise EnvConfigError(str(error)) from None


def zero_action_speed(
    env: Any, seconds: float, seed: int = 0
) -> tuple[float, list[tuple[bool, dict[str, Any]]]]:
    """Step ``env`` with zero actions for ``seconds`` of wall time: (steps per second, each
    finished episode's (terminated, last info)). Why zero: it times the simulation and the
    skill underneath, the part of a training run that does not depend on the policy."""
    env.reset(seed=seed)
    zero = np.zeros(env.action_space.shape, dtype=np.float32)
    steps, endings = 0, []
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        _, _, terminated, truncated, info = env.step(zero)
        steps += 1
        if terminated or truncated:
            endings.append((bool(terminated), info))
            env.reset()
    return steps / (time.monotonic() - start), endings


class HeldResidual:
    """A skill's residual source inside a training environment: the offsets of the step under
    way (the skill's units, set by the environment from the policy's action), zero between
    steps. The skill's observation is the environment's to hand out, so it is ignored here."""

    def __init__(self, size: int) -> None:
        self.residual = np.zeros(size)

    def hold(self, residual: np.ndarray) -> None:
        """Act with ``residual`` until :meth:`release`."""
        self.residual = residual

    def release(self) -> None:
        self.residual = np.zeros_like(self.residual)

    def residual_deg(self, observation: np.ndarray) -> np.ndarray:
        return self.residual
