"""Where the forward walk's speed goes: joint speed-cap occupancy, tracking lag and foot slip.

Runs ``walk_velocity(vx, 0, 0)`` (full speed by default) on one robot type as
``benchmarks/locomotion.py`` does and prints, over the measured seconds:

* the torso's real speed (ground truth) against the speed the steps plan;
* per leg joint and role (swing leg / stance leg), the share of cycles the sent speed sat at the
  joint's cap, and the mean tracking error (target minus perceived angle) at the step's last
  cycle (where the swing foot should land);
* per step, how far the swing foot really travelled (truth) against the step plan's two step
  lengths, and how far the stance foot slid (truth) while it carried the robot: what the
  real speed lacks against the plan is the swing foot's shortfall plus the stance foot's slip.

Why: issue 4 wants 0.9 m/s and the walk stops at 0.73-0.78 m/s with 0.14-0.15 m steps
(0.875-0.94 m/s planned); this says which of the two losses to attack. Diagnostic only (reads
the simulator's truth; the walk does not).

Run: ``python scripts/walk_speed_probe.py --type 0 [--vx 1.0] [--seconds 3] [--set key=value]``
"""

from __future__ import annotations

import argparse
import math
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.joint_control import CYCLE_SECONDS
from benchmarks.locomotion import new_driver, walk_file_with

#: leg joints by number: hip yaw-pitch, hip roll, hip pitch, knee, ankle pitch, ankle roll
LEG_JOINTS = {1: "hipyp", 2: "hiproll", 3: "hip", 4: "knee", 5: "ankle", 6: "aroll"}


def probe(
    robot_type: int,
    vx: float,
    seconds: float,
    walk_file: Path,
    seed: int = 0,
    beam: tuple[float, float, float] = (-8.0, 0.0, 0.0),
) -> dict[str, float]:
    """Walk ``seconds`` after one second of acceleration; print the breakdown and return the
    headline figures (real and planned speed, swing shortfall and stance slip in m/s)."""
    driver = new_driver(robot_type, seed, beam=beam, walk_file=walk_file)
    skill = driver.behavior.skill("walk_velocity")
    at_cap: dict[str, list[bool]] = defaultdict(list)
    lag: dict[str, list[float]] = defaultdict(list)
    swing_travel: list[float] = []
    planned_travel: list[float] = []
    stance_slip: list[float] = []
    lift_by_t: dict[int, list[float]] = defaultdict(list)
    fell = False
    try:
        for _ in range(50):
            driver.run("walk_velocity", vx, 0.0, 0.0)
        x0, y0, _ = driver.ground_pose()
        heading = math.radians(driver.robot.torso_yaw_deg())
        along = np.array([math.cos(heading), math.sin(heading)])
        planned = 0.0
        lift: dict[str, np.ndarray] = {}
        stance_start: dict[str, np.ndarray] = {}
        cycles = round(seconds / CYCLE_SECONDS)
        for _ in range(cycles):
            driver.run("walk_velocity", vx, 0.0, 0.0)
            engine = skill._engine
            t, left_active = engine.phase
            n = engine.params.step.step_cycles
            command = engine.generator.command
            planned += command.forward / n
            swing, stance = ("l", "r") if left_active else ("r", "l")
            if driver.fallen():
                fell = True
                break
            feet = driver.robot.body_positions(["lfoot", "rfoot"])
            ground = {s: np.array(feet[f"{s}foot"][:2]) for s in ("l", "r")}
            lift_by_t[t].append(feet[f"{swing}foot"][2] - feet[f"{stance}foot"][2])
            current = driver.world.robot.joints_deg
            targets = engine._previous_target or {}
            for side, role in ((swing, "swing"), (stance, "stance")):
                for k, joint in LEG_JOINTS.items():
                    name = f"{side}lj{k}"
                    speed = abs(engine._last_speed.get(name, 0.0))
                    at_cap[f"{role} {joint}"].append(speed >= engine._max_speed[name] * 0.999)
                    if t == n - 1:
                        lag[f"{role} {joint}"].append(targets[name] - current.get(name, 0.0))
            if t == 0:
                lift[swing] = ground[swing]
                stance_start[stance] = ground[stance]
            if t == n - 1 and swing in lift and stance in stance_start:
                swing_travel.append(float(along @ (ground[swing] - lift[swing])))
                planned_travel.append(2.0 * command.forward)
                stance_slip.append(float(along @ (ground[stance] - stance_start[stance])))
        x1, y1, _ = driver.ground_pose()
    finally:
        driver.session.close()
    real = 0.0 if fell else float(along @ np.array([x1 - x0, y1 - y0])) / seconds
    step_seconds = engine.params.step.step_cycles * CYCLE_SECONDS
    figures = {
        "real_mps": real,
        "planned_mps": planned / seconds,
        "swing_shortfall_mps": (np.mean(planned_travel) - np.mean(swing_travel)) / 2 / step_seconds,
        "stance_slip_mps": -float(np.mean(stance_slip)) / 2 / step_seconds,
        "fell": float(fell),
    }
    print(
        f"type{robot_type} vx {vx}{' FELL' if fell else ''}: real {real:.3f} m/s, "
        f"planned {figures['planned_mps']:.3f}; per step: swing foot (centre) "
        f"{np.mean(swing_travel):.3f} m of {np.mean(planned_travel):.3f} planned, stance foot "
        f"slid {np.mean(stance_slip):+.3f} m"
    )
    lifts = " ".join(f"{np.mean(lift_by_t[t]):.3f}" for t in sorted(lift_by_t))
    print(f"swing foot above the stance foot by cycle of the step (m): {lifts}")
    print("joint          at cap  lag at landing (deg)")
    for key in sorted(at_cap):
        print(f"  {key:13s} {np.mean(at_cap[key]):5.2f}  {np.mean(lag[key]):+6.1f}")
    return figures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--type", type=int, nargs="+", default=[0])
    parser.add_argument("--vx", type=float, default=1.0)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--starts",
        type=int,
        default=1,
        help="start positions (the benchmark's, then others 0.37 m on and 0.23 m aside each): "
        "trajectories are chaotic, so other starts give other samples of the same walk",
    )
    parser.add_argument("--set", action="append", default=[], metavar="DOTTED.KEY=VALUE")
    args = parser.parse_args()
    with walk_file_with(args.set) as walk_file:
        for robot_type in args.type:
            speeds, falls = [], 0
            for k in range(args.starts):
                beam = (-8.0 + 0.37 * k, 0.23 * k, 0.0)
                figures = probe(robot_type, args.vx, args.seconds, walk_file, args.seed, beam)
                speeds.append(figures["real_mps"])
                falls += int(figures["fell"])
            if args.starts > 1:
                print(
                    f"type{robot_type}: real m/s over {args.starts} starts: mean "
                    f"{np.mean(speeds):.3f}, slowest {min(speeds):.3f}, falls {falls}"
                )


if __name__ == "__main__":
    main()
