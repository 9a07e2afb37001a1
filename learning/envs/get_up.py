"""``GetUpResidualEnv``: learn a residual on top of the get-up keyframes.

Why a residual: the keyframes (``behaviors/data/get_up.yaml``) already stand most robots up;
they fail in a few classes (back sit-ups stalling, front get-ups tipping onto the face, squats
tipping back). A policy that only adds bounded joint-target offsets to them starts from their
success rate and can learn the corrections from the measured lean, where a fixed keyframe
cannot be right for every fall.

One path for perception and action: the environment drives the real agent objects in-process
(a :class:`~learning.local_agent.LocalAgent`'s world model, behaviour manager and the very
``get_up`` skill a match runs) through perception and effector bytes. The policy's action
reaches the skill through its ``residual`` hook (:class:`behaviors.get_up.ResidualSource`), and
its observation is :meth:`behaviors.get_up.GetUpSkill.observe`, the same function the skill
calls when a trained policy runs it in a match.

An episode: a robot of a random (or configured) type lies after a physical fall
(:func:`learning.falls.knock_over`); falls are expensive, so each environment makes a bank of
them once per robot type (:func:`learning.get_up_search.make_bank`, ``Session.save_state``)
and restores one per reset. One step is one 0.02 s agent cycle while a get-up sequence plays;
cycles where the residual does nothing (settling, a side roll) run on inside the same step
with a zero action, so every step the policy takes matters. The episode ends when the skill
reports standing (then the benchmark's half-second hold decides success) or after
``time_limit_s`` (truncated). Reward uses the simulator's ground truth (training only):
progress of torso height times uprightness, a success bonus, a penalty for a failed stand
and for an attempt that falls back, and a small action penalty.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from behaviors.get_up import (
    RESIDUAL_ACTIONS,
    RESIDUAL_MAX_DEG,
    RESIDUAL_OBS_NAMES,
    GetUpSkill,
)
from behaviors.joint_control import CYCLE_SECONDS
from learning.envs.common import (
    EnvConfigError,
    HeldResidual,
    check_robot_types,
    env_config_from_mapping,
    episode_robot_type,
    zero_action_speed,
)
from learning.falls import FALL_DIRECTIONS
from learning.get_up_search import FallBank, closeness, make_bank
from learning.local_agent import LocalAgent
from world.nao_model import ROBOT_TYPES

#: Cycles the robot must still stand after the skill reports standing (the benchmark's rule).
HOLD_CYCLES = 25
ACTION_NAMES = tuple(RESIDUAL_ACTIONS)
ACTION_SCALE = np.array([RESIDUAL_MAX_DEG[name] for name in ACTION_NAMES])


@dataclass(frozen=True)
class GetUpEnvConfig:
    """Settings of :class:`GetUpResidualEnv` (the ``env:`` block of a training config)."""

    robot_types: tuple[int, ...] = tuple(ROBOT_TYPES)
    #: relative frequency of each robot type in resets (None: equal); weights training
    #: towards the types whose keyframes fail most
    type_weights: tuple[float, ...] | None = None
    falls_per_type: int = 12
    directions: tuple[str, ...] = FALL_DIRECTIONS
    #: seed of the fall bank (the falls themselves); resets draw from it with their own seed
    bank_seed: int = 100
    time_limit_s: float = 4.0
    progress_weight: float = 5.0
    success_bonus: float = 5.0
    failure_penalty: float = 2.0
    fall_back_penalty: float = 1.0
    action_penalty: float = 0.05

    def __post_init__(self) -> None:
        check_robot_types(self.robot_types, self.type_weights)
        if self.falls_per_type < 1:
            raise EnvConfigError(f"falls_per_type must be >= 1, got {self.falls_per_type}")
        bad = [d for d in self.directions if d not in FALL_DIRECTIONS]
        if not self.directions or bad:
            raise EnvConfigError(f"directions must be taken from {FALL_DIRECTIONS}, got {bad}")
        if self.time_limit_s <= 0:
            raise EnvConfigError(f"time_limit_s must be > 0, got {self.time_limit_s}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any] | None, where: str = "env") -> GetUpEnvConfig:
        """Build from a YAML mapping (:func:`learning.envs.common.env_config_from_mapping`)."""
        return env_config_from_mapping(cls, data, where)


@dataclass
class _Episode:
    """The live state of one episode."""

    agent: LocalAgent
    skill: GetUpSkill
    robot_type: int
    fall: int
    lying_on: str | None
    cycles: int = 0
    potential: float = 0.0
    #: an episode that ended before the policy's first step (reward, truncated, info)
    ended_early: tuple[float, bool, dict[str, Any]] | None = None


class GetUpResidualEnv(gym.Env):
    """See the module docstring. ``reset(options={"robot_type": t, "fall": i})`` picks a
    given fall of the bank (evaluation); otherwise the type (by ``type_weights``) and the
    fall are drawn from the environment's seeded generator."""

    metadata = {"render_modes": []}  # noqa: RUF012  (gymnasium's convention)
    #: what an exported policy file records (learning/export.py) and the skill checks
    observation_names = RESIDUAL_OBS_NAMES
    action_names = ACTION_NAMES
    action_scale = ACTION_SCALE

    def __init__(self, config: GetUpEnvConfig | Mapping[str, Any] | None = None) -> None:
        super().__init__()
        if not isinstance(config, GetUpEnvConfig):
            config = GetUpEnvConfig.from_mapping(config)
        self.config = config
        self.observation_space = spaces.Box(
            -1e4, 1e4, shape=(len(RESIDUAL_OBS_NAMES),), dtype=np.float32
        )
        self.action_space = spaces.Box(-1.0, 1.0, shape=(len(ACTION_NAMES),), dtype=np.float32)
        self._banks: dict[int, FallBank] = {}
        self._held = HeldResidual(len(ACTION_NAMES))
        self._episode: _Episode | None = None
        self._limit_cycles = round(config.time_limit_s / CYCLE_SECONDS)

    # ------------------------------------------------------------------ the fall bank
    def bank(self, robot_type: int) -> FallBank:
        """The falls of one robot type, made on first use (seconds of simulation each)."""
        if robot_type not in self._banks:
            config = self.config
            self._banks[robot_type] = make_bank(
                robot_type,
                list(config.directions),
                config.falls_per_type,
                config.bank_seed + 1000 * robot_type,
            )
            if not self._banks[robot_type].states:
                raise RuntimeError(f"type {robot_type}: no fall came to rest lying")
        return self._banks[robot_type]

    # ------------------------------------------------------------------ gymnasium API
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        options = options or {}
        config = self.config
        robot_type = episode_robot_type(
            self.np_random, options, config.robot_types, config.type_weights
        )
        bank = self.bank(robot_type)
        fall = options.get("fall")
        if fall is None:
            fall = int(self.np_random.integers(len(bank.states)))
        agent, skill = bank.restore(fall)
        skill.residual = self._held
        # the benchmark perceives once more after the fall (the same bytes): so do we
        agent.perceive()
        lying_on = bank.states[fall].lying_on
        self._episode = _Episode(agent, skill, bank.robot_type, fall, lying_on)
        self._episode.potential = closeness(agent)
        reward, done, info = self._advance()
        if done:  # over before the residual ever acted: the first step reports it
            truncated = info.pop("truncated", False)
            self._episode.ended_early = (reward, truncated, info)
        return skill.observe(agent.state), self._info({})

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        episode = self._episode
        if episode is None:
            raise RuntimeError("step() before reset(), or after the episode ended")
        if episode.ended_early is not None:
            self._episode = None
            reward, truncated, info = episode.ended_early
            obs = episode.skill.observe(episode.agent.state)
            return obs, reward, not truncated, truncated, self._info(info, episode)
        raw = np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
        self._held.hold(raw * ACTION_SCALE)
        reward = -self.config.action_penalty * float(np.mean(raw**2))
        gained, done, info = self._cycle()
        reward += gained
        self._held.release()
        if not done:
            more, done, info = self._advance()
            reward += more
        truncated = info.pop("truncated", False)
        terminated = done and not truncated
        obs = episode.skill.observe(episode.agent.state)
        if done:
            self._episode = None
        return obs, reward, terminated, truncated, self._info(info, episode)

    # ------------------------------------------------------------------ cycles
    def _advance(self) -> tuple[float, bool, dict[str, Any]]:
        """Run cycles until the residual acts in the next one, or the episode ends."""
        episode = self._episode
        assert episode is not None
        total = 0.0
        while not episode.skill.residual_active:
            reward, done, info = self._cycle()
            total += reward
            if done:
                return total, True, info
        return total, False, {}

    def _cycle(self) -> tuple[float, bool, dict[str, Any]]:
        """One agent cycle of ``get_up`` (the rest of the cycle after perceiving: execute,
        effector bytes, server step, the next perception) and its reward."""
        episode = self._episode
        assert episode is not None
        config = self.config
        was_rising = episode.skill.residual_active
        finished = self._run_cycle(episode.agent, "get_up")
        episode.cycles += 1
        potential = closeness(episode.agent)
        reward = config.progress_weight * (potential - episode.potential)
        episode.potential = potential
        if finished:
            success = self._holds(episode.agent)
            reward += config.success_bonus if success else -config.failure_penalty
            return reward, True, {"success": success}
        if was_rising and not episode.skill.residual_active:
            reward -= config.fall_back_penalty  # the attempt ended lying: it starts over
        if episode.cycles >= self._limit_cycles:
            return reward, True, {"success": False, "truncated": True}
        return reward, False, {}

    @staticmethod
    def _run_cycle(agent: LocalAgent, name: str, *args: object) -> bool:
        """One cycle that ends perceiving (the next observation is this step's outcome)."""
        finished = agent.decide(name, *args)
        agent.session.step()
        agent.perceive()
        return finished

    def _holds(self, agent: LocalAgent) -> bool:
        """The benchmark's success: standing now and after half a second in ``stand``."""
        standing = agent.is_standing()
        for _ in range(HOLD_CYCLES):
            self._run_cycle(agent, "pose", "stand")
        return standing and agent.is_standing()

    def _info(self, info: dict[str, Any], episode: _Episode | None = None) -> dict[str, Any]:
        episode = episode or self._episode
        out = dict(info)
        if episode is not None:
            out.update(
                robot_type=episode.robot_type,
                fall=episode.fall,
                lying_on=episode.lying_on,
                seconds=episode.cycles * CYCLE_SECONDS,
            )
        return out

    def close(self) -> None:
        for bank in self._banks.values():
            bank.session.close()
        self._banks.clear()


def measure_speed(config: GetUpEnvConfig, seconds: float, seed: int = 0) -> dict[str, float]:
    """Environment steps per second with zero actions (the keyframes alone), after the fall
    bank is built, and the success rate of the episodes run meanwhile."""
    env = GetUpResidualEnv(config)
    try:
        start = time.monotonic()
        for robot_type in config.robot_types:
            env.bank(robot_type)
        bank_s = time.monotonic() - start
        steps_per_s, endings = zero_action_speed(env, seconds, seed)
    finally:
        env.close()
    successes = sum(bool(info.get("success")) for _, info in endings)
    return {
        "bank_s": bank_s,
        "steps_per_s": steps_per_s,
        "episodes": len(endings),
        "success": successes / max(1, len(endings)),
    }
