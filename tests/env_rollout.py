"""A rollout written as bytes and numbers, for the environments' reproducibility tests."""

from __future__ import annotations

import gymnasium as gym
import numpy as np


def rollout(env: gym.Env, seed: int, actions: np.ndarray) -> list[tuple]:
    """Reset ``env`` with ``seed`` and play ``actions`` until the episode ends: every
    observation (as bytes), reward and end flag, so two runs compare exactly."""
    obs, _ = env.reset(seed=seed)
    out = [(obs.tobytes(),)]
    for action in actions:
        obs, reward, terminated, truncated, _ = env.step(action)
        out.append((obs.tobytes(), reward, terminated, truncated))
        if terminated or truncated:
            break
    return out
