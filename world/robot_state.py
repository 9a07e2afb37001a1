"""The agent's own body as its perceptors describe it: joints, IMU, foot pressure, tilt.

Only perception messages feed this state; nothing reads the simulator. The torso's tilt comes
from a complementary filter: the gyro integrated over the cycle, pulled towards the gravity
direction that the accelerometer reads whenever the robot is not being shaken (|a| near g).
Axes are the model's native frame: x to the robot's right, y forward, z up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from world.nao_model import RobotSpec, robot_spec
from world.perception import CYCLE_SECONDS, ForceResistance, Perception

GRAVITY = 9.81
#: Weight of the accelerometer's gravity direction in each cycle's tilt estimate.
ACCELEROMETER_TRUST = 0.05
#: The accelerometer is trusted only while |a| is within this fraction of g.
STEADY_ACCELERATION = 0.15
#: A torso tilted more than this from upright counts as fallen.
FALLEN_TILT_DEG = 55.0


def _tilt_step(
    up: np.ndarray, gyro_deg_s: tuple, accelerometer: tuple, dt: float
) -> tuple[float, float, float]:
    """One complementary-filter step in plain floats (this runs every cycle for every agent,
    where numpy's per-call cost on 3-vectors would dominate)."""
    ux, uy, uz = float(up[0]), float(up[1]), float(up[2])
    wx, wy, wz = (math.radians(g) for g in gyro_deg_s)
    # a world-fixed vector seen from a turning frame turns the other way: du/dt = -w x u
    ux, uy, uz = (
        ux - (wy * uz - wz * uy) * dt,
        uy - (wz * ux - wx * uz) * dt,
        uz - (wx * uy - wy * ux) * dt,
    )
    ax, ay, az = accelerometer
    magnitude = math.sqrt(ax * ax + ay * ay + az * az)
    if abs(magnitude - GRAVITY) < STEADY_ACCELERATION * GRAVITY:
        keep, trust = 1 - ACCELEROMETER_TRUST, ACCELEROMETER_TRUST / magnitude
        ux, uy, uz = keep * ux + trust * ax, keep * uy + trust * ay, keep * uz + trust * az
    norm = math.sqrt(ux * ux + uy * uy + uz * uz)
    return ux / norm, uy / norm, uz / norm


@dataclass
class RobotState:
    """Joint angles (degrees, by perceptor name), IMU readings and the torso's tilt estimate."""

    robot_type: int = 0
    spec: RobotSpec = field(init=False)
    joints_deg: dict[str, float] = field(default_factory=dict)
    gyro_deg_s: np.ndarray = field(default_factory=lambda: np.zeros(3))
    accelerometer: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, GRAVITY]))
    foot_pressure: dict[str, ForceResistance] = field(default_factory=dict)
    #: world "up" expressed in the torso frame (unit vector); (0, 0, 1) when upright
    up: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))

    def __post_init__(self) -> None:
        self.spec = robot_spec(self.robot_type)
        self._limits = {j.perceptor: (j.min_deg, j.max_deg) for j in self.spec.joints}

    def update(self, perception: Perception, dt: float = CYCLE_SECONDS) -> None:
        """Take one perception message's body readings."""
        self.joints_deg = perception.joints
        self.gyro_deg_s = np.array(perception.gyro, dtype=float)
        self.accelerometer = np.array(perception.accelerometer, dtype=float)
        self.foot_pressure = perception.force_resistance
        self.up = np.array(_tilt_step(self.up, perception.gyro, perception.accelerometer, dt))

    # ------------------------------------------------------------------ derived
    @property
    def tilt_deg(self) -> float:
        """Angle between the torso's z axis and the vertical."""
        return math.degrees(math.acos(max(-1.0, min(1.0, float(self.up[2])))))

    @property
    def roll_deg(self) -> float:
        """Sideways lean: positive when the robot leans to its right."""
        return math.degrees(math.atan2(-self.up[0], self.up[2]))

    @property
    def pitch_deg(self) -> float:
        """Forward lean: positive when the robot leans forwards."""
        return math.degrees(math.atan2(-self.up[1], self.up[2]))

    @property
    def is_fallen(self) -> bool:
        return self.tilt_deg > FALLEN_TILT_DEG

    @property
    def lying_on(self) -> str | None:
        """'front', 'back', 'left' or 'right' once fallen (the side facing the ground)."""
        if not self.is_fallen:
            return None
        x, y, _ = self.up
        if abs(y) >= abs(x):
            return "front" if y < 0 else "back"
        return "right" if x < 0 else "left"

    def joint_limits_deg(self, perceptor: str) -> tuple[float, float]:
        """The joint's range; KeyError lists this robot type's joints."""
        try:
            return self._limits[perceptor]
        except KeyError:
            raise KeyError(
                f"robot type {self.robot_type} has no joint {perceptor!r}; "
                f"joints: {', '.join(self._limits)}"
            ) from None
