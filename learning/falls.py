"""Random falls by physics: the starting states for get-up trials and get-up training.

A robot is pushed over through its own joints (fast leaning motions plus noise), goes limp for
a random while, wiggles, and comes to rest lying on the ground. No teleporting: the fall is
made by the motors and gravity alone, so the lying poses are ones a match produces.
"""

from __future__ import annotations

import numpy as np

from learning.local_agent import LocalAgent
from sim.session import Session

FALL_DIRECTIONS = ("front", "back", "left", "right")


def join_at_random_spot(
    session: Session, robot_type: int, rng: np.random.Generator, team_name: str = "Fallers"
) -> LocalAgent:
    """Connect a robot of ``robot_type`` at a random spot of the own half, rise into ``stand``."""
    x, y, yaw = rng.uniform(-10, -2), rng.uniform(-5, 5), rng.uniform(-180, 180)
    beam = (round(x, 2), round(y, 2), round(yaw, 1))
    return LocalAgent.join(session, team_name, 1, robot_type, beam=beam).rise_to_stand()


#: Per fall direction, the joints a push drives hard (degrees): leaning the torso over the toes,
#: the heels or one foot's outer edge. Random amounts and noise on every joint come on top.
_PUSHES: dict[str, dict[str, float]] = {
    "front": {"rlj3": 70, "llj3": 70, "rlj5": 75, "llj5": 75, "raj1": 60, "laj1": 60},
    "back": {"rlj3": -25, "llj3": -25, "rlj5": -45, "llj5": -45, "raj1": -120, "laj1": -120},
    "left": {"rlj2": -45, "llj2": 45, "rlj6": 25, "llj6": -45, "raj2": -95, "laj2": 95},
    "right": {"rlj2": -25, "llj2": 25, "rlj6": 45, "llj6": -25, "raj2": -95, "laj2": 95},
}
#: The body is at rest once the gyro stays below this (deg/s) for a few cycles.
REST_GYRO_DEG_S = 20.0


def knock_over(driver: LocalAgent, direction: str, rng: np.random.Generator) -> bool:
    """Make the robot fall by physics towards ``direction``; True when it lies at rest.

    A push (fast motion of the leaning joints plus random speeds on all joints), a limp phase
    of random length (the motors off, as a robot hit hard), random joint motions, then rest.
    """
    robot = driver.session.agents[driver.agent].robot
    names = driver.commands.joint_names
    for _ in range(3):
        push = {n: v * rng.uniform(0.6, 1.0) for n, v in _PUSHES[direction].items()}
        noise = {n: rng.normal(0.0, 15.0) for n in names if n not in push}
        for _ in range(int(rng.integers(10, 20))):
            driver.perceive()
            driver.commands.clear()
            driver.commands.set_targets({**noise, **push}, gain=1.0)
            driver.send(driver.commands.effector_speeds(driver.state.joints_deg))
        robot.set_limp(True)
        for _ in range(int(rng.integers(10, 40))):
            driver.perceive()
            driver.send({})
        robot.set_limp(False)
        wiggle = {n: rng.uniform(-30.0, 30.0) for n in names}
        for _ in range(15):
            driver.perceive()
            driver.commands.clear()
            driver.commands.set_targets(wiggle)
            driver.send(driver.commands.effector_speeds(driver.state.joints_deg))
        quiet = 0
        for _ in range(150):
            driver.perceive()
            driver.send({name: 0.0 for name in robot.effector_names})
            quiet = quiet + 1 if max(map(abs, robot.gyro_deg_s())) < REST_GYRO_DEG_S else 0
            if quiet >= 5:
                break
        if robot.has_fallen():
            return True
    return False
