"""One simulated NAO in a :class:`~sim.physics.PhysicsWorld`, built from ``world.nao_model``.

Construction: the spec is turned into URDF text (native frame: x right, y forward, z up) that is
written once per robot type and content to the temporary directory and loaded with
``URDF_USE_INERTIA_FROM_FILE``. URDF rather than ``createMultiBody`` because it carries explicit
inertia tensors for the mass-only joint spheres (``createMultiBody`` derives inertia from a
collision shape, and those bodies must have none), it is one human-readable file to inspect
when something looks wrong, and loading a cached file is as fast as building from arrays.
Every link frame sits at its joint anchor with the torso's orientation, so all joint angles are
0 in the model's zero pose and an axis "in the body frame" is the same vector in every link.

Effectors are SimSpark's: a joint command is a target SPEED (rad/s) for a velocity motor of at
most :data:`~world.nao_model.MAX_MOTOR_TORQUE`, clipped to the joint's max speed, and kept until
changed. Limits are Bullet joint-limit constraints whose force is capped
(:attr:`RobotPhysics.joint_limit_force`), which makes them give a few degrees under a motor
pushing at full speed, like the real server's soft ODE stops.

Collisions: collider bodies collide with everything else; bodies without a collider have no
shape. By default a robot's colliders also collide with each other, except pairs joined by a
joint: because the mass-only joint spheres sit between colliders, "joined" means the nearest
collider ancestor (thigh-torso through hip1/hip2, foot-shank through the ankle); these pairs
already overlap or touch in the zero pose, where real contacts would make the robot fight
itself. The real server has no such contacts at all: ``nao_hetero.rsg`` puts every NAO in its
own ``Space`` with ``(disableInnerCollision true)``, and SimSpark's ``Space::Collide`` skips
such a space, so two parts of one robot never touch (other robots, the ball and the field
still do). :attr:`RobotPhysics.self_collision` False does the same here (opt-in:
``self_collision`` in ``config/server.yaml``).
"""

from __future__ import annotations

import hashlib
import math
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pybullet

from sim.physics import CYCLE_SECONDS, GRAVITY, PhysicsWorld
from world.nao_model import BODY_DRAG, MAX_MOTOR_TORQUE, BodySpec, RobotSpec, robot_spec
from world.perception import ForceResistance

Vec3 = tuple[float, float, float]

#: Bodies that strike the ball; their speed decides how finely the session substeps a cycle.
STRIKING_BODIES = ("lfoot", "rfoot", "lshank", "rshank", "ltoe", "rtoe")
#: Reach from a striking body's centre to its farthest point (half a foot's length), for the
#: rotational part of its surface speed.
STRIKING_REACH = 0.08


@dataclass(frozen=True)
class RobotPhysics:
    """Contact and motor parameters of a robot, tuned against the real server's traces
    (``benchmarks/fidelity.py``).

    ``contact_stiffness``/``contact_damping`` are per Bullet contact point (a foot flat on the
    ground has four). The real server's ground contact (soft ERP 0.2, CFM 0.01 at h = 0.02 s)
    is a spring of ERP / (h CFM) = 1000 N/m with damping (1 - ERP) / CFM = 80 N s/m per ODE
    contact point; the standing robot's measured sink (5.7 mm under 45.2 N) confirms it.

    ``soft_contacts`` False leaves the colliders without soft-contact parameters (and ignores
    ``contact_stiffness``/``contact_damping``). Bullet makes a contact soft when EITHER body is
    soft, so with True the foot-ball and robot-robot contacts are 1000 N/m springs too; False
    is for a world whose ground carries the softness instead (``sim.field.GroundPhysics``),
    which leaves robot-ground contacts as they are and makes the others rigid. Opt-in only
    (``benchmarks/physics.py --variant strike``).

    ``self_collision`` False lets no two parts of one robot touch, as on the real server (see
    the module docstring); True keeps today's contacts between non-neighbouring parts.
    """

    contact_stiffness: float = 1000.0
    contact_damping: float = 80.0
    lateral_friction: float = 1.0
    restitution: float = 0.0
    motor_torque: float = MAX_MOTOR_TORQUE
    joint_limit_force: float = 60.0
    servo_gain: float = 1.0
    servo_window: float = math.radians(10.0)
    linear_drag: float = BODY_DRAG
    angular_drag: float = BODY_DRAG
    soft_contacts: bool = True
    self_collision: bool = True
    #: bodies whose colliders stay rigid even with ``soft_contacts`` (research variants)
    hard_bodies: tuple[str, ...] = ()

    def collider_dynamics(self, body: str = "") -> dict[str, float]:
        """``changeDynamics`` settings of the collider of ``body``: friction, bounce and, with
        ``soft_contacts`` (unless ``body`` is one of ``hard_bodies``), the ground contact's
        spring (probes that stand in for a foot use them too, so they touch the ball as a
        robot's foot does)."""
        params = {"lateralFriction": self.lateral_friction, "restitution": self.restitution}
        if self.soft_contacts and body not in self.hard_bodies:
            params |= {
                "contactStiffness": self.contact_stiffness,
                "contactDamping": self.contact_damping,
            }
        return params


#: The physics of every robot built without an explicit ``physics`` (read when it is built).
DEFAULT_PHYSICS = RobotPhysics()


def yaw_from_beam(beam_deg: float) -> float:
    """Facing yaw (``place``'s convention: 0 = world +x) of ``(beam x y beam_deg)``."""
    return beam_deg


def yaw_from_trainer_move(move_deg: float) -> float:
    """Facing yaw of the trainer's ``(agent ... (move x y z move_deg))``: the real server applies
    the angle raw to the model, whose forward axis is native +y, so 0 faces world +y."""
    return move_deg + 90.0


# --------------------------------------------------------------------------------------------
# URDF generation
# --------------------------------------------------------------------------------------------


def _inertia(body: BodySpec) -> Vec3:
    """Principal moments about the body centre (ODE's dMassSet* formulas)."""
    m = body.mass
    if body.shape == "box":
        x, y, z = body.size
        return (m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12)
    if body.shape == "sphere":
        i = 0.4 * m * body.size[0] ** 2
        return (i, i, i)
    r, length = body.size
    cyl_vol = math.pi * r * r * length
    cap_vol = 4.0 / 3.0 * math.pi * r**3
    m_cyl = m * cyl_vol / (cyl_vol + cap_vol)
    m_cap = m - m_cyl
    side = m_cyl * (0.25 * r * r + length * length / 12) + m_cap * (
        0.4 * r * r + 0.375 * r * length + 0.25 * length * length
    )
    return (side, side, (0.5 * m_cyl + 0.4 * m_cap) * r * r)


def _geometry(body: BodySpec) -> str:
    if body.shape == "box":
        return '<box size="{:.9g} {:.9g} {:.9g}"/>'.format(*body.size)
    if body.shape == "sphere":
        return f'<sphere radius="{body.size[0]:.9g}"/>'
    return f'<capsule radius="{body.size[0]:.9g}" length="{body.size[1]:.9g}"/>'


def _xyz(v: Vec3) -> str:
    return " ".join(f"{c:.9g}" for c in v)


def _sub(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


#: Radius of the spheres at a sole's corners (see :func:`_sole_corners`).
SOLE_SPHERE_RADIUS = 0.002


def _collision_xml(offset: Vec3, geometry: str) -> str:
    return f'<collision><origin xyz="{_xyz(offset)}"/><geometry>{geometry}</geometry></collision>'


def _sole_corners(body: BodySpec, offset: Vec3) -> str:
    """A sole box as ODE's box-plane collider sees it: four contact points at its corners.

    Bullet's box-plane collision finds one point per step and collects the others over later
    steps from perturbed directions; the feet then often stand on three points, tilted and
    jittering. Four small spheres at the sole's corners (their bottoms on the sole) give the
    four stable corner contacts ODE produces, and the box, raised by one sphere radius,
    keeps its shape for every other contact (ball, other robots, tilted landings).
    """
    r = SOLE_SPHERE_RADIUS
    sx, sy, sz = body.size
    raised = (offset[0], offset[1], offset[2] + r / 2)
    parts = [_collision_xml(raised, f'<box size="{sx:.9g} {sy:.9g} {sz - r:.9g}"/>')]
    for cx in (-1, 1):
        for cy in (-1, 1):
            corner = (
                offset[0] + cx * (sx / 2 - r),
                offset[1] + cy * (sy / 2 - r),
                offset[2] - sz / 2 + r,
            )
            parts.append(_collision_xml(corner, f'<sphere radius="{r:.9g}"/>'))
    return "".join(parts)


def _link_xml(body: BodySpec, frame_origin: Vec3) -> str:
    rel = _sub(body.centre, frame_origin)
    offset = _xyz(rel)
    ixx, iyy, izz = _inertia(body)
    collision = ""
    if body.collider and body.name.endswith(("foot", "toe")):
        collision = _sole_corners(body, rel)
    elif body.collider:
        collision = _collision_xml(rel, _geometry(body))
    return (
        f'<link name="{body.name}"><inertial><origin xyz="{offset}"/>'
        f'<mass value="{body.mass:.9g}"/>'
        f'<inertia ixx="{ixx:.9g}" iyy="{iyy:.9g}" izz="{izz:.9g}" ixy="0" ixz="0" iyz="0"/>'
        f"</inertial>{collision}</link>"
    )


def urdf_text(spec: RobotSpec) -> str:
    """The URDF of ``spec``: torso as base, one revolute joint per spec joint."""
    anchors: dict[str, Vec3] = {"torso": (0.0, 0.0, 0.0)}
    for joint in spec.joints:
        anchors[joint.child] = joint.anchor
    parts = [f'<?xml version="1.0"?><robot name="nao_type{spec.robot_type}">']
    parts.extend(_link_xml(body, anchors[body.name]) for body in spec.bodies)
    for joint in spec.joints:
        lo, hi = math.radians(joint.min_deg), math.radians(joint.max_deg)
        parts.append(
            f'<joint name="{joint.perceptor}" type="revolute">'
            f'<parent link="{joint.parent}"/><child link="{joint.child}"/>'
            f'<origin xyz="{_xyz(_sub(joint.anchor, anchors[joint.parent]))}"/>'
            f'<axis xyz="{_xyz(joint.axis)}"/>'
            f'<limit lower="{lo:.9g}" upper="{hi:.9g}" effort="{MAX_MOTOR_TORQUE:.9g}" '
            f'velocity="{joint.max_speed:.9g}"/></joint>'
        )
    parts.append("</robot>")
    return "\n".join(parts)


def urdf_path(spec: RobotSpec) -> Path:
    """Write the URDF once (named by its content hash) and return its path."""
    text = urdf_text(spec)
    digest = hashlib.sha1(text.encode()).hexdigest()[:12]
    path = Path(tempfile.gettempdir()) / f"naosoccer_nao_t{spec.robot_type}_{digest}.urdf"
    if not path.exists():
        tmp = path.with_suffix(f".{id(text)}.tmp")
        tmp.write_text(text)
        tmp.replace(path)  # atomic: parallel test workers never read a half-written file
    return path


def _collider_parent(spec: RobotSpec, name: str) -> str | None:
    """The nearest collider ancestor of body ``name``."""
    parent_of = {j.child: j.parent for j in spec.joints}
    colliders = {b.name for b in spec.bodies if b.collider}
    current = parent_of.get(name)
    while current is not None and current not in colliders:
        current = parent_of.get(current)
    return current


#: Collider pairs that touch in the zero pose without being joint neighbours.
_TOUCHING_PAIRS = (("head", "torso"),)


def _excluded_pairs(spec: RobotSpec) -> list[tuple[str, str]]:
    """Self-collision pairs switched off: each collider with its nearest collider ancestor,
    plus pairs that already touch in the zero pose (the head sphere rests on the torso box)."""
    pairs = []
    for body in spec.bodies:
        parent = _collider_parent(spec, body.name) if body.collider else None
        if parent is not None:
            pairs.append((body.name, parent))
    return pairs + list(_TOUCHING_PAIRS)


def _quat_to_matrices(quats: np.ndarray) -> np.ndarray:
    """(n, 4) xyzw quaternions -> (n, 3, 3) rotation matrices."""
    x, y, z, w = quats.T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
        ],
        axis=-2,
    )


def _rotation(quat: tuple[float, ...]) -> np.ndarray:
    """One rotation matrix (Bullet's C conversion: far cheaper than numpy for a single one)."""
    return np.array(pybullet.getMatrixFromQuaternion(quat)).reshape(3, 3)


def _to_local(matrix: Sequence[float], v: Sequence[float]) -> Vec3:
    """``R^T v`` for a row-major 3x3 ``matrix`` (9 floats, as ``getMatrixFromQuaternion``
    gives): a world vector in the rotated frame. Plain floats: per-cycle sensor code calls this
    a few times for single vectors, where numpy's per-call overhead dominates."""
    x, y, z = v
    return (
        matrix[0] * x + matrix[3] * y + matrix[6] * z,
        matrix[1] * x + matrix[4] * y + matrix[7] * z,
        matrix[2] * x + matrix[5] * y + matrix[8] * z,
    )


def _clip(value: float, low: float, high: float) -> float:
    """``numpy.clip`` for one float (the same result: ``min(max(value, low), high)``)."""
    return min(max(value, low), high)


# --------------------------------------------------------------------------------------------
# The robot
# --------------------------------------------------------------------------------------------


class SimRobot:
    """One NAO of type ``robot_type`` in ``world``, driven only through its joint motors.

    Call :meth:`update_sensors` once per cycle after stepping the world; the readers
    (:meth:`joint_angles_deg`, :meth:`gyro_deg_s`, ...) then describe that cycle.
    """

    def __init__(
        self,
        world: PhysicsWorld,
        robot_type: int = 0,
        physics: RobotPhysics | None = None,
        position: Vec3 = (0.0, 0.0, 0.4),
    ) -> None:
        self.world = world
        self.spec = robot_spec(robot_type)
        self.robot_type = robot_type
        self.physics = physics if physics is not None else DEFAULT_PHYSICS
        self._client = world.client
        flags = pybullet.URDF_USE_INERTIA_FROM_FILE
        if self.physics.self_collision:
            flags |= (
                pybullet.URDF_USE_SELF_COLLISION | pybullet.URDF_USE_SELF_COLLISION_EXCLUDE_PARENT
            )
        self.body_id: int = pybullet.loadURDF(
            str(urdf_path(self.spec)), position, flags=flags, physicsClientId=self._client
        )
        self._index_links()
        self._striking_links = [
            self._link_of[name] for name in STRIKING_BODIES if name in self._link_of
        ]
        self._configure_dynamics()
        # motor state as plain float lists: numpy's per-call overhead on 22 numbers costs more
        # than the arithmetic (the results are the same IEEE operations either way)
        n = len(self.spec.joints)
        self._speeds = [0.0] * n
        self._targets = [0.0] * n
        self._cycle_start = self._targets
        self._lower = np.radians([j.min_deg for j in self.spec.joints]).tolist()
        self._upper = np.radians([j.max_deg for j in self.spec.joints]).tolist()
        self._bounds = tuple(zip(self._lower, self._upper, strict=True))
        self._position_gains = [self.physics.servo_gain] * n
        self._velocity_gains = [1.0] * n
        self._prev_velocity: Vec3 = (0.0, 0.0, 0.0)
        self._acc: Vec3 = (0.0, 0.0, -GRAVITY)
        self._limp = False
        self._apply_motors()
        world.register_state_holder(self)

    # ---------------------------------------------------------------- construction helpers
    def _index_links(self) -> None:
        n = pybullet.getNumJoints(self.body_id, physicsClientId=self._client)
        self._link_of: dict[str, int] = {"torso": -1}
        joint_index: dict[str, int] = {}
        for i in range(n):
            info = pybullet.getJointInfo(self.body_id, i, physicsClientId=self._client)
            joint_index[info[1].decode()] = i
            self._link_of[info[12].decode()] = i
        self._name_of = {i: name for name, i in self._link_of.items()}
        self._joint_indices = [joint_index[j.perceptor] for j in self.spec.joints]
        self._effector_pos = {j.effector: k for k, j in enumerate(self.spec.joints)}
        self._max_speeds = [float(j.max_speed) for j in self.spec.joints]
        self._body_names = [b.name for b in self.spec.bodies]
        self._body_links = [self._link_of[name] for name in self._body_names[1:]]
        self._foot_links = {
            sensor: self._link_of[body] for sensor, body in self.spec.foot_sensors.items()
        }
        self._sensor_of_link = {link: sensor for sensor, link in self._foot_links.items()}
        # the order the server writes FRP perceptors in: right foot (toe) before left
        self._sensor_order = [s for s in ("rf", "rf1", "lf", "lf1") if s in self._foot_links]

    def _configure_dynamics(self) -> None:
        p, cid, bid = self.physics, self._client, self.body_id
        pybullet.changeDynamics(
            bid,
            -1,
            linearDamping=p.linear_drag,
            angularDamping=p.angular_drag,
            physicsClientId=cid,
        )
        for body in self.spec.bodies:
            link = self._link_of[body.name]
            kwargs = {"jointLimitForce": p.joint_limit_force} if link >= 0 else {}
            if body.collider:
                kwargs |= p.collider_dynamics(body.name)
            if kwargs:
                pybullet.changeDynamics(bid, link, physicsClientId=cid, **kwargs)
        # Without self-collision no pair of this robot's parts collides, so none to exclude.
        excluded = _excluded_pairs(self.spec) if self.physics.self_collision else []
        for a, b in excluded:
            pybullet.setCollisionFilterPair(
                bid, bid, self._link_of[a], self._link_of[b], 0, physicsClientId=cid
            )

    def _apply_motors(self, targets: list[float] | None = None) -> None:
        """Send the motor commands (see :meth:`before_cycle`)."""
        force = 0.0 if self._limp else self.physics.motor_torque
        pybullet.setJointMotorControlArray(
            self.body_id,
            self._joint_indices,
            pybullet.POSITION_CONTROL,
            targetPositions=self._targets if targets is None else targets,
            targetVelocities=self._speeds,
            positionGains=self._position_gains,
            velocityGains=self._velocity_gains,
            forces=[force] * len(self._joint_indices),
            physicsClientId=self._client,
        )

    def before_cycle(self) -> None:
        """Advance each joint's drift-correcting target by one cycle of its commanded speed.

        Bullet's iterative solver does not converge on velocity constraints in a chain of light
        links (the hip and ankle spheres), so a plain velocity motor at speed 0 lets a standing
        robot sag. The motor here is a velocity motor plus a weak pull toward the angle the
        commanded speeds integrate to; the target never leads the joint by more than
        :attr:`RobotPhysics.servo_window` (a blocked joint does not wind up) and stays within
        the joint's limits. Within the cycle the target moves on with every substep
        (:meth:`before_substep`), so the pull never runs ahead of the commanded speed.
        """
        states = pybullet.getJointStates(
            self.body_id, self._joint_indices, physicsClientId=self._client
        )
        window = self.physics.servo_window
        # numpy.clip(x, low, high) for one float is min(max(x, low), high); written out as
        # conditionals (same results, ties included) because this runs per joint every cycle
        cycle_start, targets = [], []
        for t, v, state, (low, high) in zip(
            self._targets, self._speeds, states, self._bounds, strict=True
        ):
            c = low if low > t else t
            cycle_start.append(high if high < c else c)
            x = t + v * CYCLE_SECONDS
            edge = state[0] - window
            x = edge if edge > x else x
            edge = state[0] + window
            x = edge if edge < x else x
            x = low if low > x else x
            targets.append(high if high < x else x)
        self._cycle_start, self._targets = cycle_start, targets

    def before_substep(self, fraction: float) -> None:
        """Aim the motors at where the joint should be as this substep starts (``fraction`` of
        the cycle done). Bullet's motor asks for ``speed + gain * error / dt``: with the error
        measured against the current target, a joint on track moves at its commanded speed."""
        self._apply_motors(
            [a + (b - a) * fraction for a, b in zip(self._cycle_start, self._targets, strict=True)]
        )

    def striking_speed(self) -> float:
        """Fastest surface speed (m/s) of the feet and shanks: |v| + |omega| * reach."""
        states = pybullet.getLinkStates(
            self.body_id, self._striking_links, computeLinkVelocity=1, physicsClientId=self._client
        )
        return max(
            math.hypot(*state[6]) + math.hypot(*state[7]) * STRIKING_REACH for state in states
        )

    # ---------------------------------------------------------------- names
    @property
    def effector_names(self) -> tuple[str, ...]:
        return self.spec.effector_names

    @property
    def perceptor_names(self) -> tuple[str, ...]:
        return self.spec.perceptor_names

    def link_name(self, link_index: int) -> str:
        """The body name of a link index of :attr:`body_id` (-1 is the torso)."""
        return self._name_of[link_index]

    def link_index(self, body_name: str) -> int:
        return self._link_of[body_name]

    # ---------------------------------------------------------------- effectors
    def set_joint_speeds(self, speeds: Mapping[str, float]) -> None:
        """Set target speeds (rad/s) by effector name; others keep their last command.

        Nothing is sent to Bullet here: :meth:`before_substep` sends every motor command before
        each physics step (``PhysicsWorld.step_cycle`` is the only way the world steps)."""
        for name, speed in speeds.items():
            k = self._effector_pos.get(name)
            if k is None:
                raise KeyError(f"unknown effector {name!r}; valid: {list(self.effector_names)}")
            limit = self._max_speeds[k]
            speed = float(speed)
            clipped = 0.0 if math.isnan(speed) else _clip(speed, -limit, limit)
            if clipped != self._speeds[k]:  # (keeps the sign of a zero, as before)
                self._speeds[k] = clipped

    def joint_speed_targets(self) -> dict[str, float]:
        return dict(zip(self.effector_names, self._speeds, strict=True))

    def set_limp(self, limp: bool = True) -> None:
        """Switch every motor off (zero torque) or back on, keeping the speed targets."""
        self._limp = limp
        self._apply_motors()

    # ---------------------------------------------------------------- sensors
    def update_sensors(self) -> None:
        """Refresh the accelerometer from the torso's velocity change over the last cycle."""
        velocity = self._base_velocity()[0]
        acc_world = [(v - p) / CYCLE_SECONDS for v, p in zip(velocity, self._prev_velocity)]
        acc_world[2] -= GRAVITY
        self._acc = _to_local(self._torso_matrix(), acc_world)
        self._prev_velocity = tuple(velocity)

    def joint_angles_deg(self) -> dict[str, float]:
        """Joint perceptor name -> angle in degrees, in the server's HJ order."""
        states = pybullet.getJointStates(
            self.body_id, self._joint_indices, physicsClientId=self._client
        )
        return {
            name: math.degrees(state[0])
            for name, state in zip(self.perceptor_names, states, strict=True)
        }

    def joint_velocities(self) -> dict[str, float]:
        """Joint perceptor name -> angular speed (rad/s)."""
        states = pybullet.getJointStates(
            self.body_id, self._joint_indices, physicsClientId=self._client
        )
        return {n: s[1] for n, s in zip(self.perceptor_names, states, strict=True)}

    def gyro_deg_s(self) -> tuple[float, float, float]:
        """Torso angular velocity in the torso's native frame, deg/s."""
        omega = _to_local(self._torso_matrix(), self._base_velocity()[1])
        return (math.degrees(omega[0]), math.degrees(omega[1]), math.degrees(omega[2]))

    def accelerometer(self) -> tuple[float, float, float]:
        """Proper acceleration of the torso in its native frame (m/s^2), as of the last
        :meth:`update_sensors`: (0, 0, 9.81) standing still, 0 in free fall."""
        return self._acc

    def force_resistance(self) -> dict[str, ForceResistance]:
        """Foot (and toe) pressure sensors in contact: force-weighted contact centre and total
        force on the foot, both in the foot's frame (centre relative to the foot box centre)."""
        contacts = pybullet.getContactPoints(bodyA=self.body_id, physicsClientId=self._client)
        sums: dict[str, list] = {}
        sensor_of_link, body = self._sensor_of_link, self.body_id
        for c in contacts:
            sensor = sensor_of_link.get(c[3]) if c[1] == body else None
            n = c[9]
            if sensor is None or n <= 0.0:
                continue  # another body, or a point within Bullet's margin carrying no load
            _, _, _, _, _, pos, _, normal, _, _, f1, d1, f2, d2 = c
            acc = sums.get(sensor)
            if acc is None:
                acc = sums[sensor] = [0.0] * 7
            # unrolled over x, y, z (hot loop: every contact point of every robot, every cycle)
            acc[0] += n * normal[0] + f1 * d1[0] + f2 * d2[0]
            acc[1] += n * normal[1] + f1 * d1[1] + f2 * d2[1]
            acc[2] += n * normal[2] + f1 * d1[2] + f2 * d2[2]
            acc[3] += n * pos[0]
            acc[4] += n * pos[1]
            acc[5] += n * pos[2]
            acc[6] += n
        if not sums:
            return {}  # no foot touches anything
        links = [self._foot_links[s] for s in sums]
        states = pybullet.getLinkStates(self.body_id, links, physicsClientId=self._client)
        result = {}
        for (sensor, acc), state in zip(sums.items(), states, strict=True):
            rot = pybullet.getMatrixFromQuaternion(state[1])
            origin, weight = state[0], acc[6]
            centre_world = [m / weight for m in acc[3:6]] if weight > 0 else origin
            centre = _to_local(rot, [c - o for c, o in zip(centre_world, origin, strict=True)])
            result[sensor] = ForceResistance(sensor, centre, _to_local(rot, acc[:3]))
        return {s: result[s] for s in self._sensor_order if s in result}

    # ---------------------------------------------------------------- pose
    def _base_velocity(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return pybullet.getBaseVelocity(self.body_id, physicsClientId=self._client)

    def _base_pose(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return pybullet.getBasePositionAndOrientation(self.body_id, physicsClientId=self._client)

    def _torso_rotation(self) -> np.ndarray:
        return _rotation(self._base_pose()[1])

    def _torso_matrix(self) -> tuple[float, ...]:
        """The torso's rotation as 9 row-major floats (no numpy: see :func:`_to_local`)."""
        return pybullet.getMatrixFromQuaternion(self._base_pose()[1])

    def torso_position(self) -> Vec3:
        return tuple(self._base_pose()[0])

    def torso_world_transform(self) -> np.ndarray:
        pos, quat = self._base_pose()
        m = np.eye(4)
        m[:3, :3] = _rotation(quat)
        m[:3, 3] = pos
        return m

    def torso_yaw_deg(self) -> float:
        """Heading of the torso's forward (native +y) axis: 0 = world +x, 90 = world +y."""
        m = self._torso_matrix()
        return math.degrees(math.atan2(m[4], m[1]))  # forward: the matrix's second column

    def team_frame_pose(self, side: str) -> tuple[float, float, float]:
        """Ground truth (x, y, heading deg) in a team's frame (x towards its opponent goal): what
        an agent's localisation estimates, for tests and benchmarks to compare with."""
        x, y, _ = self.torso_position()
        heading = self.torso_yaw_deg()
        if side.lower() == "right":
            x, y, heading = -x, -y, heading + 180.0
        return x, y, (heading + 180.0) % 360.0 - 180.0

    def torso_up(self) -> np.ndarray:
        """The torso's native +z axis in world coordinates."""
        return self._torso_rotation()[:, 2]

    def has_fallen(self) -> bool:
        """Lying or nearly so: the torso is tilted more than 60 deg from upright."""
        return self._torso_matrix()[8] < 0.5  # the z component of the torso's up axis

    def body_world_transforms(self) -> dict[str, np.ndarray]:
        """Every body of the spec -> 4x4 world transform of its centre (native axes)."""
        pos, quat = self._base_pose()
        states = pybullet.getLinkStates(
            self.body_id, self._body_links, computeForwardKinematics=1, physicsClientId=self._client
        )
        positions = np.array([pos] + [s[0] for s in states])
        rotations = _quat_to_matrices(np.array([quat] + [s[1] for s in states]))
        mats = np.zeros((len(positions), 4, 4))
        mats[:, :3, :3] = rotations
        mats[:, :3, 3] = positions
        mats[:, 3, 3] = 1.0
        return dict(zip(self._body_names, mats, strict=True))

    def body_positions(self, names: Sequence[str]) -> dict[str, Vec3]:
        """World positions of the centres of the named bodies (cheaper than full transforms:
        vision needs only where other robots' heads, arms and feet are)."""
        links = [self._link_of[name] for name in names]
        states = pybullet.getLinkStates(
            self.body_id, links, computeForwardKinematics=1, physicsClientId=self._client
        )
        return {name: tuple(state[0]) for name, state in zip(names, states, strict=True)}

    def camera_world_transform(self) -> np.ndarray:
        """World transform of the head centre (the camera; axes: x right, y forward, z up)."""
        state = pybullet.getLinkState(
            self.body_id, self._link_of["head"], computeForwardKinematics=1,
            physicsClientId=self._client,
        )  # fmt: skip
        m = np.eye(4)
        m[:3, :3] = _rotation(state[1])
        m[:3, 3] = state[0]
        return m

    def place(
        self,
        x: float,
        y: float,
        z: float,
        yaw_deg: float,
        joint_angles_deg: Mapping[str, float] | None = None,
    ) -> None:
        """Put the torso upright at (x, y, z) facing ``yaw_deg`` (0 = world +x, see
        :func:`yaw_from_beam`, :func:`yaw_from_trainer_move`), set the joint angles (default all
        0) and zero every velocity. Speed targets are kept, as on the real server."""
        quat = pybullet.getQuaternionFromEuler((0.0, 0.0, math.radians(yaw_deg - 90.0)))
        self._reset_base((x, y, z), quat)
        angles = joint_angles_deg or {}
        for perceptor, index in zip(self.perceptor_names, self._joint_indices, strict=True):
            value = math.radians(angles.get(perceptor, 0.0))
            self._targets[self.perceptor_names.index(perceptor)] = value
            pybullet.resetJointState(self.body_id, index, value, 0.0, physicsClientId=self._client)

    def translate(self, x: float, y: float, z: float) -> None:
        """Move the torso to (x, y, z) keeping orientation and joint angles, and stop every
        body part, as the real server's agent move does (base and joint velocities zeroed;
        the speed commands stay, so the motors go on as commanded)."""
        self._reset_base((x, y, z), self._base_pose()[1])
        cid = self._client
        states = pybullet.getJointStates(self.body_id, self._joint_indices, physicsClientId=cid)
        for index, state in zip(self._joint_indices, states, strict=True):
            pybullet.resetJointState(self.body_id, index, state[0], 0.0, physicsClientId=cid)

    def _reset_base(self, position: Vec3, quat: tuple[float, ...]) -> None:
        cid = self._client
        pybullet.resetBasePositionAndOrientation(self.body_id, position, quat, physicsClientId=cid)
        pybullet.resetBaseVelocity(self.body_id, (0, 0, 0), (0, 0, 0), physicsClientId=cid)
        self._prev_velocity = (0.0, 0.0, 0.0)
        self._acc = (0.0, 0.0, -GRAVITY)

    # ---------------------------------------------------------------- state
    def python_state(self) -> dict:
        """What Bullet's own snapshot lacks: motor targets and the accelerometer's memory."""
        return {
            "speeds": list(self._speeds),
            "targets": list(self._targets),
            "prev_velocity": self._prev_velocity,
            "acc": self._acc,
            "limp": self._limp,
        }

    def restore_python_state(self, state: Mapping) -> None:
        self._speeds = [float(v) for v in state["speeds"]]
        self._targets = [float(v) for v in state["targets"]]
        self._prev_velocity = tuple(float(v) for v in state["prev_velocity"])
        self._acc = tuple(float(v) for v in state["acc"])
        self._limp = bool(state.get("limp", False))
        self._apply_motors()

    def remove(self) -> None:
        """Take the robot out of the world."""
        self.world.unregister_state_holder(self)
        if pybullet.isConnected(self._client):
            pybullet.removeBody(self.body_id, physicsClientId=self._client)
