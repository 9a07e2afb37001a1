"""Random-target walk figures over many seed sets in one process, per set and in total.

``benchmarks/locomotion.py --skip-velocity --skip-dribble --skip-kick --random-seeds 3 --seed S``
run once per ``S``, with the figures summed: falls per type (and which run seeds fell, for
``scripts/walk_trace.py``), the mean of the per-type mean stop errors, the largest stop error
and how many per-type largest stop errors were above 0.1 m; per type, falls, the mean of all
its stops, its largest and the targets reached. Why: falls are rare, one seed set
says little, and comparing walk settings needs the same 15 sets run the same way each time.

Run: ``python scripts/walk_seed_sets.py --seeds 0 7 13 21 29 [--types 2] [--set key=value]``
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.locomotion import random_targets, walk_file_with
from world.nao_model import ROBOT_TYPES


def run_sets(
    seeds: list[int], types: list[int], runs: int, seconds: float, walk_file: Path
) -> None:
    """Print one line per seed set and type, then the totals."""
    falls_by_type = dict.fromkeys(types, 0)
    errors_by_type: dict[int, list[float]] = {t: [] for t in types}
    type_means: list[float] = []
    largest: list[float] = []
    reached_total = 0
    fell_runs: list[str] = []
    for s in seeds:
        for robot_type in types:
            falls, errors = 0, []
            for k in range(runs):
                seed = s + robot_type + 100 * k
                run_falls, run_errors, _ = random_targets(robot_type, seconds, seed, walk_file)
                falls += run_falls
                errors.extend(run_errors)
                if run_falls:
                    fell_runs.append(f"type{robot_type}/seed{seed}x{run_falls}")
            falls_by_type[robot_type] += falls
            errors_by_type[robot_type].extend(errors)
            mean = float(np.mean(errors)) if errors else float("nan")
            top = max(errors, default=float("nan"))
            type_means.append(mean)
            largest.append(top)
            reached_total += len(errors)
            print(
                f"S={s} type{robot_type}: falls {falls} stop mean {mean:.3f} max {top:.3f} "
                f"reached {len(errors)}",
                flush=True,
            )
    print(f"falls per type: {falls_by_type} total {sum(falls_by_type.values())}")
    for robot_type, errors in errors_by_type.items():
        mean = float(np.mean(errors)) if errors else float("nan")
        top = max(errors, default=float("nan"))
        print(
            f"type{robot_type}: falls {falls_by_type[robot_type]} stop mean {mean:.3f} "
            f"largest {top:.3f} reached {len(errors)}"
        )
    print(f"fell runs: {' '.join(fell_runs) or '-'}")
    print(
        f"mean of per-type mean stop errors {np.nanmean(type_means):.3f} m, largest "
        f"{np.nanmax(largest):.3f} m, per-type largest > 0.1 m in "
        f"{sum(v > 0.1 for v in largest)} of {len(largest)}, targets reached {reached_total}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, nargs="+", required=True)
    parser.add_argument("--types", type=int, nargs="+", default=list(ROBOT_TYPES))
    parser.add_argument("--random-seeds", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--set", action="append", default=[], metavar="DOTTED.KEY=VALUE")
    args = parser.parse_args()
    with walk_file_with(args.set) as walk_file:
        run_sets(args.seeds, args.types, args.random_seeds, args.seconds, walk_file)


if __name__ == "__main__":
    main()
