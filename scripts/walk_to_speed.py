"""How fast ``walk`` gets to targets 3-6 m away: seconds per target and mean speed per type.

One robot per type and start seed walks to ``--targets`` targets in a row, each drawn 3-6 m
from where it stands (in the benchmark's area, x -10..-2, y -4..4, half of them with a final
heading), as players walk to the ball and to their formation places. Per target it measures
the seconds from the order to ``walk`` reporting arrival and the straight distance, and prints
per type: targets reached, mean seconds, mean speed (sum of distances over sum of seconds),
falls and the largest stop error (ground truth). Why: the random-target figures
(``scripts/walk_seed_sets.py``) count targets reached per minute, which mixes short and long
walks; this one says what a raised ``walk_to_max_speed`` buys on the walks a match is made of.

Run: ``python scripts/walk_to_speed.py [--types 0 1 2 3 4] [--seeds 0 1] [--targets 6]
[--set key=value]``
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.locomotion import new_driver, walk_file_with
from world.nao_model import ROBOT_TYPES

#: how long one target may take before it counts as not reached
TARGET_TIMEOUT_S = 30.0


def _target_from(rng: np.random.Generator, x: float, y: float) -> tuple[float, float, float | None]:
    """A target 3-6 m from (x, y) inside the benchmark's area (x -10..-2, y -4..4)."""
    while True:
        distance = rng.uniform(3.0, 6.0)
        bearing = rng.uniform(-math.pi, math.pi)
        tx, ty = x + distance * math.cos(bearing), y + distance * math.sin(bearing)
        if -10.0 <= tx <= -2.0 and -4.0 <= ty <= 4.0:
            heading = None if rng.random() < 0.5 else float(rng.uniform(-180, 180))
            return float(tx), float(ty), heading


def walk_to_targets(
    robot_type: int, seed: int, targets: int, walk_file: Path
) -> tuple[list[float], list[float], list[float], int]:
    """(seconds, distances, stop errors) of the reached targets and the falls of one run."""
    rng = np.random.default_rng(seed)
    driver = new_driver(robot_type, seed, beam=(-6.0, 0.0, 0.0), walk_file=walk_file)
    seconds: list[float] = []
    distances: list[float] = []
    errors: list[float] = []
    falls = 0
    try:
        for _ in range(targets):
            x, y, _ = driver.ground_pose()
            target = _target_from(rng, x, y)
            for cycle in range(round(TARGET_TIMEOUT_S / 0.02)):
                fell, done = driver.walk_cycle(target)
                falls += fell
                if fell:
                    break
                if done:
                    ex, ey, _ = driver.ground_pose()
                    seconds.append((cycle + 1) * 0.02)
                    distances.append(math.hypot(target[0] - x, target[1] - y))
                    errors.append(math.hypot(target[0] - ex, target[1] - ey))
                    break
        return seconds, distances, errors, falls
    finally:
        driver.session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--types", type=int, nargs="+", default=list(ROBOT_TYPES))
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
    parser.add_argument("--targets", type=int, default=6)
    parser.add_argument("--set", action="append", default=[], metavar="DOTTED.KEY=VALUE")
    args = parser.parse_args()
    with walk_file_with(args.set) as walk_file:
        all_seconds: list[float] = []
        all_distances: list[float] = []
        for robot_type in args.types:
            seconds: list[float] = []
            distances: list[float] = []
            errors: list[float] = []
            falls = 0
            for seed in args.seeds:
                s, d, e, f = walk_to_targets(robot_type, seed + robot_type, args.targets, walk_file)
                seconds += s
                distances += d
                errors += e
                falls += f
            all_seconds += seconds
            all_distances += distances
            mean_s = float(np.mean(seconds)) if seconds else float("nan")
            speed = sum(distances) / sum(seconds) if seconds else float("nan")
            print(
                f"type{robot_type}: reached {len(seconds)} of {args.targets * len(args.seeds)} "
                f"mean {mean_s:.2f} s for {np.mean(distances):.2f} m, speed {speed:.3f} m/s, "
                f"falls {falls}, stop largest {max(errors, default=float('nan')):.3f} m",
                flush=True,
            )
        total = sum(all_distances) / sum(all_seconds) if all_seconds else float("nan")
        print(f"all types: speed {total:.3f} m/s over {len(all_seconds)} targets")


if __name__ == "__main__":
    main()
