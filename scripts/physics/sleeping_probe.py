"""Would Bullet's sleeping make an 11 v 11 match real time? Two measurements.

Why: 22 robots cost 25-28 ms of physics per 0.02 s cycle here (``benchmarks/physics.py``), and
Bullet can stop simulating a multibody whose speeds stayed near zero for 2 s (``loadURDF``'s
sleeping option; woken by contacts, by ``changeDynamics(activationState=WAKE_UP)``). A server
would wake a robot whenever its agent's speed commands change, so a robot can sleep only after
2 s (100 cycles) of unchanged commands.

1. ``idle_ms_per_cycle[awake|sleeping]``: 22 robots standing with zero speed commands, the CPU
   time of a cycle after 4 s, without and with sleeping allowed (sleeping robots cost nothing).
2. An 11 v 11 match (``agent.match.run_match``, one process): per robot, the longest run of
   cycles in which its speed commands stayed exactly the same (``longest_unchanged_cycles``),
   and the share of robot-cycles inside runs of 100 cycles or more
   (``sleepable_robot_cycle_share``). Session 31: 1 and 0.000: every agent changes some joint's
   command every cycle (the head scans, the balance loops), so sleeping buys nothing in a game
   and was not adopted.

Run: ``PYTHONPATH=. python scripts/physics/sleeping_probe.py [--duration 20]``.
"""

from __future__ import annotations

import argparse
import time

import pybullet

from agent.match import run_match
from benchmarks.physics import world_with_robots

#: Bullet's sleep timeout (btMultiBody): 2 s of stillness, in cycles.
SLEEP_CYCLES = 100


def idle_cycle_ms(sleeping: bool, settle: int = 200, cycles: int = 100) -> float:
    """CPU ms per cycle of 22 idle robots after ``settle`` cycles."""
    world, team = world_with_robots(2, 22)
    if sleeping:
        for robot in team:
            pybullet.changeDynamics(
                robot.body_id,
                -1,
                activationState=pybullet.ACTIVATION_STATE_ENABLE_SLEEPING,
                physicsClientId=world.client,
            )
    for _ in range(settle):
        world.step_cycle()
    start = time.process_time()
    for _ in range(cycles):
        world.step_cycle()
        for robot in team:
            robot.update_sensors()
    elapsed = time.process_time() - start
    world.close()
    return 1000.0 * elapsed / cycles


def command_runs(duration_s: float) -> tuple[int, float]:
    """(longest run of unchanged speed commands of any robot, share of robot-cycles in runs
    of at least SLEEP_CYCLES) over an 11 v 11 match."""
    last: dict[int, tuple[float, ...]] = {}
    run: dict[int, int] = {}
    longest = 0
    sleepable = total = 0

    def on_cycle(session) -> None:
        nonlocal longest, sleepable, total
        for slot in session.agents.values():
            if slot.robot is None:
                continue
            commands = tuple(slot.robot.joint_speed_targets().values())
            same = last.get(slot.agent_id) == commands
            run[slot.agent_id] = run.get(slot.agent_id, 0) + 1 if same else 0
            last[slot.agent_id] = commands
            longest = max(longest, run[slot.agent_id])
            sleepable += run[slot.agent_id] >= SLEEP_CYCLES
            total += 1

    run_match(duration_s, seed=0, on_event=lambda _: None, on_cycle=on_cycle)
    return longest, sleepable / max(total, 1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=20.0, help="match game seconds")
    args = parser.parse_args()
    print(f"idle_ms_per_cycle[awake]: {idle_cycle_ms(False):.2f}")
    print(f"idle_ms_per_cycle[sleeping]: {idle_cycle_ms(True):.2f}")
    longest, share = command_runs(args.duration)
    print(f"longest_unchanged_cycles: {longest}")
    print(f"sleepable_robot_cycle_share: {share:.3f}")


if __name__ == "__main__":
    main()
