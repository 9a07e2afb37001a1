"""``learned_walk(vx, vy, vturn_deg)``: the walk engine plus a learned residual on the leg joints.

Why: the scripted walk (``behaviors/walk.py``) tops out at 0.73-0.78 m/s forward and the
dribbles that ride on it at 0.57-0.73 m/s, short of issue 4's 0.9 m/s walk and 1.0 m/s
dribble; the step limits are not what caps it (0.15 m steps plan 0.94 m/s), the joint speed
caps and the gait's shape are. A policy that adds bounded offsets to the twelve leg joint
targets the engine is about to track keeps the engine's phase, balance corrections and
odometry, and may learn a faster, steadier stride where hand tuning stalled.
``learning/envs/walk.py`` trains it (``config/train/walk.yaml``).

Mirror symmetry by construction: the policy only ever sees the robot with its LEFT leg
swinging (the canonical frame). While the right leg swings, the observation is mirrored
(:func:`behaviors.mirror.mirror_observation`) before the policy and its action mirrored back
(:func:`behaviors.mirror.mirror_action`), so one policy walks both half-cycles and the gait
is left-right symmetric whatever it learned: the thesis's mirror inversion, applied every step.

The observation is read before the engine's cycle, so its phase is the step cycle last
executed (``t`` in 0..7, or not stepping yet); the swing leg of that step picks the frame. A
training environment reads the same function after each cycle, so the policy sees in training
exactly what it sees in a match. Without a policy (no ``behaviors/data/walk_residual.npz``)
``learned_walk`` walks exactly as ``walk_velocity`` (tested).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from types import MappingProxyType
from typing import Protocol

import numpy as np

from behaviors.mirror import ObservationLayout, Segment, mirror_action, mirror_observation
from behaviors.policy import load_checked_policy
from behaviors.skill import SkillContext
from behaviors.walk import WALK_FILE, WalkEngine, WalkSkillBase
from world.robot_state import RobotState

#: The joints the residual moves and observes, in the policy's order (left leg, then right).
LEG_JOINTS: tuple[str, ...] = (
    *(f"llj{i}" for i in range(1, 7)),
    *(f"rlj{i}" for i in range(1, 7)),
)
#: The largest offset (deg) per leg joint (a policy output of +-1): larger in the sagittal
#: joints that shape the stride, smaller in the roll and yaw-pitch joints that hold balance.
_MAX_BY_JOINT = {1: 5.0, 2: 8.0, 3: 15.0, 4: 15.0, 5: 15.0, 6: 8.0}
RESIDUAL_MAX_DEG: Mapping[str, float] = MappingProxyType(
    {name: _MAX_BY_JOINT[int(name[-1])] for name in LEG_JOINTS}
)
ACTION_SCALE = np.array([RESIDUAL_MAX_DEG[name] for name in LEG_JOINTS])

#: Share of the gap to the policy's new offsets closed per cycle (a first-order filter). Why:
#: the engine feeds each cycle's change of a target forward as joint speed, so unfiltered
#: offsets that change every 20 ms jerk the legs: iid exploration noise of 0.1 (1.5 deg on the
#: knees) felled 7 of 10 episodes, 0.05 3 of 10, none without noise (session 8).
RESIDUAL_SMOOTHING = 0.25

#: The observation, entry by entry, in the canonical (left leg swinging) frame.
OBS_NAMES: tuple[str, ...] = (
    *(f"gyro_{a}" for a in "xyz"),
    *(f"acc_{a}" for a in "xyz"),
    "roll_deg",
    "pitch_deg",
    *(f"joint_{name}" for name in LEG_JOINTS),
    "phase_sin",
    "phase_cos",
    "stepping",
    "command_vx",
    "command_vy",
    "command_turn_deg_s",
    "engine_vx",
    "engine_vy",
    "engine_turn_deg_s",
    *(f"offset_{name}" for name in LEG_JOINTS),
)
#: How each stretch of :data:`OBS_NAMES` mirrors (roll, sideways and turning values flip).
OBS_LAYOUT = ObservationLayout(
    (
        Segment.gyro(),
        Segment.accelerometer(),
        Segment.negate(),  # roll
        Segment.scalar(),  # pitch
        Segment.joints(LEG_JOINTS),
        Segment.scalar(3),  # phase sin, cos, stepping
        Segment.scalar(),  # command vx
        Segment.negate(2),  # command vy, turn
        Segment.scalar(),  # engine vx
        Segment.negate(2),  # engine vy, turn
        Segment.joints(LEG_JOINTS),  # the smoothed offsets now applied
    )
)
assert OBS_LAYOUT.size == len(OBS_NAMES)

#: The packaged policy (absent: ``learned_walk`` walks as the engine alone).
RESIDUAL_FILE = WALK_FILE.parent / "walk_residual.npz"


class WalkResidualSource(Protocol):
    """Where the skill gets its residual: offsets (deg, in :data:`LEG_JOINTS` order, canonical
    frame) for an observation laid out as :data:`OBS_NAMES` (canonical frame)."""

    def residual_deg(self, observation: np.ndarray) -> np.ndarray: ...


class PolicyWalkResidual:
    """A trained policy (numpy MLP, ``learning/export.py``'s file) as the residual source."""

    def __init__(self, path: Path) -> None:
        self.policy = load_checked_policy(path, OBS_NAMES, LEG_JOINTS, ACTION_SCALE)

    def residual_deg(self, observation: np.ndarray) -> np.ndarray:
        return self.policy.act(observation)


def default_walk_residual() -> WalkResidualSource | None:
    """The packaged residual where ``behaviors/data/walk_residual.npz`` exists, else None."""
    return PolicyWalkResidual(RESIDUAL_FILE) if RESIDUAL_FILE.exists() else None


def is_mirrored(phase: tuple[int, bool]) -> bool:
    """Whether the canonical frame is the mirror image now: a step is under way (t >= 0) with
    the right leg swinging."""
    t, left_active = phase
    return t >= 0 and not left_active


def walk_observation(
    state: RobotState,
    engine: WalkEngine | None,
    command: tuple[float, float, float],
    offsets_deg: np.ndarray | None = None,
) -> np.ndarray:
    """The residual's observation in the canonical frame (perception and the skill's own
    state only): IMU, tilt estimate, leg angles, step phase, command, the engine's smoothed
    velocity and the smoothed offsets applied now (``offsets_deg``, real frame, in
    :data:`LEG_JOINTS` order; None: zero)."""
    phase = engine.phase if engine is not None else (-1, False)
    t = phase[0]
    if t >= 0:
        step_cycles = engine.params.step.step_cycles
        angle = 2.0 * math.pi * t / step_cycles
        phase_features = [math.sin(angle), math.cos(angle), 1.0]
    else:
        phase_features = [0.0, 0.0, 0.0]
    vx, vy, w = engine.velocity if engine is not None else (0.0, 0.0, 0.0)
    raw = np.concatenate(
        [
            state.gyro_deg_s,
            state.accelerometer,
            [state.roll_deg, state.pitch_deg],
            [state.joints_deg.get(name, 0.0) for name in LEG_JOINTS],
            phase_features,
            command,
            [vx, vy, math.degrees(w)],
            np.zeros(len(LEG_JOINTS)) if offsets_deg is None else offsets_deg,
        ]
    )
    if is_mirrored(phase):
        raw = mirror_observation(raw, OBS_LAYOUT)
    return raw.astype(np.float32)


def real_frame_residual(canonical_deg: np.ndarray, mirrored: bool) -> np.ndarray:
    """A canonical-frame residual (deg, :data:`LEG_JOINTS` order) in the real frame, mirrored
    back where the frame is mirrored, each clipped to :data:`RESIDUAL_MAX_DEG`."""
    values = np.asarray(canonical_deg, dtype=float)
    if mirrored:
        values = mirror_action(values, LEG_JOINTS)
    return np.clip(values, -ACTION_SCALE, ACTION_SCALE)


class LearnedWalkSkill(WalkSkillBase):
    """Walk at (vx, vy) m/s and vturn_deg deg/s (robot frame) with the learned residual;
    finishes, as ``walk_velocity``, only while standing still on a zero command."""

    name = "learned_walk"

    def __init__(self, residual: WalkResidualSource | None = None) -> None:
        super().__init__()
        #: the residual (None: the engine alone); the packaged one where it exists
        self.residual: WalkResidualSource | None = (
            default_walk_residual() if residual is None else residual
        )
        self._offsets = np.zeros(len(LEG_JOINTS))

    def validate(self, vx: float, vy: float, vturn_deg: float) -> None:
        if not all(math.isfinite(v) for v in (vx, vy, vturn_deg)):
            raise ValueError("velocities must be finite")

    def reset(self) -> None:
        super().reset()
        self._offsets = np.zeros(len(LEG_JOINTS))

    @property
    def offsets_deg(self) -> dict[str, float]:
        """The smoothed residual applied in the last cycle, by joint (deg, real frame)."""
        return dict(zip(LEG_JOINTS, self._offsets.tolist()))

    def observe(self, state: RobotState, command: tuple[float, float, float]) -> np.ndarray:
        """The observation the next cycle's residual gets for ``command`` (what a training
        environment hands its policy)."""
        return walk_observation(state, self._engine, command, self._offsets)

    def step(self, context: SkillContext, vx: float, vy: float, vturn_deg: float) -> bool:
        command = (vx, vy, vturn_deg)
        offsets = None
        if self.residual is not None:
            observation = self.observe(context.world.robot, command)
            wanted = real_frame_residual(
                self.residual.residual_deg(observation), is_mirrored(self.phase)
            )
            self._offsets = self._offsets + RESIDUAL_SMOOTHING * (wanted - self._offsets)
            offsets = self.offsets_deg
        engine = self.engine(context)
        engine.step(context, vx, vy, vturn_deg, offsets)
        return engine.is_stopped and vx == 0.0 and vy == 0.0 and vturn_deg == 0.0
