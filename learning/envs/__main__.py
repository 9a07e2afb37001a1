"""``python -m learning.envs [--env get_up|walk] [--seconds 30]``: how fast an environment
steps with zero actions (the keyframes or the walk engine alone) and how long its setup takes
(the get-up's fall bank, the walk's standing robots); the figure that sizes a training run."""

from __future__ import annotations

import argparse

from learning.envs import get_up, walk


def main() -> None:
    """``python -m learning.envs --env walk --seconds 30``: an environment's speed."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--env", choices=("get_up", "walk"), default="get_up")
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--falls-per-type", type=int, default=40, help="get_up only")
    args = parser.parse_args()
    if args.env == "walk":
        result = walk.measure_speed(walk.WalkEnvConfig(), args.seconds)
        print(
            f"standing robots: {result['setup_s']:.1f} s; env steps/s (zero action): "
            f"{result['steps_per_s']:.0f}; {result['episodes']} episodes, fall rate "
            f"{result['fall_rate']:.3f}"
        )
        return
    config = get_up.GetUpEnvConfig(falls_per_type=args.falls_per_type)
    result = get_up.measure_speed(config, args.seconds)
    print(
        f"fall bank: {result['bank_s']:.1f} s; env steps/s (zero action): "
        f"{result['steps_per_s']:.0f}; {result['episodes']} episodes, success "
        f"{result['success']:.3f}"
    )


if __name__ == "__main__":
    main()
