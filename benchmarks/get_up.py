"""Get-up trials: knock a robot over by physics, then let the ``get_up`` skill stand it up.

A trial: one robot of a given type stands in an in-process :class:`~sim.session.Session`, then
falls through its own joints (a push made of random fast leg and arm speeds towards one side, a
limp phase of random length, random joint motions while it lies) and comes to rest. From then on
the agent side runs alone: perception bytes -> :class:`~world.robot_state.RobotState` -> skill ->
:class:`~behaviors.joint_control.JointCommands` -> effector bytes, exactly as over TCP. The trial
succeeds when the skill reports standing within ``time_limit`` seconds and the simulator agrees
(torso upright and at standing height, both feet on the ground) and the robot is still up half a
second later.

Run: ``.venv/bin/python benchmarks/get_up.py [--trials-per-type 20] [--seed 0]
[--directions front,back] [--types 0,3]``; prints
``get_up_success_rate: X``, ``get_up_time_s_median: Y`` and per-type success rates.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import behaviors.get_up  # noqa: F401  (registers the skills)
from behaviors.joint_control import CYCLE_SECONDS
from behaviors.manager import Behavior
from sim.session import Session, SessionConfig
from world.effectors import EffectorMessage, write_effectors
from world.nao_model import ROBOT_TYPES
from world.perception import parse_perception
from world.robot_state import RobotState

FALL_DIRECTIONS = ("front", "back", "left", "right")
#: Ground truth for "standing": torso within this angle of vertical ...
UPRIGHT_DEG = 25.0
#: ... and its centre at least this fraction of the zero-pose torso height.
STANDING_HEIGHT_FRACTION = 0.8


class LocalDriver:
    """One agent's loop in-process: perceive, run skills through the manager, send, step.

    The skills see only what the perception bytes say (through ``RobotState``); the simulator
    is read by the trial's own checks alone.
    """

    def __init__(self, session: Session, agent: int, robot_type: int) -> None:
        self.session = session
        self.agent = agent
        self.state = RobotState(robot_type)
        self.behavior = Behavior(SimpleNamespace(robot=self.state), robot_type)
        self.commands = self.behavior.commands

    def perceive(self) -> None:
        self.state.update(parse_perception(self.session.perception(self.agent)))

    def send(self, speeds: dict[str, float]) -> None:
        message = EffectorMessage(joint_speeds=speeds, syn=True)
        self.session.handle_message(self.agent, write_effectors(message))
        self.session.step()

    def run_skill(self, name: str, *args: object) -> bool:
        """One cycle of ``Behavior.execute(name, *args)``; True when the skill has finished."""
        self.perceive()
        self.behavior.begin_cycle()
        finished = self.behavior.execute(name, *args)
        self.send(self.behavior.effector_speeds())
        return finished


def join(session: Session, robot_type: int, rng: np.random.Generator) -> LocalDriver:
    """Connect a robot of ``robot_type``, beam it, rise slowly into the stand pose, settle."""
    x, y, yaw = rng.uniform(-10, -2), rng.uniform(-5, 5), rng.uniform(-180, 180)
    agent = session.join(
        "Fallers", 1, robot_type, beam=(round(x, 2), round(y, 2), round(yaw, 1)), settle_cycles=2
    )
    return rise_to_stand(LocalDriver(session, agent, robot_type))


def rise_to_stand(driver: LocalDriver) -> LocalDriver:
    """From the beam's zero pose rise slowly into ``stand`` and hold it half a second: jumping
    into the stand's bent knees at once tips the robot over."""
    while not driver.run_skill("keyframe", "stand_up_slowly"):
        pass
    for _ in range(25):
        driver.run_skill("pose", "stand")
    return driver


def robot_is_standing(session: Session, agent: int) -> bool:
    """Ground truth from the simulator: upright torso at standing height, both feet down."""
    robot = session.agents[agent].robot
    upright = robot.torso_up()[2] > math.cos(math.radians(UPRIGHT_DEG))
    height = robot.torso_position()[2] > STANDING_HEIGHT_FRACTION * robot.spec.sole_height()
    feet = robot.force_resistance()
    return bool(upright and height and "lf" in feet and "rf" in feet)


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


def knock_over(driver: LocalDriver, direction: str, rng: np.random.Generator) -> bool:
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


@dataclass(frozen=True)
class TrialResult:
    robot_type: int
    direction: str
    lying_on: str | None
    succeeded: bool
    #: seconds from the first get_up cycle to the cycle it reported standing (None: it did not)
    time_s: float | None


def run_trial(robot_type: int, direction: str, seed: int, time_limit: float = 4.0) -> TrialResult:
    """One fall and one get-up; see the module docstring for what counts as success."""
    rng = np.random.default_rng(seed)
    session = Session(SessionConfig(seed=seed, beam_noise=False))
    try:
        driver = join(session, robot_type, rng)
        if not knock_over(driver, direction, rng):
            raise RuntimeError(f"type {robot_type} seed {seed}: the robot did not fall {direction}")
        driver.perceive()
        lying_on = driver.state.lying_on
        cycles = 0
        finished = False
        while not finished and cycles < round(time_limit / CYCLE_SECONDS):
            finished = driver.run_skill("get_up")
            cycles += 1
        if not finished:
            return TrialResult(robot_type, direction, lying_on, False, None)
        elapsed = cycles * CYCLE_SECONDS
        standing_now = robot_is_standing(session, driver.agent)
        for _ in range(25):  # still up half a second later, holding the stand pose
            driver.run_skill("pose", "stand")
        ok = standing_now and robot_is_standing(session, driver.agent)
        return TrialResult(robot_type, direction, lying_on, ok, elapsed if ok else None)
    finally:
        session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--trials-per-type", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--time-limit", type=float, default=4.0)
    parser.add_argument(
        "--directions",
        default=",".join(FALL_DIRECTIONS),
        help="fall directions, comma-separated, taken in turn (one side alone for tuning)",
    )
    parser.add_argument("--types", default=",".join(map(str, ROBOT_TYPES)))
    args = parser.parse_args()
    directions = args.directions.split(",")
    robot_types = [int(t) for t in args.types.split(",")]
    results = []
    for robot_type in robot_types:
        for k in range(args.trials_per_type):
            direction = directions[k % len(directions)]
            seed = args.seed + 1000 * robot_type + k
            results.append(run_trial(robot_type, direction, seed, args.time_limit))
    times = [r.time_s for r in results if r.time_s is not None]
    print(f"get_up_success_rate: {sum(r.succeeded for r in results) / len(results):.3f}")
    print(f"get_up_time_s_median: {statistics.median(times) if times else float('nan'):.2f}")
    for robot_type in robot_types:
        mine = [r for r in results if r.robot_type == robot_type]
        rate = sum(r.succeeded for r in mine) / len(mine)
        print(f"get_up_success_rate[type={robot_type}]: {rate:.3f}")
    for side in ("front", "back", "left", "right"):
        mine = [r for r in results if r.lying_on == side]
        if mine:
            rate = sum(r.succeeded for r in mine) / len(mine)
            print(f"get_up_success_rate[lying_on={side}]: {rate:.3f} ({len(mine)} trials)")


if __name__ == "__main__":
    main()
