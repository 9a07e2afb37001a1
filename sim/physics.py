"""The PyBullet world that every session steps: one private physics client per world.

Each :class:`PhysicsWorld` owns its own ``pybullet.DIRECT`` client, so many worlds (sessions)
live side by side in one process without sharing state.

Save and restore (:meth:`PhysicsWorld.save_state`, :meth:`PhysicsWorld.restore_state`) must let
a restored world continue bit for bit like the original. The world captures every moving body's
state itself (base pose and velocity, joint positions and velocities: :class:`BodyState`)
rather than with Bullet's ``saveState``, whose ``restoreState`` looks bodies up by ids that go
wrong once another client in the process has created bodies, and whose snapshots are never
freed. Neither keeps what the solver carries from step to step: the persistent contact
manifolds (which contact points exist, their cached impulses) and the motor targets. The world
therefore

* sorts overlapping pairs (``deterministicOverlappingPairs``) so pair order never depends on
  history, and switches warm starting off (``warmStartingFactor = 0``): cached impulses then
  have no influence on the next step;
* drops every contact manifold on save AND on restore (:meth:`_forget_contacts`),
  self-collision pairs inside a robot included, so the original world continues from exactly
  the state that a restore reproduces;
* keeps Python-side state (motor targets, sensor memories) of registered holders such as
  :class:`sim.robot.SimRobot` in the snapshot;
* writes the captured state straight back into the live world on save: reading a pose and
  setting it again is not exact in the last bit (Bullet converts between quaternion and
  matrix), so the original continues from the very numbers a restore will set.

The price: one collision pass per save/restore, and no warm starting (a few more solver
iterations would compensate; the fidelity benchmark is measured with this setting).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import pybullet

from world.perception import CYCLE_SECONDS

GRAVITY = -9.81
#: Sequential-impulse iterations per step (Bullet's default is 50). With 10, loaded joints give
#: under the robot's weight (type 4's toes sag 30-50 deg) and an agent holding a crouch through
#: its delayed speed loop rocks 5-10 deg at about 1 Hz; from 20 on the robot holds still (30
#: for type 4's toes). But at 30 the joints of a robot on one leg still give: a basic kick fell
#: after contact about one time in five, and the stand itself leans up to 0.4 deg one way
#: (the solver's fixed order is not left-right symmetric; benchmarks/symmetry.py). At 60 the
#: kicks stand (1 fall in 80 against 19) and the get-up succeeds more often (376 of 400
#: against 353); the fidelity checks pass at both. The price: 22 robots cost about 20 ms of
#: CPU per cycle against 14 at 30 (benchmarks/physics.py; session 27, runs/kick_abort/).
SOLVER_ITERATIONS = 60
#: Bullet's collision filter of dynamic bodies (btBroadphaseProxy::DefaultFilter, AllFilter)
DYNAMIC_FILTER_GROUP = 1
ALL_FILTER_MASK = -1


class StateHolder(Protocol):
    """An object living in the world that keeps state outside Bullet (e.g. motor targets)."""

    def python_state(self) -> Any: ...

    def before_cycle(self) -> None: ...

    def before_substep(self, fraction: float) -> None: ...

    def restore_python_state(self, state: Any) -> None: ...


Vec = tuple[float, ...]


@dataclass(frozen=True)
class BodyState:
    """The dynamic state of one moving body: what Bullet integrates from step to step."""

    body_id: int
    position: Vec
    orientation: Vec
    linear_velocity: Vec
    angular_velocity: Vec
    joint_positions: tuple[float, ...]
    joint_velocities: tuple[float, ...]


@dataclass(frozen=True)
class WorldSnapshot:
    """A saved world: every moving body's state plus the holders' Python states."""

    bodies: tuple[BodyState, ...]
    holders: tuple[tuple[int, Any], ...]


class PhysicsWorld:
    """A PyBullet client stepped in server cycles of 0.02 s, each split into ``substeps``."""

    def __init__(self, substeps: int = 4, min_bounce_speed: float | None = None) -> None:
        """``min_bounce_speed`` (m/s): contacts closing slower than this do not bounce (Bullet's
        ``restitutionVelocityThreshold``, 0.2 m/s when None); the real server's ball contact
        bounces from 0.8 m/s (``sim.contact_models``)."""
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
        if min_bounce_speed is not None:
            pybullet.setPhysicsEngineParameter(
                restitutionVelocityThreshold=min_bounce_speed, physicsClientId=self.client
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
        """Snapshot the world. The live world is normalised too (body states written back,
        contact caches dropped), so it continues exactly as a world restored from this
        snapshot will."""
        bodies = tuple(self._body_state(body) for body in self._moving_bodies())
        holders = tuple((key, h.python_state()) for key, h in self._holders.items())
        for body in bodies:
            self._set_body_state(body)
        self._forget_contacts()
        return WorldSnapshot(bodies, holders)

    def restore_state(self, state: WorldSnapshot) -> None:
        """Return to ``state`` (taken from this world, with the same bodies present)."""
        present = set(self._moving_bodies())
        missing = [b.body_id for b in state.bodies if b.body_id not in present]
        if missing:
            raise ValueError(f"bodies {missing} of the snapshot are no longer in the world")
        for body in state.bodies:
            self._set_body_state(body)
        for key, holder_state in state.holders:
            holder = self._holders.get(key)
            if holder is not None:
                holder.restore_python_state(holder_state)
        self._forget_contacts()

    def _moving_bodies(self) -> list[int]:
        """Ids of the bodies that move (static ones have mass 0 and no joints)."""
        cid = self.client
        ids = [
            pybullet.getBodyUniqueId(i, physicsClientId=cid)
            for i in range(pybullet.getNumBodies(physicsClientId=cid))
        ]
        return [body for body in ids if not self._is_static(body)]

    def _is_static(self, body: int) -> bool:
        cid = self.client
        return (
            pybullet.getNumJoints(body, physicsClientId=cid) == 0
            and pybullet.getDynamicsInfo(body, -1, physicsClientId=cid)[0] == 0.0
        )

    def _body_state(self, body: int) -> BodyState:
        cid = self.client
        position, orientation = pybullet.getBasePositionAndOrientation(body, physicsClientId=cid)
        linear, angular = pybullet.getBaseVelocity(body, physicsClientId=cid)
        joints = range(pybullet.getNumJoints(body, physicsClientId=cid))
        states = pybullet.getJointStates(body, joints, physicsClientId=cid) if joints else []
        return BodyState(
            body,
            tuple(position),
            tuple(orientation),
            tuple(linear),
            tuple(angular),
            tuple(s[0] for s in states),
            tuple(s[1] for s in states),
        )

    def _set_body_state(self, state: BodyState) -> None:
        cid, body = self.client, state.body_id
        pybullet.resetBasePositionAndOrientation(
            body, state.position, state.orientation, physicsClientId=cid
        )
        pybullet.resetBaseVelocity(
            body, state.linear_velocity, state.angular_velocity, physicsClientId=cid
        )
        for joint, (q, qdot) in enumerate(
            zip(state.joint_positions, state.joint_velocities, strict=True)
        ):
            pybullet.resetJointState(body, joint, q, qdot, physicsClientId=cid)

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
        for body in self._moving_bodies():  # static bodies keep their own filter
            for link in range(-1, pybullet.getNumJoints(body, physicsClientId=cid)):
                pybullet.setCollisionFilterGroupMask(
                    body, link, DYNAMIC_FILTER_GROUP, ALL_FILTER_MASK, physicsClientId=cid
                )

    def close(self) -> None:
        if self.client >= 0 and pybullet.isConnected(self.client):
            pybullet.disconnect(self.client)
        self.client = -1
