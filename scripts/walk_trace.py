"""Trace ``walk`` to random targets (as ``benchmarks/locomotion.py`` runs it) to find out why a
run falls and where the stop error comes from.

Per reached target it prints the ground-truth stop error, the localiser's own distance to the
target when ``walk`` reported arrival, the localisation error (estimate against truth) and the
cycles from the arrival decision to standing still with how far the torso went meanwhile. Per
fall it prints the cycles before it (every ``--every`` cycles): the target, the estimate's
distance and heading error, the engine's smoothed velocity, the step under way, IMU pitch / roll
and gyro. Diagnostic only (reads the simulator's truth).

Run: ``python scripts/walk_trace.py --type 1 --seed 107 [--seconds 60] [--set key=value]``
(``--seed`` is the run's own seed: ``benchmarks/locomotion.py --seed S`` runs type T's k-th run
with seed ``S + T + 100 k``).
"""

from __future__ import annotations

import argparse
import math
import sys
from collections import deque
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.locomotion import _random_target, new_driver, walk_file_with


def _record(driver, target, cycle: int) -> dict:
    tx, ty, _ = target
    x, y, h = driver.ground_pose()
    pose = driver.world.pose
    skill = driver.behavior.skill("walk")
    engine = skill._engine
    robot = driver.world.robot
    row = {
        "c": cycle,
        "truth": (x, y, h),
        "est": None if pose is None else (pose.x, pose.y, pose.heading_deg),
        "d_truth": math.hypot(tx - x, ty - y),
        "d_est": None if pose is None else math.hypot(tx - pose.x, ty - pose.y),
        "pitch": robot.pitch_deg,
        "roll": robot.roll_deg,
        "gyro": tuple(float(g) for g in robot.gyro_deg_s),
    }
    if engine is not None:
        c = engine.generator.command
        row.update(
            vel=engine.velocity,
            step=(c.forward, c.left, math.degrees(c.turn)),
            phase=engine.phase,
            drift=engine._heading_drift,
            stopped=engine.is_stopped,
        )
    row["arrived"] = skill._arrived
    return row


def _fmt(r: dict) -> str:
    est = r["est"]
    vel = r.get("vel", (0, 0, 0))
    step = r.get("step", (0, 0, 0))
    t, left = r.get("phase", (-1, False))
    est_text = (
        "lost" if est is None else f"est_d {r['d_est']:.2f} h_err {r['truth'][2] - est[2]:+5.1f}"
    )
    return (
        f"c{r['c']:5d} d {r['d_truth']:.2f} {est_text} h {r['truth'][2]:+6.1f} "
        f"v ({vel[0]:+.2f} {vel[1]:+.2f} {math.degrees(vel[2]):+5.0f}) "
        f"step ({step[0]:+.3f} {step[1]:+.3f} {step[2]:+5.1f}) ph {t}{'L' if left else 'R'} "
        f"drift {r.get('drift', 0):+5.1f} pitch {r['pitch']:+5.1f} roll {r['roll']:+5.1f} "
        f"gyro ({r['gyro'][0]:+6.0f} {r['gyro'][1]:+6.0f} {r['gyro'][2]:+6.0f})"
    )


def trace(robot_type: int, seed: int, seconds: float, walk_file: Path, every: int) -> None:
    rng = np.random.default_rng(seed)
    driver = new_driver(robot_type, seed, beam=(-6.0, 0.0, 0.0), walk_file=walk_file)
    history: deque = deque(maxlen=100)
    try:
        target = _random_target(rng)
        start = driver.ground_pose()
        arrival_cycle = None
        arrival_row = None
        for cycle in range(round(seconds / 0.02)):
            done = driver.run("walk", *target)
            row = _record(driver, target, cycle)
            history.append(row)
            if row["arrived"] and arrival_cycle is None:
                arrival_cycle, arrival_row = cycle, row
            if not row["arrived"]:
                arrival_cycle = None
            if driver.fallen():
                print(f"FALL type{robot_type} seed {seed} at cycle {cycle}, target {target}")
                for r in list(history)[::-1][::every][::-1]:
                    print("  " + _fmt(r))
                x, y, _ = driver.ground_pose()
                driver.put_back(x, y)
                print(f"  put back: standing {driver.is_standing()}")
                history.clear()
                continue
            if done:
                x, y, h = driver.ground_pose()
                est = driver.world.pose
                loc = math.hypot(est.x - x, est.y - y)
                went = (
                    math.hypot(x - arrival_row["truth"][0], y - arrival_row["truth"][1])
                    if arrival_row
                    else float("nan")
                )
                travel = math.hypot(target[0] - start[0], target[1] - start[1])
                # the truth's miss in the frame of the approach: along (+ = beyond the target)
                # and across the way from the arrival point to the target
                ax, ay = (arrival_row or row)["truth"][:2]
                way = math.atan2(target[1] - ay, target[0] - ax)
                ex, ey = x - target[0], y - target[1]
                along = math.cos(way) * ex + math.sin(way) * ey
                across = -math.sin(way) * ex + math.cos(way) * ey
                vel = (arrival_row or row).get("vel", (0.0, 0.0, 0.0))
                print(
                    f"target ({target[0]:+.2f} {target[1]:+.2f} "
                    f"{'-' if target[2] is None else f'{target[2]:+.0f}'}) travel {travel:.1f} "
                    f"err_truth {row['d_truth']:.3f} err_est {row['d_est']:.3f} loc {loc:.3f} "
                    f"arrive_est {arrival_row['d_est'] if arrival_row else float('nan'):.3f} "
                    f"arrive_truth {arrival_row['d_truth'] if arrival_row else float('nan'):.3f} "
                    f"stop_cycles {cycle - (arrival_cycle or cycle)} went {went:.3f} "
                    f"t {cycle * 0.02:.1f} along {along:+.3f} across {across:+.3f} "
                    f"v_arrive ({vel[0]:+.2f} {vel[1]:+.2f} {math.degrees(vel[2]):+.0f})"
                )
                target = _random_target(rng)
                start = (x, y, h)
                arrival_cycle, arrival_row = None, None
    finally:
        driver.session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--type", type=int, required=True)
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--every", type=int, default=2, help="print every n-th cycle of a fall")
    parser.add_argument("--set", action="append", default=[], metavar="DOTTED.KEY=VALUE")
    args = parser.parse_args()
    with walk_file_with(args.set) as walk_file:
        trace(args.type, args.seed, args.seconds, walk_file, args.every)


if __name__ == "__main__":
    main()
