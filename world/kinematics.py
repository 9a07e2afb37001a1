"""Forward kinematics of the simulated NAO from its spec (``world.nao_model``), numpy only.

Every body's pose relative to the torso follows from the joint angles alone: each joint turns
its child about an axis through an anchor, and in the zero pose every body shares the torso's
orientation (the spec's convention, which the server's URDF shares). So a joint's frame can sit
at its anchor with the torso's axes; moving down a chain is a translation by the anchor offset
followed by the joint's rotation, and a body's centre is a fixed offset in its joint's frame.

This runs every cycle, so everything that does not depend on the angles (offsets, axis cross
products, the chain order) is computed once per robot type in :class:`KinematicModel`, and
the rotations are built and chained for all joints at the same depth of the tree in single
numpy operations (depth 7 at most: the toe), rather than one small matrix product per joint.

Frames: the model's native frame, x = robot's right, y = forward, z = up, origin at the torso
centre. Results are 4x4 homogeneous transforms of each body centre relative to the torso.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cache

import numpy as np
from numpy.typing import NDArray

from world.nao_model import RobotSpec, robot_spec

__all__ = [
    "KinematicModel",
    "body_transforms",
    "camera_transform",
    "kinematic_model",
    "level_rotation",
    "polar_to_camera",
]

Matrix = NDArray[np.float64]


class KinematicModel:
    """Precomputed forward kinematics of one robot type.

    Use :func:`kinematic_model` to get the shared instance for a spec; it holds no state that
    changes after construction.

    How it stays cheap: the joints form five chains from the torso (head, two arms, two legs),
    at most seven joints deep. Each joint's local transform (anchor offset from its parent's
    anchor, then its rotation) is built for all joints at once, laid out in a (chains, depth)
    grid padded with identities, and the grid is multiplied out along each chain with a
    parallel prefix product: three batched matrix products instead of one per joint.
    """

    def __init__(self, spec: RobotSpec) -> None:
        self.spec = spec
        joints = spec.joints
        self.joint_names: tuple[str, ...] = tuple(j.perceptor for j in joints)
        self.body_names: tuple[str, ...] = tuple(b.name for b in spec.bodies)
        index_of_child = {j.child: k for k, j in enumerate(joints)}
        anchors = np.array([j.anchor for j in joints], dtype=float)
        parent = [index_of_child.get(j.parent, -1) for j in joints]
        offsets = np.array(
            [anchors[k] - (anchors[p] if p >= 0 else 0.0) for k, p in enumerate(parent)]
        )
        axes = np.array([j.axis for j in joints], dtype=float)
        axes /= np.linalg.norm(axes, axis=1, keepdims=True)
        self._offsets = offsets
        self._parent = parent
        (chains, depth), self._slot = self._chain_grid(parent)
        # the grid has one extra chain that no joint uses: its slots stay identities, and the
        # torso's row points at one of them
        self._grid_shape = (chains + 1, depth)
        size = (chains + 1) * depth
        self._torso_slot = chains * depth
        # Rodrigues: R = I + sin(a) K + (1 - cos(a)) K^2, laid out in the grid as 4x4
        # transforms whose translation is the anchor offset (translate to the anchor, then
        # turn); padding slots have K = 0 and no offset, so they stay identities
        skew = np.zeros((size, 4, 4))
        ax = np.zeros((size, 3))
        ax[self._slot] = axes
        skew[:, 0, 1], skew[:, 0, 2] = -ax[:, 2], ax[:, 1]
        skew[:, 1, 0], skew[:, 1, 2] = ax[:, 2], -ax[:, 0]
        skew[:, 2, 0], skew[:, 2, 1] = -ax[:, 1], ax[:, 0]
        self._skew = skew
        self._skew2 = skew @ skew
        self._base = np.tile(np.eye(4), (size, 1, 1))
        self._base[self._slot, :3, 3] = offsets
        self._grid_angles = np.zeros(size)
        # each body: the joint that moves it (-1: torso) and its centre in that joint's frame
        body_joint = [index_of_child.get(b.name, -1) for b in spec.bodies]
        self._body_slot = np.array(
            [self._slot[k] if k >= 0 else self._torso_slot for k in body_joint]
        )
        self._body_offset = np.tile(np.eye(4), (len(body_joint), 1, 1))
        for i, (body, k) in enumerate(zip(spec.bodies, body_joint, strict=True)):
            if k >= 0:
                self._body_offset[i, :3, 3] = np.subtract(body.centre, anchors[k])
        self._head_chain = self._chain_to(index_of_child["head"])
        self._head_offset = tuple(self._body_offset[self.body_names.index("head"), :3, 3])

    @staticmethod
    def _chain_grid(parent: list[int]) -> tuple[tuple[int, int], NDArray[np.intp]]:
        """Lay the joint tree out as chains: (chains, depth) and each joint's flat grid slot.

        Every joint has at most one child in the NAO's tree (it is five chains); a joint whose
        parent is the torso starts a new chain.
        """
        chain_of: list[int] = []
        depth_of: list[int] = []
        chains = 0
        for p in parent:  # spec order: parents before children
            if p < 0:
                chain_of.append(chains)
                depth_of.append(0)
                chains += 1
            else:
                chain_of.append(chain_of[p])
                depth_of.append(depth_of[p] + 1)
        if len(set(zip(chain_of, depth_of, strict=True))) != len(parent):
            raise ValueError("forward kinematics expects chains: a joint with two children")
        depth = max(depth_of) + 1
        slots = np.array([c * depth + d for c, d in zip(chain_of, depth_of, strict=True)])
        return (chains, depth), slots

    def _chain_to(self, joint: int) -> list[int]:
        """Joint indices from the torso down to ``joint``."""
        chain = []
        while joint >= 0:
            chain.append(joint)
            joint = self._parent[joint]
        return chain[::-1]

    # ------------------------------------------------------------------ evaluation
    def angles_rad(self, joints_deg: Mapping[str, float]) -> NDArray[np.float64]:
        """Joint angles in spec order (radians); missing joints count as 0."""
        get = joints_deg.get
        return np.radians([get(name, 0.0) for name in self.joint_names])

    def _chain_products(self, angles_rad: NDArray[np.float64]) -> NDArray[np.float64]:
        """The whole grid of joint frames relative to the torso, (slots, 4, 4)."""
        angles = self._grid_angles.copy()
        angles[self._slot] = angles_rad
        s = np.sin(angles)[:, None, None]
        c = np.cos(angles)[:, None, None]
        grid = self._base + s * self._skew + (1.0 - c) * self._skew2
        chains, depth = self._grid_shape
        grid = grid.reshape(chains, depth, 4, 4)
        step = 1
        while step < depth:  # Hillis-Steele prefix product along each chain
            grid[:, step:] = grid[:, :-step] @ grid[:, step:]
            step *= 2
        return grid.reshape(-1, 4, 4)

    def joint_frames(self, angles_rad: NDArray[np.float64]) -> NDArray[np.float64]:
        """4x4 transforms (n, 4, 4) of every joint frame (at its anchor, turned by its angle)
        relative to the torso, in spec joint order."""
        return self._chain_products(angles_rad)[self._slot]

    def transforms(self, joints_deg: Mapping[str, float]) -> NDArray[np.float64]:
        """4x4 transforms of every body centre relative to the torso, (bodies, 4, 4) in the
        spec's body order."""
        grid = self._chain_products(self.angles_rad(joints_deg))
        return grid[self._body_slot] @ self._body_offset

    def body_transforms(self, joints_deg: Mapping[str, float]) -> dict[str, Matrix]:
        """Body name -> 4x4 transform of its centre relative to the torso."""
        return dict(zip(self.body_names, self.transforms(joints_deg), strict=True))

    def camera_transform(self, joints_deg: Mapping[str, float]) -> Matrix:
        """4x4 transform of the head centre (the camera) relative to the torso.

        Only the neck chain (two joints) is evaluated, in plain float arithmetic: for a chain
        this short that is several times cheaper than numpy's per-call overhead.
        """
        rot = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
        pos = (0.0, 0.0, 0.0)
        for k in self._head_chain:
            pos = _add(pos, _apply(rot, self._offsets[k]))
            angle = math.radians(joints_deg.get(self.joint_names[k], 0.0))
            rot = _matmul(rot, _rodrigues(self.spec.joints[k].axis, angle))
        pos = _add(pos, _apply(rot, self._head_offset))
        out = np.eye(4)
        out[:3, :3] = np.reshape(rot, (3, 3))
        out[:3, 3] = pos
        return out


Rot9 = tuple[float, float, float, float, float, float, float, float, float]
Vec3 = tuple[float, float, float]


def _rodrigues(axis: tuple[float, ...], angle: float) -> Rot9:
    """Row-major rotation about a unit ``axis`` by ``angle`` radians."""
    x, y, z = axis
    norm = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / norm, y / norm, z / norm
    s, c = math.sin(angle), math.cos(angle)
    t = 1.0 - c
    return (
        c + t * x * x, t * x * y - s * z, t * x * z + s * y,
        t * x * y + s * z, c + t * y * y, t * y * z - s * x,
        t * x * z - s * y, t * y * z + s * x, c + t * z * z,
    )  # fmt: skip


def _matmul(a: Rot9, b: Rot9) -> Rot9:
    return tuple(
        a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j]
        for i in range(3)
        for j in range(3)
    )  # type: ignore[return-value]


def _apply(r: Rot9, v: tuple[float, ...] | NDArray[np.float64]) -> Vec3:
    x, y, z = float(v[0]), float(v[1]), float(v[2])
    return (
        r[0] * x + r[1] * y + r[2] * z,
        r[3] * x + r[4] * y + r[5] * z,
        r[6] * x + r[7] * y + r[8] * z,
    )


def _add(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@cache
def _model_for_type(robot_type: int) -> KinematicModel:
    return KinematicModel(robot_spec(robot_type))


def kinematic_model(spec: RobotSpec) -> KinematicModel:
    """The precomputed model of ``spec`` (shared per standard robot type; other specs, e.g.
    modified ones in tests, get a fresh model)."""
    if spec is robot_spec(spec.robot_type):
        return _model_for_type(spec.robot_type)
    return KinematicModel(spec)


def body_transforms(spec: RobotSpec, joints_deg: Mapping[str, float]) -> dict[str, Matrix]:
    """Every body of ``spec`` -> 4x4 transform of its centre relative to the torso (native
    axes), for the joint angles ``joints_deg`` (perceptor name -> degrees; missing = 0)."""
    return kinematic_model(spec).body_transforms(joints_deg)


def camera_transform(spec: RobotSpec, joints_deg: Mapping[str, float]) -> Matrix:
    """4x4 transform of the camera (the head body's centre, the head's axes) relative to the
    torso: what the server's vision perceptor measures from."""
    return kinematic_model(spec).camera_transform(joints_deg)


def polar_to_camera(polars: NDArray[np.float64]) -> NDArray[np.float64]:
    """Camera-frame points (n, 3) of vision polars (n, 3): distance, phi (deg, + left), theta
    (deg, + up), the inverse of the server's ``phi = atan2(y, x) - 90``, ``theta = atan2(z,
    hypot(x, y))`` in the camera's native axes (x right, y forward, z up)."""
    polars = np.asarray(polars, dtype=float).reshape(-1, 3)
    distance = polars[:, 0]
    phi = np.radians(polars[:, 1])
    theta = np.radians(polars[:, 2])
    flat = distance * np.cos(theta)
    return np.stack([-flat * np.sin(phi), flat * np.cos(phi), distance * np.sin(theta)], axis=1)


def level_rotation(up: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation from the torso's native frame to its *level* frame: same origin, z along the
    world's up, y along the torso's forward axis projected onto the ground, x = y cross z (the
    robot's right, level). ``up`` is the world's up direction in torso coordinates (e.g.
    ``RobotState.up``).

    The level frame's heading is exactly the torso heading the server reports (the direction
    of its forward axis on the ground), which is why the forward axis is projected rather than
    the tilt undone by the smallest rotation. When the forward axis points almost straight up
    or down (lying on the back or front) its projection is meaningless, and the right axis'
    projection (turned a quarter) takes its place.
    """
    # plain float arithmetic: for one 3x3 result numpy's per-call overhead dominates
    ux, uy, uz = (float(v) for v in up)
    n = math.sqrt(ux * ux + uy * uy + uz * uz)
    ux, uy, uz = ux / n, uy / n, uz / n
    # forward (0, 1, 0) minus its vertical part
    yx, yy, yz = -uy * ux, 1.0 - uy * uy, -uy * uz
    norm = math.sqrt(yx * yx + yy * yy + yz * yz)
    if norm >= 0.2:
        yx, yy, yz = yx / norm, yy / norm, yz / norm
        # x = y cross z
        xx, xy, xz = yy * uz - yz * uy, yz * ux - yx * uz, yx * uy - yy * ux
    else:
        xx, xy, xz = 1.0 - ux * ux, -ux * uy, -ux * uz
        norm = math.sqrt(xx * xx + xy * xy + xz * xz)
        xx, xy, xz = xx / norm, xy / norm, xz / norm
        # y = z cross x
        yx, yy, yz = uy * xz - uz * xy, uz * xx - ux * xz, ux * xy - uy * xx
    return np.array([[xx, xy, xz], [yx, yy, yz], [ux, uy, uz]])
