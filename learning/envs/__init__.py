"""Gymnasium environments of naosoccer's trained skills.

Importing this package registers them with gymnasium, so that
``gymnasium.make("naosoccer/GetUpResidual-v0", config={...})`` works.
"""

from __future__ import annotations

from gymnasium.envs.registration import register, registry

from learning.envs.get_up import GetUpEnvConfig, GetUpResidualEnv

GET_UP_RESIDUAL_ID = "naosoccer/GetUpResidual-v0"

if GET_UP_RESIDUAL_ID not in registry:
    register(id=GET_UP_RESIDUAL_ID, entry_point="learning.envs.get_up:GetUpResidualEnv")

__all__ = ["GET_UP_RESIDUAL_ID", "GetUpEnvConfig", "GetUpResidualEnv"]
