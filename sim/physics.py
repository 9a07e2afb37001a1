"""The PyBullet world that every session steps: one private physics client per world.

Each :class:`PhysicsWorld` owns its own ``pybullet.DIRECT`` client, so many worlds (sessions)
live side by side in one process without sharing state.

Save and restore (:meth:`PhysicsWorld.save_state`, :meth:`PhysicsWorld.restore_state`) must let
a restored world continue bit for bit like the original. Bullet's own ``saveState`` keeps
positions and velocities but not what the solver carries from step to step: the persistent
contact manifolds (which contact points exist, their cached impulses) and the motor targets.
The world therefore

* sorts overlapping pairs (``deterministicOverlappingPairs``) so pair order never depends on
  history, and switches warm starting off (``warmStartingFactor = 0``): cached impulses then
  have no influence on the next step;
* drops every contact manifold on save AND on restore (:meth:`_forget_contacts`),
  self-collision pairs inside a robot included, so the original world continues from exactly
  the state that a restore reproduces;
* keeps Python-side state (motor targets, sensor memories) of registered holders such as
  :class:`sim.robot.SimRobot` in the snapshot.

The price: one collision pass per save/restore, and no warm starting (a few more solver
iterations would compensate; the fidelity benchmark is measured with this setting).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import pybullet

CYCLE_SECONDS = 0.02
GRAVITY = -9.81
#: Sequential-impulse iterations per step (Bullet's default is 50). With 10, loaded joints give
#: under the robot's weight (type 4's toes sag 30-50 deg) and an agent holding a crouch through
#: its delayed speed loop rocks 5-10 deg at about 1 Hz; from 20 on the robot holds still (30
#: for type 4's toes). 30 costs about 20 % of the 22-robot cycle rate (benchmarks/physics.py).
SOLVER_ITERATIONS = 30
#: Bullet's collision filter of dynamic bodies (btBroadphaseProxy::DefaultFilter, AllFilter)
DYNAMIC_FILTER_GROUP = 1
ALL_FILTER_MASK = -1


class StateHolder(Protocol):
    """An object living in the world that keeps state outside Bullet (e.g. motor targets)."""

    def python_state(self) -> Any: ...

    def before_cycle(self) -> None: ...

    def before_substep(self, fraction: float) -> None: ...

    def restore_python_state(self, state: Any) -> None: ...


@dataclass(frozen=True)
class WorldSnapshot:
    """A saved world: Bullet's in-memory state id plus the holders' Python states."""

    bullet_state_id: int
    holders: tuple[tuple[int, Any], ...]


class PhysicsWorld:
    """A PyBullet client stepped in server cycles of 0.02 s, each split into ``substeps``."""

    def __init__(self, substeps: int = 4) -> None:
        if substeps < 1:
            raise ValueError(f"substeps must be >= 1, got {substeps}")
        self.substeps = substeps
        self._current_substeps = substeps
        self.client = pybullet.connect(pybullet.DIRECT)
        self._holders: dict[int, StateHolder] = {}
        pybullet.setGravity(0.0, 0.0, GRAVITY, physicsClientId=self.client)
        pybullet.setPhysicsEngineParameter(
            fixedTimeStep=CYCLE_SECONDS / substeps,
            numSubSteps=0,
            numSolverIterations=SOLVER_ITERATIONS,
            deterministicOverlappingPairs=1,
            warmStartingFactor=0.0,
            physicsClientId=self.client,
        )

    def step_cycle(self, substeps: int | None = None) -> None:
        """Advance the world by one server cycle (0.02 s), letting every registered holder
        (robot) prepare its motors first. ``substeps`` overrides the world's count for this
        cycle (the session refines cycles in which a fast foot nears the ball)."""
        substeps = substeps or self.substeps
        if substeps != self._current_substeps:
            pybullet.setPhysicsEngineParameter(
                fixedTimeStep=CYCLE_SECONDS / substeps, physicsClientId=self.client
            )
            self._current_substeps = substeps
        holders = list(self._holders.values())
        for holder in holders:
            holder.before_cycle()
        for k in range(substeps):
            for holder in holders:
                holder.before_substep(k / substeps)
            pybullet.stepSimulation(physicsClientId=self.client)

    # ---------------------------------------------------------------- save / restore
    def register_state_holder(self, holder: StateHolder) -> None:
        """Include ``holder``'s Python state in every snapshot (robots call this)."""
        self._holders[id(holder)] = holder

    def unregister_state_holder(self, holder: StateHolder) -> None:
        self._holders.pop(id(holder), None)

    def save_state(self) -> WorldSnapshot:
        """Snapshot the world. The live world is normalised too (contact caches dropped), so it
        continues exactly as a world restored from this snapshot will."""
        self._forget_contacts()
        state_id = pybullet.saveState(physicsClientId=self.client)
        holders = tuple((key, h.python_state()) for key, h in self._holders.items())
        return WorldSnapshot(state_id, holders)

    def restore_state(self, state: WorldSnapshot) -> None:
        """Return to ``state`` (taken from this world, with the same bodies present)."""
        pybullet.restoreState(stateId=state.bullet_state_id, physicsClientId=self.client)
        for key, holder_state in state.holders:
            holder = self._holders.get(key)
            if holder is not None:
                holder.restore_python_state(holder_state)
        self._forget_contacts()

    def _forget_contacts(self) -> None:
        """Empty every persistent contact manifold, leaving no trace of the world's history.

        PyBullet has no call for this, but setting a link's collision filter removes its
        collision object from the broadphase and adds it again, which destroys every pair (and
        contact manifold) it was part of, self-collision pairs inside a robot included. The
        filter is set to the value the loaders give dynamic bodies (group 1, mask all), so
        collisions are unchanged; static bodies (ground, goals, walls) lose their pairs with
        the moving bodies all the same.
        """
        cid = self.client
        for i in range(pybullet.getNumBodies(physicsClientId=cid)):
            body = pybullet.getBodyUniqueId(i, physicsClientId=cid)
            links = pybullet.getNumJoints(body, physicsClientId=cid)
            if links == 0 and pybullet.getDynamicsInfo(body, -1, physicsClientId=cid)[0] == 0.0:
                continue  # static: keeps its own filter
            for link in range(-1, links):
                pybullet.setCollisionFilterGroupMask(
                    body, link, DYNAMIC_FILTER_GROUP, ALL_FILTER_MASK, physicsClientId=cid
                )

    def close(self) -> None:
        if self.client >= 0 and pybullet.isConnected(self.client):
            pybullet.disconnect(self.client)
        self.client = -1
