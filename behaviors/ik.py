"""Leg inverse kinematics of the simulated NAO, every robot type, in closed form.

Each leg is six hinges (``world.nao_model``): lj1 hip yaw-pitch about the 45-degree axis
``a = (-s, 0, +-s)``, lj2 hip roll (y), lj3 hip pitch (x), lj4 knee (x), lj5 ankle pitch (x),
lj6 ankle roll (y). The hip yaw-pitch and roll axes meet in the hip H; the hip-pitch anchor is
``p`` below it (zero on types 0, 2, 4; 18 mm on types 1 and 3). Below it the chain is offset
vectors whose x (sideways) component is zero: thigh ``t`` (hip-pitch -> knee anchor), shank
``k`` (knee -> ankle pitch), and ``d`` (ankle pitch -> ankle roll, a few mm down, and
backwards on type 4). Because lj3-lj5 all turn about x, ``p``, ``t``, ``k`` and ``d`` stay in
the leg's sagittal plane, which gives an exact closed form in five steps (R_foot = Ra(lj1)
Ry(lj2) Rx(phi) Ry(lj6) with phi = lj3 + lj4 + lj5):

1. the ankle-roll anchor follows from the foot pose; seen from the foot, the hip direction has
   no x component once lj6 is undone: ``lj6 = atan2(-w_x, w_z)``;
2. B = R_foot Ry(-lj6) = Ra(lj1) Ry(lj2) Rx(phi): its x column turned back about ``a`` must
   have no y component, one ``a cos + b sin = 0`` equation for lj1 (of its two solutions the
   one in range);
3. lj2 and phi then follow from Ra(-lj1) B = Ry(lj2) Rx(phi);
4. with phi known, the hip-pitch offset's part of the hip -> ankle vector is known too, and the
   rest is a two-link planar chain: the law of cosines with ``t`` and ``k`` fixes the knee, the
   direction fixes lj5;
5. lj3 = phi - lj4 - lj5.

The exact solution replaced Newton steps that types 1 and 3 took from an approximate start: the
two agree to the steps' 1e-6 m tolerance, types 0, 2 and 4 are unchanged to 1e-11 degrees.

Frames: the model's native frame (x = robot's right, y = forward, z = up, origin at the torso
centre), as :mod:`world.kinematics`; angles in degrees by perceptor name at the interface. The
convenience :meth:`LegIK.solve_sole` takes the *sole point* (the point of the sole under the
ankle-roll anchor) in the usual ego axes (x forward, y left, z up), which is what a walk plans.
Results are clipped to the joint limits; :class:`LegSolution` says whether clipping or an
out-of-reach target changed anything.

Speed: a walking agent solves both legs every cycle, so the arithmetic is plain floats on
tuples (rotations as row-major 9-tuples), not numpy: on 3-vectors and 3x3 matrices numpy's
per-call cost is several times the arithmetic. Products with the elementary rotations are
written out (a turn about y only mixes two columns), and every constant of a leg is computed
once per robot type. ``numpy`` appears only at the public interface (4x4 transforms in,
positions out).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from world.nao_model import RobotSpec, robot_spec

__all__ = [
    "LegIK",
    "LegSolution",
    "Side",
    "leg_ik",
    "leg_ik_for",
    "rotation_rpy",
]

Side = Literal["left", "right"]
Matrix = NDArray[np.float64]
Vec3 = tuple[float, float, float]
#: a 3x3 rotation as a row-major 9-tuple
Rot = tuple[float, float, float, float, float, float, float, float, float]

#: Joint numbers of a leg, in chain order.
LEG_JOINTS = (1, 2, 3, 4, 5, 6)
_IDENTITY: Rot = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


# ---------------------------------------------------------------------- 3x3 helpers (floats)
def _mul(a: Rot, b: Rot) -> Rot:
    """a @ b."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return (
        a0 * b0 + a1 * b3 + a2 * b6, a0 * b1 + a1 * b4 + a2 * b7, a0 * b2 + a1 * b5 + a2 * b8,
        a3 * b0 + a4 * b3 + a5 * b6, a3 * b1 + a4 * b4 + a5 * b7, a3 * b2 + a4 * b5 + a5 * b8,
        a6 * b0 + a7 * b3 + a8 * b6, a6 * b1 + a7 * b4 + a8 * b7, a6 * b2 + a7 * b5 + a8 * b8,
    )  # fmt: skip


def _apply(r: Rot, v: Vec3) -> Vec3:
    """r @ v."""
    x, y, z = v
    return (
        r[0] * x + r[1] * y + r[2] * z,
        r[3] * x + r[4] * y + r[5] * z,
        r[6] * x + r[7] * y + r[8] * z,
    )


def _apply_t(r: Rot, v: Vec3) -> Vec3:
    """r.T @ v."""
    x, y, z = v
    return (
        r[0] * x + r[3] * y + r[6] * z,
        r[1] * x + r[4] * y + r[7] * z,
        r[2] * x + r[5] * y + r[8] * z,
    )


def _times_ry(r: Rot, angle: float) -> Rot:
    """r @ Ry(angle): only the x and z columns change."""
    c, s = math.cos(angle), math.sin(angle)
    return (
        r[0] * c - r[2] * s, r[1], r[0] * s + r[2] * c,
        r[3] * c - r[5] * s, r[4], r[3] * s + r[5] * c,
        r[6] * c - r[8] * s, r[7], r[6] * s + r[8] * c,
    )  # fmt: skip


@dataclass(frozen=True, slots=True)
class _AxisTurn:
    """Rotations about one fixed unit axis (Rodrigues), with K and K^2 computed once."""

    k: Rot
    k2: Rot

    @classmethod
    def about(cls, axis: Vec3) -> _AxisTurn:
        x, y, z = axis
        k = (0.0, -z, y, z, 0.0, -x, -y, x, 0.0)
        return cls(k, _mul(k, k))

    def rotation(self, angle: float) -> Rot:
        """I + sin(a) K + (1 - cos(a)) K^2."""
        s, t = math.sin(angle), 1.0 - math.cos(angle)
        k0, k1, k2, k3, k4, k5, k6, k7, k8 = self.k
        m0, m1, m2, m3, m4, m5, m6, m7, m8 = self.k2
        return (
            1.0 + s * k0 + t * m0, s * k1 + t * m1, s * k2 + t * m2,
            s * k3 + t * m3, 1.0 + s * k4 + t * m4, s * k5 + t * m5,
            s * k6 + t * m6, s * k7 + t * m7, 1.0 + s * k8 + t * m8,
        )  # fmt: skip


def _rpy(roll: float, pitch: float, yaw: float) -> Rot:
    """Rz(yaw) @ Ry(pitch) @ Rx(roll), row-major."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (
        cy * cp, -sy * cr + cy * sp * sr, sy * sr + cy * sp * cr,
        sy * cp, cy * cr + sy * sp * sr, -cy * sr + sy * sp * cr,
        -sp, cp * sr, cp * cr,
    )  # fmt: skip


def _ego_to_native_rotation(r: Rot) -> Rot:
    """E @ r @ E.T for E = :data:`_EGO_TO_NATIVE` (native x = -ego y, native y = ego x)."""
    return (r[4], -r[3], -r[5], -r[1], r[0], r[2], -r[7], r[6], r[8])


def rotation_rpy(roll: float, pitch: float, yaw: float) -> Matrix:
    """Foot orientation in ego axes (x forward, y left, z up) from roll about x, pitch about y
    (positive = toes down) and yaw about z (positive = toes turned left), radians, applied
    yaw first then pitch then roll in the turned frame (R = Rz(yaw) Ry(pitch) Rx(roll))."""
    return np.array(_rpy(roll, pitch, yaw)).reshape(3, 3)


#: Native (x right, y forward, z up) from ego (x forward, y left, z up) axes: native = E @ ego.
_EGO_TO_NATIVE = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True, slots=True)
class LegSolution:
    """Joint angles for one leg (degrees by perceptor name, within the joint limits)."""

    angles_deg: dict[str, float]
    #: False when the target was further than the stretched leg reaches (the knee is straight)
    reachable: bool
    #: False when some angle had to be clipped to its joint's range
    within_limits: bool

    @property
    def exact(self) -> bool:
        """Whether the forward kinematics of these angles meets the target."""
        return self.reachable and self.within_limits


@dataclass(frozen=True, slots=True)
class _Leg:
    """The constant geometry of one leg (native frame, zero pose), plain floats."""

    names: tuple[str, ...]
    hip: Vec3
    yaw_pitch_axis: Vec3
    yaw_pitch: _AxisTurn  # rotations about the yaw-pitch axis
    pitch_offset: Vec3  # hip -> hip-pitch anchor (zero on types 0, 2, 4)
    thigh: Vec3  # hip-pitch anchor -> knee anchor
    shank: Vec3  # knee -> ankle-pitch anchor
    ankle: Vec3  # ankle-pitch -> ankle-roll anchor
    foot: Vec3  # ankle-roll anchor -> foot body centre
    sole: Vec3  # ankle-roll anchor -> sole point (straight down to the sole)
    low_deg: tuple[float, ...]
    high_deg: tuple[float, ...]
    # derived once: y, z of the hip-pitch offset, the thigh and the shank (step 4), the last
    # two's lengths and directions, lj1's range in radians
    pitch_yz: tuple[float, float]
    thigh_yz: tuple[float, float]
    shank_yz: tuple[float, float]
    thigh_length: float
    shank_length: float
    thigh_angle: float
    shank_angle: float
    yaw_pitch_range: tuple[float, float]


class LegIK:
    """Closed-form inverse kinematics of both legs of one robot type."""

    def __init__(self, spec: RobotSpec) -> None:
        self.spec = spec
        self._legs = {side: self._leg_geometry(spec, side) for side in ("left", "right")}

    @staticmethod
    def _leg_geometry(spec: RobotSpec, side: Side) -> _Leg:
        prefix = side[0]
        joints = [spec.joint(f"{prefix}lj{n}") for n in LEG_JOINTS]
        anchors = [np.array(j.anchor, dtype=float) for j in joints]
        if not np.allclose(anchors[0], anchors[1]):
            raise ValueError("leg IK expects the hip yaw-pitch and roll axes to meet")
        axes = [np.array(j.axis, dtype=float) / np.linalg.norm(j.axis) for j in joints]
        expected = ((0, 1, 0), (1, 0, 0), (1, 0, 0), (1, 0, 0), (0, 1, 0))
        if not all(np.allclose(a, e) for a, e in zip(axes[1:], expected, strict=True)):
            raise ValueError("leg IK expects roll, pitch, pitch, pitch, roll axes below the hip")
        foot = spec.body(f"{prefix}foot")
        offsets = (
            anchors[2] - anchors[0],
            anchors[3] - anchors[2],
            anchors[4] - anchors[3],
            anchors[5] - anchors[4],
        )
        if any(abs(v[0]) > 1e-12 for v in offsets):
            raise ValueError("leg IK expects the leg's offsets in the y-z plane")
        roll_anchor = anchors[5]
        sole_z = foot.centre[2] - foot.size[2] / 2
        thigh = offsets[1][1:]
        shank = offsets[2][1:]
        axis = _vec(axes[0])
        return _Leg(
            names=tuple(j.perceptor for j in joints),
            hip=_vec(anchors[0]),
            yaw_pitch_axis=axis,
            yaw_pitch=_AxisTurn.about(axis),
            pitch_offset=_vec(offsets[0]),
            thigh=_vec(offsets[1]),
            shank=_vec(offsets[2]),
            ankle=_vec(offsets[3]),
            foot=_vec(np.array(foot.centre) - roll_anchor),
            sole=(0.0, 0.0, float(sole_z - roll_anchor[2])),
            low_deg=tuple(float(j.min_deg) for j in joints),
            high_deg=tuple(float(j.max_deg) for j in joints),
            pitch_yz=(float(offsets[0][1]), float(offsets[0][2])),
            thigh_yz=(float(thigh[0]), float(thigh[1])),
            shank_yz=(float(shank[0]), float(shank[1])),
            thigh_length=math.hypot(*thigh),
            shank_length=math.hypot(*shank),
            thigh_angle=math.atan2(thigh[1], thigh[0]),
            shank_angle=math.atan2(shank[1], shank[0]),
            yaw_pitch_range=(math.radians(joints[0].min_deg), math.radians(joints[0].max_deg)),
        )

    # ------------------------------------------------------------------ geometry helpers
    def joint_names(self, side: Side) -> tuple[str, ...]:
        """Perceptor names of the leg's six joints (lj1..lj6) in chain order."""
        return self._legs[side].names

    def hip_position(self, side: Side) -> Matrix:
        """The hip point (where the three hip axes meet) in ego axes relative to the torso."""
        return _EGO_TO_NATIVE.T @ np.array(self._legs[side].hip)

    def sole_position_zero(self, side: Side) -> Matrix:
        """The sole point in the zero pose (legs straight), ego axes relative to the torso."""
        leg = self._legs[side]
        parts = (leg.hip, leg.pitch_offset, leg.thigh, leg.shank, leg.ankle, leg.sole)
        native = np.sum([np.array(p) for p in parts], axis=0)
        return _EGO_TO_NATIVE.T @ native

    def leg_length(self, side: Side) -> float:
        """Hip to sole point with the leg straight (m)."""
        return float(self.hip_position(side)[2] - self.sole_position_zero(side)[2])

    # ------------------------------------------------------------------ solving
    def solve(self, side: Side, foot_transform: Matrix) -> LegSolution:
        """Angles that put the foot body's centre at ``foot_transform`` (4x4, native frame,
        relative to the torso, as :func:`world.kinematics.body_transforms` reports it)."""
        leg = self._legs[side]
        rows = np.asarray(foot_transform, dtype=float)[:3].tolist()
        rotation: Rot = (*rows[0][:3], *rows[1][:3], *rows[2][:3])  # type: ignore[assignment]
        fx, fy, fz = _apply(rotation, leg.foot)
        roll_anchor = (rows[0][3] - fx, rows[1][3] - fy, rows[2][3] - fz)
        return _solve(leg, rotation, roll_anchor)

    def solve_sole(
        self,
        side: Side,
        position: Matrix | tuple[float, float, float],
        roll: float = 0.0,
        pitch: float = 0.0,
        yaw: float = 0.0,
    ) -> LegSolution:
        """Angles that put the sole point at ``position`` (ego axes: x forward, y left, z up,
        metres relative to the torso centre) with the foot turned by ``roll``, ``pitch``,
        ``yaw`` (radians, see :func:`rotation_rpy`) relative to the torso."""
        leg = self._legs[side]
        rotation = _ego_to_native_rotation(_rpy(roll, pitch, yaw))
        forward, left, up = (float(v) for v in position)
        sx, sy, sz = _apply(rotation, leg.sole)
        return _solve(leg, rotation, (-left - sx, forward - sy, up - sz))


def _vec(values) -> Vec3:
    return (float(values[0]), float(values[1]), float(values[2]))


def _solve(leg: _Leg, rotation: Rot, roll_anchor: Vec3) -> LegSolution:
    """The closed form's usual branch (ankle roll small, knee bent backwards, lj1 in range);
    where that leaves the joint ranges, the other branches of the ankle roll and the knee are
    tried too and the one needing the least clipping wins."""
    best: tuple[float, list[float], bool] | None = None
    low, high = leg.low_deg, leg.high_deg
    for roll_flipped, knee_forward in _BRANCHES:
        q, reachable = _closed_form(leg, rotation, roll_anchor, roll_flipped, knee_forward)
        degrees = [math.degrees(a) for a in q]
        excess = sum(max(lo - d, 0.0) for lo, d in zip(low, degrees, strict=True))
        excess += sum(max(d - hi, 0.0) for hi, d in zip(high, degrees, strict=True))
        if best is None or excess < best[0]:
            best = (excess, degrees, reachable)
        if excess == 0.0:
            break
    assert best is not None
    excess, degrees, reachable = best
    angles = {
        name: min(max(d, lo), hi)
        for name, d, lo, hi in zip(leg.names, degrees, low, high, strict=True)
    }
    return LegSolution(angles, reachable, excess == 0.0)


def _closed_form(
    leg: _Leg,
    rotation: Rot,
    roll_anchor: Vec3,
    roll_flipped: bool = False,
    knee_forward: bool = False,
) -> tuple[list[float], bool]:
    """The exact solution on one branch of the ankle roll and of the knee (see the module
    docstring for the steps)."""
    # 1. ankle roll: undo it and the hip, seen from the foot, lies in the y-z plane
    hip = leg.hip
    wx, wy, wz = _apply_t(
        rotation, (hip[0] - roll_anchor[0], hip[1] - roll_anchor[1], hip[2] - roll_anchor[2])
    )
    q6 = math.atan2(wx, -wz) if roll_flipped else math.atan2(-wx, wz)
    # u = Ry(q6) w; only its y and z are needed (u_y = w_y)
    uz = -math.sin(q6) * wx + math.cos(q6) * wz
    # 2. B = Ra(q1) Ry(q2) Rx(phi): q1 from B's x column
    b = _times_ry(rotation, -q6)
    q1 = _yaw_pitch(leg, (b[0], b[3], b[6]))
    # 3. Ra(-q1) B = Ry(q2) Rx(phi); Ry(-q2)'s middle row is (0, 1, 0), its last (sin q2, 0,
    # cos q2)
    rest = _mul(leg.yaw_pitch.rotation(-q1), b)
    q2 = math.atan2(-rest[6], rest[0])
    c2, s2 = math.cos(-q2), math.sin(-q2)
    phi = math.atan2(-s2 * rest[1] + c2 * rest[7], rest[4])
    # 4. knee and ankle pitch in the sagittal plane: -u - d - Rx(-phi) p = Rx(-q5) (k + Rx(-q4) t)
    cp, sp = math.cos(-phi), math.sin(-phi)
    (p0, p1), (t0, t1), (s0, s1) = leg.pitch_yz, leg.thigh_yz, leg.shank_yz
    v0 = -wy - leg.ankle[1] - (cp * p0 - sp * p1)
    v1 = -uz - leg.ankle[2] - (sp * p0 + cp * p1)
    lt, ls, lv = leg.thigh_length, leg.shank_length, math.hypot(v0, v1)
    cos_gap = (lv * lv - lt * lt - ls * ls) / (2.0 * lt * ls)
    reachable = -1.0 <= cos_gap <= 1.0
    gap = math.acos(min(1.0, max(-1.0, cos_gap)))
    # the usual branch bends the knee backwards (lj4 <= 0)
    q4 = leg.thigh_angle - leg.shank_angle + (gap if knee_forward else -gap)
    c4, s4 = math.cos(-q4), math.sin(-q4)
    m0, m1 = s0 + (c4 * t0 - s4 * t1), s1 + (s4 * t0 + c4 * t1)
    q5 = _wrap(math.atan2(m1, m0) - math.atan2(v1, v0))
    # 5. the hip pitch takes the rest of phi
    q3 = _wrap(phi - q4 - q5)
    return [q1, q2, q3, q4, q5, q6], reachable


def _yaw_pitch(leg: _Leg, column: Vec3) -> float:
    """lj1 such that Ra(-lj1) turns ``column`` into the x-z plane; of the two solutions (half a
    turn apart) the one nearer the joint's range."""
    kx, _, kz = leg.yaw_pitch_axis
    cross_y = kz * column[0] - kx * column[2]
    phi = math.atan2(-column[1], cross_y)  # = -lj1
    low, high = leg.yaw_pitch_range
    first, second = _wrap(-phi), _wrap(-phi + math.pi)
    key_first = (max(low - first, first - high, 0.0), abs(first))
    key_second = (max(low - second, second - high, 0.0), abs(second))
    return second if key_second < key_first else first


#: (ankle roll flipped by half a turn, knee bent the other way), the usual branch first
_BRANCHES = ((False, False), (True, False), (False, True), (True, True))


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


@cache
def _ik_for_type(robot_type: int) -> LegIK:
    return LegIK(robot_spec(robot_type))


def leg_ik_for(robot_type: int) -> LegIK:
    """The shared (stateless) solver of robot type ``robot_type``."""
    return _ik_for_type(robot_type)


def leg_ik(robot_type: int, side: Side, foot_transform: Matrix) -> LegSolution:
    """Leg angles putting the foot body centre at ``foot_transform`` (4x4, native frame,
    relative to the torso) for robot type ``robot_type``; see :meth:`LegIK.solve`."""
    return leg_ik_for(robot_type).solve(side, foot_transform)
