"""``WalkResidualEnv``: learn a residual on the walk engine's leg joints (``learned_walk``).

Why a residual: the engine (``behaviors/walk.py``) already walks every robot type at
0.73-0.78 m/s with its phase, balance corrections and odometry; what it lacks is speed (issue
4 asks 0.9 m/s of the walk and 1.0 m/s of the dribbles on top of it) and a stop that never
tips type 2 back. A policy that adds bounded leg-joint offsets starts from the engine's gait
and keeps everything the dribbles and the kick in motion rely on (the phase above all).

One path for perception and action, as in the get-up environment: the real agent objects run
in-process (a :class:`~learning.local_agent.LocalAgent`'s world model and behaviour manager,
the very ``learned_walk`` skill a match runs) through perception and effector bytes; the
policy's action reaches the skill through its ``residual`` hook and its observation is
:meth:`behaviors.learned_walk.LearnedWalkSkill.observe` (canonical frame: left leg swinging;
the skill mirrors the right leg's half-cycles, see its module).

An episode: a robot of a random (or configured) type stands in its own half in PlayOn (one
standing snapshot per type, ``Session.save_state``, restored per reset); it is commanded a
velocity (forward up to ``max_forward`` m/s, some sideways and turning) that changes every
``command_every_s``; one step is one 0.02 s cycle. Reward (simulator ground truth, training
only): how closely the torso's velocity over the last step (8 cycles, so the sway averages
out) tracks the command, forward-sideways and turning, a small action penalty, and a penalty
for a fall, which ends the episode; ``episode_s`` truncates it.
"""

from __future__ import annotations

import copy
import math
import time
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from behaviors.joint_control import CYCLE_SECONDS
from behaviors.learned_walk import ACTION_SCALE, LEG_JOINTS, OBS_NAMES, LearnedWalkSkill
from learning.envs.common import (
    EnvConfigError,
    HeldResidual,
    check_robot_types,
    env_config_from_mapping,
    episode_robot_type,
    zero_action_speed,
)
from learning.local_agent import LocalAgent
from sim.session import Session, SessionConfig, SessionSnapshot
from world.nao_model import ROBOT_TYPES
from world.world_model import WorldModel

#: Where the robot stands at the start: deep in its own half facing the opponent goal, so
#: 8 s at 1 m/s stays clear of the ball at the centre.
START_POSE = (-12.0, 0.0, 0.0)
#: Cycles of one step: the window the torso's velocity is measured over.
VELOCITY_WINDOW = 8
#: A torso tilted further than this from upright counts as fallen (ends the episode).
FALL_TILT_DEG = 45.0


@dataclass(frozen=True)
class WalkEnvConfig:
    """Settings of :class:`WalkResidualEnv` (the ``env:`` block of a training config)."""

    robot_types: tuple[int, ...] = tuple(ROBOT_TYPES)
    #: relative frequency of each robot type in resets (None: equal)
    type_weights: tuple[float, ...] | None = None
    episode_s: float = 8.0
    command_every_s: float = 2.0
    #: forward commands are drawn from [min_forward, max_forward] m/s ...
    min_forward: float = 0.0
    max_forward: float = 1.0
    #: ... sideways from +-max_side m/s and turning from +-max_turn_deg deg/s, except in the
    #: share ``straight_share`` of commands, which only go forward
    max_side: float = 0.2
    max_turn_deg: float = 45.0
    straight_share: float = 0.5
    #: tracking reward: exp(-(velocity error / sigma)^2)
    speed_sigma: float = 0.25
    turn_sigma_deg: float = 30.0
    turn_weight: float = 0.5
    fall_penalty: float = 10.0
    action_penalty: float = 0.05
    seed: int = 0
    #: walk settings to use instead of ``behaviors/data/walk.yaml`` (None: that file); a study
    #: of other gait settings points this at its edited copy
    walk_file: str | None = None

    def __post_init__(self) -> None:
        check_robot_types(self.robot_types, self.type_weights)
        positive = ("episode_s", "command_every_s", "speed_sigma", "turn_sigma_deg")
        for key in positive:
            if getattr(self, key) <= 0:
                raise EnvConfigError(f"{key} must be > 0, got {getattr(self, key)}")
        if not 0 <= self.min_forward <= self.max_forward:
            raise EnvConfigError(
                f"need 0 <= min_forward <= max_forward, got {self.min_forward}, {self.max_forward}"
            )
        if not 0 <= self.straight_share <= 1:
            raise EnvConfigError(f"straight_share must be in [0, 1], got {self.straight_share}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any] | None, where: str = "env") -> WalkEnvConfig:
        """Build from a YAML mapping (:func:`learning.envs.common.env_config_from_mapping`)."""
        return env_config_from_mapping(cls, data, where)


@dataclass
class _Standing:
    """One robot type standing in its own session, ready to be restored."""

    session: Session
    agent: int
    snapshot: SessionSnapshot
    world: WorldModel


@dataclass
class _Episode:
    agent: LocalAgent
    skill: LearnedWalkSkill
    robot_type: int
    command: tuple[float, float, float] = (0.0, 0.0, 0.0)
    cycles: int = 0
    #: ground-truth torso (x, y, yaw deg) of the last VELOCITY_WINDOW + 1 cycles
    poses: deque = field(default_factory=lambda: deque(maxlen=VELOCITY_WINDOW + 1))


def draw_command(rng: np.random.Generator, config: WalkEnvConfig) -> tuple[float, float, float]:
    """A random ``walk_velocity`` command (vx m/s, vy m/s, turn deg/s) in ``config``'s ranges:
    the episodes' commands, and those of ``learning.walk_search``'s mixed runs."""
    forward = float(rng.uniform(config.min_forward, config.max_forward))
    if rng.uniform() < config.straight_share:
        return (forward, 0.0, 0.0)
    side = float(rng.uniform(-config.max_side, config.max_side))
    turn = float(rng.uniform(-config.max_turn_deg, config.max_turn_deg))
    return (forward, side, turn)


class WalkResidualEnv(gym.Env):
    """See the module docstring. ``reset(options={"robot_type": t, "command": (vx, vy,
    turn)})`` fixes the type and holds one command for the whole episode (evaluation)."""

    metadata = {"render_modes": []}  # noqa: RUF012  (gymnasium's convention)
    #: what an exported policy file records (learning/export.py) and the skill checks
    observation_names = OBS_NAMES
    action_names = LEG_JOINTS
    action_scale = ACTION_SCALE

    def __init__(self, config: WalkEnvConfig | Mapping[str, Any] | None = None) -> None:
        super().__init__()
        if not isinstance(config, WalkEnvConfig):
            config = WalkEnvConfig.from_mapping(config)
        self.config = config
        self.observation_space = spaces.Box(-1e4, 1e4, shape=(len(OBS_NAMES),), dtype=np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, shape=(len(LEG_JOINTS),), dtype=np.float32)
        self._standing: dict[int, _Standing] = {}
        self._held = HeldResidual(len(LEG_JOINTS))
        self._episode: _Episode | None = None
        self._fixed_command: tuple[float, float, float] | None = None
        self._limit_cycles = round(config.episode_s / CYCLE_SECONDS)
        self._command_cycles = max(1, round(config.command_every_s / CYCLE_SECONDS))

    # ------------------------------------------------------------------ standing robots
    def standing(self, robot_type: int) -> _Standing:
        """A robot of ``robot_type`` standing at the start pose (made on first use)."""
        if robot_type not in self._standing:
            session = Session(SessionConfig(seed=self.config.seed + robot_type, beam_noise=False))
            local = LocalAgent.join(session, "Walkers", 1, robot_type, beam=START_POSE)
            local.trainer("(playMode PlayOn)")
            local.rise_to_stand()
            local.perceive()
            self._standing[robot_type] = _Standing(
                session, local.agent, session.save_state(), copy.deepcopy(local.world)
            )
        return self._standing[robot_type]

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
        standing = self.standing(robot_type)
        agent = LocalAgent.from_snapshot(
            standing.session,
            standing.agent,
            robot_type,
            "Walkers",
            standing.snapshot,
            standing.world,
        )
        skill = agent.behavior.skill("learned_walk")
        assert isinstance(skill, LearnedWalkSkill)
        skill.residual = self._held
        if config.walk_file is not None:
            skill.walk_file = Path(config.walk_file)
        fixed = options.get("command")
        self._fixed_command = None if fixed is None else tuple(float(v) for v in fixed)
        episode = _Episode(agent, skill, robot_type)
        episode.command = self._fixed_command or self._draw_command()
        episode.poses.append(self._ground_pose(agent))
        self._episode = episode
        return skill.observe(agent.state, episode.command), self._info(episode, (0.0, 0.0, 0.0))

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        episode = self._episode
        if episode is None:
            raise RuntimeError("step() before reset(), or after the episode ended")
        config = self.config
        raw = np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
        self._held.hold(raw * ACTION_SCALE)
        agent = episode.agent
        agent.decide("learned_walk", *episode.command)
        agent.session.step()
        agent.perceive()
        self._held.release()
        episode.cycles += 1
        episode.poses.append(self._ground_pose(agent))
        velocity = self.measured_velocity(episode.poses)
        reward = self._tracking_reward(velocity, episode.command)
        reward -= config.action_penalty * float(np.mean(raw**2))
        fell = self._fallen(agent)
        if fell:
            reward -= config.fall_penalty
        truncated = not fell and episode.cycles >= self._limit_cycles
        if not fell and episode.cycles % self._command_cycles == 0 and not self._fixed_command:
            episode.command = self._draw_command()
        obs = episode.skill.observe(agent.state, episode.command)
        info = self._info(episode, velocity)
        if fell or truncated:
            # an episode succeeds when it ends on its feet (the training log's success rate)
            info.update(fell=fell, success=not fell)
            self._episode = None
        return obs, reward, fell, truncated, info

    # ------------------------------------------------------------------ pieces
    def _draw_command(self) -> tuple[float, float, float]:
        return draw_command(self.np_random, self.config)

    @staticmethod
    def _ground_pose(agent: LocalAgent) -> tuple[float, float, float]:
        x, y, _ = agent.robot.torso_position()
        return x, y, agent.robot.torso_yaw_deg()

    @staticmethod
    def measured_velocity(poses: deque) -> tuple[float, float, float]:
        """Torso (forward, left) m/s in the heading of the window's start, and turn deg/s,
        over the poses held (ground truth)."""
        if len(poses) < 2:
            return 0.0, 0.0, 0.0
        (x0, y0, h0), (x1, y1, h1) = poses[0], poses[-1]
        seconds = (len(poses) - 1) * CYCLE_SECONDS
        c, s = math.cos(math.radians(h0)), math.sin(math.radians(h0))
        dx, dy = x1 - x0, y1 - y0
        turn = ((h1 - h0 + 180.0) % 360.0 - 180.0) / seconds
        return (c * dx + s * dy) / seconds, (-s * dx + c * dy) / seconds, turn

    def _tracking_reward(
        self, velocity: tuple[float, float, float], command: tuple[float, float, float]
    ) -> float:
        config = self.config
        vx, vy, turn = velocity
        cx, cy, cturn = command
        speed_error = math.hypot(vx - cx, vy - cy) / config.speed_sigma
        turn_error = (turn - cturn) / config.turn_sigma_deg
        return math.exp(-(speed_error**2)) + config.turn_weight * math.exp(-(turn_error**2))

    @staticmethod
    def _fallen(agent: LocalAgent) -> bool:
        return bool(agent.robot.torso_up()[2] < math.cos(math.radians(FALL_TILT_DEG)))

    @staticmethod
    def _info(episode: _Episode, velocity: tuple[float, float, float]) -> dict[str, Any]:
        """What a step reports: the command of the next step and the velocity just measured."""
        return {
            "robot_type": episode.robot_type,
            "command": episode.command,
            "seconds": episode.cycles * CYCLE_SECONDS,
            "velocity": velocity,
        }

    def close(self) -> None:
        for standing in self._standing.values():
            standing.session.close()
        self._standing.clear()


def measure_speed(config: WalkEnvConfig, seconds: float, seed: int = 0) -> dict[str, float]:
    """Environment steps per second with zero actions (the engine alone) once the standing
    robots exist, and the episodes' fall rate meanwhile."""
    env = WalkResidualEnv(config)
    try:
        start = time.monotonic()
        for robot_type in config.robot_types:
            env.standing(robot_type)
        setup_s = time.monotonic() - start
        steps_per_s, endings = zero_action_speed(env, seconds, seed)
    finally:
        env.close()
    falls = sum(terminated for terminated, _ in endings)
    return {
        "setup_s": setup_s,
        "steps_per_s": steps_per_s,
        "episodes": len(endings),
        "fall_rate": falls / max(1, len(endings)),
    }
