"""From what skills want (joint angles, or raw speeds) to the speed effectors the server takes.

The server's joint effectors are speeds in rad/s held until changed, and an action answering
perception ``k`` first shows in perception ``k + 2``. Targets are followed with a proportional
speed command, ``speed = gain * error / cycle``, clipped to the joint's maximum speed.

Why :data:`DEFAULT_GAIN` is 0.25: with the two-cycle latency the error obeys
``e[k+2] = e[k+1] - gain * e[k]``, whose characteristic roots ``(1 +- sqrt(1 - 4 gain)) / 2`` are
real (no overshoot, no oscillation) only for ``gain <= 1/4``; 1/4 gives the double root 0.5, the
fastest such response (the error halves every cycle once the joint is off its speed limit). The
earlier 0.5 has complex roots of modulus 0.71 and overshot 3-6 degrees in the simulator. 0.25 also
stays stable and non-oscillating if the latency is one cycle (roots 0.75) and stable with about
14 % overshoot if it is three (an agent answering late on a real-time server). Measured in
``tests/test_joint_control.py``: head and arm steps of 10-90 degrees end within 0.1 degree of the
target with < 0.1 degree overshoot; loaded leg joints of a standing robot wobble by a degree or
two with the body and settle.

A consequence to plan for: a moving target is followed with a lag of ``speed * cycle / gain``,
i.e. four cycles of motion; motions that need exact timing should aim ahead or send speeds.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from world.nao_model import robot_spec
from world.perception import CYCLE_SECONDS

#: Fraction of the remaining error a joint is asked to close per cycle (see the module docstring).
DEFAULT_GAIN = 0.25


class JointCommands:
    """One cycle's joint commands for one robot type, by perceptor name (hj1, llj3, ...).

    Each joint is either aimed at a target angle or driven at a raw speed, whichever was set
    last this cycle; :meth:`clear` starts the next cycle with no commands.
    """

    def __init__(self, robot_type: int = 0) -> None:
        spec = robot_spec(robot_type)
        self._effector = {j.perceptor: j.effector for j in spec.joints}
        self._max_speed = {j.perceptor: j.max_speed for j in spec.joints}
        self._limits = {j.perceptor: (j.min_deg, j.max_deg) for j in spec.joints}
        self._targets: dict[str, tuple[float, float]] = {}
        self._speeds: dict[str, float] = {}

    @property
    def joint_names(self) -> tuple[str, ...]:
        """Perceptor names of this robot type's joints, in the server's order."""
        return tuple(self._effector)

    def clear(self) -> None:
        """Forget this cycle's commands (the manager calls this at the start of every cycle)."""
        self._targets.clear()
        self._speeds.clear()

    def set_targets(self, targets_deg: Mapping[str, float], gain: float = DEFAULT_GAIN) -> None:
        """Ask joints to move towards angles (degrees, clipped to the joint range)."""
        if not 0.0 < gain <= 1.0:
            raise ValueError(f"gain must be in (0, 1], got {gain!r}")
        for name, value in targets_deg.items():
            low, high = self._check(name)
            if not math.isfinite(value):
                raise ValueError(f"target of {name!r} must be a finite angle, got {value!r}")
            self._targets[name] = (min(max(value, low), high), gain)
            self._speeds.pop(name, None)

    def set_speeds(self, speeds: Mapping[str, float]) -> None:
        """Command raw joint speeds (rad/s), e.g. from a learned policy."""
        for name, value in speeds.items():
            self._check(name)
            if not math.isfinite(value):
                raise ValueError(f"speed of {name!r} must be finite, got {value!r}")
            self._speeds[name] = value
            self._targets.pop(name, None)

    def targets(self) -> dict[str, float]:
        """The target angles set this cycle (degrees, after clipping to the joint ranges)."""
        return {name: target for name, (target, _) in self._targets.items()}

    def speeds(self) -> dict[str, float]:
        """The raw speeds set this cycle (rad/s, before clipping to the speed limits)."""
        return dict(self._speeds)

    def effector_speeds(self, joints_deg: Mapping[str, float]) -> dict[str, float]:
        """Effector name -> rad/s for this cycle, given the current joint angles (degrees).

        Joints nobody commanded get speed 0, so a finished motion holds still. A target for a
        joint missing from ``joints_deg`` counts from 0 degrees.
        """
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
