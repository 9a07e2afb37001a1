"""Omnidirectional walk: ``walk_velocity(vx, vy, vturn_deg)`` and ``walk(x, y, heading_deg)``.

The engine (:class:`WalkEngine`) turns a velocity into joint speeds every cycle:

1. the commanded velocity is smoothed (bounded acceleration), then scaled to one step's torso
   motion (:class:`~behaviors.step_generator.StepCommand`) and kept inside the step limits
   (each axis, then all together: :func:`norm_limited`);
2. the :class:`~behaviors.step_generator.StepGenerator` gives both soles' targets for the
   cycle the command will act in, with the IMU's corrections added (below);
3. :class:`~behaviors.ik.LegIK` turns them into leg angles;
4. joint speeds are sent directly, not through the target follower, because the follower lags
   four cycles and a step lasts eight: the server shows an action two perceptions later, so the
   speed answering perception ``k`` moves the joint from ``k + 1`` to ``k + 2``. The angle at
   ``k + 1`` is predicted from the current angle and the speed sent last cycle (a Smith
   predictor), and the new speed is the target's own motion plus a share of the predicted error.

Staying upright: a tilt makes the stance leg's ankle push back (pitch: ankle pitch; roll: ankle
and hip roll), and the torso's pitch rate shifts the swing foot's landing point forward or back
(a fall forwards is caught by stepping further forwards). Gains and the gait's shape per robot
type are in ``behaviors/data/walk.yaml``.

Odometry: every cycle the torso motion the step plan assumes (scaled by the per-type
``odometry_scale`` measured in the simulator) goes to ``world.localizer.add_odometry``.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from functools import cache
from pathlib import Path
from typing import Any

import yaml

from behaviors.ik import LegIK, leg_ik_for
from behaviors.joint_control import CYCLE_SECONDS
from behaviors.skill import Skill, SkillContext
from behaviors.step_generator import (
    FootTargets,
    StepCommand,
    StepGenerator,
    StepParameters,
    swing_progress,
)
from world.localization import wrap_deg
from world.nao_model import ROBOT_TYPES, robot_spec

__all__ = [
    "WALK_FILE",
    "WalkEngine",
    "WalkParameters",
    "WalkSkill",
    "WalkSkillBase",
    "WalkVelocitySkill",
    "norm_limited",
    "walk_parameters",
]

WALK_FILE = Path(__file__).resolve().parent / "data" / "walk.yaml"
#: walk settings newer than the kick's walk (the ``inside_skills`` block of walk.yaml): inside
#: another skill they keep their defaults (off) unless that block sets them, so the kick walks
#: as it was tuned and the block stays as the kick's owner left it (session 12)
OFF_INSIDE_SKILLS = ("go_to_fast_speed", "go_to_settle_frames", "go_to_max_backward_speed")
#: what the heading drift may be measured against (``WalkParameters.heading_hold_reference``)
HEADING_HOLD_REFERENCES = ("command", "step")


@dataclass(frozen=True)
class WalkParameters:
    """Everything tunable about the walk of one robot type (see ``walk.yaml``)."""

    step: StepParameters = field(default_factory=StepParameters)
    #: largest velocity change per second: forward/sideways (m/s^2), turn (deg/s^2)
    acceleration: float = 1.5
    turn_acceleration_deg: float = 600.0
    #: share of the predicted joint error corrected per cycle (0..1)
    error_gain: float = 0.6
    #: joint speed cap (rad/s) of the walk on top of the model's own caps: type 2's faster
    #: ankle pitch (8.8 rad/s) following the swing targets that fast made it walk slower
    #: (measured 0.57 against 0.69 m/s capped at 6.14 rad/s, 0.15 m steps)
    max_joint_speed: float = math.inf
    #: ankle pitch correction per degree of torso pitch and per deg/s of pitch rate
    ankle_pitch_gain: float = 0.0
    ankle_pitch_rate_gain: float = 0.0
    #: ankle and hip roll corrections per degree of torso roll
    ankle_roll_gain: float = 0.0
    hip_roll_gain: float = 0.0
    #: swing foot landing shift (m) per deg/s of pitch rate (forward fall -> longer step)
    landing_pitch_rate_gain: float = 0.0
    #: landing shift (m) per degree of pitch
    landing_pitch_gain: float = 0.0
    #: share (0..1) of the step's extra forward lean (``step.speed_lean`` times the speed
    #: share, in degrees) taken off the torso's pitch before the landing shift. Why: with a
    #: large ``speed_lean`` the torso leans into the walk by design, and read as a forward fall
    #: that lean lengthened every step: session 22's fast type-0 gait walked 0.48 m/s asked
    #: 0.39 and 0.75-0.87 asked 0.61, pitched ever further and fell (23 of 200 random-command
    #: episodes). 0, the default, keeps the absolute pitch of the gaits tuned before it
    landing_pitch_lean_share: float = 0.0
    #: ``landing_pitch_lean_share`` walking to a target (``walk``): 0 by default, the absolute
    #: pitch. Why: there the speed is capped (``walk_to_max_speed``) and the go-to's own loop
    #: brings the robot in, and session 22's fast type-0 gait reached 164 targets in 12
    #: random-target sets without a fall reading the absolute pitch, 125 with the lean off it
    go_to_landing_pitch_lean_share: float = 0.0
    #: sideways landing shift (m, to the right) per deg/s of roll rate and per degree of roll
    landing_roll_rate_gain: float = 0.0
    landing_roll_gain: float = 0.0
    #: sideways landing shift (m) per degree of roll on the steps whose swing leg is on the
    #: side the torso rolls to (the swing foot lands further out, under the fall); the other
    #: steps keep their plan. 0 (the default) is off; ``walk`` to a target sets it from
    #: ``go_to_landing_roll_lean_gain``
    landing_roll_lean_gain: float = 0.0
    #: share of max_turn left at full forward or sideways speed (walking fast and turning hard
    #: trips the robot: the turning swing foot catches the support foot); in between it shrinks
    #: linearly
    turn_share_at_full_speed: float = 1.0
    #: how forward, sideways and turning share the step's limits (:func:`norm_limited`):
    #: ``inf`` (a box: each axis on its own) lets a fast step also go fully sideways and turn,
    #: which trips the robot; 2 is an ellipsoid, 1 a diamond.
    step_norm: float = math.inf
    #: the fastest forward speed (m/s) of ``walk`` to a target (``walk_velocity`` may go up to
    #: max_forward per step): turning or braking at full speed tipped robots over in random
    #: target walks (5 falls in 3 x 60 s on types 1, 3 and 4 at 0.15 m steps)
    walk_to_max_speed: float = math.inf
    #: walking to a target, the fastest forward speed (m/s) on a straight stretch: facing the
    #: way of travel with the heading within ``go_to_fast_heading_deg`` of it, the cap rises
    #: from ``walk_to_max_speed`` (at that heading error) to this (heading on the way);
    #: turning and near the target (``GoToGains.position_gain``) it stays as it was. Why
    #: (session 12): the cap was set for the turns and stops that tipped robots at 0.75 m/s
    #: (session 7), and players walk to the ball and their places with ``walk``, mostly
    #: straight on. 0 (the default) is off: ``walk_to_max_speed`` everywhere.
    go_to_fast_speed: float = 0.0
    go_to_fast_heading_deg: float = 10.0
    #: ... and only far from the target: fully from this distance (m) on, not at all within
    #: half of it (linear in between). Why: at 0.8 m/s up to 0.5 m before the target (the
    #: position gain's own slow-down starts at 0.53 m) type 1's foot spun and it fell
    #: (run seed 4108, session 12)
    go_to_fast_distance_m: float = 2.0
    #: walking to a target (session 13): once arrived and standing, the robot stands on for
    #: this many fresh vision frames (accepted localiser updates), averages the estimates and,
    #: if that says the target is more than ``go_to_settle_distance_m`` away (or the heading
    #: off by more than the arrival's tolerance), walks again, at most
    #: ``go_to_settle_retries`` times per target; only then does ``walk`` report arrival.
    #: Why: the stop errors above 0.08 m were the localiser's error at the arrival (type 4,
    #: run seed 7211: 0.088 m off after a 3.3 m walk, stopped 0.102 m from the target)
    #: while standing still its per-frame error is 0.01-0.03 m (odometry is exact then).
    #: 0 (the default) is off: arrival is reported as soon as the robot stands.
    go_to_settle_frames: int = 0
    go_to_settle_distance_m: float = 0.05
    go_to_settle_retries: int = 2
    #: the longest settle (cycles) when no frame comes (facing away from every landmark)
    go_to_settle_max_cycles: int = 40
    #: turn correction (deg/s) per degree of heading drift from the commanded turn (gyro)
    heading_hold_gain: float = 0.0
    #: what the gyro's turn is compared with to measure the drift: "command" (the smoothed
    #: commanded turn rate: an integral heading hold, which keeps ``walk_velocity`` straight)
    #: or "step" (the turn the step under way plans, its own correction included: only the
    #: feet's slip counts, and once the robot turns as planned the drift stops growing; a
    #: slip gets one steady correction, no integral action, so on its own the walk curves by
    #: about 3 deg/s) ...
    heading_hold_reference: str = "command"
    #: ... and the same while walking to a target (``walk``), where the heading loop on the
    #: localiser's pose (``GoToGains.heading_gain``) keeps the heading: "step" there, because
    #: the integral hold fought that loop. In random target walks the falls at 0.7 m/s began
    #: with a foot spinning (gyro 150-400 deg/s) while the hold's drift swung between -30 and
    #: 0 deg and the step's turn flipped sign step by step (walk.yaml has the figures)
    go_to_heading_hold_reference: str = "command"
    #: walking to a target (``walk``, session 7): the seconds of ``odometry_drift`` foreseen
    #: when the way left is measured: after arriving the robot steps out the step under way and
    #: two more that bring the feet home, drifting back all the while (it stopped 2-6 cm short
    #: of its targets with the drift in the odometry alone) ...
    go_to_drift_lookahead_s: float = 0.0
    #: ... whether, once arrived, it steps out its stop before it tests whether it has left
    #: the target again (the drift of the stop steps, and the look-ahead, sent type 2 off
    #: again with its torso pitched back, and the restart's backward steps tipped it over) ...
    go_to_stop_before_leaving: bool = False
    #: ... and the fastest turn (deg/s) it asks for (``GoToGains.max_turn_deg``)
    go_to_max_turn_deg: float = 120.0
    #: walking to a target (session 8): while the torso pitches back by more than this
    #: (degrees, IMU), the forward command is at most ``-go_to_pitch_back_speed`` (m/s): the
    #: robot steps back under its torso until the pitch is back within
    #: ``go_to_pitch_back_release_deg``. Why: type 2 pitched back 7-12 deg stopping at a
    #: target, walked off again towards it, and its landing correction's backward steps
    #: fought the forward command (which grew as it tipped away from the target) until it fell
    #: backwards. ``inf`` (the default) is off.
    go_to_pitch_back_deg: float = math.inf
    go_to_pitch_back_release_deg: float = 3.0
    go_to_pitch_back_speed: float = 0.1
    #: walking to a target: the fastest backward walk (m/s), the sideways share scaled with
    #: it so that the direction holds. Why (session 15): the last random-target falls of types
    #: 2 and 3 (runs 10102 and 10145, scripts/walk_trace.py) both began as a backward walk at
    #: about 0.4 m/s to a target 0.4 m behind, a foot spin, and a fall backwards. ``inf`` (the
    #: default) is off; walk.yaml sets 0.25 with its figures.
    go_to_max_backward_speed: float = math.inf
    #: walking to a target, the engine's ``landing_roll_lean_gain``. Why (session 10): types
    #: 2 and 4 fell turning at 60-120 deg/s (mostly on the spot) far from their targets, the
    #: torso rolling to one side over 1-2 s (-10 -> -25 deg) while the feet kept their stance
    #: width, then rolling over. 0 (the default) is off.
    go_to_landing_roll_lean_gain: float = 0.0
    #: whether ``walk`` to a target lands with the step's heel strike
    #: (``StepParameters.speed_heel_strike``) as ``walk_velocity`` does. Why off in
    #: walk.yaml (session 11): in random target walks (at most 0.65 m/s) it added falls
    #: (scripts/walk_seed_sets.py, two groups of 12 sets: types 0 and 1 0 -> 1 each on one,
    #: types 2 and 3 0 -> 1 and 0 -> 4 on the other)
    go_to_heel_strike: bool = True
    #: walking to a target with the heel strike, the step's ``heel_strike_turn_fade`` (rad of
    #: turn per step at which the heel strike has faded out; 0, the default, no fade)
    go_to_heel_strike_turn_fade: float = 0.0
    #: walking to a target: within this distance (m) of it the command has the
    #: ``odometry_drift`` taken off (feed-forward: the robot then really moves at the velocity
    #: it wants). Why (session 9): at the 0.2 m/s approach floor the drift (-0.1 m/s forward
    #: on every type) halves the real speed towards a target ahead and makes it 0.3 m/s
    #: towards one behind, and type 2 circled its targets for seconds, sideways and
    #: backwards, until it tipped over. 0 (the default) is off.
    go_to_drift_feedforward_m: float = 0.0
    #: how much of the planned torso motion really happens (measured)
    odometry_scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    #: torso drift (m/s, forward and left in the robot frame) while stepping that the step plan
    #: does not know about, added to the odometry: measured in the simulator (session 7,
    #: walk_velocity for 3 s at 0.15, 0.3 and 0.7 m/s forward, 0.2 m/s sideways): every type
    #: walks 0.08-0.12 m/s less forward than its steps plan, at any speed, so the localiser
    #: ran ahead of the robot and ``walk`` stopped short of its targets (by 6-11 cm on type 4)
    odometry_drift: tuple[float, float] = (0.0, 0.0)
    #: arm pose while walking (degrees), right side; the left mirrors it
    arm_pitch_deg: float = -90.0
    arm_out_deg: float = -10.0
    #: arm swing (degrees of shoulder pitch each way) at a full forward step, in proportion
    #: below it: each arm swings with the opposite leg (forward while that leg swings
    #: forward), as people walk, so the arms' yaw moment answers the legs'. Why: at full
    #: speed the torso yaws 10-30 deg a step and feet spin (session 7). 0 (the default) is off
    arm_swing_deg: float = 0.0
    #: toe joints (type 4) while walking, degrees: curled up, the loaded toes yield
    toe_deg: float = 70.0
    #: cycles to blend from the pose the walk found into the walk's stance
    blend_cycles: int = 10

    def __post_init__(self) -> None:
        for name in ("heading_hold_reference", "go_to_heading_hold_reference"):
            if getattr(self, name) not in HEADING_HOLD_REFERENCES:
                raise ValueError(
                    f"{name} must be one of {HEADING_HOLD_REFERENCES}, got {getattr(self, name)!r}"
                )


def _read_parameters(data: dict[str, Any], source: str) -> WalkParameters:
    """A :class:`WalkParameters` from a mapping with an optional ``step`` sub-mapping."""
    known = {f.name for f in fields(WalkParameters)}
    step_known = {f.name for f in fields(StepParameters)}
    unknown = set(data) - known
    if unknown:
        raise ValueError(f"{source}: unknown walk parameter(s) {sorted(unknown)}")
    step_data = dict(data.get("step") or {})
    unknown = set(step_data) - step_known
    if unknown:
        raise ValueError(f"{source}: unknown step parameter(s) {sorted(unknown)}")
    values = {k: v for k, v in data.items() if k != "step"}
    for name in ("odometry_scale", "odometry_drift"):
        if name in values:
            values[name] = tuple(float(v) for v in values[name])
    return WalkParameters(step=StepParameters(**step_data), **values)


@cache
def walk_parameters(
    robot_type: int, path: Path = WALK_FILE, inside_skill: bool = False
) -> WalkParameters:
    """The walk parameters of ``robot_type``: the file's ``default`` block overridden by its
    ``type<N>`` block (both may hold a ``step`` sub-block), and with ``inside_skill`` (the walk
    run by another skill) the ``inside_skills`` block's keys on top, then its own ``type<N>``
    sub-block's (a type whose walk changed after the kick's approach was tuned keeps the old
    values there); there the keys of :data:`OFF_INSIDE_SKILLS` keep their defaults unless
    that block sets them."""
    if robot_type not in ROBOT_TYPES:
        raise ValueError(f"robot type must be one of {ROBOT_TYPES}, got {robot_type!r}")
    data = yaml.safe_load(path.read_text()) or {}
    base = dict(data.get("default") or {})
    own = dict(data.get(f"type{robot_type}") or {})
    nested = _nested_block(data.get("inside_skills") or {}, robot_type) if inside_skill else {}
    step = {**(base.get("step") or {}), **(own.get("step") or {}), **(nested.get("step") or {})}
    merged = {**base, **own, **nested, "step": step}
    if inside_skill:
        for name in OFF_INSIDE_SKILLS:
            if name not in nested:
                merged.pop(name, None)
    return _read_parameters(merged, f"{path} (type{robot_type})")


def _nested_block(block: dict[str, Any], robot_type: int) -> dict[str, Any]:
    """The ``inside_skills`` keys for ``robot_type``: the block's own keys, then its
    ``type<N>`` sub-block's (one level deep for ``step``)."""
    shared = {k: v for k, v in block.items() if not (k.startswith("type") and k[4:].isdigit())}
    own = dict(block.get(f"type{robot_type}") or {})
    step = {**(shared.get("step") or {}), **(own.get("step") or {})}
    merged = {**shared, **own}
    if step:
        merged["step"] = step
    return merged


def norm_limited(command: StepCommand, step: StepParameters, norm: float) -> StepCommand:
    """``command`` scaled down (all axes alike, so its direction stays) until the ``norm``-norm
    of its shares of the step limits (forward or backward, sideways, turn) is at most 1;
    ``norm = inf`` leaves it as it is (each axis is clipped on its own elsewhere)."""
    if math.isinf(norm):
        return command
    forward_limit = step.max_forward * (1.0 if command.forward >= 0.0 else step.backward_share)
    limits = (forward_limit, step.max_side, step.max_turn)
    values = (command.forward, command.left, command.turn)
    shares = [abs(v) / max(limit, 1e-9) for v, limit in zip(values, limits, strict=True)]
    size = sum(share**norm for share in shares) ** (1.0 / norm)
    if size <= 1.0:
        return command
    return StepCommand(command.forward / size, command.left / size, command.turn / size)


class WalkEngine:
    """The walk's state for one robot: step generator, smoothed velocity, joint predictor."""

    def __init__(self, robot_type: int, params: WalkParameters | None = None) -> None:
        self.robot_type = robot_type
        self.params = params or walk_parameters(robot_type)
        self.ik: LegIK = leg_ik_for(robot_type)
        self.generator = StepGenerator(self.params.step)
        spec = robot_spec(robot_type)
        cap = self.params.max_joint_speed
        self._max_speed = {j.perceptor: min(j.max_speed, cap) for j in spec.joints}
        self._has_toes = spec.has_toes
        self.reset()

    def reset(self) -> None:
        """Start from standing still: no velocity, feet at the neutral stance."""
        self.generator = StepGenerator(self.params.step)
        self.velocity = (0.0, 0.0, 0.0)  # m/s, m/s, rad/s (smoothed)
        self._last_speed: dict[str, float] = {}
        self._previous_target: dict[str, float] | None = None
        self._start_pose: dict[str, float] | None = None
        self._cycles = 0
        self._stepping = False
        self._heading_drift = 0.0
        #: step parameters that take over at the next step boundary (see continue_from)
        self._pending_step: StepParameters | None = None
        #: the longest forward step (m) the next step to start may take; set by a caller for
        #: one step (the dribble's touch planner), cleared when that step starts
        self.next_step_forward_cap: float | None = None
        #: the manager cycle of the last step() (None before the first): a skill taking
        #: over checks that this engine walked in the cycle just before
        self.last_cycle: int | None = None

    def continue_from(self, other: WalkEngine) -> None:
        """Carry on the steps ``other`` is taking instead of starting from the stance.

        Why: a skill that starts while another walking skill was mid-step (the strategy's
        walk to the ball handing over to a dribble) used to restart from standing still: the
        new engine planned the feet at their neutral places and zero velocity while the robot
        was mid-stride at 0.3-0.6 m/s, and the lurch tipped it 15-30 deg (the kick-off taker
        fell that way, ``scripts/attack/kickoff_probe.py``). The step under way finishes with
        ``other``'s step shape; this engine's own shape takes over at the next step. Engines
        of different robot types do not hand over.
        """
        if other.robot_type != self.robot_type:
            return
        self.generator = copy.deepcopy(other.generator)
        own_step = self.params.step
        self._pending_step = None if other.params.step == own_step else own_step
        self.velocity = other.velocity
        self._last_speed = dict(other._last_speed)
        self._previous_target = (
            None if other._previous_target is None else dict(other._previous_target)
        )
        self._start_pose = None if other._start_pose is None else dict(other._start_pose)
        self._cycles = other._cycles
        self._stepping = other._stepping
        self._heading_drift = other._heading_drift

    # ------------------------------------------------------------------ state
    @property
    def phase(self) -> tuple[int, bool]:
        """(t, left_active) of the step under way (t = -1 before the first step)."""
        return self.generator.phase

    @property
    def step_seconds(self) -> float:
        """How long one step lasts (s): ``step_cycles`` server cycles."""
        return self.params.step.step_cycles * CYCLE_SECONDS

    @property
    def is_stepping(self) -> bool:
        """Whether a step is under way (the last cycle's targets came from a step)."""
        return self._stepping

    @property
    def is_stopped(self) -> bool:
        """Standing on both feet with no velocity and no step under way."""
        return not self._stepping and self.velocity == (0.0, 0.0, 0.0)

    # ------------------------------------------------------------------ one cycle
    def step(
        self,
        context: SkillContext,
        vx: float,
        vy: float,
        vturn_deg: float,
        offsets_deg: Mapping[str, float] | None = None,
    ) -> None:
        """One cycle walking at (vx, vy) m/s and vturn_deg deg/s in the robot frame.

        ``offsets_deg`` (joint -> degrees) is added to the angles the engine is about to
        track: the hook a learned residual acts through (``behaviors.learned_walk``), so the
        residual rides on the engine's own tracking instead of replacing it."""
        if self._pending_step is not None and (
            self.generator.phase[0] < 0 or self.generator.at_step_end
        ):
            self.generator.with_params(self._pending_step)
            self._pending_step = None
        self.last_cycle = getattr(context.manager, "cycle", None)
        self._smooth_velocity(vx, vy, math.radians(vturn_deg))
        self._track_heading(context)
        targets = self._next_foot_targets(context)
        angles = self._leg_angles(targets, context)
        self._add_arms(angles, targets)
        for name, offset in (offsets_deg or {}).items():
            angles[name] = angles.get(name, 0.0) + offset
        self._send(context, angles)
        self._report_odometry(context)
        self._cycles += 1

    def _smooth_velocity(self, vx: float, vy: float, vturn: float) -> None:
        a = self.params.acceleration * CYCLE_SECONDS
        at = math.radians(self.params.turn_acceleration_deg) * CYCLE_SECONDS
        x, y, w = self.velocity
        x += min(max(vx - x, -a), a)
        y += min(max(vy - y, -a), a)
        w += min(max(vturn - w, -at), at)
        self.velocity = (x, y, w)

    def _track_heading(self, context: SkillContext) -> None:
        """Integrate how far the gyro's turn has drifted from the commanded (or the step's
        planned) turn (feet slip and the swing leg twists the body); the step's turn works
        against the drift."""
        turn = float(context.world.robot.gyro_deg_s @ context.world.robot.up)
        drift = self._heading_drift + (turn - self._reference_turn_deg_s()) * CYCLE_SECONDS
        moving = self._stepping and self.velocity != (0.0, 0.0, 0.0)
        # stopping, the drift is forgotten: a correcting turn would keep the robot stepping
        self._heading_drift = max(-30.0, min(30.0, drift)) if moving else 0.0

    def _step_turn_deg_s(self) -> float:
        """The turn rate (deg/s) the step under way plans (0 standing)."""
        if not self._stepping:
            return 0.0
        return math.degrees(self.generator.command.turn) / self.step_seconds

    def _reference_turn_deg_s(self) -> float:
        """The turn rate the gyro's turn is held to (``heading_hold_reference``)."""
        if self.params.heading_hold_reference == "step":
            return self._step_turn_deg_s()
        return math.degrees(self.velocity[2])

    def _step_command(self) -> StepCommand:
        duration = self.step_seconds
        x, y, w = self.velocity
        w -= math.radians(self.params.heading_hold_gain * self._heading_drift)
        command = StepCommand(x * duration, y * duration, w * duration).clipped(self.params.step)
        command = norm_limited(command, self.params.step, self.params.step_norm)
        return self._turn_limited(command)

    def _turn_limited(self, command: StepCommand) -> StepCommand:
        """The command with its turn reduced as the forward or sideways step grows."""
        step = self.params.step
        speed_share = max(
            abs(command.forward) / step.max_forward, abs(command.left) / step.max_side
        )
        speed_share = min(1.0, speed_share)
        keep = 1.0 - (1.0 - self.params.turn_share_at_full_speed) * speed_share
        limit = step.max_turn * keep
        return replace(command, turn=min(max(command.turn, -limit), limit))

    def _next_foot_targets(self, context: SkillContext) -> FootTargets:
        """Targets of the next cycle, or the stance when standing still between steps."""
        generator = self.generator
        command = self._step_command()
        still = command.is_zero or max(abs(command.forward), abs(command.left)) < 1e-3
        still = still and abs(command.turn) < 1e-3
        feet_home = self._feet_at_neutral()
        between_steps = generator.phase[0] < 0 or generator.at_step_end
        if still and between_steps and feet_home:
            self._stepping = False
            return generator.stand_targets()
        self._stepping = True
        if between_steps and not still:  # stopping: the feet go home, the robot stays put
            command = self._balanced(command, context)
        if between_steps and self.next_step_forward_cap is not None:
            command = self._capped(command, self.next_step_forward_cap)
            self.next_step_forward_cap = None
        return generator.next_targets(command)

    def _capped(self, command: StepCommand, cap: float) -> StepCommand:
        """The step shortened to ``cap`` m forward at most, with the smoothed velocity brought
        down to match (so the steps after it grow back at the walk's acceleration instead of
        jumping back to the old length)."""
        if command.forward <= cap:
            return command
        x, y, w = self.velocity
        self.velocity = (min(x, cap / self.step_seconds), y, w)
        return replace(command, forward=cap)

    def _feet_at_neutral(self) -> bool:
        left, right = self.generator.feet
        spread = self.params.step.foot_spread
        return (
            abs(left.x) < 0.005
            and abs(right.x) < 0.005
            and abs(left.y - spread) < 0.005
            and abs(right.y + spread) < 0.005
            and abs(left.yaw) < 0.02
            and abs(right.yaw) < 0.02
        )

    def _balanced(self, command: StepCommand, context: SkillContext) -> StepCommand:
        """The next step's length corrected by the torso's pitch (stepping into a fall)."""
        robot = context.world.robot
        p = self.params
        rate = -float(robot.gyro_deg_s[0])  # + = pitching forward (gyro x: about the right)
        lean = p.landing_pitch_lean_share * math.degrees(
            p.step.speed_lean * self.generator.speed_share
        )
        pitch = robot.pitch_deg - lean
        shift = p.landing_pitch_rate_gain * rate + p.landing_pitch_gain * pitch
        roll_rate = float(robot.gyro_deg_s[1])  # + = rolling to the right
        side = p.landing_roll_rate_gain * roll_rate + p.landing_roll_gain * robot.roll_deg
        next_left_swings = not self.generator.phase[1]
        leaning_left = robot.roll_deg < 0.0
        if p.landing_roll_lean_gain and leaning_left == next_left_swings:
            side += p.landing_roll_lean_gain * robot.roll_deg  # the swing foot lands further out
        return replace(command, forward=command.forward + shift, left=command.left - side).clipped(
            p.step
        )

    def _leg_angles(self, targets: FootTargets, context: SkillContext) -> dict[str, float]:
        pitch = -targets.lean  # soles flat on the ground under a leaning torso
        left_pitch, right_pitch = pitch - targets.left_pitch, pitch - targets.right_pitch
        left = self.ik.solve_sole("left", targets.left, 0.0, left_pitch, targets.left_yaw)
        right = self.ik.solve_sole("right", targets.right, 0.0, right_pitch, targets.right_yaw)
        angles = {**left.angles_deg, **right.angles_deg}
        self._imu_corrections(angles, targets, context)
        return angles

    def _imu_corrections(
        self, angles: dict[str, float], targets: FootTargets, context: SkillContext
    ) -> None:
        """Ankle and hip corrections against the torso's tilt, on the support leg."""
        p = self.params
        robot = context.world.robot
        support = "r" if targets.left_active else "l"
        supports = (support,) if self._stepping else ("l", "r")
        pitch_rate = -float(robot.gyro_deg_s[0])  # + = pitching forward
        pitch_fix = p.ankle_pitch_gain * robot.pitch_deg + p.ankle_pitch_rate_gain * pitch_rate
        roll = robot.roll_deg  # + = leaning to the right
        for side in supports:
            angles[f"{side}lj5"] = angles[f"{side}lj5"] - pitch_fix
            angles[f"{side}lj6"] = angles[f"{side}lj6"] + p.ankle_roll_gain * roll
            angles[f"{side}lj2"] = angles[f"{side}lj2"] + p.hip_roll_gain * roll

    def _add_arms(self, angles: dict[str, float], targets: FootTargets) -> None:
        p = self.params
        right_forward = self._arm_swing_deg(targets)  # the right arm goes with the left leg
        angles.update(
            raj1=p.arm_pitch_deg + right_forward,
            laj1=p.arm_pitch_deg - right_forward,
            raj2=p.arm_out_deg,
            laj2=-p.arm_out_deg,
            raj3=0.0,
            laj3=0.0,
            raj4=10.0,
            laj4=-10.0,
        )
        if self._has_toes:
            angles.update(rlj7=p.toe_deg, llj7=p.toe_deg)

    def _arm_swing_deg(self, targets: FootTargets) -> float:
        """How far forward (degrees) the right arm swings now (``arm_swing_deg``): from back
        to front while the left leg swings, and back while the right one does."""
        p = self.params
        if p.arm_swing_deg == 0.0 or not self._stepping or targets.t < 0:
            return 0.0
        progress = swing_progress((targets.t + 1) / p.step.step_cycles, p.step)
        forward = 2.0 * progress - 1.0
        if not targets.left_active:
            forward = -forward
        return p.arm_swing_deg * self.generator.speed_share * forward

    def _send(self, context: SkillContext, angles: dict[str, float]) -> None:
        """Joint speeds that bring each joint to its target at the cycle the speed acts in."""
        current = context.world.robot.joints_deg
        if self._start_pose is None:
            self._start_pose = {n: current.get(n, 0.0) for n in angles}
        blend = min(1.0, (self._cycles + 1) / max(1, self.params.blend_cycles))
        if blend < 1.0:
            angles = {
                n: self._start_pose[n] + (a - self._start_pose[n]) * blend
                for n, a in angles.items()
            }
        previous = self._previous_target or angles
        gain = self.params.error_gain
        speeds = {}
        for name, target in angles.items():
            low, high = context.world.robot.joint_limits_deg(name)
            target = min(max(target, low), high)
            predicted = current.get(name, 0.0) + math.degrees(
                self._last_speed.get(name, 0.0) * CYCLE_SECONDS
            )
            before = min(max(previous.get(name, target), low), high)
            feedforward = target - before
            error = before - predicted
            speed = math.radians(feedforward + gain * error) / CYCLE_SECONDS
            limit = self._max_speed[name]
            speeds[name] = max(-limit, min(limit, speed))
        context.commands.set_speeds(speeds)
        self._last_speed = speeds
        self._previous_target = angles

    def _report_odometry(self, context: SkillContext) -> None:
        if not self._stepping:
            return
        command = self.generator.command
        share = 1.0 / self.params.step.step_cycles
        sx, sy, st = self.params.odometry_scale
        drift_x, drift_y = self.params.odometry_drift
        localizer = getattr(context.world, "localizer", None)
        if localizer is not None:
            localizer.add_odometry(
                command.forward * share * sx + drift_x * CYCLE_SECONDS,
                command.left * share * sy + drift_y * CYCLE_SECONDS,
                math.degrees(command.turn * share * st),
            )


def carry_on_gait(context: SkillContext, skill_name: str, engine: WalkEngine) -> None:
    """On the first cycle of a top-level run, let ``engine`` (of skill ``skill_name``, the
    top-level skill itself or the sub-behaviour it walks with) carry on the steps of the
    previous top-level behaviour (:meth:`WalkEngine.continue_from`) if that skill walks with an
    engine (``gait_engine``) that was mid-step in the cycle just before; on any other cycle,
    and after a start from a stand or a skill that does not walk, nothing. The manager's run
    length says which cycle is the first, so the skills keep no flag of their own.

    Why sub-behaviours too (session 32): the attacker in range of the goal hands over from its
    dribble to ``basic_kick``, whose approach walks as a sub-behaviour; that walk started from
    the stance under a robot mid-stride, and 4 of 21 shots in eight 3 v 3 matches fell within
    two seconds of the hand-over (``python scripts/attack/shot_probe.py --players 3 --matches
    4 --seed S``, S = 1 / 9)."""
    manager = context.manager
    current = getattr(manager, "current", None)
    previous = getattr(manager, "previous", None)
    if current is None or previous is None or current.cycles != 1:
        return
    running = tuple(getattr(manager, "running", ()))
    if not running or running[-1] != skill_name or running[0] != current.name:
        return
    other = getattr(manager.skill(previous.name), "gait_engine", None)
    if other is None or other is engine or not other.is_stepping:
        return
    if other.last_cycle == manager.cycle - 1:
        engine.continue_from(other)


def _inside_another_skill(context: SkillContext) -> bool:
    """Whether the walk runs as another skill's sub-behaviour (``basic_kick`` runs ``walk`` and
    ``walk_velocity``): the manager's stack of running skills holds more than the walk."""
    running = getattr(context.manager, "running", ())
    return len(running) > 1


class WalkSkillBase(Skill):
    """Shared state of the walking skills: one engine, made for the robot type on first use.
    Public so that skills built on the engine elsewhere (``behaviors.learned_walk``) share it."""

    def __init__(self) -> None:
        self._engine: WalkEngine | None = None
        #: where the walk's parameters come from (a benchmark trying other settings points it
        #: at its own copy of ``walk.yaml``; read once per file and robot type)
        self.walk_file: Path = WALK_FILE
        self._file: Path = WALK_FILE
        #: whether the engine was made for a walk run by another skill (``inside_skills``)
        self._inside = False

    def reset(self) -> None:
        if self._engine is not None:
            self._engine.reset()

    @property
    def gait_engine(self) -> WalkEngine | None:
        """The engine this skill walks with (None before its first cycle): a walking skill
        that takes over carries on its steps (:func:`carry_on_gait`)."""
        return self._engine

    def engine(self, context: SkillContext) -> WalkEngine:
        robot_type = context.world.robot.robot_type
        inside = _inside_another_skill(context)
        engine = self._engine
        if (
            engine is None
            or engine.robot_type != robot_type
            or self._file != self.walk_file
            or self._inside != inside
        ):
            params = walk_parameters(robot_type, self.walk_file, inside)
            self._engine = WalkEngine(robot_type, self.engine_parameters(params))
            self._file = self.walk_file
            self._inside = inside
        carry_on_gait(context, self.name, self._engine)
        return self._engine

    def engine_parameters(self, params: WalkParameters) -> WalkParameters:
        """The parameters this skill's engine walks with (the file's, by default)."""
        return params

    @property
    def phase(self) -> tuple[int, bool]:
        """(t, left_active): the cycle inside the current step (0..7) and whether the left
        leg swings; (-1, False) before the first step."""
        if self._engine is None:
            return (-1, False)
        return self._engine.phase


class WalkVelocitySkill(WalkSkillBase):
    """Walk at (vx, vy) m/s and vturn_deg deg/s in the robot frame (x forward, y left); never
    finishes (returns True only while standing still on a zero command)."""

    name = "walk_velocity"

    def validate(self, vx: float, vy: float, vturn_deg: float) -> None:
        if not all(math.isfinite(v) for v in (vx, vy, vturn_deg)):
            raise ValueError("velocities must be finite")

    def step(self, context: SkillContext, vx: float, vy: float, vturn_deg: float) -> bool:
        engine = self.engine(context)
        engine.step(context, vx, vy, vturn_deg)
        return engine.is_stopped and vx == 0.0 and vy == 0.0 and vturn_deg == 0.0


#: Walking to a target: arrive within this distance (m) and heading error (deg) ...
ARRIVE_DISTANCE = 0.04
ARRIVE_HEADING_DEG = 8.0
#: ... and count as left again beyond these (hysteresis)
LEAVE_DISTANCE = 0.08
LEAVE_HEADING_DEG = 20.0
#: Beyond this distance a heading of None means facing the direction of travel.
FACE_TRAVEL_DISTANCE = 0.4


@dataclass(frozen=True)
class GoToGains:
    """How ``walk`` turns the remaining way into a velocity."""

    #: m/s per m of remaining distance, and the cap near the target
    position_gain: float = 1.5
    #: the slowest approach (m/s): much shorter steps barely move the robot (stepping in
    #: place drifts a little), and it treads on the spot short of the target
    min_speed: float = 0.2
    #: deg/s per degree of heading error
    heading_gain: float = 2.0
    max_turn_deg: float = 120.0


@dataclass
class _Settle:
    """One target's settle (``WalkParameters.go_to_settle_frames``): the estimates of the
    fresh frames seen standing, the cycles stood, the walks again so far, and whether the
    settled estimate was accepted (arrival reported)."""

    target: tuple[float, float, float | None]
    frames: list[tuple[float, float, float]] = field(default_factory=list)
    cycles: int = 0
    retries: int = 0
    done: bool = False
    #: the localiser's update count last cycle (None: not standing at the target last cycle)
    updates: int | None = None


class WalkSkill(WalkSkillBase):
    """Walk to (x, y) in the team frame, facing heading_deg at the end (None: the direction of
    travel); finished once within 0.1 m (aiming for 0.04) and standing still (and, with
    ``go_to_settle_frames``, once a few frames seen standing agree)."""

    name = "walk"

    def __init__(self) -> None:
        super().__init__()
        self.gains = GoToGains()
        self._arrived = False
        #: stepping back under a torso pitched back (``go_to_pitch_back_deg``)
        self._catching = False
        self._settle = _Settle((math.nan, math.nan, None))

    def reset(self) -> None:
        super().reset()
        self._arrived = False
        self._catching = False
        self._settle = _Settle((math.nan, math.nan, None))

    def engine_parameters(self, params: WalkParameters) -> WalkParameters:
        """Walking to a target, the heading hold measures against
        ``go_to_heading_hold_reference`` (the go-to's own heading loop keeps the heading),
        without ``go_to_heel_strike`` the feet land flat, and the ``go_to_`` landings apply."""
        step = params.step
        if not params.go_to_heel_strike:
            step = replace(step, speed_heel_strike=0.0)
        elif params.go_to_heel_strike_turn_fade > 0.0:
            step = replace(step, heel_strike_turn_fade=params.go_to_heel_strike_turn_fade)
        return replace(
            params,
            step=step,
            heading_hold_reference=params.go_to_heading_hold_reference,
            landing_roll_lean_gain=params.go_to_landing_roll_lean_gain,
            landing_pitch_lean_share=params.go_to_landing_pitch_lean_share,
        )

    def validate(self, x: float, y: float, heading_deg: float | None = None) -> None:
        values = (x, y) if heading_deg is None else (x, y, heading_deg)
        if not all(math.isfinite(v) for v in values):
            raise ValueError("target coordinates must be finite")

    def step(self, context: SkillContext, x: float, y: float, heading_deg: float | None) -> bool:
        engine = self.engine(context)
        pose = context.world.pose
        if pose is None:  # lost: stand (step out the current step) until localised
            engine.step(context, 0.0, 0.0, 0.0)
            return False
        stopping = self._arrived and not engine.is_stopped
        if stopping and engine.params.go_to_stop_before_leaving:
            engine.step(context, 0.0, 0.0, 0.0)
            return False
        px, py = _looked_ahead(engine, pose.x, pose.y, pose.heading_deg)
        vx, vy, vturn = self._velocity(engine, px, py, pose.heading_deg, x, y, heading_deg)
        vx = self._pitch_guarded(engine, context.world.robot.pitch_deg, vx)
        engine.step(context, vx, vy, vturn)
        standing = self._arrived and engine.is_stopped
        if engine.params.go_to_settle_frames <= 0:
            return standing
        return self._settled(context, engine.params, standing, (x, y, heading_deg))

    def _settled(
        self,
        context: SkillContext,
        params: WalkParameters,
        standing: bool,
        target: tuple[float, float, float | None],
    ) -> bool:
        """Whether arrival may be reported: standing at the target, the mean of
        ``go_to_settle_frames`` fresh estimates is within ``go_to_settle_distance_m`` and the
        arrival's heading tolerance (or the walks again are used up, or no frame came in
        ``go_to_settle_max_cycles``). A mean outside them sends the robot walking again."""
        settle = self._settle
        if settle.target != target:
            settle = self._settle = _Settle(target)
        localizer = getattr(context.world, "localizer", None)
        if not standing or localizer is None:
            settle.frames.clear()
            settle.cycles, settle.updates, settle.done = 0, None, False
            return standing
        if settle.done:
            return True
        fresh = settle.updates is not None and localizer.updates != settle.updates
        settle.updates = localizer.updates
        settle.cycles += 1
        pose = context.world.pose
        if fresh and pose is not None:
            settle.frames.append((pose.x, pose.y, pose.heading_deg))
        if len(settle.frames) < params.go_to_settle_frames:
            if settle.cycles < params.go_to_settle_max_cycles:
                return False
            settle.done = True
            return True
        # the filter's estimate takes a few standing frames to shed the walk's error
        mx, my, error = _mean_offset(settle.frames[len(settle.frames) // 2 :], target)
        x, y, _ = target
        off = math.hypot(x - mx, y - my) > params.go_to_settle_distance_m
        off = off or abs(error) > ARRIVE_HEADING_DEG
        if off and settle.retries < params.go_to_settle_retries:
            settle.retries += 1
            settle.frames.clear()
            settle.cycles, settle.updates = 0, None
            self._arrived = False
            return False
        settle.done = True
        return True

    def _pitch_guarded(self, engine: WalkEngine, pitch_deg: float, vx: float) -> float:
        """``vx`` capped at a backward step while the torso pitches back
        (``go_to_pitch_back_deg``; the engine's landing correction lengthens the backward
        step by the pitch), with hysteresis."""
        p = engine.params
        if pitch_deg < -p.go_to_pitch_back_deg:
            self._catching = True
        elif pitch_deg > -p.go_to_pitch_back_release_deg:
            self._catching = False
        if not self._catching:
            return vx
        return min(vx, -p.go_to_pitch_back_speed)

    def _velocity(
        self,
        engine: WalkEngine,
        px: float,
        py: float,
        ph: float,
        x: float,
        y: float,
        heading: float | None,
    ) -> tuple[float, float, float]:
        dx, dy = x - px, y - py
        distance = math.hypot(dx, dy)
        h = math.radians(ph)
        forward = math.cos(h) * dx + math.sin(h) * dy
        left = -math.sin(h) * dx + math.cos(h) * dy
        travel = math.degrees(math.atan2(dy, dx))
        facing_travel = distance > (FACE_TRAVEL_DISTANCE if heading is None else 1.5)
        goal_heading = travel if facing_travel else (ph if heading is None else heading)
        heading_error = wrap_deg(goal_heading - ph)
        final_error = 0.0 if heading is None else wrap_deg(heading - ph)
        if self._arrived:
            if distance > LEAVE_DISTANCE or abs(final_error) > LEAVE_HEADING_DEG:
                self._arrived = False
        elif distance < ARRIVE_DISTANCE and abs(final_error) < ARRIVE_HEADING_DEG:
            self._arrived = True
        if self._arrived:
            return 0.0, 0.0, 0.0
        g = replace(self.gains, max_turn_deg=engine.params.go_to_max_turn_deg)
        step = engine.params.step
        duration = engine.step_seconds
        step_top = step.max_forward / duration
        max_forward = min(step_top, engine.params.walk_to_max_speed)
        if facing_travel:
            max_forward = _straight_cap(
                engine.params, step_top, max_forward, heading_error, distance
            )
        max_side = step.max_side / duration
        speed = max(min(g.position_gain * distance, max_forward), g.min_speed)
        vx = speed * forward / max(distance, 1e-9)
        vy = speed * left / max(distance, 1e-9)
        backward_cap = engine.params.go_to_max_backward_speed
        if vx < -backward_cap:
            share = backward_cap / -vx
            vx, vy = vx * share, vy * share
        # turning first when the target is off to one side: walking and turning hard at once
        # trips the robot; at 45 degrees or more off it turns on the spot
        slow = math.cos(math.radians(min(2.0 * abs(heading_error), 90.0)))
        if distance > FACE_TRAVEL_DISTANCE:  # far away: face the way first
            vx *= slow
            # facing the way of travel no sidestepping: turning brings the target ahead, and
            # a fast step that also goes sideways and turns trips the robot (type 2 fell at
            # 0.8 m/s forward with 0.25 m/s sideways)
            vy = 0.0 if facing_travel else vy * slow
        if distance < engine.params.go_to_drift_feedforward_m:
            drift_x, drift_y = engine.params.odometry_drift
            vx = min(vx - drift_x, max_forward)
            vy -= drift_y
        vy = max(-max_side, min(max_side, vy))
        vturn = max(-g.max_turn_deg, min(g.max_turn_deg, g.heading_gain * heading_error))
        return vx, vy, vturn


def _mean_offset(
    frames: list[tuple[float, float, float]], target: tuple[float, float, float | None]
) -> tuple[float, float, float]:
    """The mean (x, y) of ``frames`` (estimates x, y, heading) and their mean heading error
    from the target's heading (0 without one)."""
    mx = sum(f[0] for f in frames) / len(frames)
    my = sum(f[1] for f in frames) / len(frames)
    heading = target[2]
    if heading is None:
        return mx, my, 0.0
    error = sum(wrap_deg(heading - f[2]) for f in frames) / len(frames)
    return mx, my, error


def _straight_cap(
    params: WalkParameters,
    step_top: float,
    cap: float,
    heading_error_deg: float,
    distance: float,
) -> float:
    """The forward cap of ``walk`` facing the way of travel: ``cap`` rising to
    ``go_to_fast_speed`` (at most the step's top speed ``step_top``) as the heading error
    falls from ``go_to_fast_heading_deg`` to 0 and the distance left grows from half of
    ``go_to_fast_distance_m`` to all of it; ``cap`` with the fast speed off."""
    fast = min(params.go_to_fast_speed, step_top)
    if fast <= cap:
        return cap
    straight = max(0.0, 1.0 - abs(heading_error_deg) / max(params.go_to_fast_heading_deg, 1e-9))
    half = 0.5 * params.go_to_fast_distance_m
    far = min(1.0, max(0.0, (distance - half) / half)) if half > 0.0 else 1.0
    return cap + (fast - cap) * straight * far


def _looked_ahead(
    engine: WalkEngine, x: float, y: float, heading_deg: float
) -> tuple[float, float]:
    """Where (x, y) the torso will have drifted to once the robot stands, as far as
    ``go_to_drift_lookahead_s`` looks ahead (``odometry_drift`` over that time, added to the
    pose of the moment; standing, no drift is foreseen)."""
    p = engine.params
    seconds = p.go_to_drift_lookahead_s
    if seconds <= 0.0 or not engine.is_stepping:
        return x, y
    forward, left = (d * seconds for d in p.odometry_drift)
    h = math.radians(heading_deg)
    c, s = math.cos(h), math.sin(h)
    return x + c * forward - s * left, y + s * forward + c * left
