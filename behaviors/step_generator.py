"""The step generator: where each sole should be, cycle by cycle, for a commanded step.

A walk is a sequence of steps of ``step_cycles`` server cycles (default 8, 0.16 s). In every
step one leg swings (``left_active`` True while the LEFT leg swings) and the other carries the
robot; the phase is ``(t, left_active)`` with ``t = 0 .. step_cycles - 1`` the cycle inside
the step, and the swinging leg changes with every step.

Each step moves the torso by a :class:`StepCommand` (forward, left, turn). The generator keeps
both soles as 2-D poses (x forward, y left, yaw) in the *walk frame*: the torso's point on the
ground, axes along its heading. The support sole stays put on the ground, so in the walk frame
it slides backwards by the torso's motion, a share of the step every cycle; the swing sole
goes from where it lifted off to its landing pose (its neutral place plus half the step, so
that it lands as far ahead as the support foot will end up behind) along a smooth profile,
raised by ``swing_height * sin(pi s)``. A lateral sway shifts the torso over the support foot
(``sway * sin(pi s)``). Heights are relative to the torso centre and the walk frame is tilted
forward by ``lean`` so that the torso leans into the walk. The output,
:class:`FootTargets`, is sole points and foot yaw in ego axes relative to the torso, ready for
:meth:`behaviors.ik.LegIK.solve_sole`.

Numpy-free and deterministic: the same commands give the same targets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

__all__ = [
    "SWING_PROFILES",
    "FootPose",
    "FootTargets",
    "StepCommand",
    "StepGenerator",
    "StepParameters",
    "swing_progress",
]


#: the swing profiles :func:`swing_progress` knows
SWING_PROFILES = ("cosine", "trapezoid")


@dataclass(frozen=True, slots=True)
class StepParameters:
    """The shape of the gait (metres, radians, cycles)."""

    #: cycles per step (one leg's swing)
    step_cycles: int = 8
    #: sole height below the torso centre while walking (positive number)
    torso_height: float = 0.35
    #: neutral sideways distance of each sole from the torso's centre line
    foot_spread: float = 0.06
    #: neutral forward position of the soles relative to the torso centre
    foot_forward: float = 0.0
    #: highest lift of the swing sole
    swing_height: float = 0.03
    #: sideways torso shift towards the support foot at mid-step
    sway: float = 0.0
    #: forward tilt of the torso over the feet (rad)
    lean: float = 0.0
    #: the largest step (torso motion per step): forward, sideways, turn
    max_forward: float = 0.12
    max_side: float = 0.05
    max_turn: float = 0.4
    #: how far the backward steps may go, as a share of max_forward
    backward_share: float = 0.6
    #: the swing foot's forward profile over the step: "cosine" (raised cosine, peak speed
    #: pi/2 times the mean) or "trapezoid" (constant speed between two ramps of ``swing_ramp``
    #: of the step each, peak 1 / (1 - swing_ramp) times the mean). The swing leg's joints hit
    #: their speed cap first, so a flatter profile allows longer steps. Sideways and turning
    #: keep the cosine: short steps, and a foot turned at full speed tipped robots turning on
    #: the spot.
    swing_profile: str = "cosine"
    swing_ramp: float = 0.25
    #: extra forward lean (rad) and sole shift (m, + = forward) at a full forward step
    #: (``max_forward``), in proportion below it and none walking backwards: at speed the
    #: torso must lean further into the walk than standing allows. Blended over each step.
    speed_lean: float = 0.0
    speed_foot_forward: float = 0.0
    #: heel strike at speed (0, the default, is off): the swing foot pitches toe-up from
    #: ``heel_strike_from`` of the step on and lands up to ``speed_heel_strike`` (rad) toe-up
    #: at a full forward step (in proportion below it), then rolls flat over its first
    #: ``heel_strike_cycles`` cycles of stance, pitched about a point ``heel_pivot`` (m)
    #: behind the sole point. That point lies further back than the heel (0.05 m): in effect
    #: the landing sole point is also planned ``heel_pivot * sin(pitch)`` higher (0.012 m at
    #: 0.12 rad), so the swing knee need not stretch as far by the landing. Why (session 11,
    #: scripts/walk_speed_probe.py): at full speed the swing knee and ankle pitch sit at their
    #: speed cap for 75-87 % of the swing and land 26-39 deg short of the flat-foot plan (knee
    #: bent, toe up), the foot lands a cycle late and 0.03 m short, and the stance foot does
    #: not slip: the missing speed is the landing. Pivot 0.03 / 0.05 / 0.08 / 0.1 / 0.15 m
    #: and toe-ups 0.1-0.3 rad were screened; 0.1 m and the toe rising from 0.6 of the step
    #: walked fastest without falls
    speed_heel_strike: float = 0.0
    heel_strike_from: float = 0.6
    heel_strike_cycles: int = 2
    heel_pivot: float = 0.1
    #: sole shift forward (m) at a full forward step while the heel strike is on (a type
    #: whose soles sit far back: type 4 rolled over sideways within 2 s at full speed)
    heel_strike_foot_forward: float = 0.0
    #: the step's turn (rad) at which the heel strike has faded out (linearly from a straight
    #: step; 0, the default, is no fade). Why (session 12): walking to targets with the heel
    #: strike, feet spun out of turns (session 11: type 3 fell 4 times in 12 sets)
    heel_strike_turn_fade: float = 0.0

    def __post_init__(self) -> None:
        if self.step_cycles < 2:
            raise ValueError(f"step_cycles must be at least 2, got {self.step_cycles}")
        if self.torso_height <= 0.0 or self.foot_spread <= 0.0:
            raise ValueError("torso_height and foot_spread must be positive")
        if self.swing_height < 0.0 or self.sway < 0.0:
            raise ValueError("swing_height and sway must not be negative")
        if self.swing_profile not in SWING_PROFILES:
            raise ValueError(f"swing_profile must be one of {SWING_PROFILES}")
        if not 0.0 < self.swing_ramp <= 0.5:
            raise ValueError(f"swing_ramp must be in (0, 0.5], got {self.swing_ramp}")
        if not 1 <= self.heel_strike_cycles < self.step_cycles:
            raise ValueError(
                f"heel_strike_cycles must be in [1, step_cycles), got {self.heel_strike_cycles}"
            )
        if not 0.0 <= self.heel_strike_from < 1.0:
            raise ValueError(f"heel_strike_from must be in [0, 1), got {self.heel_strike_from}")
        if self.speed_heel_strike < 0.0 or self.heel_pivot < 0.0 or self.heel_strike_turn_fade < 0:
            raise ValueError(
                "speed_heel_strike, heel_pivot and heel_strike_turn_fade must not be negative"
            )


@dataclass(frozen=True, slots=True)
class StepCommand:
    """The torso's motion over one step: forward and left (m), turn (rad, counter-clockwise)."""

    forward: float = 0.0
    left: float = 0.0
    turn: float = 0.0

    def clipped(self, params: StepParameters) -> StepCommand:
        """The command within the step limits (an ellipse-like box: each axis on its own)."""
        low = -params.max_forward * params.backward_share
        return StepCommand(
            min(max(self.forward, low), params.max_forward),
            min(max(self.left, -params.max_side), params.max_side),
            min(max(self.turn, -params.max_turn), params.max_turn),
        )

    @property
    def is_zero(self) -> bool:
        return self.forward == 0.0 and self.left == 0.0 and self.turn == 0.0


@dataclass(frozen=True, slots=True)
class FootPose:
    """A sole on (or above) the ground, in the walk frame: x forward, y left, yaw (rad)."""

    x: float
    y: float
    yaw: float = 0.0

    def moved_back(self, forward: float, left: float, turn: float) -> FootPose:
        """The same ground point seen after the walk frame moved by (forward, left, turn)."""
        dx, dy = self.x - forward, self.y - left
        c, s = math.cos(turn), math.sin(turn)
        return FootPose(c * dx + s * dy, -s * dx + c * dy, self.yaw - turn)


@dataclass(frozen=True, slots=True)
class FootTargets:
    """One cycle's goal for both soles: ego axes (x forward, y left, z up) relative to the
    torso centre, and each foot's yaw (rad) relative to the torso."""

    left: tuple[float, float, float]
    right: tuple[float, float, float]
    left_yaw: float
    right_yaw: float
    #: the phase these targets belong to
    t: int
    left_active: bool
    #: the torso's forward lean over the soles (rad): the soles are pitched by ``-lean``
    lean: float = 0.0
    #: each sole's own toe-up pitch (rad) on top (``speed_heel_strike``)
    left_pitch: float = 0.0
    right_pitch: float = 0.0


def _smooth(s: float) -> float:
    """0 -> 1 with zero slope at both ends: the swing foot leaves and lands gently."""
    return 0.5 - 0.5 * math.cos(math.pi * s)


def _trapezoid(s: float, ramp: float) -> float:
    """0 -> 1 at constant speed between two ramps of length ``ramp`` (constant acceleration):
    the lowest peak speed for a profile that still starts and ends at rest."""
    peak = 1.0 / (1.0 - ramp)
    if s < ramp:
        return 0.5 * peak * s * s / ramp
    if s > 1.0 - ramp:
        return 1.0 - _trapezoid(1.0 - s, ramp)
    return peak * (s - 0.5 * ramp)


def swing_progress(s: float, params: StepParameters) -> float:
    """How far (0 -> 1) the swing foot has gone at step share ``s`` (0 -> 1)."""
    s = min(max(s, 0.0), 1.0)
    if params.swing_profile == "trapezoid":
        return _trapezoid(s, params.swing_ramp)
    return _smooth(s)


class StepGenerator:
    """Foot targets per cycle for a stream of step commands (see the module docstring).

    Call :meth:`next_targets` once per cycle with the command for the current step; the
    command is taken when a step starts (``t == 0``) and held for the whole step.
    """

    def __init__(self, params: StepParameters | None = None) -> None:
        self.params = params or StepParameters()
        self.reset()

    def reset(self, left_first: bool = True) -> None:
        """Feet side by side at their neutral places; the next step swings the left leg if
        ``left_first``."""
        p = self.params
        self._left = FootPose(0.0, p.foot_spread)
        self._right = FootPose(0.0, -p.foot_spread)
        self._t = -1  # the first next_targets call starts a step
        self._left_active = not left_first
        self._command = StepCommand()
        self._lift_off = self._left
        self._landing = self._left
        # share of a full forward step (0..1) at the start and the end of the step under way,
        # and where in between this cycle is: speed_lean and speed_foot_forward scale with it
        self._speed_share = (0.0, 0.0)
        self._speed_now = 0.0
        # share of the heel strike the step under way keeps (heel_strike_turn_fade)
        self._heel_share = 1.0
        # heel strike (speed_heel_strike): toe-up pitch of each foot now, and the support
        # foot's when it landed
        self._support_pitch = 0.0
        self._swing_pitch = 0.0
        self._landed_pitch = 0.0

    # ------------------------------------------------------------------ the phase
    @property
    def phase(self) -> tuple[int, bool]:
        """(t, left_active) of the targets returned last (t = -1 before the first)."""
        return self._t, self._left_active

    @property
    def command(self) -> StepCommand:
        """The command of the step under way."""
        return self._command

    @property
    def speed_share(self) -> float:
        """How much of a full forward step (0..1) the gait is at this cycle (blended over the
        step from its start to its end): what ``speed_lean`` scales with."""
        return self._speed_now

    @property
    def feet(self) -> tuple[FootPose, FootPose]:
        """Where the left and right soles are (walk frame, as planned)."""
        return self._left, self._right

    @property
    def at_step_end(self) -> bool:
        """Whether the last targets ended a step (the next call starts a new one)."""
        return self._t == self.params.step_cycles - 1

    def with_params(self, params: StepParameters) -> None:
        """Change the gait's shape; takes effect at once (use between steps)."""
        self.params = params

    # ------------------------------------------------------------------ stepping
    def next_targets(self, command: StepCommand) -> FootTargets:
        """Advance one cycle and return the soles' targets for it."""
        p = self.params
        if self._t < 0 or self._t >= p.step_cycles - 1:
            self._start_step(command)
        else:
            self._t += 1
        n = p.step_cycles
        c = self._command
        # the support foot moves back by 1/n of the step every cycle
        share = 1.0 / n
        support = self._support.moved_back(c.forward * share, c.left * share, c.turn * share)
        # the swing foot's lift-off pose moves with the walk frame too, its landing is planned
        # in the frame at the end of the step
        s = (self._t + 1) / n
        self._lift_off = self._lift_off.moved_back(
            c.forward * share, c.left * share, c.turn * share
        )
        remaining = 1.0 - s
        landing = self._landing_planned.moved_back(
            -c.forward * remaining, -c.left * remaining, -c.turn * remaining
        )
        k = swing_progress(s, p)
        k_side = _smooth(s)  # sideways and turning keep the cosine (see swing_profile)
        swing = FootPose(
            self._lift_off.x + (landing.x - self._lift_off.x) * k,
            self._lift_off.y + (landing.y - self._lift_off.y) * k_side,
            self._lift_off.yaw + (landing.yaw - self._lift_off.yaw) * k_side,
        )
        if self._left_active:
            self._left, self._right = swing, support
        else:
            self._left, self._right = support, swing
        start, end = self._speed_share
        self._speed_now = start + (end - start) * s
        lift = p.swing_height * math.sin(math.pi * s)
        if p.speed_heel_strike > 0.0 or self._landed_pitch != 0.0 or self._swing_pitch != 0.0:
            self._update_heel_strike(s)
        # sway: the torso moves towards the support side, i.e. the soles move away from it
        sway = p.sway * math.sin(math.pi * s) * (1.0 if self._left_active else -1.0)
        return self._targets(lift, sway)

    def _update_heel_strike(self, s: float) -> None:
        """The swing foot's toe rising towards its landing and the support foot rolling flat
        (speed_heel_strike)."""
        p = self.params
        rise = min(1.0, max(0.0, (s - p.heel_strike_from) / (1.0 - p.heel_strike_from)))
        toe_up = p.speed_heel_strike * self._speed_share[1] * self._heel_share
        self._swing_pitch = toe_up * _smooth(rise)
        left = max(0.0, 1.0 - (self._t + 1) / p.heel_strike_cycles)
        self._support_pitch = self._landed_pitch * left

    def _start_step(self, command: StepCommand) -> None:
        p = self.params
        self._t = 0
        self._left_active = not self._left_active
        side = 1.0 if self._left_active else -1.0
        self._command = self._turn_allowed(command.clipped(p), side)
        c = self._command
        full = max(0.0, c.forward) / p.max_forward if p.max_forward > 0.0 else 0.0
        self._heel_share = _turn_faded(p, c.turn)
        self._speed_share = (self._speed_now, min(1.0, full))
        swing = self._left if self._left_active else self._right
        self._lift_off = swing
        self._landed_pitch = self._swing_pitch  # the old swing foot supports now
        self._swing_pitch = 0.0
        # landing pose in the walk frame at the END of this step. Forward: half the step ahead
        # (the support foot ends half a step behind). Sideways and turning, the feet must not
        # close in on each other (the soles are 0.08 m wide, 0.03 m apart at the neutral
        # stance): the leg on the side of the motion opens by the whole step, the other one
        # closes back to its neutral place, but never nearer the support foot than the neutral
        # stance (the first step from standing may be the other leg's)
        left = c.left if c.left * side > 0.0 else 0.0
        yaw = c.turn if c.turn * side > 0.0 else 0.0
        cy, sy = math.cos(yaw), math.sin(yaw)
        neutral = side * p.foot_spread
        y = cy * neutral + left
        support_end = self._support.y - c.left
        y = (
            max(y, support_end + 2.0 * p.foot_spread)
            if side > 0
            else min(y, support_end - 2.0 * p.foot_spread)
        )
        self._landing_planned = FootPose(-sy * neutral + c.forward * 0.5, y, yaw)

    def _turn_allowed(self, command: StepCommand, side: float) -> StepCommand:
        """The command with no more turn than the support foot allows: the torso turning over
        it turns the foot inwards relative to the torso, and the hip yaw-pitch joint only turns
        a foot outwards, so the support foot can only give back the yaw it opened by."""
        support_yaw = self._support.yaw  # >= 0 for the left foot, <= 0 for the right one
        if side > 0:  # left swings, right supports: turning right needs an opened right foot
            return replace(command, turn=max(command.turn, min(0.0, support_yaw)))
        return replace(command, turn=min(command.turn, max(0.0, support_yaw)))

    @property
    def _support(self) -> FootPose:
        return self._right if self._left_active else self._left

    def _targets(
        self,
        lift: float,
        sway: float,
        speed_share: float | None = None,
        pitched: bool = True,
    ) -> FootTargets:
        p = self.params
        share = self._speed_now if speed_share is None else speed_share
        lean = p.lean + p.speed_lean * share
        forward = p.foot_forward + p.speed_foot_forward * share
        if p.speed_heel_strike > 0.0:
            forward += p.heel_strike_foot_forward * share
        left_z = -p.torso_height + (lift if self._left_active else 0.0)
        right_z = -p.torso_height + (0.0 if self._left_active else lift)
        swing_pitch, support_pitch = (
            (self._swing_pitch, self._support_pitch) if pitched else (0.0, 0.0)
        )
        left_pitch, right_pitch = (
            (swing_pitch, support_pitch) if self._left_active else (support_pitch, swing_pitch)
        )
        lx, lz = _heel_pivoted(p, left_pitch)
        rx, rz = _heel_pivoted(p, right_pitch)
        left = _tilted(self._left.x + forward + lx, self._left.y + sway, left_z + lz, lean)
        right = _tilted(self._right.x + forward + rx, self._right.y + sway, right_z + rz, lean)
        return FootTargets(
            left,
            right,
            self._left.yaw,
            self._right.yaw,
            self._t,
            self._left_active,
            lean,
            left_pitch,
            right_pitch,
        )

    def stand_targets(self) -> FootTargets:
        """The neutral stance (both soles at their neutral places, no lift, no sway)."""
        saved = (self._left, self._right)
        p = self.params
        self._left = FootPose(0.0, p.foot_spread)
        self._right = FootPose(0.0, -p.foot_spread)
        targets = self._targets(0.0, 0.0, speed_share=0.0, pitched=False)
        self._left, self._right = saved
        return replace(targets, t=self._t, left_active=self._left_active)


def _turn_faded(params: StepParameters, turn: float) -> float:
    """The share (0..1) of the heel strike a step turning by ``turn`` (rad) keeps."""
    if params.heel_strike_turn_fade <= 0.0:
        return 1.0
    return max(0.0, 1.0 - abs(turn) / params.heel_strike_turn_fade)


def _heel_pivoted(params: StepParameters, pitch: float) -> tuple[float, float]:
    """(forward, up) shift of the sole point of a foot pitched toe-up by ``pitch`` about a
    point ``heel_pivot`` behind it (the heel stays put)."""
    if pitch == 0.0:
        return 0.0, 0.0
    d = params.heel_pivot
    return -d * (1.0 - math.cos(pitch)), d * math.sin(pitch)


def _tilted(x: float, y: float, z: float, lean: float) -> tuple[float, float, float]:
    """A point of the walk frame seen from a torso leaning forward by ``lean``."""
    c, s = math.cos(lean), math.sin(lean)
    return (c * x - s * z, y, s * x + c * z)
