"""Falls of the walk under random command sequences: the walk residual environment's episodes.

Each episode (``naosoccer/WalkResidual-v0`` with zero residual, so the packaged walk alone) starts
from a standing snapshot and changes its ``walk_velocity``-like command every ``--every``
seconds: forward 0-1 m/s, half of the commands with up to +-0.2 m/s sideways and +-45 deg/s
turning. Prints the falls and the seeds that fell. Why: the benchmark's walk figures hold one
command per run and walk to targets at 0.65 m/s at most; session 22's searched fast type-0 gait
passed those and fell here (3 of 30, seeds 0-29, where the packaged walk falls none).

Run: ``python scripts/walk_command_falls.py --type 0 --seeds 0 30`` (the packaged walk);
``--set type4.step.max_forward=0.17`` (repeatable) walks with a ``walk.yaml`` setting changed (a
temporary copy, as ``benchmarks/locomotion.py --set``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.locomotion import walk_file_with
from learning.envs.walk import WalkResidualEnv
from learning.walk_eval import run_episode


def command_falls(
    robot_type: int, seeds: range, seconds: float, every: float, walk_file: Path | None = None
) -> list[int]:
    """The seeds whose episode ended in a fall (``learning.walk_eval``'s episodes, no
    policy: the residual is zero), walking with ``walk_file`` (None: the packaged walk)."""
    config = {"robot_types": [robot_type], "episode_s": seconds, "command_every_s": every}
    if walk_file is not None:
        config["walk_file"] = str(walk_file)
    env = WalkResidualEnv(config)
    try:
        return [seed for seed in seeds if run_episode(env, None, seed, {})[1]]
    finally:
        env.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--type", type=int, default=0)
    parser.add_argument("--seeds", type=int, nargs=2, default=[0, 30], metavar=("FIRST", "END"))
    parser.add_argument("--seconds", type=float, default=6.0, help="episode length")
    parser.add_argument("--every", type=float, default=1.5, help="seconds between commands")
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="DOTTED.KEY=VALUE",
        help="walk with a walk.yaml setting changed (a temporary copy)",
    )
    args = parser.parse_args()
    seeds = range(*args.seeds)
    with walk_file_with(args.set) as walk_file:
        fell = command_falls(args.type, seeds, args.seconds, args.every, walk_file)
    print(f"command_falls[type{args.type}]: {len(fell)} of {len(seeds)}")
    print(f"fell_seeds[type{args.type}]: {' '.join(map(str, fell)) or '-'}")


if __name__ == "__main__":
    main()
