"""A landing catch for the kick: when the torso tips after the swing, put the kicking foot flat
on the ground now, where the ground is, instead of finishing the keyframed landing.

Why: weak basic kicks fell half the time 0.4-1.2 s after contact (session 12,
``scripts/kick/trace_rolls.py --distance 1.5``). The slow swing keeps the robot on one leg; its
torso roll creeps from the weight shift's 4-6 deg to 9-13 deg over the support foot's outer
edge, and the keyframed landing (joint angles written for an upright torso) leaves the kicking
foot hovering above the ground on the raised side, so it never arrives. The catch reads the
world's "up" in the torso frame (the IMU tilt estimate), finds the ground plane through the
support foot (forward kinematics of the measured joint angles), and drives the kicking foot to
a flat pose on that plane beside the support foot (leg inverse kinematics, ``behaviors.ik``),
its goal fixed when the catch starts. Once that foot bears weight, both feet stay planted while
the torso moves upright to the middle between them (:class:`TorsoToMiddle`), then the legs
blend into the stand.

Triggered by the torso roll or roll rate towards either side (thresholds in ``kicks.yaml``,
``catch`` of a kick motion; 0 / 0: always), only between the end of the swing (``early_s``
before it at the earliest) and the start of the kick's last frame (the return to the stand).
A roll towards the kicking side widens the landing by ``widen_m_per_deg`` (a capture step: the
foot lands further out, under the falling torso).

Not packaged (session 14, the figures at the end of ``kicks.yaml``): no setting fell less on
both the tuned and an untuned seed set. In the falling weak kicks the torso has already rolled
6-7 deg over the support foot when the swing ends, and from the landing posture the kicking
foot cannot reach the ground beside it even with a straight leg.

Written for the left kick (the right leg supports); the right kick mirrors sides and signs.
No pybullet: everything comes from the perceived joint angles and the tilt estimate.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np

from behaviors.ik import leg_ik_for
from behaviors.joint_control import CYCLE_SECONDS, JointCommands
from behaviors.keyframes import KeyframePlayer, KeyframeSequence, ease, parse_sequences
from behaviors.poses import PoseError, check_fields, check_number, get_pose
from world.kinematics import body_transforms
from world.nao_model import robot_spec


@dataclass(frozen=True)
class CatchParams:
    """When and how the landing catch acts (the ``catch`` block of a kick in ``kicks.yaml``)."""

    #: torso roll (deg) towards the support foot that triggers the catch
    support_roll_deg: float = 8.0
    #: torso roll (deg) towards the kicking foot that triggers it
    kicking_roll_deg: float = 4.0
    #: roll rate (deg/s, gyro) towards either side that triggers it
    rate_deg_s: float = 1000.0
    #: seconds for the kicking foot to reach the ground from where it is
    catch_s: float = 0.16
    #: seconds the feet then stay so (both feet on the ground, the weight where it is)
    hold_s: float = 0.3
    #: seconds to blend both legs to the stand pose afterwards, and to hold it
    stand_s: float = 0.6
    stand_hold_s: float = 0.3
    #: horizontal distance (m) between the foot centres, across the support foot's heading
    width_m: float = 0.11
    #: extra width (m) per degree of roll towards the kicking foot (a step under the torso)
    widen_m_per_deg: float = 0.0
    #: how far (m) below the support sole's plane the kicking foot is aimed; 0: pressing the
    #: foot down extends the kicking leg and rolls the torso further over the support foot
    press_m: float = 0.0
    #: degrees the support knee bends further while the foot comes down (hip and ankle pitch
    #: half as much each, so the torso keeps its pitch): lowers the torso so that the kicking
    #: leg reaches the ground beside a tilted support foot (from the kick's tall landing
    #: posture a straight leg reaches about 0.13 m out on level ground, less when tilted)
    support_bend_deg: float = 0.0
    #: seconds before the swing's end that the catch may start already (0: at its end)
    early_s: float = 0.0
    #: 1: once the foot is down, hold it there and hand back to the kick's own return to the
    #: stand (its last frame); 0: move the torso to the middle with both feet planted
    #: (:class:`TorsoToMiddle`)
    hand_back: float = 0.0


_CATCH_FIELDS = set(CatchParams.__dataclass_fields__)


def parse_catch(data: Any, where: str) -> CatchParams:
    """A :class:`CatchParams` from a ``catch`` mapping (every field optional, numbers; times
    positive, width at least 0.08 m)."""
    check_fields(data, where, set(), _CATCH_FIELDS)
    values = {name: check_number(value, f"{where}.{name}") for name, value in data.items()}
    params = CatchParams(**values)
    for name in ("catch_s", "stand_s"):
        if getattr(params, name) <= 0:
            raise PoseError(f"{where}.{name}: must be positive")
    for name in ("hold_s", "stand_hold_s", "widen_m_per_deg", "press_m", "early_s"):
        if getattr(params, name) < 0:
            raise PoseError(f"{where}.{name}: must not be negative")
    if not 0.08 <= params.width_m <= 0.25:
        raise PoseError(f"{where}.width_m: expected 0.08-0.25 m, got {params.width_m}")
    return params


#: Normal force (N) on the kicking foot's FRP perceptor from which it counts as landed.
TOUCHDOWN_FORCE_N = 15.0
#: Seconds of the joint-space blend into the exact stand pose after :class:`TorsoToMiddle`
#: (which ends a degree or two from it: flat feet, the stand pitches them slightly).
STAND_BLEND_S = 0.2


@cache
def _stand_sequence(stand_s: float, hold_s: float) -> KeyframeSequence:
    entry = {"frames": [{"duration": stand_s, "hold": hold_s, "pose": "stand"}]}
    return parse_sequences({"catch_stand": entry}, "kick_recovery")["catch_stand"]


def ground_frame(
    robot_type: int, joints_deg: Mapping[str, float], up: np.ndarray, support: str
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The ground frame under the ``support`` foot ("left"/"right") in the torso's native frame
    (4x4: x right and y forward along the support foot's heading, z = world up; the origin
    under the foot's centre at the height of its lowest sole corner), and both foot bodies'
    transforms relative to the torso (from the measured joint angles). ``up``: world up in the
    torso's native frame (x right, y forward, z up), as
    :attr:`world.robot_state.RobotState.up`.

    Why the lowest corner: a support foot tipping over its outer edge stands on that edge;
    through its centre the plane would rise with the tipping foot and lift the other foot's
    target with it, instead of pressing it down against the roll."""
    spec = robot_spec(robot_type)
    transforms = body_transforms(spec, joints_deg)
    feet = {"left": transforms["lfoot"], "right": transforms["rfoot"]}
    support_pose = feet[support]
    u = np.asarray(up, dtype=float)
    u = u / np.linalg.norm(u)
    forward = support_pose[:3, 1] - float(support_pose[:3, 1] @ u) * u
    forward /= np.linalg.norm(forward)
    half = np.asarray(spec.body("lfoot").size, dtype=float) / 2.0
    corners = [
        support_pose[:3, :3] @ np.array([sx * half[0], sy * half[1], -half[2]])
        for sx in (-1.0, 1.0)
        for sy in (-1.0, 1.0)
    ]
    centre = support_pose[:3, 3]
    lowest = min(float(c @ u) for c in corners)  # below the centre, along up
    frame = np.eye(4)
    frame[:3, 0], frame[:3, 1], frame[:3, 2] = np.cross(forward, u), forward, u
    frame[:3, 3] = centre + lowest * u
    return frame, feet


def flat_foot(frame: np.ndarray, x: float, y: float, robot_type: int) -> np.ndarray:
    """The transform (torso native frame) of a foot body lying flat on the ground of ``frame``
    (:func:`ground_frame`) with its centre above the ground point ``(x, y)`` of that frame."""
    half_height = robot_spec(robot_type).body("lfoot").size[2] / 2.0
    pose = frame.copy()
    pose[:3, 3] = frame[:3, :3] @ np.array([x, y, half_height]) + frame[:3, 3]
    return pose


def foot_on_ground(
    robot_type: int,
    joints_deg: Mapping[str, float],
    up: np.ndarray,
    kicking: str,
    width_m: float,
    press_m: float,
) -> dict[str, float]:
    """Joint angles (deg) of the ``kicking`` leg ("left"/"right") that put its foot flat on the
    ground plane through the other (support) foot, ``width_m`` beside it across the support
    foot's heading and ``press_m`` below the plane (:func:`ground_frame`)."""
    support = "right" if kicking == "left" else "left"
    frame, _ = ground_frame(robot_type, joints_deg, up, support)
    side = -1.0 if kicking == "left" else 1.0  # the kicking foot lies left of a right support
    target = flat_foot(frame, side * width_m, 0.0, robot_type)
    target[:3, 3] -= press_m * frame[:3, 2]
    return leg_ik_for(robot_type).solve(kicking, target).angles_deg  # type: ignore[arg-type]


def _rotation_power(rotation: np.ndarray, share: float) -> np.ndarray:
    """``rotation`` (3x3) turned only ``share`` (0..1) of its angle about its own axis."""
    angle = math.acos(max(-1.0, min(1.0, (float(np.trace(rotation)) - 1.0) / 2.0)))
    if angle < 1e-9:
        return np.eye(3)
    axis = np.array(
        [
            rotation[2, 1] - rotation[1, 2],
            rotation[0, 2] - rotation[2, 0],
            rotation[1, 0] - rotation[0, 1],
        ]
    ) / (2.0 * math.sin(angle))
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = share * angle
    return np.eye(3) + math.sin(a) * k + (1.0 - math.cos(a)) * (k @ k)


class TorsoToMiddle:
    """Both feet planted where they are; the torso moves upright to the stand's place between
    them (leg inverse kinematics for both feet every cycle), so that the weight shifts onto
    both feet without either foot leaving the ground. Why not a joint-space blend to the stand
    pose: blending the joint angles from a catch with the torso rolled over the support foot
    lifted the kicking foot again half-way (the robot then fell over the support foot)."""

    def __init__(
        self,
        robot_type: int,
        joints_deg: Mapping[str, float],
        up: np.ndarray,
        support: str,
        seconds: float,
    ) -> None:
        self._type = robot_type
        self._seconds = seconds
        self._elapsed = 0.0
        frame, feet = ground_frame(robot_type, joints_deg, up, support)
        to_ground = np.linalg.inv(frame)
        #: foot bodies in the ground frame (fixed: the feet stay planted, flat on the ground)
        ground = np.eye(4)
        self._feet = {}
        for side, pose in feet.items():
            x, y, _ = (to_ground @ pose)[:3, 3]
            self._feet[side] = flat_foot(ground, float(x), float(y), robot_type)
        #: the torso in the ground frame now and where the stand puts it
        self._torso_start = to_ground.copy()
        stand = _stand_feet(robot_type)
        middle = (self._feet["left"][:3, 3] + self._feet["right"][:3, 3]) / 2.0
        stand_middle = (stand["left"][:3, 3] + stand["right"][:3, 3]) / 2.0
        self._torso_end = np.eye(4)
        self._torso_end[:3, 3] = middle - stand_middle

    def step(self, commands: JointCommands) -> bool:
        """Write both legs' targets for this cycle; True once the torso is in place."""
        self._elapsed += CYCLE_SECONDS
        share = min(self._elapsed / self._seconds, 1.0)
        blend = ease("smooth", share)
        start, end = self._torso_start, self._torso_end
        torso = np.eye(4)
        turn = start[:3, :3].T @ end[:3, :3]
        torso[:3, :3] = start[:3, :3] @ _rotation_power(turn, blend)
        torso[:3, 3] = start[:3, 3] + (end[:3, 3] - start[:3, 3]) * blend
        from_ground = np.linalg.inv(torso)
        ik = leg_ik_for(self._type)
        for side, pose in self._feet.items():
            commands.set_targets(ik.solve(side, from_ground @ pose).angles_deg)  # type: ignore[arg-type]
        return share >= 1.0


@cache
def _stand_feet(robot_type: int) -> dict[str, np.ndarray]:
    """Both foot bodies' transforms relative to the torso (native frame) in ``stand``."""
    transforms = body_transforms(robot_spec(robot_type), get_pose("stand").joints)
    return {"left": transforms["lfoot"], "right": transforms["rfoot"]}


class LandingCatch:
    """The catch of one kick (see the module docstring): :meth:`triggered` says whether to
    start it; once started, :meth:`step` writes every cycle's leg targets until it returns
    True (the robot stands)."""

    def __init__(self, params: CatchParams, robot_type: int, mirror: bool) -> None:
        self.params = params
        self._type = robot_type
        self._mirror = mirror
        self._kicking = "right" if mirror else "left"
        self._elapsed = 0.0
        self._start: dict[str, float] | None = None
        self._stand: KeyframePlayer | None = None
        self._middle: TorsoToMiddle | None = None
        self._middled = False
        #: the kicking leg's targets this catch wrote last (where the stand blend starts)
        self._last: dict[str, float] = {}
        self._goal: dict[str, float] = {}
        self.active = False

    def triggered(self, roll_deg: float, roll_rate: float) -> bool:
        """Whether the torso (roll deg, + = to the right; gyro deg/s, + = rolling right) tips
        beyond the thresholds, towards the support or the kicking foot."""
        roll = -roll_deg if self._mirror else roll_deg  # + = towards the support foot
        rate = -roll_rate if self._mirror else roll_rate
        p = self.params
        return (
            roll >= p.support_roll_deg or roll <= -p.kicking_roll_deg or abs(rate) >= p.rate_deg_s
        )

    def start(
        self,
        joints_deg: Mapping[str, float],
        up: np.ndarray,
        roll_deg: float,
        support_plan: Mapping[str, float] | None = None,
    ) -> None:
        """Begin the catch from the measured joint angles and tilt: the kicking foot's goal on
        the ground is fixed now. ``support_plan``: the support leg's targets that the kick
        will reach while the foot comes down (its landing frame); the goal is where the ground
        will be then, the support foot keeping its present tilt to the world. Why fixed and
        not re-aimed every cycle: a goal that follows the tilt extends the kicking leg as the
        torso rolls over the support foot, which pushes it further over (screened: more
        falls). Why the plan: after the swing the support leg is nearly straight, and a goal
        beside it is a straight kicking leg."""
        self.active = True
        self._elapsed = 0.0
        names = leg_ik_for(self._type).joint_names(self._kicking)  # type: ignore[arg-type]
        self._start = {name: float(joints_deg[name]) for name in names}
        roll = -roll_deg if self._mirror else roll_deg
        p = self.params
        width = p.width_m + p.widen_m_per_deg * max(0.0, -roll)
        planned = {**joints_deg, **(support_plan or {})}
        for name, value in self._bend(1.0).items():
            planned[name] = planned.get(name, 0.0) + value
        support = "rfoot" if self._kicking == "left" else "lfoot"
        spec = robot_spec(self._type)
        now = body_transforms(spec, joints_deg)[support][:3, :3]
        later = body_transforms(spec, planned)[support][:3, :3]
        up_later = later @ (now.T @ np.asarray(up, dtype=float))
        self._goal = foot_on_ground(self._type, planned, up_later, self._kicking, width, p.press_m)

    def _bend(self, share: float) -> dict[str, float]:
        """The support leg's extra bend (deg per joint) at ``share`` (0..1) of it."""
        bend = self.params.support_bend_deg * share
        leg = "llj" if self._kicking == "right" else "rlj"
        return {f"{leg}3": bend / 2.0, f"{leg}4": -bend, f"{leg}5": bend / 2.0}

    def step(
        self,
        commands: JointCommands,
        joints_deg: Mapping[str, float],
        up: np.ndarray,
        kicking_force_n: float = 0.0,
    ) -> bool:
        """Write this cycle's targets over what the kick wrote (the kicking leg while it
        catches; both legs once the kicking foot is down; every joint in the final stand
        blend); True when it stands. ``kicking_force_n``: the kicking foot's normal force
        (FRP perceptor), which says it has landed."""
        assert self._start is not None
        p = self.params
        self._elapsed += CYCLE_SECONDS
        landed = self._elapsed >= p.catch_s and kicking_force_n >= TOUCHDOWN_FORCE_N
        if p.hand_back or (
            self._middle is None and not landed and self._elapsed <= p.catch_s + p.hold_s
        ):
            blend = ease("smooth", self._elapsed / p.catch_s)
            goal = self._goal
            self._last = {n: a + (goal[n] - a) * blend for n, a in self._start.items()}
            commands.set_targets(self._last)
            if p.support_bend_deg:
                written = commands.targets()
                bent = {
                    n: written.get(n, float(joints_deg.get(n, 0.0))) + v
                    for n, v in self._bend(blend).items()
                }
                commands.set_targets(bent)
            return False
        if self._middle is None:
            support = "right" if self._kicking == "left" else "left"
            self._middle = TorsoToMiddle(self._type, joints_deg, up, support, p.stand_s)
        if not self._middled:
            self._middled = self._middle.step(commands)
            self._last = commands.targets()
            return False
        if self._stand is None:
            self._stand = KeyframePlayer(_stand_sequence(STAND_BLEND_S, p.stand_hold_s), self._type)
            return self._stand.step(commands, {**joints_deg, **self._last})
        return self._stand.step(commands, joints_deg)
