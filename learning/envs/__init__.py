"""Gymnasium environments of naosoccer's trained skills.

Importing this package registers them with gymnasium, so that
``gymnasium.make("naosoccer/GetUpResidual-v0", config={...})`` (and
``"naosoccer/WalkResidual-v0"``) works.
"""

from __future__ import annotations

from gymnasium.envs.registration import register, registry

from learning.envs.get_up import GetUpEnvConfig, GetUpResidualEnv
from learning.envs.walk import WalkEnvConfig, WalkResidualEnv

GET_UP_RESIDUAL_ID = "naosoccer/GetUpResidual-v0"
WALK_RESIDUAL_ID = "naosoccer/WalkResidual-v0"

if GET_UP_RESIDUAL_ID not in registry:
    register(id=GET_UP_RESIDUAL_ID, entry_point="learning.envs.get_up:GetUpResidualEnv")
if WALK_RESIDUAL_ID not in registry:
    register(id=WALK_RESIDUAL_ID, entry_point="learning.envs.walk:WalkResidualEnv")

__all__ = [
    "GET_UP_RESIDUAL_ID",
    "WALK_RESIDUAL_ID",
    "GetUpEnvConfig",
    "GetUpResidualEnv",
    "WalkEnvConfig",
    "WalkResidualEnv",
]
