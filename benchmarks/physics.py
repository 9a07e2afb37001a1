"""Cycles per second of the stand-in with 1 and 22 robots whose joints keep moving.

Each cycle does what the server does per robot: new joint speeds, one world step, sensor update,
joint angles, gyro, accelerometer and foot pressure. Prints ``cycles_per_s[substeps=S,robots=N]``.
Run: ``.venv/bin/python benchmarks/physics.py [--cycles N]``
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import pybullet

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sim.physics import PhysicsWorld
from sim.robot import SimRobot


def measure(substeps: int, robots: int, cycles: int) -> float:
    world = PhysicsWorld(substeps=substeps)
    plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=world.client)
    pybullet.createMultiBody(0, plane, physicsClientId=world.client)
    team = []
    for k in range(robots):
        robot = SimRobot(world, k % 5)
        robot.place(-10.0 + 2.0 * (k % 11), -3.0 + 6.0 * (k // 11), 0.4, 0.0)
        team.append(robot)
    start = time.perf_counter()
    for c in range(cycles):
        s = math.sin(0.1 * c)
        for robot in team:
            robot.set_joint_speeds({"he1": s, "rae1": 2 * s, "lae1": -2 * s, "rle3": 0.3 * s})
        world.step_cycle()
        for robot in team:
            robot.update_sensors()
            robot.joint_angles_deg()
            robot.gyro_deg_s()
            robot.accelerometer()
            robot.force_resistance()
    elapsed = time.perf_counter() - start
    world.close()
    return cycles / elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--cycles", type=int, default=500)
    args = parser.parse_args()
    for substeps in (1, 2, 4):
        for robots in (1, 22):
            cycles = args.cycles if robots == 1 else max(50, args.cycles // 10)
            rate = measure(substeps, robots, cycles)
            print(f"cycles_per_s[substeps={substeps},robots={robots}]: {rate:.1f}")


if __name__ == "__main__":
    main()
