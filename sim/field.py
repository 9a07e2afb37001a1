"""The soccer field in the physics world: ground, goals with nets, border walls, and the ball.

Geometry follows rcssserver3d 0.7.2 (``goal.rsg`` and the monitor scene in
``shared/reference/rcssserver3d-traces/07_monitor_first_full_state.txt``): each goal is a box
0.6 m deep, 2.1 m wide and 0.8 m high behind the goal line, closed by side, back and top
colliders 0.04 m thick; the far walls are unit boxes at x = +-24.99 and y = +-25. The posts and
the crossbar are cylinders of radius 0.02 m whose front touches the goal line.

Ball dynamics follow the real server's ``DragController`` values (linear drag 0.01 N s/m,
angular drag 5e-5 N m s, from ``nao-model-facts.md``). Bullet applies damping as an exponential
decay of the body's velocities, so the drags are converted to Bullet damping coefficients. The
ball's friction (0.9, times the ground's 1.0) ends the sliding phase within a few decimetres,
then the ball rolls at 5/7 of its launch speed; a rolling ball decays with rate
(c_lin + c_ang / r^2) / (m + I / r^2) = 1.05 /s, a time constant of 0.95 s: what the real
server was measured to do (0.94 s). A very small rolling friction ends the exponential tail
so the ball comes to rest after about 5-6 s instead of creeping forever.

Fast contacts: a 0.02 s step lets a fast foot jump over the ball. :data:`DEFAULT_SUBSTEPS` is
the smallest substep count at which a foot box driven at 2..10 m/s (straight, or swung on a
0.2 m pendulum) always hits a resting ball; see ``tests/test_field.py`` and
``benchmarks/ball.py``. The ball also gets Bullet's continuous collision detection so a fast
ball cannot tunnel through a post or a net.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import pybullet

from sim.physics import CYCLE_SECONDS, PhysicsWorld
from world.field_geometry import (
    BALL_MASS,
    BALL_RADIUS,
    GOAL_DEPTH,
    GOAL_HEIGHT,
    GOAL_POST_RADIUS,
    GOAL_WIDTH,
    HALF_LENGTH,
)

Vec3 = tuple[float, float, float]

#: Physics substeps per 0.02 s server cycle for every world that has a ball: the smallest count
#: at which a foot at up to 10 m/s never passes (partly) through a resting ball, whatever the
#: phase of the steps (``foot_strike_speed``, worst of 4 phases). Measured (benchmarks/ball.py):
#: a foot sliding straight is safe to 10 m/s from 3 substeps (1: fails from 4 m/s, 2: from
#: 6 m/s); a foot swung on a 0.2 m hinge (50 rad/s at 10 m/s) needs 6 (3: safe to 4 m/s,
#: 4: to 6 m/s, 5: to 8 m/s). Swept-sphere CCD does not help: Bullet only applies it to rigid
#: bodies, not to multibody links such as robot feet.
DEFAULT_SUBSTEPS = 6

#: Thickness of the goal's side, back and top colliders (the real server's BarDiameter).
NET_THICKNESS = 2 * GOAL_POST_RADIUS

#: Border walls as (centre, full extents), from the real server's monitor scene (StdUnitBox).
WALL_BOXES: tuple[tuple[Vec3, Vec3], ...] = (
    ((-24.99, 0.0, 0.0), (1.0, 51.0, 1.0)),
    ((24.99, 0.0, 0.0), (1.0, 51.0, 1.0)),
    ((0.0, 25.0, 0.0), (50.98, 1.0, 1.0)),
    ((0.0, -25.0, 0.0), (50.98, 1.0, 1.0)),
)

#: Lateral friction of the ground. Bullet multiplies the two bodies' coefficients.
GROUND_FRICTION = 1.0


@dataclass(frozen=True)
class GroundPhysics:
    """Material of the ground plane. Bullet multiplies the two bodies' friction and restitution.

    By default the ground is rigid (no soft-contact parameters) and the robots carry the
    softness of the real server's ground contact (``sim.robot.RobotPhysics``).
    ``contact_stiffness`` (N/m per contact point, with ``contact_damping`` N s/m) moves that
    softness onto the ground instead: Bullet makes a contact soft when either body is soft,
    combining stiffness in series and adding damping, so robot-ground contacts stay the same
    while robots built with ``RobotPhysics(soft_contacts=False)`` touch the ball and each other
    rigidly. Opt-in only (``benchmarks/physics.py --variant strike``).
    """

    lateral_friction: float = GROUND_FRICTION
    restitution: float = 1.0
    rolling_friction: float = 0.0
    contact_stiffness: float | None = None
    contact_damping: float = 0.0

    def dynamics(self) -> dict[str, float]:
        """``changeDynamics`` keyword arguments for the ground plane."""
        params = {
            "lateralFriction": self.lateral_friction,
            "restitution": self.restitution,
            "rollingFriction": self.rolling_friction,
        }
        if self.contact_stiffness is not None:
            params |= {
                "contactStiffness": self.contact_stiffness,
                "contactDamping": self.contact_damping,
            }
        return params


#: The ground of every field built without an explicit ``ground`` (read when it is built).
DEFAULT_GROUND = GroundPhysics()
#: Goal nets swallow the ball (restitution 0); posts and bar return it (restitution 1, so the
#: ball's own 0.8 decides the bounce).
NET_RESTITUTION = 0.0
POST_RESTITUTION = 1.0
NET_FRICTION = 0.5


@dataclass(frozen=True)
class BallPhysics:
    """Ball material and damping. Drags are in the real server's units (force per velocity).

    ``lateral_friction`` is a compromise. The real server's contacts have unbounded friction
    with force-dependent slip: a launched ball rolls after a few centimetres, yet a pushed ball
    slips easily. Bullet has plain Coulomb friction, multiplied by the other body's (ground and
    robot feet: 1.0). At 1.0 or more a ball pushed at its equator by a flat foot jams (friction
    at the foot and at the ground lock its rolling) and the solver drives it into the ground;
    at 0.9 it never jams, at the price of a longer sliding phase: rolls are 6 % (4 m/s) and
    14 % (8 m/s) longer than on the real server (10.0 would give 1 % and 0.5 %).
    ``rolling_friction`` is Bullet's (ignored by its Dantzig LCP solver); it only ends the
    exponential tail of a roll.
    """

    radius: float = BALL_RADIUS
    mass: float = BALL_MASS
    linear_drag: float = 0.01
    angular_drag: float = 5e-5
    lateral_friction: float = 0.9
    rolling_friction: float = 5e-5
    restitution: float = 0.8
    ccd_swept_sphere_radius: float = 0.8 * BALL_RADIUS

    @property
    def inertia(self) -> float:
        """Moment of inertia of a solid sphere (kg m^2)."""
        return 0.4 * self.mass * self.radius**2

    @property
    def bullet_linear_damping(self) -> float:
        """Bullet's ``linearDamping`` d (v *= (1 - d)^dt) equal to a force of -drag * v."""
        return 1.0 - math.exp(-self.linear_drag / self.mass)

    @property
    def bullet_angular_damping(self) -> float:
        """Bullet's ``angularDamping`` equal to a torque of -drag * omega on this sphere."""
        return 1.0 - math.exp(-self.angular_drag / self.inertia)

    @property
    def rolling_time_constant(self) -> float:
        """Predicted e-folding time (s) of a rolling ball's speed, without rolling friction."""
        rate = (self.linear_drag + self.angular_drag / self.radius**2) / (
            self.mass + self.inertia / self.radius**2
        )
        return 1.0 / rate


#: The physics of every ball built without an explicit ``physics`` (read when it is built).
DEFAULT_BALL = BallPhysics()


@dataclass(frozen=True)
class Goal:
    """One goal: its static bodies and the inside of its box (where a ball scores).

    ``side`` is ``"left"`` (x = -15, defended by the left team) or ``"right"`` (x = +15).
    """

    side: str
    post_ids: tuple[int, int]
    crossbar_id: int
    net_ids: tuple[int, ...]

    @property
    def sign(self) -> int:
        return -1 if self.side == "left" else 1

    @property
    def body_ids(self) -> tuple[int, ...]:
        return (*self.post_ids, self.crossbar_id, *self.net_ids)

    def contains(self, point: Vec3) -> bool:
        """True if ``point`` lies inside the goal box: behind the line, between the side nets,
        in front of the back net and below the top net."""
        depth = self.sign * point[0] - HALF_LENGTH
        return (
            0.0 < depth < GOAL_DEPTH
            and abs(point[1]) < GOAL_WIDTH / 2
            and 0.0 <= point[2] < GOAL_HEIGHT
        )


@dataclass(frozen=True)
class Field:
    """The static world: ground plane, both goals and the four border walls."""

    ground_id: int
    goals: tuple[Goal, Goal]
    wall_ids: tuple[int, ...]

    def goal(self, side: str) -> Goal:
        """The goal on ``side`` (``"left"`` or ``"right"``)."""
        for goal in self.goals:
            if goal.side == side:
                return goal
        raise ValueError(f"no goal on side {side!r}")


def _static_box(world: PhysicsWorld, centre: Vec3, extents: Vec3, **dynamics: float) -> int:
    """A fixed box of full size ``extents`` centred at ``centre``."""
    half = [e / 2 for e in extents]
    shape = pybullet.createCollisionShape(
        pybullet.GEOM_BOX, halfExtents=half, physicsClientId=world.client
    )
    return _static_body(world, shape, centre, (0.0, 0.0, 0.0, 1.0), dynamics)


def _static_cylinder(
    world: PhysicsWorld, centre: Vec3, length: float, along_y: bool, **dynamics: float
) -> int:
    """A fixed cylinder of the post radius, vertical or lying along the y axis."""
    shape = pybullet.createCollisionShape(
        pybullet.GEOM_CYLINDER,
        radius=GOAL_POST_RADIUS,
        height=length,
        physicsClientId=world.client,
    )
    orientation = (
        pybullet.getQuaternionFromEuler((math.pi / 2, 0.0, 0.0)) if along_y else (0, 0, 0, 1)
    )
    return _static_body(world, shape, centre, orientation, dynamics)


def _static_body(
    world: PhysicsWorld, shape: int, position: Vec3, orientation, dynamics: dict[str, float]
) -> int:
    body = pybullet.createMultiBody(
        baseMass=0.0,
        baseCollisionShapeIndex=shape,
        basePosition=position,
        baseOrientation=orientation,
        useMaximalCoordinates=True,
        physicsClientId=world.client,
    )
    pybullet.changeDynamics(body, -1, physicsClientId=world.client, **dynamics)
    return body


def _build_goal(world: PhysicsWorld, side: str, post_restitution: float) -> Goal:
    """Posts and crossbar at the goal line, then side, back and top nets closing the box."""
    sign = -1.0 if side == "left" else 1.0
    half_width = GOAL_WIDTH / 2
    r = GOAL_POST_RADIUS
    post = {"restitution": post_restitution, "lateralFriction": NET_FRICTION}
    net = {"restitution": NET_RESTITUTION, "lateralFriction": NET_FRICTION}
    line_x = sign * (HALF_LENGTH + r)  # post axis: its front touches the goal line
    posts = tuple(
        _static_cylinder(
            world, (line_x, y * (half_width + r), GOAL_HEIGHT / 2), GOAL_HEIGHT, False, **post
        )
        for y in (1.0, -1.0)
    )
    bar_length = GOAL_WIDTH + 4 * r
    crossbar = _static_cylinder(world, (line_x, 0.0, GOAL_HEIGHT + r), bar_length, True, **post)
    # Nets start behind the posts so the posts alone shape the goal mouth.
    net_depth = GOAL_DEPTH - 2 * r
    net_mid_x = sign * (HALF_LENGTH + 2 * r + net_depth / 2)
    side_nets = tuple(
        _static_box(
            world,
            (net_mid_x, y * (half_width + r), GOAL_HEIGHT / 2),
            (net_depth, NET_THICKNESS, GOAL_HEIGHT),
            **net,
        )
        for y in (1.0, -1.0)
    )
    back_net = _static_box(
        world,
        (sign * (HALF_LENGTH + GOAL_DEPTH - r), 0.0, (GOAL_HEIGHT + 2 * r) / 2),
        (NET_THICKNESS, bar_length, GOAL_HEIGHT + 2 * r),
        **net,
    )
    top_net = _static_box(
        world,
        (net_mid_x, 0.0, GOAL_HEIGHT + r),
        (net_depth, bar_length, NET_THICKNESS),
        **net,
    )
    return Goal(
        side=side,
        post_ids=posts,  # type: ignore[arg-type]
        crossbar_id=crossbar,
        net_ids=(*side_nets, back_net, top_net),
    )


def build_field(
    world: PhysicsWorld,
    ground: GroundPhysics | None = None,
    post_restitution: float | None = None,
) -> Field:
    """Add the ground plane (z = 0), both goals and the border walls to ``world``;
    ``ground`` defaults to :data:`DEFAULT_GROUND`, ``post_restitution`` (posts and crossbar)
    to :data:`POST_RESTITUTION`."""
    ground_physics = ground if ground is not None else DEFAULT_GROUND
    post = POST_RESTITUTION if post_restitution is None else post_restitution
    plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=world.client)
    ground_id = _static_body(
        world, plane, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), ground_physics.dynamics()
    )
    goals = (_build_goal(world, "left", post), _build_goal(world, "right", post))
    walls = tuple(
        _static_box(world, centre, extents, restitution=NET_RESTITUTION)
        for centre, extents in WALL_BOXES
    )
    return Field(ground_id=ground_id, goals=goals, wall_ids=walls)


class Ball:
    """The match ball: a solid sphere moved only by contacts and by explicit placement.

    Build it with :meth:`create`. The body is a Bullet rigid body (maximal coordinates) because
    Bullet's rigid-body damping is an exact exponential and its continuous collision detection
    only runs for rigid bodies.
    """

    def __init__(self, world: PhysicsWorld, body_id: int, physics: BallPhysics) -> None:
        self._world = world
        self._body_id = body_id
        self.physics = physics
        #: bodies the ball touched in the substeps of this cycle before the last one
        self._touched: set[int] = set()
        world.register_state_holder(self)

    @classmethod
    def create(
        cls,
        world: PhysicsWorld,
        position: Vec3 = (0.0, 0.0, BALL_RADIUS),
        physics: BallPhysics | None = None,
    ) -> Ball:
        """Add a ball resting at ``position`` (its centre) to ``world``; ``physics`` defaults
        to :data:`DEFAULT_BALL`."""
        physics = physics if physics is not None else DEFAULT_BALL
        client = world.client
        shape = pybullet.createCollisionShape(
            pybullet.GEOM_SPHERE, radius=physics.radius, physicsClientId=client
        )
        body = pybullet.createMultiBody(
            baseMass=physics.mass,
            baseCollisionShapeIndex=shape,
            basePosition=position,
            useMaximalCoordinates=True,
            physicsClientId=client,
        )
        pybullet.changeDynamics(
            body,
            -1,
            lateralFriction=physics.lateral_friction,
            rollingFriction=physics.rolling_friction,
            spinningFriction=0.0,
            restitution=physics.restitution,
            linearDamping=physics.bullet_linear_damping,
            angularDamping=physics.bullet_angular_damping,
            ccdSweptSphereRadius=physics.ccd_swept_sphere_radius,
            physicsClientId=client,
        )
        return cls(world, body, physics)

    @property
    def body_id(self) -> int:
        return self._body_id

    def position(self) -> Vec3:
        """Centre of the ball in world coordinates (m)."""
        pos, _ = pybullet.getBasePositionAndOrientation(
            self._body_id, physicsClientId=self._world.client
        )
        return (pos[0], pos[1], pos[2])

    def velocity(self) -> Vec3:
        """Linear velocity of the centre (m/s)."""
        lin, _ = pybullet.getBaseVelocity(self._body_id, physicsClientId=self._world.client)
        return (lin[0], lin[1], lin[2])

    def angular_velocity(self) -> Vec3:
        """Spin (rad/s, world axes)."""
        _, ang = pybullet.getBaseVelocity(self._body_id, physicsClientId=self._world.client)
        return (ang[0], ang[1], ang[2])

    def speed(self) -> float:
        """Magnitude of :meth:`velocity`."""
        return math.sqrt(sum(c * c for c in self.velocity()))

    def launch_speed(self) -> float:
        """Horizontal speed the ball had just after its last impulse, recovered from its linear
        and angular momentum about the ground contact point, which ground friction cannot
        change: v + (2/5) r (omega x z). A ball kicked at v and settling into rolling at 5/7 v
        keeps reporting v, so a kick can be judged at any time after it."""
        vx, vy, _ = self.velocity()
        wx, wy, _ = self.angular_velocity()
        k = 0.4 * self.physics.radius  # I / (m r) for a solid sphere
        return math.hypot(vx + k * wy, vy - k * wx)

    def world_transform(self) -> np.ndarray:
        """4x4 world transform of the ball (rotation and centre), as the monitor sends it."""
        pos, quat = pybullet.getBasePositionAndOrientation(
            self._body_id, physicsClientId=self._world.client
        )
        matrix = np.eye(4)
        matrix[:3, :3] = np.reshape(pybullet.getMatrixFromQuaternion(quat), (3, 3))
        matrix[:3, 3] = pos
        return matrix

    def touching_bodies(self) -> frozenset[int]:
        """Ids of the bodies the ball touched during the last cycle (ground included), in any
        of its substeps. Why every substep: Bullet reports the contacts of the last substep
        only, and a foot that strikes the ball and bounces off within the cycle was missed, so
        the referee saw the kick-off taken seconds late (the ball rolling at 1.1 s, PlayOn at
        3.4 s in an 11 v 11 match, seed 0)."""
        return frozenset(self._touched | self._contacts_now())

    def _contacts_now(self) -> set[int]:
        contacts = pybullet.getContactPoints(
            bodyA=self._body_id, physicsClientId=self._world.client
        )
        return {c[2] for c in contacts}

    # the world's state-holder hooks: collect the contacts of every substep of a cycle
    def before_cycle(self) -> None:
        self._touched = set()

    def before_substep(self, fraction: float) -> None:
        if fraction > 0.0:  # the substep before this one ended with these contacts
            self._touched |= self._contacts_now()

    def python_state(self) -> None:
        """Nothing to keep: the touches are collected anew every cycle."""
        return None

    def restore_python_state(self, state: None) -> None:
        self._touched = set()

    def place(self, position: Vec3, velocity: Vec3 = (0.0, 0.0, 0.0)) -> None:
        """Trainer/referee placement: put the ball at ``position`` with ``velocity`` and no spin.

        This is the only way besides contacts to move the ball, as on the real server (the
        monitor's ``(ball (pos ...) (vel ...))`` command and the referee's ball resets).
        """
        client = self._world.client
        pybullet.resetBasePositionAndOrientation(
            self._body_id, position, (0.0, 0.0, 0.0, 1.0), physicsClientId=client
        )
        pybullet.resetBaseVelocity(self._body_id, velocity, (0.0, 0.0, 0.0), physicsClientId=client)


# --- Fast-contact probe --------------------------------------------------------------------
# A motor-driven foot box is sent through a resting ball, to find the substep count at which
# no contact is missed. It lives here, next to DEFAULT_SUBSTEPS, because it is the measurement
# that justifies that constant (used by tests/test_field.py and benchmarks/ball.py).

#: The NAO foot box (x across, y along the foot, z up) and its mass.
FOOT_EXTENTS: Vec3 = (0.08, 0.16, 0.02)
FOOT_MASS = 0.2
#: Length of the swinging "leg" of the pendulum probe: hinge to foot centre.
SWING_LEG_LENGTH = 0.2
#: Torque/force limit of the probe motors: large, so the foot keeps its commanded speed.
_PROBE_MOTOR_FORCE = 1e5
#: Contact settings of the probe foot: the robot's foot friction (sim/robot.py RobotPhysics).
PROBE_FOOT_DYNAMICS: Mapping[str, float] = MappingProxyType({"lateralFriction": 1.0})


def _foot_shape(world: PhysicsWorld, offset: Vec3 = (0.0, 0.0, 0.0)) -> int:
    """The foot box with its long axis along world x (the direction of motion), its centre at
    ``offset`` in the link frame."""
    width, length, height = FOOT_EXTENTS
    return pybullet.createCollisionShape(
        pybullet.GEOM_BOX,
        halfExtents=(length / 2, width / 2, height / 2),
        collisionFramePosition=offset,
        physicsClientId=world.client,
    )


def _one_link_multibody(
    world: PhysicsWorld, base: Vec3, joint_type: int, axis: Vec3, foot_offset: Vec3
) -> int:
    """A fixed base carrying the foot on one motorised joint (``joint_type`` about/along
    ``axis``), the foot centre ``foot_offset`` from the joint."""
    return pybullet.createMultiBody(
        baseMass=0.0,
        basePosition=base,
        linkMasses=[FOOT_MASS],
        linkCollisionShapeIndices=[_foot_shape(world, foot_offset)],
        linkVisualShapeIndices=[-1],
        linkPositions=[(0.0, 0.0, 0.0)],
        linkOrientations=[(0.0, 0.0, 0.0, 1.0)],
        linkInertialFramePositions=[foot_offset],
        linkInertialFrameOrientations=[(0.0, 0.0, 0.0, 1.0)],
        linkParentIndices=[0],
        linkJointTypes=[joint_type],
        linkJointAxis=[axis],
        physicsClientId=world.client,
    )


def foot_strike_speed(
    speed: float,
    substeps: int,
    swing: bool = False,
    foot_ccd: bool = False,
    phase: float = 0.0,
    ball_physics: BallPhysics | None = None,
    foot_dynamics: Mapping[str, float] | None = None,
    min_bounce_speed: float | None = None,
) -> float:
    """Launch speed (m/s, :meth:`Ball.launch_speed`) a foot moving at ``speed`` gives a
    resting ball.

    The foot is driven by a velocity-controlled motor with a large force limit, so it moves at
    the commanded speed through real physics: along a prismatic joint at the ball's centre
    height (``swing=False``), or swung on a hinge ``SWING_LEG_LENGTH`` above the foot so that
    the foot centre moves at ``speed`` (``swing=True``). A hit gives the ball about the foot's
    speed; a missed contact (the foot jumps over the ball within one step) leaves it near 0,
    and a contact found only once the foot is deep inside the ball gives it much less.
    ``foot_ccd`` turns on Bullet's swept-sphere CCD for the foot link, to test whether it helps.
    ``phase`` (0..1) shifts the start back by that fraction of one step's travel: whether a
    step lands on the ball depends on it, so a safety check must try several phases.
    ``foot_dynamics`` are ``changeDynamics`` settings of the foot link (default: the robot's foot
    friction, :data:`PROBE_FOOT_DYNAMICS`); ``min_bounce_speed`` the world's
    (:class:`~sim.physics.PhysicsWorld`).
    """
    world = PhysicsWorld(substeps=substeps, min_bounce_speed=min_bounce_speed)
    try:
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=world.client)
        _static_body(world, plane, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), {})
        foot_half_length = FOOT_EXTENTS[1] / 2
        world_step = CYCLE_SECONDS / substeps
        if swing:
            # Ball just ahead of the lowest point, so the foot meets it moving horizontally.
            ball_x = foot_half_length + BALL_RADIUS + 0.005
            hinge = (0.0, 0.0, BALL_RADIUS + SWING_LEG_LENGTH)
            foot = _one_link_multibody(
                world,
                hinge,
                pybullet.JOINT_REVOLUTE,
                (0.0, 1.0, 0.0),
                (0.0, 0.0, -SWING_LEG_LENGTH),
            )
            step_angle = speed * world_step / SWING_LEG_LENGTH
            start = math.radians(60.0) + phase * step_angle
            velocity = -speed / SWING_LEG_LENGTH
            travel = 2 * start * SWING_LEG_LENGTH
        else:
            ball_x = 0.0
            start_x = -(foot_half_length + BALL_RADIUS + 0.05) - phase * speed * world_step
            foot = _one_link_multibody(
                world,
                (start_x, 0.0, BALL_RADIUS),
                pybullet.JOINT_PRISMATIC,
                (1.0, 0.0, 0.0),
                (0.0, 0.0, 0.0),
            )
            start, velocity = 0.0, speed
            travel = 2 * abs(start_x) + 0.2
        ball = Ball.create(world, (ball_x, 0.0, BALL_RADIUS), ball_physics)
        dynamics = dict(PROBE_FOOT_DYNAMICS if foot_dynamics is None else foot_dynamics)
        if foot_ccd:
            dynamics["ccdSweptSphereRadius"] = FOOT_EXTENTS[2] / 2
        if dynamics:
            pybullet.changeDynamics(foot, 0, physicsClientId=world.client, **dynamics)
        pybullet.resetJointState(foot, 0, start, velocity, physicsClientId=world.client)
        pybullet.setJointMotorControl2(
            foot,
            0,
            pybullet.VELOCITY_CONTROL,
            targetVelocity=velocity,
            force=_PROBE_MOTOR_FORCE,
            physicsClientId=world.client,
        )
        peak = 0.0
        for _ in range(math.ceil(travel / (speed * CYCLE_SECONDS)) + 2):
            world.step_cycle()
            peak = max(peak, ball.launch_speed())
        return peak
    finally:
        world.close()
