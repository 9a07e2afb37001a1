"""From what skills want (joint angles, or raw speeds) to the speed effectors the server takes.

The server's joint effectors are speeds in rad/s held until changed, and an action answering
perception k shows in perception k + 2. Targets are therefore followed with a proportional
speed command, ``speed = gain * error / cycle``, clipped to the joint's maximum speed for the
robot type; a gain below 1 keeps the two-cycle latency from making joints overshoot.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from world.nao_model import robot_spec

CYCLE_SECONDS = 0.02
#: Fraction of the remaining error a joint is asked to close per cycle.
DEFAULT_GAIN = 0.5


class JointCommands:
    """One cycle's joint commands for one robot type, by perceptor name (hj1, llj3, ...)."""

    def __init__(self, robot_type: int = 0) -> None:
        spec = robot_spec(robot_type)
        self._effector = {j.perceptor: j.effector for j in spec.joints}
        self._max_speed = {j.perceptor: j.max_speed for j in spec.joints}
        self._limits = {j.perceptor: (j.min_deg, j.max_deg) for j in spec.joints}
        self._targets: dict[str, tuple[float, float]] = {}
        self._speeds: dict[str, float] = {}

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(self._effector)

    def clear(self) -> None:
        self._targets.clear()
        self._speeds.clear()

    def set_targets(self, targets_deg: Mapping[str, float], gain: float = DEFAULT_GAIN) -> None:
        """Ask joints to move towards angles (degrees, clipped to the joint range)."""
        for name, value in targets_deg.items():
            low, high = self._check(name)
            self._targets[name] = (min(max(value, low), high), gain)
            self._speeds.pop(name, None)

    def set_speeds(self, speeds: Mapping[str, float]) -> None:
        """Command raw joint speeds (rad/s), e.g. from a learned policy."""
        for name, value in speeds.items():
            self._check(name)
            self._speeds[name] = value
            self._targets.pop(name, None)

    def targets(self) -> dict[str, float]:
        return {name: target for name, (target, _) in self._targets.items()}

    def effector_speeds(self, joints_deg: Mapping[str, float]) -> dict[str, float]:
        """Effector name -> rad/s for this cycle, given the current joint angles (degrees).
        Joints nobody commanded get speed 0, so a finished motion holds still."""
        out = {}
        for name, effector in self._effector.items():
            limit = self._max_speed[name]
            if name in self._speeds:
                speed = self._speeds[name]
            elif name in self._targets:
                target, gain = self._targets[name]
                error = math.radians(target - joints_deg.get(name, 0.0))
                speed = gain * error / CYCLE_SECONDS
            else:
                speed = 0.0
            out[effector] = max(-limit, min(limit, speed))
        return out

    def _check(self, name: str) -> tuple[float, float]:
        try:
            return self._limits[name]
        except KeyError:
            raise KeyError(
                f"unknown joint {name!r}; this robot has {', '.join(self._limits)}"
            ) from None
