"""``python -m learning.envs [--seconds 30] [--falls-per-type 40]``: how fast the get-up
residual environment steps (zero actions: the keyframes alone) and how long its fall bank
takes to build; the figure that sizes a training run."""

from __future__ import annotations

import argparse

from learning.envs.get_up import GetUpEnvConfig, measure_speed


def main() -> None:
    """``python -m learning.envs --seconds 30``: the get-up environment's speed."""
    parser = argparse.ArgumentParser(description=measure_speed.__doc__)
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--falls-per-type", type=int, default=40)
    args = parser.parse_args()
    result = measure_speed(GetUpEnvConfig(falls_per_type=args.falls_per_type), args.seconds)
    print(
        f"fall bank: {result['bank_s']:.1f} s; env steps/s (zero action): "
        f"{result['steps_per_s']:.0f}; {result['episodes']} episodes, success "
        f"{result['success']:.3f}"
    )


if __name__ == "__main__":
    main()
