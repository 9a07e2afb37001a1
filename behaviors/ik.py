"""Leg inverse kinematics of the simulated NAO, every robot type, closed form (numpy only).

Each leg is six hinges (``world.nao_model``): lj1 hip yaw-pitch about the 45-degree axis
(-s, 0, +-s), lj2 hip roll (y), lj3 hip pitch (x), lj4 knee (x), lj5 ankle pitch (x), lj6
ankle roll (y). The three hip axes meet in one point, the hip H. Below it the chain is offset
vectors whose x (sideways) component is zero: thigh ``t`` (hip -> knee anchor, slightly
forward), shank ``k`` (knee -> ankle pitch), and ``d`` (ankle pitch -> ankle roll, a few mm
down, and backwards on type 4). Because lj3-lj5 all turn about x, those offsets stay in the
leg's sagittal plane, which gives a closed form in four steps:

1. the ankle-roll anchor follows from the foot pose; seen from the foot, the hip direction has
   no x component once lj6 is undone: ``lj6 = atan2(-w_x, w_z)``;
2. the distance from the hip to the ankle-pitch anchor fixes the knee (law of cosines with the
   tilted thigh and shank vectors), and the direction fixes lj5;
3. the hip rotation R123 = R_foot Ry(-lj6) Rx(-(lj4 + lj5)) is split as Ra(lj1) Ry(lj2)
   Rx(lj3): its x column turned back about the 45-degree axis must have no y component, which
   is one ``a cos + b sin = 0`` equation for lj1; lj2 and lj3 then follow from the remaining
   matrix.

Frames: the model's native frame (x = robot's right, y = forward, z = up, origin at the torso
centre), as :mod:`world.kinematics`; angles in degrees by perceptor name at the interface. The
convenience :meth:`LegIK.solve_sole` takes the *sole point* (the point of the sole under the
ankle-roll anchor) in the usual ego axes (x forward, y left, z up), which is what a walk plans.
Results are clipped to the joint limits; :class:`LegSolution` says whether clipping or an
out-of-reach target changed anything.
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

#: Joint numbers of a leg, in chain order.
LEG_JOINTS = (1, 2, 3, 4, 5, 6)


def _rx(angle: float) -> Matrix:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _ry(angle: float) -> Matrix:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(angle: float) -> Matrix:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _axis_rotation(axis: Matrix, angle: float) -> Matrix:
    """Rodrigues: rotation by ``angle`` about the unit vector ``axis``."""
    x, y, z = axis
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def rotation_rpy(roll: float, pitch: float, yaw: float) -> Matrix:
    """Foot orientation in ego axes (x forward, y left, z up) from roll about x, pitch about y
    (positive = toes down) and yaw about z (positive = toes turned left), radians, applied
    yaw first then pitch then roll in the turned frame (R = Rz(yaw) Ry(pitch) Rx(roll))."""
    return _rz(yaw) @ _ry(pitch) @ _rx(roll)


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
    """The constant geometry of one leg (native frame, zero pose)."""

    names: tuple[str, ...]
    hip: Matrix
    yaw_pitch_axis: Matrix
    pitch_offset: Matrix  # hip -> hip-pitch anchor (zero on types 0, 2, 4)
    thigh: Matrix  # hip-pitch anchor -> knee anchor
    shank: Matrix  # knee -> ankle-pitch anchor
    ankle: Matrix  # ankle-pitch -> ankle-roll anchor
    foot: Matrix  # ankle-roll anchor -> foot body centre
    sole: Matrix  # ankle-roll anchor -> sole point (straight down to the sole)
    low_deg: Matrix
    high_deg: Matrix


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
        return _Leg(
            names=tuple(j.perceptor for j in joints),
            hip=anchors[0],
            yaw_pitch_axis=axes[0],
            pitch_offset=offsets[0],
            thigh=offsets[1],
            shank=offsets[2],
            ankle=offsets[3],
            foot=np.array(foot.centre) - roll_anchor,
            sole=np.array([0.0, 0.0, sole_z - roll_anchor[2]]),
            low_deg=np.array([j.min_deg for j in joints]),
            high_deg=np.array([j.max_deg for j in joints]),
        )

    # ------------------------------------------------------------------ geometry helpers
    def joint_names(self, side: Side) -> tuple[str, ...]:
        """Perceptor names of the leg's six joints (lj1..lj6) in chain order."""
        return self._legs[side].names

    def hip_position(self, side: Side) -> Matrix:
        """The hip point (where the three hip axes meet) in ego axes relative to the torso."""
        return _EGO_TO_NATIVE.T @ self._legs[side].hip

    def sole_position_zero(self, side: Side) -> Matrix:
        """The sole point in the zero pose (legs straight), ego axes relative to the torso."""
        leg = self._legs[side]
        native = leg.hip + leg.pitch_offset + leg.thigh + leg.shank + leg.ankle + leg.sole
        return _EGO_TO_NATIVE.T @ native

    def leg_length(self, side: Side) -> float:
        """Hip to sole point with the leg straight (m)."""
        return float(self.hip_position(side)[2] - self.sole_position_zero(side)[2])

    # ------------------------------------------------------------------ solving
    def solve(self, side: Side, foot_transform: Matrix) -> LegSolution:
        """Angles that put the foot body's centre at ``foot_transform`` (4x4, native frame,
        relative to the torso, as :func:`world.kinematics.body_transforms` reports it)."""
        leg = self._legs[side]
        rotation = np.asarray(foot_transform[:3, :3], dtype=float)
        roll_anchor = np.asarray(foot_transform[:3, 3], dtype=float) - rotation @ leg.foot
        return self._solve(leg, rotation, roll_anchor)

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
        ego_rotation = rotation_rpy(roll, pitch, yaw)
        rotation = _EGO_TO_NATIVE @ ego_rotation @ _EGO_TO_NATIVE.T
        sole = _EGO_TO_NATIVE @ np.asarray(position, dtype=float)
        return self._solve(leg, rotation, sole - rotation @ leg.sole)

    def _solve(self, leg: _Leg, rotation: Matrix, roll_anchor: Matrix) -> LegSolution:
        """The closed form's usual branch (ankle roll small, knee bent backwards, lj1 in
        range); where that leaves the joint ranges, the other branches of the ankle roll and
        the knee are tried too and the one needing the least clipping wins."""
        best: tuple[float, Matrix, bool] | None = None
        for branch in _BRANCHES:
            q, reachable = self._closed_form(leg, rotation, roll_anchor, *branch)
            if np.any(leg.pitch_offset):
                q = _refine(leg, q, rotation, roll_anchor)
            degrees = np.degrees(q)
            excess = float(np.sum(np.maximum(leg.low_deg - degrees, 0.0)))
            excess += float(np.sum(np.maximum(degrees - leg.high_deg, 0.0)))
            if best is None or excess < best[0]:
                best = (excess, degrees, reachable)
            if excess == 0.0:
                break
        assert best is not None
        excess, degrees, reachable = best
        clipped = np.clip(degrees, leg.low_deg, leg.high_deg)
        angles = dict(zip(leg.names, (float(a) for a in clipped), strict=True))
        return LegSolution(angles, reachable, excess == 0.0)

    def _closed_form(
        self,
        leg: _Leg,
        rotation: Matrix,
        roll_anchor: Matrix,
        roll_flipped: bool = False,
        knee_forward: bool = False,
    ) -> tuple[Matrix, bool]:
        """The exact solution when the hip pitch axis meets the other two (types 0, 2, 4); with
        the hip-pitch anchor lower (types 1, 3) it treats that offset as part of the thigh,
        exact for lj3 = 0 and a close start for :func:`_refine` otherwise."""
        # 1. ankle roll: undo it and the hip, seen from the foot, lies in the y-z plane
        w = rotation.T @ (leg.hip - roll_anchor)
        q6 = math.atan2(w[0], -w[2]) if roll_flipped else math.atan2(-w[0], w[2])
        u = _ry(q6) @ w
        # 2. knee and ankle pitch in the sagittal plane: v = Rx(-q5) (shank + Rx(-q4) thigh)
        v = -u[1:] - leg.ankle[1:]
        thigh, shank = (leg.pitch_offset + leg.thigh)[1:], leg.shank[1:]
        lt, ls, lv = math.hypot(*thigh), math.hypot(*shank), math.hypot(*v)
        cos_gap = (lv * lv - lt * lt - ls * ls) / (2.0 * lt * ls)
        reachable = -1.0 <= cos_gap <= 1.0
        gap = math.acos(min(1.0, max(-1.0, cos_gap)))
        angle_t = math.atan2(thigh[1], thigh[0])
        angle_s = math.atan2(shank[1], shank[0])
        # the usual branch bends the knee backwards (lj4 <= 0)
        q4 = angle_t - angle_s + (gap if knee_forward else -gap)
        c4, s4 = math.cos(-q4), math.sin(-q4)
        m = shank + np.array([c4 * thigh[0] - s4 * thigh[1], s4 * thigh[0] + c4 * thigh[1]])
        q5 = _wrap(math.atan2(m[1], m[0]) - math.atan2(v[1], v[0]))
        # 3. the hip: R123 = Ra(q1) Ry(q2) Rx(q3)
        r123 = rotation @ _ry(-q6) @ _rx(-(q4 + q5))
        q1 = self._yaw_pitch(leg, r123[:, 0])
        rest = _axis_rotation(leg.yaw_pitch_axis, -q1) @ r123
        q2 = math.atan2(-rest[2, 0], rest[0, 0])
        rest = _ry(-q2) @ rest
        q3 = math.atan2(rest[2, 1], rest[1, 1])
        return np.array([q1, q2, q3, q4, q5, q6]), reachable

    @staticmethod
    def _yaw_pitch(leg: _Leg, column: Matrix) -> float:
        """lj1 such that Ra(-lj1) turns ``column`` into the x-z plane; of the two solutions
        (half a turn apart) the one nearer the joint's range."""
        k = leg.yaw_pitch_axis
        cross_y = float(np.cross(k, column)[1])
        phi = math.atan2(-column[1], cross_y)  # = -lj1
        candidates = (_wrap(-phi), _wrap(-phi + math.pi))
        low, high = math.radians(leg.low_deg[0]), math.radians(leg.high_deg[0])

        def excess(q: float) -> float:
            return max(low - q, q - high, 0.0)

        return min(candidates, key=lambda q: (excess(q), abs(q)))


def _leg_forward(leg: _Leg, q: Matrix) -> tuple[Matrix, Matrix, Matrix, Matrix]:
    """Forward kinematics of one leg: foot rotation, ankle-roll anchor, and every joint's
    anchor (6, 3) and axis (6, 3) in the torso frame, for angles ``q`` (radians)."""
    axes_local = (leg.yaw_pitch_axis, _Y, _X, _X, _X, _Y)
    offsets = (_ZERO, _ZERO, leg.pitch_offset, leg.thigh, leg.shank, leg.ankle)
    turns = (_axis_rotation(leg.yaw_pitch_axis, float(q[0])), _ry(q[1]), _rx(q[2]))
    turns += (_rx(q[3]), _rx(q[4]), _ry(q[5]))
    rotation = np.eye(3)
    position = leg.hip
    anchors = np.empty((6, 3))
    axes = np.empty((6, 3))
    for i in range(6):
        position = position + rotation @ offsets[i]
        anchors[i] = position
        axes[i] = rotation @ axes_local[i]
        rotation = rotation @ turns[i]
    return rotation, position, anchors, axes


#: Newton steps stop once position (m) and orientation errors are below this: a micrometre is
#: far below what a joint command in hundredths of a degree can express.
REFINE_TOLERANCE = 1e-6


def _refine(leg: _Leg, q: Matrix, rotation: Matrix, roll_anchor: Matrix, steps: int = 8) -> Matrix:
    """Newton steps on the full chain (geometric Jacobian) from a close start: the closed form
    is off by the small hip-pitch offset's effect only, so one or two steps reach 1e-6 m."""
    for _ in range(steps):
        current, end, anchors, axes = _leg_forward(leg, q)
        turn = rotation @ current.T
        error = np.concatenate(
            [roll_anchor - end, 0.5 * np.array([turn[2, 1] - turn[1, 2],
                                                 turn[0, 2] - turn[2, 0],
                                                 turn[1, 0] - turn[0, 1]])]
        )  # fmt: skip
        if float(np.abs(error).max()) < REFINE_TOLERANCE:
            break
        lever = end - anchors
        linear = axes[:, [1, 2, 0]] * lever[:, [2, 0, 1]] - axes[:, [2, 0, 1]] * lever[:, [1, 2, 0]]
        jacobian = np.vstack([linear.T, axes.T])
        try:
            q = q + np.linalg.solve(jacobian, error)
        except np.linalg.LinAlgError:  # a stretched or folded leg: keep the closest so far
            break
    return q


#: (ankle roll flipped by half a turn, knee bent the other way), the usual branch first
_BRANCHES = ((False, False), (True, False), (False, True), (True, True))
_ZERO = np.zeros(3)
_X = np.array([1.0, 0.0, 0.0])
_Y = np.array([0.0, 1.0, 0.0])


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
