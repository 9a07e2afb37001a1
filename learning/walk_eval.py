"""Evaluate the learned walk's residual (or the engine alone) in its training environment.

Run::

    python -m learning.walk_eval [--policy runs/walk_X/policy.npz] [--types 0 1 2 3 4]
        [--episodes 4] [--seconds 8] [--seed 0]

Prints one ``name: value`` line per figure and robot type: ``walk_full_mps[typeT]`` (forward
speed over the last step windows of a straight 1.0 m/s command, mean of the episodes),
``walk_full_falls[typeT]``, and for random commands (the training distribution)
``walk_tracking[typeT]`` (mean tracking reward per cycle, 1.5 = perfect) and
``walk_random_falls[typeT]``. Without ``--policy`` the residual is zero: the engine alone, the
baseline a trained policy must beat.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from behaviors.learned_walk import LEG_JOINTS, PolicyWalkResidual
from learning.envs.walk import WalkEnvConfig, WalkResidualEnv

#: The straight command of the speed figure: the fastest the environment asks.
FULL_SPEED_COMMAND = (1.0, 0.0, 0.0)


def run_episode(
    env: WalkResidualEnv,
    policy: PolicyWalkResidual | None,
    seed: int,
    options: dict,
) -> tuple[float, bool, list[float]]:
    """One episode: (mean tracking reward per cycle, fell, forward speeds after 1 s)."""
    obs, _ = env.reset(seed=seed, options=options)
    zero = np.zeros(len(LEG_JOINTS), dtype=np.float32)
    rewards, speeds = [], []
    while True:
        action = zero if policy is None else policy.policy.raw_action(obs).astype(np.float32)
        obs, reward, terminated, truncated, info = env.step(action)
        rewards.append(reward)
        if info["seconds"] >= 1.0:
            speeds.append(info["velocity"][0])
        if terminated or truncated:
            return float(np.mean(rewards)), bool(terminated), speeds


def evaluate(
    policy: PolicyWalkResidual | None,
    types: Sequence[int],
    episodes: int,
    seconds: float,
    seed: int,
) -> dict[str, float]:
    """The figures of the module docstring, by name."""
    figures: dict[str, float] = {}
    env = WalkResidualEnv(WalkEnvConfig(robot_types=tuple(types), episode_s=seconds))
    try:
        for robot_type in types:
            full_speeds, full_falls, tracking, random_falls = [], 0, [], 0
            for episode in range(episodes):
                fixed = {"robot_type": robot_type, "command": FULL_SPEED_COMMAND}
                _, fell, speeds = run_episode(env, policy, seed + episode, fixed)
                full_falls += fell
                full_speeds.extend(speeds)
                reward, fell, _ = run_episode(
                    env, policy, seed + 1000 + episode, {"robot_type": robot_type}
                )
                tracking.append(reward)
                random_falls += fell
            tag = f"[type{robot_type}]"
            figures[f"walk_full_mps{tag}"] = float(np.mean(full_speeds)) if full_speeds else 0.0
            figures[f"walk_full_falls{tag}"] = full_falls
            figures[f"walk_tracking{tag}"] = float(np.mean(tracking))
            figures[f"walk_random_falls{tag}"] = random_falls
            print(f"# type {robot_type} done", flush=True)
    finally:
        env.close()
    return figures


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--policy", type=Path, help="policy.npz (default: the engine alone)")
    parser.add_argument("--types", type=int, nargs="+", default=[0, 1, 2, 3, 4])
    parser.add_argument("--episodes", type=int, default=4)
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    policy = PolicyWalkResidual(args.policy) if args.policy else None
    figures = evaluate(policy, args.types, args.episodes, args.seconds, args.seed)
    for name, value in figures.items():
        print(f"{name}: {value:.3f}" if isinstance(value, float) else f"{name}: {value}")


if __name__ == "__main__":
    main()
