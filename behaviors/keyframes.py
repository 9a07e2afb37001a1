"""Keyframe motions: sequences of joint targets played back with per-cycle interpolation.

A sequence is a list of frames in YAML::

    my_motion:
      description: what it is for
      frames:
        - {duration: 0.3, interpolation: smooth, hold: 0.1, pose: stand, joints: {rlj3: 40}}

Each frame moves the targets from where the previous frame ended (the measured joint angles for
the first frame) to its own targets over ``duration`` seconds, then keeps them for ``hold``
seconds. ``pose`` starts the frame's targets from a named pose of ``poses.yaml`` and ``joints``
overrides or adds joints; joints a frame does not name keep their previous target. Interpolation
is ``linear``, ``smooth`` (cosine ease-in/out: no jerk at the frame boundaries, which matters for
motions that lift the whole body) or ``step`` (jump at once and let the joint controller chase).
``gain`` overrides the joint controller's proportional gain for the frame (see
``behaviors.joint_control``).

``track: predictive`` follows the frame's targets the way FCP's slot engine does instead: an
action answering perception ``k`` first shows in perception ``k + 2``, so the angle measured now
does not yet contain the motion of the command sent last cycle. The speed sent is the rest of the
way in one cycle, ``(target - measured - still_to_move) / cycle``, clipped to the joint's maximum
speed, where ``still_to_move`` is that last command's motion. Measured in the simulator on a
free arm following a 225 deg/s ramp: with the last command subtracted the joint follows the
targets exactly two cycles behind (the transport delay) with no overshoot; subtracting the last
two commands (or three) oscillates +-7 deg around the target. This removes the four-cycle lag
of the gain-0.25 controller, which fast whole-body motions such as getting up cannot afford, at
the price of following loaded joints less gently.

The targets are computed every 0.02 s cycle and handed to ``JointCommands.set_targets``; the
player counts cycles rather than reading a clock, so a motion is reproducible step for step.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from functools import cache
from pathlib import Path
from typing import Any

from behaviors.joint_control import CYCLE_SECONDS, DEFAULT_GAIN, JointCommands
from behaviors.poses import (
    DATA_DIR,
    PoseError,
    check_fields,
    check_number,
    default_poses,
    read_yaml_mapping,
    validate_joint_targets,
)
from behaviors.skill import Skill, SkillContext
from world.nao_model import robot_spec

#: The packaged keyframe files, read in this order (a name may appear in only one of them).
KEYFRAME_FILES = (DATA_DIR / "keyframes.yaml", DATA_DIR / "get_up.yaml")
INTERPOLATIONS = ("linear", "smooth", "step")
_FRAME_FIELDS = {"duration"}
_FRAME_OPTIONAL = {"interpolation", "hold", "pose", "joints", "gain", "track"}
TRACKING_MODES = ("gain", "predictive")
#: Commands sent but not yet visible in the measured angles (see the module docstring).
PREDICTED_COMMANDS = 1


@dataclass(frozen=True)
class Keyframe:
    """Targets (degrees by perceptor name) reached after ``duration`` s, then held ``hold`` s."""

    joints: Mapping[str, float]
    duration: float
    interpolation: str = "smooth"
    hold: float = 0.0
    gain: float = DEFAULT_GAIN
    #: "gain" (proportional, ``JointCommands.set_targets``) or "predictive" (raw speeds)
    track: str = "gain"

    @property
    def total(self) -> float:
        return self.duration + self.hold


@dataclass(frozen=True)
class KeyframeSequence:
    name: str
    frames: tuple[Keyframe, ...]
    description: str = ""

    @property
    def predictive(self) -> bool:
        """True if a frame tracks predictively (playing it needs the robot type)."""
        return any(frame.track == "predictive" for frame in self.frames)

    @property
    def duration(self) -> float:
        """Seconds from the first cycle to the end of the last hold."""
        return sum(frame.total for frame in self.frames)


# ------------------------------------------------------------------------------- loading
def _parse_frame(data: Any, where: str, poses: Mapping[str, Any]) -> Keyframe:
    check_fields(data, where, _FRAME_FIELDS, _FRAME_OPTIONAL)
    if "pose" not in data and "joints" not in data:
        raise PoseError(f"{where}: a frame needs 'pose' or 'joints' (or both)")
    joints: dict[str, float] = {}
    if "pose" in data:
        pose = data["pose"]
        if pose not in poses:
            raise PoseError(f"{where}.pose: unknown pose {pose!r}; poses: {', '.join(poses)}")
        joints.update(poses[pose].joints)
    if "joints" in data:
        joints.update(validate_joint_targets(data["joints"], f"{where}.joints"))
    duration = check_number(data["duration"], f"{where}.duration")
    hold = check_number(data.get("hold", 0.0), f"{where}.hold")
    gain = check_number(data.get("gain", DEFAULT_GAIN), f"{where}.gain")
    if duration < 0 or hold < 0:
        raise PoseError(f"{where}: duration and hold must be >= 0 s, got {duration}, {hold}")
    if not 0 < gain <= 1:
        raise PoseError(f"{where}.gain: must be in (0, 1], got {gain}")
    interpolation = data.get("interpolation", "smooth")
    if interpolation not in INTERPOLATIONS:
        raise PoseError(
            f"{where}.interpolation: {interpolation!r} is not one of {', '.join(INTERPOLATIONS)}"
        )
    track = data.get("track", "gain")
    if track not in TRACKING_MODES:
        raise PoseError(f"{where}.track: {track!r} is not one of {', '.join(TRACKING_MODES)}")
    return Keyframe(joints, duration, interpolation, hold, gain, track)


def parse_sequences(
    data: Mapping[str, Any], source: str, poses: Mapping[str, Any] | None = None
) -> dict[str, KeyframeSequence]:
    """Build sequences from the mapping read out of ``source`` (a file name, for messages)."""
    poses = default_poses() if poses is None else poses
    sequences = {}
    for name, entry in data.items():
        where = f"{source}: sequence {name!r}"
        check_fields(entry, where, {"frames"}, {"description"})
        frames = entry["frames"]
        if not isinstance(frames, list) or not frames:
            raise PoseError(f"{where}.frames: expected a non-empty list of frames")
        parsed = tuple(
            _parse_frame(frame, f"{where}.frames[{i}]", poses) for i, frame in enumerate(frames)
        )
        sequences[str(name)] = KeyframeSequence(
            str(name), parsed, str(entry.get("description", ""))
        )
    return sequences


def load_sequences(*paths: str | Path) -> dict[str, KeyframeSequence]:
    """Read and validate keyframe files; a sequence name defined twice is an error."""
    sequences: dict[str, KeyframeSequence] = {}
    for path in map(Path, paths):
        for name, sequence in parse_sequences(read_yaml_mapping(path), str(path)).items():
            if name in sequences:
                raise PoseError(f"{path}: sequence {name!r} is already defined in another file")
            sequences[name] = sequence
    return sequences


@cache
def default_sequences() -> dict[str, KeyframeSequence]:
    """The packaged sequences, read once per process (they are immutable)."""
    return load_sequences(*KEYFRAME_FILES)


def get_sequence(name: str, mirror: bool = False) -> KeyframeSequence:
    """A packaged sequence; ``mirror=True`` swaps left and right (see :func:`mirrored`)."""
    sequences = default_sequences()
    try:
        sequence = sequences[name]
    except KeyError:
        raise KeyError(
            f"unknown keyframe sequence {name!r}; known: {', '.join(sequences)}"
        ) from None
    return mirrored(sequence) if mirror else sequence


def mirrored(sequence: KeyframeSequence) -> KeyframeSequence:
    """The same motion with left and right swapped (``behaviors.mirror.mirror_keyframes``)."""
    from behaviors.mirror import mirror_keyframes  # imported on use: mirror pulls in numpy tables

    swapped = mirror_keyframes((frame.joints, frame.duration) for frame in sequence.frames)
    frames = tuple(
        replace(frame, joints=joints)
        for frame, (joints, _) in zip(sequence.frames, swapped, strict=True)
    )
    return replace(sequence, name=f"{sequence.name} (mirrored)", frames=frames)


# ------------------------------------------------------------------------------- playback
def ease(interpolation: str, fraction: float) -> float:
    """How far (0..1) along a frame the targets are at ``fraction`` of its duration."""
    fraction = min(max(fraction, 0.0), 1.0)
    if interpolation == "step":
        return 1.0
    if interpolation == "smooth":
        return 0.5 - 0.5 * math.cos(math.pi * fraction)
    return fraction


class PredictiveTracker:
    """Joint speeds that reach a target in one cycle despite the server's two-cycle delay.

    Remembers the speeds it sent (rad/s, after clipping) for the last ``PREDICTED_COMMANDS``
    cycles: the joint will still move by those, so they are subtracted from the measured error.
    Joints it did not command in a cycle count as sent 0 (the manager's default).
    """

    def __init__(self, robot_type: int, predicted_commands: int = PREDICTED_COMMANDS) -> None:
        spec = robot_spec(robot_type)
        self._max_speed = {j.perceptor: j.max_speed for j in spec.joints}
        self._limits = {j.perceptor: (j.min_deg, j.max_deg) for j in spec.joints}
        self._history: list[dict[str, float]] = [{} for _ in range(predicted_commands)]

    def still_to_move_deg(self, name: str) -> float:
        """Degrees the joint will still turn from the commands already sent."""
        return math.degrees(sum(sent.get(name, 0.0) for sent in self._history) * CYCLE_SECONDS)

    def speeds(
        self, targets_deg: Mapping[str, float], joints_deg: Mapping[str, float]
    ) -> dict[str, float]:
        """Speeds (rad/s) for this cycle; call once per cycle, it records what it returns."""
        out = {}
        for name, target in targets_deg.items():
            if name not in self._max_speed:
                continue
            low, high = self._limits[name]
            target = min(max(target, low), high)
            error = target - joints_deg.get(name, 0.0) - self.still_to_move_deg(name)
            limit = self._max_speed[name]
            out[name] = max(-limit, min(limit, math.radians(error) / CYCLE_SECONDS))
        self.record(out)
        return out

    def record(self, speeds: Mapping[str, float]) -> None:
        """Remember this cycle's speeds (rad/s) as sent, dropping the oldest cycle."""
        self._history = [*self._history[1:], dict(speeds)]

    def record_gain(
        self, targets_deg: Mapping[str, float], joints_deg: Mapping[str, float], gain: float
    ) -> None:
        """Remember the speeds ``JointCommands`` sends for targets at ``gain`` (a gain frame
        played before a predictive one)."""
        sent = {}
        for name, target in targets_deg.items():
            if name in self._max_speed:
                limit = self._max_speed[name]
                speed = gain * math.radians(target - joints_deg.get(name, 0.0)) / CYCLE_SECONDS
                sent[name] = max(-limit, min(limit, speed))
        self.record(sent)


class KeyframePlayer:
    """Plays one sequence: call :meth:`step` once per cycle until it returns True.

    Cycle ``k`` (counting from 0) sends the targets of time ``(k + 1) * 0.02`` s, so the first
    cycle already moves and the last one sends exactly the final frame's targets.

    Frames with ``track: predictive`` need ``robot_type`` (for the joints' speed limits).
    """

    def __init__(self, sequence: KeyframeSequence, robot_type: int | None = None) -> None:
        self.sequence = sequence
        if sequence.predictive and robot_type is None:
            raise ValueError(f"{sequence.name}: predictive frames need the robot type")
        self._tracker = PredictiveTracker(robot_type) if robot_type is not None else None
        self._cycle = 0
        self._frame_starts: list[dict[str, float]] | None = None
        self._frame_ends = list(_cumulative(f.total for f in sequence.frames))
        self._total_cycles = max(1, round(sequence.duration / CYCLE_SECONDS))
        named: set[str] = set()
        self._named_before: list[frozenset[str]] = []
        for frame in sequence.frames:
            self._named_before.append(frozenset(named))
            named.update(frame.joints)

    @property
    def finished(self) -> bool:
        return self._cycle >= self._total_cycles

    @property
    def elapsed(self) -> float:
        return self._cycle * CYCLE_SECONDS

    def _start_targets(self, joints_deg: Mapping[str, float]) -> list[dict[str, float]]:
        """Where each frame starts from: the measured angles, updated by every earlier frame."""
        starts = []
        current = dict(joints_deg)
        for frame in self.sequence.frames:
            starts.append(dict(current))
            current.update(frame.joints)
        return starts

    def _frame_index(self, seconds: float) -> int:
        """Index of the frame whose targets the player sends ``seconds`` into the sequence."""
        return next(
            (i for i, end in enumerate(self._frame_ends) if seconds <= end + 1e-9),
            len(self._frame_ends) - 1,
        )

    def frame_at(self, seconds: float) -> Keyframe:
        """The frame whose targets the player sends ``seconds`` into the sequence (after
        :meth:`step`, ``frame_at(elapsed)`` is the frame that cycle played)."""
        return self.sequence.frames[self._frame_index(seconds)]

    def targets(self, joints_deg: Mapping[str, float]) -> tuple[dict[str, float], Keyframe]:
        """The targets for the current cycle and the frame they belong to."""
        if self._frame_starts is None:
            self._frame_starts = self._start_targets(joints_deg)
        time = min(self._cycle + 1, self._total_cycles) * CYCLE_SECONDS
        index = self._frame_index(time)
        frame = self.sequence.frames[index]
        frame_start_time = self._frame_ends[index] - frame.total
        duration = frame.duration
        fraction = (time - frame_start_time) / duration if duration > 0 else 1.0
        weight = ease(frame.interpolation, fraction)
        start = self._frame_starts[index]
        # joints named by earlier frames keep their last target; unnamed ones are left alone
        targets = {name: start[name] for name in self._named_before[index]}
        targets.update(
            (name, start.get(name, target) + (target - start.get(name, target)) * weight)
            for name, target in frame.joints.items()
        )
        return targets, frame

    def step(self, commands: JointCommands, joints_deg: Mapping[str, float]) -> bool:
        """Write this cycle's targets into ``commands``; True on the cycle the sequence ends
        (and on any call after it, which keeps sending the final targets)."""
        targets, frame = self.targets(joints_deg)
        known = frozenset(commands.joint_names)
        targets = {n: v for n, v in targets.items() if n in known}
        if frame.track == "predictive":
            assert self._tracker is not None
            commands.set_speeds(self._tracker.speeds(targets, joints_deg))
        else:
            commands.set_targets(targets, frame.gain)
            if self._tracker is not None:
                self._tracker.record_gain(targets, joints_deg, frame.gain)
        self._cycle += 1
        return self.finished


def _cumulative(values: Iterable[float]) -> Iterable[float]:
    total = 0.0
    for value in values:
        total += value
        yield total


class KeyframeSkill(Skill):
    """``execute("keyframe", name, mirror=False)``: play a packaged sequence once.

    Finished when the last frame's hold is over. Asking for another sequence (or the other
    side) while one is playing starts the new one from the current joint angles.
    """

    name = "keyframe"

    def __init__(self) -> None:
        self._player: KeyframePlayer | None = None
        self._playing: tuple[str, bool] | None = None

    def reset(self) -> None:
        self._player = None
        self._playing = None

    def step(self, context: SkillContext, sequence: str, mirror: bool = False) -> bool:
        if self._player is None or self._playing != (sequence, mirror):
            chosen = get_sequence(sequence, mirror)
            # only predictive frames need to know the robot (its joints' speed limits)
            robot_type = context.world.robot.robot_type if chosen.predictive else None
            self._player = KeyframePlayer(chosen, robot_type)
            self._playing = (sequence, mirror)
        return self._player.step(context.commands, context.world.robot.joints_deg)
