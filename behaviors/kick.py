"""The kick from a stand: weight onto the support leg, kicking leg back, swing, back to stand.

``execute("kick", foot, strength)`` plays the motion of ``behaviors/data/kicks.yaml`` for the
``"left"`` foot, or its mirror image for the ``"right"`` foot (``behaviors.keyframes.mirrored``:
one motion, so the two sides can never drift apart). The skill expects the robot standing with
the ball just in front of the kicking foot; walking there and aligning is the caller's job.

Why the swing is scaled by speed rather than by range: the ball leaves the foot at roughly
``(1 + e)`` times the foot's speed (the foot is far heavier than the ball), so the swing's joint
speed is what decides the distance, while the swing's range decides where the foot meets the
ball, which must not change with strength. The swing frames therefore keep their targets and
only stretch their duration: at strength 1 they last ``fast_s`` (the joints' speed limits then
cap the motion, so this is the strongest kick), at strength 0 ``slow_s``; in between the foot
*speed* (1 / duration) is interpolated linearly, which keeps the distance close to linear in
strength. The swing frames track predictively (``track: predictive``): the gain controller's
four-cycle lag would cut off a fast swing before the foot reaches the ball.

Each kick also says where it wants the ball (``ball_gap_m`` ahead of the toe, ``ball_side_m``
outwards), which ``basic_kick`` aligns to, and may carry a calibration table ``distances``
(strength -> metres, measured by ``benchmarks/kick.py``) from which :meth:`KickMotion.strength_for`
picks the strength for a distance. A kick may instead be calibrated by its ball gap
(``gap_distances``, metres -> gap): it then always swings at full strength and ``basic_kick``
lines the ball up further ahead of the toe for a shorter kick (session 12's candidate against
the slow swings' falls; see the end of ``kicks.yaml``). The packaged kicks are calibrated by
strength since session 29: the gap table sent kicks asked 3.5 m anywhere in 2.3-5.4 m, because
the alignment leaves the ball within about a centimetre and a centimetre of gap was a metre.

Sequences are looked up per robot type first (``kick_left_type3``), then by the common name, as
the get-up does.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import cache
from pathlib import Path
from typing import Any

from behaviors.joint_control import JointCommands
from behaviors.keyframes import KeyframePlayer, KeyframeSequence, mirrored, parse_sequences
from behaviors.kick_recovery import CatchParams, LandingCatch, parse_catch
from behaviors.poses import DATA_DIR, PoseError, check_fields, check_number, read_yaml_mapping
from behaviors.skill import Skill, SkillContext
from world.perception import ForceResistance

KICKS_FILE = DATA_DIR / "kicks.yaml"
#: The name of the packaged left-foot kick; the right foot plays its mirror image.
KICK_LEFT = "kick_left"
#: The name of an optional motion for the right foot, written for the left foot like
#: :data:`KICK_LEFT` and played mirrored (see :func:`kick_motion`).
KICK_RIGHT = "kick_right"
#: Suffix of a motion that ``basic_kick`` plays after its approach and alignment shuffle
#: (``kick_right_aligned``) in place of the plain one (see :func:`kick_motion`).
ALIGNED_SUFFIX = "_aligned"
#: Suffix of a motion that ``basic_kick`` plays after its alignment when asked for more than
#: the aligned motion's table reaches, or for "long" (``kick_right_aligned_long``; see
#: :func:`kick_motion`).
LONG_SUFFIX = "_long"
FEET = ("left", "right")
#: Balance on one leg: degrees of support-ankle roll per degree of torso roll away from the
#: roll measured when the weight has just moved onto the support leg. Why: standing on one foot
#: is marginal, and an open-loop motion drifts over the foot's edge within a second (measured:
#: the same mirrored motion fell on one side and not on the other). 3 and 16 deg rather than 2
#: and 10: after a walk and a shuffle the torso rolled up to 15 deg over the support foot on
#: the way back to the stand, and basic kicks fell 3 of 8 (then 1 of 8; 2 of 16 over 16 layouts).
BALANCE_GAIN = 3.0
#: The support ankle's roll correction is limited to this many degrees either way. 28 (16
#: until session 35): type 3's weak long kicks (asked 4-5 m) fell after contact as the torso
#: rolled over the kicking foot on its way down, with the correction at 16 deg. Basic kicks
#: (``scripts/kick/approach_variants.py --set kick.BALANCE_LIMIT_DEG=L -- --robot-type T
#: --strengths --basic-trials 20 --basic-distance D --layout-seed S``, ``runs/kick_abort/``
#: ``s35_limit/``, ``s35_t3_land/``): type 3 asked 4 m, seeds 2-5, falls of 80 at 16 / 22 /
#: 28 / 36 deg: 7 / 4 / 2 / 2; asked 5 m, seeds 2-9, 4 -> 1 of 160. Types 0, 1, 2, 4 asked
#: 5 m (seeds 2-5), every type asked 3 m (seeds 2-3) and type 3 asked long (seeds 2-5): the
#: same trials, the same falls.
BALANCE_LIMIT_DEG = 28.0
#: Degrees of support-ankle roll per deg/s of torso roll rate (gyro), added to the roll term:
#: damping, so the correction acts while the lean is still growing rather than after.
BALANCE_DAMPING = 0.0
#: Degrees of support-ankle roll per centimetre the support foot's centre of pressure (FRP
#: perceptor) lies outwards of the foot's centre line, subtracted from the roll terms. Why: the
#: ankle can only push while the pressure stays inside the foot; in falling kicks the roll term
#: drove the pressure to the foot's edge (1 cm steps, the edge at 4 cm) and the foot then tipped
#: over that edge, rolling the robot sideways. Moving the ankle against the pressure's offset
#: keeps it inside the sole. Off: 2 made basic kicks far worse (``benchmarks/kick.py --strengths
#: --basic-trials 20 --basic-distance 3 --cop-gain 2``: 18 falls of 20; ``--layout-seed 1``: 12),
#: and the other sign is no better (``--cop-gain -1``: 8 falls of 20 on both layout seeds, was
#: 2 and 4), so this proportional term on the FRP point does not help either way (sixth round).
#: A skill's own ``cop_gain`` overrides it.
COP_GAIN = 0.0
#: Share of the roll correction that also goes to the support hip's roll (1: the same degrees
#: on the ankle and the hip, as since the first round). Why both: in falling basic kicks the
#: support foot stood on its inner edge (FRP 4 cm off its centre line) from the wind-up on, so
#: the ankle alone only tips the foot further; the hip moves the torso. Measured in session 10
#: (scripts/kick/sweep.py --layout-seeds 0 1 2 --set kick.BALANCE_HIP_SHARE=S): falls in 60
#: basic kicks 48 at 0 (the ankle alone), 18 at 1, 20 at 1.5 (and shorter kicks).
BALANCE_HIP_SHARE = 1.0
#: Seconds over which the one-leg balance's last correction fades out once the kick's last
#: frame (the return to the stand) starts; 0: it stops at once, as it did up to session 34.
#: Why a fade: in type 3's falls after its long kick (asked 5 m) the torso rolled 20-23 deg
#: towards the kicking foot as it landed wide, the correction sat at its limit (then 16), and its
#: sudden end at the last frame threw the torso over the support foot (roll -23 -> +40 deg in
#: 0.9 s; session 35, a per-cycle trace of layout seed 6, trial 7). 0.6: about the last
#: frame's move. Basic kicks (``scripts/kick/approach_variants.py --set
#: kick.BALANCE_RELEASE_S=R -- --robot-type T --strengths --basic-trials 20 --basic-distance D
#: --layout-seed L``, R = 0 against 0.6; ``runs/kick_abort/s35_release/``): type 3 asked 5 m,
#: layout seeds 2-9, falls 10 -> 4 of 160 (after the kick 6 -> 0); asked 4 m, seeds 2-5, 12 ->
#: 7 of 80; every other figure the same (the ball has gone by then). Types 0, 1, 2, 4 asked
#: 5 m (seeds 2-5) and every type asked 3 m (seeds 2-3): the same trials, the same falls.
BALANCE_RELEASE_S = 0.6
#: Below this normal force (N) the support foot's pressure point is not trusted (a foot in the
#: air or barely touching reports a meaningless point).
COP_MIN_FORCE_N = 10.0


@dataclass(frozen=True)
class KickMotion:
    """A left-foot kick: keyframes plus which frames form the swing and how strength scales it.

    ``swing_frames`` index ``frames.frames``; at strength ``s`` each of them lasts
    ``1 / ((1 - s) / slow_s + s / fast_s)`` of its ``fast_s``-normalised share, i.e. the swing
    as a whole lasts ``fast_s`` at ``s = 1`` and ``slow_s`` at ``s = 0``.
    """

    name: str
    frames: KeyframeSequence
    swing_frames: tuple[int, ...]
    fast_s: float
    slow_s: float
    #: where the kick expects the ball before it starts: metres from the kicking foot's toe to
    #: the ball's surface along the foot, and sideways from the foot's centre line (+ = outwards,
    #: away from the support foot; the right kick mirrors it)
    ball_gap_m: float = 0.03
    ball_side_m: float = 0.0
    #: measured (strength, metres) pairs, increasing in both (``benchmarks/kick.py``); empty
    #: when the kick has not been calibrated
    distances: tuple[tuple[float, float], ...] = ()
    #: measured (metres, ball gap m) pairs at full strength, the distance increasing and the gap
    #: decreasing: a kick whose distance is set by how far ahead of the toe the ball lies (the
    #: foot meets a ball further ahead later in its swing, and it goes shorter) instead of by
    #: a slower swing. When present it replaces ``distances``: the kick plays at full strength
    #: and ``basic_kick`` lines the ball up at :meth:`gap_for`. Why: after the approach the
    #: slow swings fell half the time (session 11: 20 / 21 falls of 40 kicks asked for 1.5 /
    #: 2 m), the full-speed swing with the ball further ahead far less (session 12).
    gap_distances: tuple[tuple[float, float], ...] = ()
    #: the ball's mean direction (deg) off the robot's facing in basic kicks, + = towards the
    #: kicking foot's side as written (left; the right kick mirrors it): ``basic_kick`` faces
    #: this much the other way so that the ball goes where it is asked. Why: the long kicks
    #: searched on the bounce contacts send the ball 9-13 deg to the left (session 20)
    aim_deg: float = 0.0
    #: measured (strength, deg) pairs, the strength increasing: the ball's direction off the
    #: facing per swing strength, as ``aim_deg`` (which it replaces when present). Why: the long
    #: kick's weakest swings send the ball 8-9 deg further out than its full swing (session 30)
    aims: tuple[tuple[float, float], ...] = ()
    #: the landing catch after the swing (``behaviors/kick_recovery.py``); None: off, the
    #: keyframed landing plays whatever the torso does
    catch: CatchParams | None = None

    def strength_for(self, distance_m: float) -> float:
        """The strength (0..1) whose measured distance is ``distance_m``, interpolated linearly
        in the calibration table and clipped to its ends (1 for a kick calibrated by its ball
        gap, :attr:`gap_distances`). Raises ValueError without a calibration."""
        if self.gap_distances:
            return 1.0
        if not self.distances:
            raise ValueError(f"kick {self.name!r} has no distance calibration")
        return _interpolate(self.distances, distance_m, 1, 0)

    def aim_for(self, strength: float) -> float:
        """The ball's direction off the facing (deg, :attr:`aim_deg`) for a swing of
        ``strength``: interpolated in :attr:`aims` (clipped to its ends) where there is one."""
        if not self.aims:
            return self.aim_deg
        return _interpolate(self.aims, strength, 0, 1)

    def gap_for(self, distance_m: float) -> float:
        """The ball gap (m) that :attr:`gap_distances` gives for ``distance_m``, interpolated
        linearly and clipped to its ends; the kick's own ``ball_gap_m`` without that table."""
        if not self.gap_distances:
            return self.ball_gap_m
        return _interpolate(self.gap_distances, distance_m, 0, 1)

    @property
    def distance_range_m(self) -> tuple[float, float]:
        """The shortest and longest calibrated distance (m); (0, 0) without a calibration."""
        if self.gap_distances:
            return (self.gap_distances[0][0], self.gap_distances[-1][0])
        if not self.distances:
            return (0.0, 0.0)
        return (self.distances[0][1], self.distances[-1][1])

    def swing_duration(self, strength: float) -> float:
        """Seconds the swing lasts at ``strength`` (0..1): foot speed linear in strength."""
        strength = min(max(strength, 0.0), 1.0)
        return 1.0 / ((1.0 - strength) / self.slow_s + strength / self.fast_s)

    def sequence(self, strength: float, mirror: bool = False) -> KeyframeSequence:
        """The keyframes to play for ``strength``; ``mirror=True`` gives the right-foot kick."""
        written = sum(self.frames.frames[i].duration for i in self.swing_frames)
        scale = self.swing_duration(strength) / written
        frames = tuple(
            replace(frame, duration=frame.duration * scale) if i in self.swing_frames else frame
            for i, frame in enumerate(self.frames.frames)
        )
        sequence = replace(self.frames, frames=frames)
        return mirrored(sequence) if mirror else sequence

    def catch_window(self, strength: float) -> tuple[float, float]:
        """Seconds from the first cycle between which the landing catch may start: from the
        swing's end to the start of the last frame (the return to the stand)."""
        frames = self.sequence(strength).frames
        swing_end = sum(frames[i].total for i in range(max(self.swing_frames) + 1))
        early = self.catch.early_s if self.catch is not None else 0.0
        return swing_end - early, sum(frame.total for frame in frames[:-1])

    def contact_time(self, strength: float) -> float:
        """Seconds from the first cycle to the start of the swing (the foot then meets the
        ball within the swing's first part)."""
        frames = self.sequence(strength).frames
        return sum(frames[i].total for i in range(min(self.swing_frames)))


def _interpolate(
    table: tuple[tuple[float, float], ...], x: float, given: int, wanted: int
) -> float:
    """Column ``wanted`` of ``table`` at ``x`` in column ``given`` (increasing), linearly
    interpolated and clipped to the table's ends."""
    if x <= table[0][given]:
        return table[0][wanted]
    for a, b in itertools.pairwise(table):
        if x <= b[given]:
            share = (x - a[given]) / (b[given] - a[given])
            return a[wanted] + (b[wanted] - a[wanted]) * share
    return table[-1][wanted]


def parse_kicks(data: Mapping[str, Any], source: str) -> dict[str, KickMotion]:
    """Build kick motions from the mapping read out of ``source`` (a file name, for messages)."""
    kicks = {}
    for name, entry in data.items():
        where = f"{source}: kick {name!r}"
        check_fields(entry, where, {"frames", "swing"}, _KICK_OPTIONAL)
        sequence_entry = {"frames": entry["frames"], "description": entry.get("description", "")}
        sequence = parse_sequences({name: sequence_entry}, source)[str(name)]
        kicks[str(name)] = KickMotion(
            str(name),
            sequence,
            *_parse_swing(entry["swing"], f"{where}.swing", sequence),
            ball_gap_m=check_number(entry.get("ball_gap_m", 0.03), f"{where}.ball_gap_m"),
            ball_side_m=check_number(entry.get("ball_side_m", 0.0), f"{where}.ball_side_m"),
            distances=_parse_distances(entry.get("distances", []), f"{where}.distances"),
            gap_distances=_parse_gaps(entry.get("gap_distances", []), f"{where}.gap_distances"),
            aim_deg=check_number(entry.get("aim_deg", 0.0), f"{where}.aim_deg"),
            aims=_parse_aims(entry.get("aims", []), f"{where}.aims"),
            catch=parse_catch(entry["catch"], f"{where}.catch") if "catch" in entry else None,
        )
    return kicks


_KICK_OPTIONAL = {
    "description",
    "ball_gap_m",
    "ball_side_m",
    "distances",
    "gap_distances",
    "aim_deg",
    "aims",
    "catch",
}


def _parse_pairs(data: Any, where: str, columns: str) -> tuple[tuple[float, float], ...]:
    """``[[a, b], ...]`` of numbers (``columns`` names a and b for the message)."""
    if not isinstance(data, list) or not all(
        isinstance(row, list) and len(row) == 2 for row in data
    ):
        raise PoseError(f"{where}: expected a list of [{columns}] pairs")
    return tuple(
        (check_number(a, f"{where}[{i}]"), check_number(b, f"{where}[{i}]"))
        for i, (a, b) in enumerate(data)
    )


def _parse_gaps(data: Any, where: str) -> tuple[tuple[float, float], ...]:
    """``[[metres, ball gap m], ...]`` with the distance increasing and the gap decreasing
    (so that a distance names one gap)."""
    table = _parse_pairs(data, where, "metres, ball gap m")
    for (d0, g0), (d1, g1) in itertools.pairwise(table):
        if not (d1 > d0 and g1 < g0):
            raise PoseError(f"{where}: distances must increase and gaps decrease")
    return table


def _parse_aims(data: Any, where: str) -> tuple[tuple[float, float], ...]:
    """``[[strength, deg], ...]`` with the strength increasing within [0, 1]."""
    table = _parse_pairs(data, where, "strength, deg")
    if any(s1 <= s0 for (s0, _), (s1, _) in itertools.pairwise(table)):
        raise PoseError(f"{where}: strengths must increase")
    _check_strengths(table, where)
    return table


def _check_strengths(table: tuple[tuple[float, float], ...], where: str) -> None:
    """Every strength of a ``[[strength, ...], ...]`` table within [0, 1]."""
    if table and not all(0.0 <= s <= 1.0 for s, _ in table):
        raise PoseError(f"{where}: strengths must lie in [0, 1]")


def _parse_distances(data: Any, where: str) -> tuple[tuple[float, float], ...]:
    """``[[strength, metres], ...]`` with both columns strictly increasing (so that a distance
    names one strength)."""
    table = _parse_pairs(data, where, "strength, metres")
    for (s0, d0), (s1, d1) in itertools.pairwise(table):
        if not (s1 > s0 and d1 > d0):
            raise PoseError(f"{where}: strengths and distances must both increase")
    _check_strengths(table, where)
    return table


def _parse_swing(
    data: Any, where: str, sequence: KeyframeSequence
) -> tuple[tuple[int, ...], float, float]:
    check_fields(data, where, {"frames", "fast_s", "slow_s"}, set())
    indices = data["frames"]
    count = len(sequence.frames)
    if (
        not isinstance(indices, list)
        or not indices
        or not all(isinstance(i, int) and 0 <= i < count for i in indices)
    ):
        raise PoseError(f"{where}.frames: expected a list of frame indices in 0..{count - 1}")
    fast = check_number(data["fast_s"], f"{where}.fast_s")
    slow = check_number(data["slow_s"], f"{where}.slow_s")
    if not 0 < fast <= slow:
        raise PoseError(f"{where}: need 0 < fast_s <= slow_s, got {fast}, {slow}")
    return tuple(indices), fast, slow


def load_kicks(path: str | Path = KICKS_FILE) -> dict[str, KickMotion]:
    """Read and validate a kick file (default: the packaged ``kicks.yaml``)."""
    path = Path(path)
    return parse_kicks(read_yaml_mapping(path), str(path))


@cache
def default_kicks() -> dict[str, KickMotion]:
    """The packaged kicks, read once per process (they are immutable)."""
    return load_kicks(KICKS_FILE)


def kick_motion(
    robot_type: int,
    kicks: Mapping[str, KickMotion] | None = None,
    foot: str = "left",
    aligned: bool = False,
    long: bool = False,
) -> KickMotion:
    """The motion that ``foot`` kicks with: the robot type's own if there is one, else the
    common one. The right foot plays :data:`KICK_RIGHT` where the file has one, else
    :data:`KICK_LEFT`; either way it is written for the left foot and played mirrored.
    ``aligned`` (``basic_kick``, after its walk and alignment shuffle) prefers the name with
    :data:`ALIGNED_SUFFIX` (``kick_right_aligned``) where the file has one.

    Why a file may give the right foot a kick of its own: the simulator is not mirror-symmetric
    in the last detail (the solver visits the joints in order). Under 30 solver iterations the
    mirrored left kick fell before contact in 5 of 12 right kicks after an approach, so until
    session 28 the file had right motions of their own; under today's 60 the mirrored left
    kicks fell less on the right foot than those (0 against 8 of 126 right-footed basic kicks)
    and they went (``kicks.yaml``). Why one for after the alignment: a kick leans 2-4 deg
    further over its support foot after a shuffle than from a stand, and after the alignment
    the left kick's support hip extends further (about 0.3 m more, no more falls).
    ``long`` prefers the name with :data:`LONG_SUFFIX` (``kick_right_aligned_long``,
    ``kick_left_aligned_long``): the kicks with their support side's arm raised go further and
    fall less at full strength, but their weaker swings miss their distances by more or fall
    (sessions 10 and 11), so they serve long requests."""
    kicks = default_kicks() if kicks is None else kicks
    names: tuple[str, ...] = (KICK_RIGHT, KICK_LEFT) if foot == "right" else (KICK_LEFT,)
    if aligned:
        names = tuple(itertools.chain.from_iterable((n + ALIGNED_SUFFIX, n) for n in names))
    if long:
        names = tuple(itertools.chain.from_iterable((n + LONG_SUFFIX, n) for n in names))
    for name in names:
        motion = kicks.get(f"{name}_type{robot_type}") or kicks.get(name)
        if motion is not None:
            return motion
    raise KeyError(f"no kick {KICK_LEFT!r} in the kick file")


class KickSkill(Skill):
    """``execute("kick", foot, strength, aligned=False, long=False)``: kick with
    ``"left"``/``"right"`` at 0..1; ``aligned``: the motion for after ``basic_kick``'s
    alignment, ``long``: its long version where there is one (:func:`kick_motion`).

    Finished once the motion has brought the robot back into the stand pose. Asking for the
    other foot or another strength while a kick plays does not interrupt it: a half-played
    kick would leave the robot on one leg.
    """

    name = "kick"

    def __init__(self, cop_gain: float = COP_GAIN) -> None:
        self._player: KeyframePlayer | None = None
        self._done = False
        self._balance: _OneLegBalance | None = None
        self._catch: LandingCatch | None = None
        self._catch_window = (0.0, 0.0)
        self._support_plan: dict[str, float] = {}
        #: the one-leg balance's centre-of-pressure gain (:data:`COP_GAIN`; trials set their own)
        self.cop_gain = cop_gain
        #: the kick motions to choose from (None: the packaged ones); searches set their own
        self.motions: Mapping[str, KickMotion] | None = None

    def reset(self) -> None:
        self._player = None
        self._done = False
        self._balance = None
        self._catch = None

    def validate(
        self, foot: str, strength: float = 1.0, aligned: bool = False, long: bool = False
    ) -> None:
        if foot not in FEET:
            raise ValueError(f"foot must be one of {', '.join(FEET)}, got {foot!r}")
        if not 0.0 <= strength <= 1.0:
            raise ValueError(f"strength must be in [0, 1], got {strength!r}")

    def step(
        self,
        context: SkillContext,
        foot: str,
        strength: float = 1.0,
        aligned: bool = False,
        long: bool = False,
    ) -> bool:
        robot = context.world.robot
        if self._player is None or self._done:
            motion = kick_motion(robot.robot_type, self.motions, foot, aligned, long)
            sequence = motion.sequence(strength, mirror=foot == "right")
            self._player = KeyframePlayer(sequence, robot.robot_type)
            self._balance = _OneLegBalance(sequence, foot == "right")
            self._catch = None
            if motion.catch is not None:
                self._catch = LandingCatch(motion.catch, robot.robot_type, foot == "right")
                self._catch_window = motion.catch_window(strength)
                self._support_plan = _support_plan(sequence, foot)
            self._done = False
        elapsed = self._player.elapsed
        self._done = self._player.step(context.commands, robot.joints_deg)
        assert self._balance is not None
        roll_rate = float(robot.gyro_deg_s[1])  # + = rolling to the right
        # the pressure term is off by default; only then is the FRP perceptor read
        cop = None
        if self.cop_gain:
            cop = self._balance.support_cop_outwards_cm(robot.foot_pressure)
        self._balance.correct(
            context.commands, elapsed, robot.roll_deg, roll_rate, cop, self.cop_gain
        )
        catch = self._catch
        low, high = self._catch_window
        starts = catch is not None and not catch.active and low <= elapsed < high
        if starts and catch.triggered(robot.roll_deg, roll_rate):  # type: ignore[union-attr]
            catch.start(robot.joints_deg, robot.up, robot.roll_deg, self._support_plan)  # type: ignore[union-attr]
        if catch is not None and catch.active and catch.params.hand_back and elapsed >= high:
            catch.active = False  # the kick's own return to the stand from here on
            self._catch = None
        if catch is not None and catch.active:
            frp = robot.foot_pressure.get("rf" if foot == "right" else "lf")
            force = 0.0 if frp is None else float(frp.force[2])
            self._done = catch.step(context.commands, robot.joints_deg, robot.up, force)
        return self._done


def _support_plan(sequence: KeyframeSequence, foot: str) -> dict[str, float]:
    """The support leg's targets at the end of the landing frame (the last before the return
    to the stand): where the landing catch expects the support leg while the foot comes down."""
    targets: dict[str, float] = {}
    for frame in sequence.frames[:-1]:
        targets.update(frame.joints)
    prefix = "llj" if foot == "right" else "rlj"
    return {name: value for name, value in targets.items() if name.startswith(prefix)}


class _OneLegBalance:
    """Keeps the torso's roll while the robot stands on the support leg.

    From the end of the first frame (the weight shift) to the start of the last (the return to
    the stand) the support ankle's roll target is moved by ``BALANCE_GAIN`` times the change of
    the torso roll since the shift ended; from there the last correction fades out over
    :data:`BALANCE_RELEASE_S`. Written for the left kick (support: the right ankle,
    ``rlj6``; decreasing it tips the body to its right); the right kick mirrors roll and joint.
    """

    def __init__(self, sequence: KeyframeSequence, mirror: bool) -> None:
        frames = sequence.frames
        self._start = frames[0].total
        self._end = sequence.duration - frames[-1].total
        self._mirror = mirror
        self._joints = ("llj6", "llj2") if mirror else ("rlj6", "rlj2")
        #: the support foot's FRP perceptor; its +x points to the robot's right, i.e. outwards
        #: for the right (support) foot of the left kick
        self._foot = "lf" if mirror else "rf"
        self._reference: float | None = None
        #: the support ankle's roll target of the last gain-tracked frame (predictive frames
        #: send speeds, not targets)
        self._last_targets = dict.fromkeys(self._joints, 0.0)
        #: the correction of the last balanced cycle (deg, as sent), faded out afterwards
        self._last_correction = 0.0

    def support_cop_outwards_cm(self, pressure: Mapping[str, ForceResistance]) -> float | None:
        """Centimetres the support foot's centre of pressure lies outwards of its centre line
        (away from the kicking foot), or None while the foot bears too little weight."""
        frp = pressure.get(self._foot)
        if frp is None or frp.force[2] < COP_MIN_FORCE_N:
            return None
        lateral_cm = 100.0 * frp.contact[0]
        return -lateral_cm if self._mirror else lateral_cm

    def correct(
        self,
        commands: JointCommands,
        elapsed: float,
        roll_deg: float,
        roll_rate: float = 0.0,
        cop_outwards_cm: float | None = None,
        cop_gain: float = COP_GAIN,
    ) -> None:
        if elapsed < self._start:
            return
        if elapsed >= self._end:
            self._release(commands, elapsed - self._end)
            return
        roll = -roll_deg if self._mirror else roll_deg  # roll as the left kick sees it
        rate = -roll_rate if self._mirror else roll_rate
        if self._reference is None:
            self._reference = roll
        correction = BALANCE_GAIN * (roll - self._reference) + BALANCE_DAMPING * rate
        if cop_outwards_cm is not None:
            correction -= cop_gain * cop_outwards_cm
        correction = max(-BALANCE_LIMIT_DEG, min(BALANCE_LIMIT_DEG, correction))
        if self._mirror:
            correction = -correction  # roll joints change sign in the mirror image
        self._last_correction = correction
        self._apply(commands, correction)

    def _release(self, commands: JointCommands, since_end_s: float) -> None:
        """Fade the last correction out over :data:`BALANCE_RELEASE_S` from the last frame's
        start (nothing when that is 0)."""
        if since_end_s >= BALANCE_RELEASE_S:
            return
        self._apply(commands, self._last_correction * (1.0 - since_end_s / BALANCE_RELEASE_S))

    def _apply(self, commands: JointCommands, correction: float) -> None:
        """Add ``correction`` (deg) to the support ankle's and hip's roll targets."""
        written = commands.targets()
        ankle, hip = self._joints
        for joint, share in ((ankle, 1.0), (hip, BALANCE_HIP_SHARE)):
            target = written.get(joint, self._last_targets[joint])
            self._last_targets[joint] = target
            commands.set_targets({joint: target + share * correction})
