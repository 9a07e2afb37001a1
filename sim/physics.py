"""The PyBullet world that every session steps: one private physics client per world.

Each :class:`PhysicsWorld` owns its own ``pybullet.DIRECT`` client, so many worlds (sessions)
live side by side in one process without sharing state.
"""

from __future__ import annotations

import pybullet

CYCLE_SECONDS = 0.02
GRAVITY = -9.81


class PhysicsWorld:
    """A PyBullet client stepped in server cycles of 0.02 s, each split into ``substeps``."""

    def __init__(self, substeps: int = 4) -> None:
        if substeps < 1:
            raise ValueError(f"substeps must be >= 1, got {substeps}")
        self.substeps = substeps
        self.client = pybullet.connect(pybullet.DIRECT)
        pybullet.setGravity(0.0, 0.0, GRAVITY, physicsClientId=self.client)
        pybullet.setPhysicsEngineParameter(
            fixedTimeStep=CYCLE_SECONDS / substeps,
            numSubSteps=0,
            deterministicOverlappingPairs=1,
            physicsClientId=self.client,
        )

    def step_cycle(self) -> None:
        """Advance the world by one server cycle (0.02 s)."""
        for _ in range(self.substeps):
            pybullet.stepSimulation(physicsClientId=self.client)

    def close(self) -> None:
        if self.client >= 0 and pybullet.isConnected(self.client):
            pybullet.disconnect(self.client)
        self.client = -1
