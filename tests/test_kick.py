"""The kick: the packaged motion, strength scaling, mirroring, and kicks in the simulator.

The issue asks for at least 3 m at full strength. On the soft contacts of sessions 1-19 the
plain motion reached 2.98 / 3.10 m (left / right) from a stand, the foot pushing the ball at its
own top speed (``benchmarks/kick.py --impact``: about 3 m/s with the joint caps). Since session
20 the ball bounces off the foot as on the real server: the plain stand kicks go 2.03 / 2.62 m,
the long kicks searched on these contacts 6.87 / 4.26 m after a small alignment shuffle, and
after walking to the ball 6.2-6.7 m median over layout seeds asked for "long". The trials also
assert that the robot stays up and the ball leaves forwards off the kicking foot's side.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

import behaviors.basic_kick as basic_kick_module
import behaviors.kick as kick_module
from behaviors.basic_kick import (
    LONG,
    REACH_PREFERENCE_M,
    SHUFFLE_LIFT_S,
    SHUFFLE_SHIFT_S,
    TYPE_LONG_KICK_FOOT_CREDIT_M,
    BasicKickSkill,
    FootShuffle,
    aimed_target,
    choose_foot,
    detour_point,
    expected_ball_ego,
    kick_spot,
    motion_for,
    shuffle_stages,
    shuffle_weight_shift,
    strength_for,
    wants_long,
)
from behaviors.joint_control import CYCLE_SECONDS, JointCommands
from behaviors.kick import (
    ALIGNED_SUFFIX,
    BALANCE_GAIN,
    FEET,
    KICK_LEFT,
    KICK_RIGHT,
    LONG_SUFFIX,
    KickMotion,
    KickSkill,
    _OneLegBalance,
    default_kicks,
    kick_motion,
    load_kicks,
    parse_kicks,
)
from behaviors.mirror import MIRROR_TABLE
from behaviors.poses import PoseError, get_pose

pytest.importorskip("pybullet")

import benchmarks.kick as kick_benchmark
from benchmarks.kick import (
    BasicKickResult,
    basic_layouts,
    measure_impact,
    run_basic_trial,
    run_trial,
    shuffle_in_place,
    stand_up,
)
from learning.kick_search import motions_for, start_parameters, write_candidate
from sim.session import Session, SessionConfig
from world.nao_model import ROBOT_TYPES


def test_packaged_kick_loads_and_ends_in_the_stand():
    motion = kick_motion(0)
    assert motion.name == KICK_LEFT
    last = motion.frames.frames[-1]
    assert dict(last.joints) == dict(get_pose("stand").joints)
    assert all(motion.frames.frames[i].track == "predictive" for i in motion.swing_frames)


def test_strength_sets_the_swing_duration_between_fast_and_slow():
    motion = default_kicks()[KICK_LEFT]
    assert motion.swing_duration(1.0) == pytest.approx(motion.fast_s)
    assert motion.swing_duration(0.0) == pytest.approx(motion.slow_s)
    durations = [motion.swing_duration(s / 10) for s in range(11)]
    assert durations == sorted(durations, reverse=True)
    # foot speed (1 / duration) is linear in strength
    speeds = [1 / d for d in durations]
    steps = [b - a for a, b in itertools.pairwise(speeds)]
    assert max(steps) == pytest.approx(min(steps))
    for strength in (0.0, 0.5, 1.0):
        frames = motion.sequence(strength).frames
        swing = sum(frames[i].duration for i in motion.swing_frames)
        assert swing == pytest.approx(motion.swing_duration(strength))
        others = [f.duration for i, f in enumerate(frames) if i not in motion.swing_frames]
        written = [
            f.duration for i, f in enumerate(motion.frames.frames) if i not in motion.swing_frames
        ]
        assert others == written


def test_the_right_kick_is_the_mirror_image_of_the_left():
    motion = default_kicks()[KICK_LEFT]
    left, right = motion.sequence(0.7), motion.sequence(0.7, mirror=True)
    for lf, rf in zip(left.frames, right.frames, strict=True):
        assert lf.duration == rf.duration and lf.track == rf.track
        for name, angle in lf.joints.items():
            entry = MIRROR_TABLE[name]
            assert rf.joints[entry.twin] == pytest.approx(entry.sign * angle)
    # the left kick swings the left leg: its hip pitch changes most during the swing
    swing = [left.frames[i].joints for i in motion.swing_frames]
    assert swing[-1]["llj3"] - swing[0]["llj3"] > 30


@pytest.mark.parametrize(
    ("swing", "message"),
    [
        ({"frames": [9], "fast_s": 0.1, "slow_s": 1}, "frame indices in 0..0"),
        ({"frames": [0], "fast_s": 1, "slow_s": 0.1}, "need 0 < fast_s <= slow_s"),
        ({"frames": [0], "fast_s": 0.1}, "missing field(s) slow_s"),
    ],
)
def test_bad_kick_files_name_the_problem(swing, message):
    data = {"k": {"frames": [{"duration": 0.1, "pose": "stand"}], "swing": swing}}
    with pytest.raises(PoseError, match=message.replace("(", r"\(").replace(")", r"\)")):
        parse_kicks(data, "k.yaml")


def test_the_right_foot_plays_its_own_kick_where_the_file_has_one():
    left = default_kicks()[KICK_LEFT]
    right = replace(left, name=KICK_RIGHT, ball_gap_m=left.ball_gap_m + 0.01)
    assert kick_motion(0, {KICK_LEFT: left}, "right") is left
    both = {KICK_LEFT: left, KICK_RIGHT: right}
    assert kick_motion(0, both, "right") is right
    assert kick_motion(0, both, "left") is left
    # written for the left foot, played mirrored: the right foot's ball lies mirror-wise
    ahead, side = expected_ball_ego(0, "right", right)
    mirror_ahead, mirror_side = expected_ball_ego(0, "left", right)
    assert (ahead, side) == pytest.approx((mirror_ahead, -mirror_side))


def test_basic_kick_plays_the_aligned_motion_where_the_file_has_one():
    """After its alignment shuffle ``basic_kick`` asks for ``aligned`` motions: the packaged left
    one extends its support hip further in the swing than the stand kick; the right foot plays
    it mirrored (the packaged file has no right motions since session 29), and a foot without an
    aligned motion falls back to its plain one."""
    packaged = default_kicks()
    stand = packaged[KICK_LEFT]
    aligned_left = kick_motion(0, None, "left", aligned=True)
    assert aligned_left.name == KICK_LEFT + ALIGNED_SUFFIX
    assert kick_motion(0, None, "right", aligned=True) is aligned_left
    assert not any(name.startswith(KICK_RIGHT) for name in packaged)
    assert kick_motion(0, None, "right").name == KICK_LEFT  # stand kicks: the mirrored left
    assert kick_motion(0, None, "left") is stand
    swing_end = max(stand.swing_frames)
    assert (
        aligned_left.frames.frames[swing_end].joints["rlj3"]
        < stand.frames.frames[swing_end].joints["rlj3"]
    )
    # the same ball spot, so the foot choice and the alignment do not change
    for foot in FEET:
        assert expected_ball_ego(0, foot, aligned_left) == expected_ball_ego(0, foot, stand)
    only_left = {KICK_LEFT: stand}
    assert kick_motion(0, only_left, "right", aligned=True) is stand


def test_the_long_kicks_meet_the_ball_with_the_foot_flat_at_their_own_ball_spot():
    """The long kicks (session 20) were searched under the bounce contacts
    (``learning/kick_search.py``, ``runs/kick_bounce/``): they meet the ball with the kicking
    foot flat (contact-frame ankle within 5 deg of 0; the short kicks' toe points 20.5 deg down)
    and swing both arms in the swing's end. Each wants the ball at its own spot, so
    ``basic_kick`` lines the ball up for the long motion when the request wants it
    (``motion_for``): with the short kick's spot the long ones went 4.1-4.9 m median asked for
    long at layout seeds 0-2 and fell 23 times in 60."""
    for foot in FEET:
        short = kick_motion(0, None, foot, aligned=True)
        long = kick_motion(0, None, foot, aligned=True, long=True)
        assert long.name.endswith(LONG_SUFFIX) and not short.name.endswith(LONG_SUFFIX)
        contact, swing_end = min(long.swing_frames), max(long.swing_frames)
        assert abs(long.frames.frames[contact].joints["llj5"]) < 5.0
        assert short.frames.frames[contact].joints["llj5"] > 15.0
        assert {"laj1", "raj1"} <= set(long.frames.frames[swing_end].joints)
        assert not {"laj1", "raj1"} & set(short.frames.frames[swing_end].joints)
        assert motion_for(0, None, foot, LONG) == (long, True)
        assert motion_for(0, None, foot, 0.5 * short.distance_range_m[1]) == (short, False)
        assert expected_ball_ego(0, foot, long, LONG) != expected_ball_ego(0, foot, short)


def test_the_foot_whose_kick_reaches_wins_within_a_metre_of_walking():
    """Each foot's kick reaches its own distance (on the bounce contacts the left long kick
    about 6.5 m, the right about 4.3 m): the nearer spot wins while both reach the distance,
    the reaching foot wins within ``REACH_PREFERENCE_M`` of extra walking."""
    reach = {"left": 6.47, "right": 4.3}
    near_right = {"left": 1.0, "right": 0.5}
    assert choose_foot(near_right, reach, 3.5) == "right"  # both reach
    assert choose_foot(near_right, reach, 5.0) == "left"
    assert choose_foot(near_right, reach, LONG) == "left"
    far_left = {"left": 0.5 + REACH_PREFERENCE_M + 0.1, "right": 0.5}
    assert choose_foot(far_left, reach, LONG) == "right"
    assert choose_foot({"left": 0.5, "right": 1.0}, {"left": 4.0, "right": 4.0}, LONG) == "left"


def test_a_robot_types_steadier_foot_wins_within_its_credit():
    """Type 1's left long kick fell in its swing far more often than its right, so for a long
    kick type 1's right foot wins within ``TYPE_LONG_KICK_FOOT_CREDIT_M``'s metres of extra
    walking; without a credit the nearer spot wins."""
    foot, credit = TYPE_LONG_KICK_FOOT_CREDIT_M[1]
    other = "left" if foot == "right" else "right"
    reach = {"left": 6.0, "right": 6.0}
    within = {other: 0.5, foot: 0.5 + 0.8 * credit}
    beyond = {other: 0.5, foot: 0.5 + 1.2 * credit}
    assert choose_foot(within, reach, 5.0) == other  # no credit: the nearer spot
    assert choose_foot(within, reach, 5.0, (foot, credit)) == foot
    assert choose_foot(beyond, reach, 5.0, (foot, credit)) == other


def test_the_long_left_kick_raises_the_support_arm_until_the_recover_frame():
    """Session 20: the left long kick lifts its support side's (right) arm 10 deg sideways from
    the weight shift and lowers it in the recover frame after the swing (replayed from 100 saved
    approaches, falls 22 -> 8); the right long kick keeps its arms (raised, it missed the ball
    or fell before contact). Since session 29 the right foot plays the left motion mirrored,
    so its support side's (left) arm rises the same way."""
    stand = get_pose("stand").joints
    long = kick_motion(0, None, "left", aligned=True, long=True)
    frames = long.sequence(1.0).frames
    recover = max(long.swing_frames) + 1
    assert frames[0].joints["raj2"] <= stand["raj2"] - 10.0  # right arm out: - on the right
    assert all("raj2" not in frames[i].joints for i in range(1, recover))  # held up
    assert frames[recover].joints["raj2"] == stand["raj2"]
    right = kick_motion(0, None, "right", aligned=True, long=True).sequence(1.0, mirror=True)
    assert right.frames[0].joints["laj2"] >= stand["laj2"] + 10.0  # left arm out: + on the left


def test_a_kick_that_goes_left_is_aimed_right_of_the_target():
    """``aim_deg``: the left long kick's ball goes about 10 deg left of the robot's facing, so
    ``basic_kick`` faces the target turned 10 deg right about the ball; the right foot plays the
    motion mirrored, so its aim turns the other way (``basic_kick`` negates it)."""
    turned = aimed_target((1.0, 2.0), (11.0, 2.0), 10.0)
    assert math.degrees(math.atan2(turned[1] - 2.0, turned[0] - 1.0)) == pytest.approx(-10.0)
    assert math.dist(turned, (1.0, 2.0)) == pytest.approx(10.0)
    assert aimed_target((1.0, 2.0), (11.0, 2.0), 0.0) == pytest.approx((11.0, 2.0))
    long = kick_motion(0, None, "left", aligned=True, long=True)
    short = kick_motion(0, None, "left", aligned=True)
    # the short kick's ball goes 2-3 deg outwards (session 30), the long one's about 10
    assert long.aim_deg > short.aim_deg > 0.0


def test_basic_kick_plays_the_long_motion_only_beyond_the_plain_table():
    """Requests within the aligned kick's table keep it (its swings are the more accurate);
    farther ones play the long version at the strength its own table gives (session 29: both
    are calibrated by strength, the long table starting where the short one ends), "long" at
    full strength."""
    for foot in FEET:
        plain = kick_motion(0, None, foot, aligned=True)
        top = plain.distance_range_m[1]
        assert not wants_long(plain, top)
        assert not wants_long(plain, 2.0)
        assert wants_long(plain, top + 0.1)
        assert wants_long(plain, LONG)
        long = kick_motion(0, None, foot, aligned=True, long=True)
        low, high = long.distance_range_m
        assert top <= low < high
        assert strength_for(long, top + 0.1) == long.distances[0][0] < 1.0
        assert strength_for(long, 0.5 * (low + high)) < strength_for(long, LONG) == 1.0


def test_distance_table_gives_the_strength_by_linear_interpolation_clipped_at_its_ends():
    motion = replace(default_kicks()[KICK_LEFT], distances=((0.0, 1.0), (0.5, 2.0), (1.0, 4.0)))
    assert motion.strength_for(1.5) == pytest.approx(0.25)
    assert motion.strength_for(3.0) == pytest.approx(0.75)
    assert motion.strength_for(0.2) == 0.0
    assert motion.strength_for(9.0) == 1.0
    assert motion.distance_range_m == (1.0, 4.0)
    with pytest.raises(ValueError, match="no distance calibration"):
        replace(motion, distances=()).strength_for(2.0)


def test_packaged_kick_is_calibrated_with_increasing_distances():
    motion = kick_motion(0)
    strengths = [s for s, _ in motion.distances]
    distances = [d for _, d in motion.distances]
    assert strengths == sorted(strengths) and distances == sorted(distances)
    assert len(motion.distances) >= 2


def test_both_feet_play_the_left_motions_with_one_table_after_the_approach():
    """After the approach the kicks have tables of their own (measured on basic kicks, not stand
    kicks). The right foot plays the left motions mirrored (session 29: under 60 solver
    iterations its own motions fell 8 of 126 right-footed basic kicks, the mirrored left ones
    none), so both feet ask the same strength for a distance; beyond the short table a request
    asks for its top strength (``basic_kick`` plays the long kick there)."""
    stand = kick_motion(0)
    for long in (False, True):
        left = kick_motion(0, None, "left", aligned=True, long=long)
        assert kick_motion(0, None, "right", aligned=True, long=long) is left
        assert left.distances != stand.distances
    left = kick_motion(0, None, "left", aligned=True)
    assert left.strength_for(left.distance_range_m[1] + 1.0) == left.distances[-1][0]


def test_a_distance_table_that_does_not_increase_is_refused():
    data = {
        "k": {
            "frames": [{"duration": 0.1, "pose": "stand"}],
            "swing": {"frames": [0], "fast_s": 0.1, "slow_s": 1},
            "distances": [[0.0, 2.0], [1.0, 1.0]],
        }
    }
    with pytest.raises(PoseError, match="must both increase"):
        parse_kicks(data, "k.yaml")


def test_a_gap_table_sets_the_distance_by_where_the_ball_lies_at_full_strength():
    """A kick calibrated by its ball gap plays at full strength and asks for the ball further
    ahead of the toe the shorter the kick; ``basic_kick`` lines up for that gap (the robot
    stands further back), but a long kick keeps the motion's own gap."""
    motion = replace(
        default_kicks()[KICK_LEFT], gap_distances=((2.0, 0.08), (2.4, 0.06), (2.6, 0.045))
    )
    assert motion.strength_for(2.2) == 1.0
    assert motion.gap_for(2.2) == pytest.approx(0.07)
    assert motion.gap_for(1.0) == 0.08 and motion.gap_for(2.6) == 0.045
    assert motion.distance_range_m == (2.0, 2.6)
    assert replace(motion, gap_distances=()).gap_for(2.2) == motion.ball_gap_m
    short, near = expected_ball_ego(0, "left", motion, 2.0), expected_ball_ego(0, "left", motion)
    assert short[0] - near[0] == pytest.approx(0.08 - motion.ball_gap_m, abs=2e-3)
    assert short[1] == pytest.approx(near[1], abs=2e-3)
    assert expected_ball_ego(0, "left", motion, 3.0) == near  # beyond the table: long
    assert expected_ball_ego(0, "left", motion, LONG) == near
    data = {
        "k": {
            "frames": [{"duration": 0.1, "pose": "stand"}],
            "swing": {"frames": [0], "fast_s": 0.1, "slow_s": 1},
            "gap_distances": [[2.0, 0.06], [2.5, 0.07]],
        }
    }
    with pytest.raises(PoseError, match="gaps decrease"):
        parse_kicks(data, "k.yaml")


def test_kick_spot_puts_the_ball_at_the_offset_facing_the_target():
    ball, target, offset = (1.0, 2.0), (1.0, 5.0), (0.18, 0.05)
    x, y, heading = kick_spot(ball, target, offset)
    assert heading == pytest.approx(90.0)
    # facing +y: forward is +y, left is -x
    assert (ball[1] - y, -(ball[0] - x)) == pytest.approx(offset)


def test_a_robot_beyond_the_ball_walks_round_it_on_its_own_side():
    ball = (0.0, 0.0)
    spot = kick_spot(ball, (5.0, 0.0), (0.18, 0.05))  # kick towards +x: spot behind, at -x
    assert detour_point(ball, spot, (-1.0, 0.1)) is None  # behind the ball: straight there
    assert detour_point(ball, spot, spot[:2]) is None  # at the spot
    left = detour_point(ball, spot, (1.0, 0.05))  # beyond the ball, a little to its left
    assert left is not None and left[0] < -0.2 and left[1] > 0.3
    right = detour_point(ball, spot, (1.0, -0.2))
    assert right is not None and right[1] < -0.3


def test_the_ball_is_expected_mirror_symmetrically_in_front_of_either_foot():
    motion: KickMotion = kick_motion(0)
    left, right = expected_ball_ego(0, "left", motion), expected_ball_ego(0, "right", motion)
    assert left[0] == pytest.approx(right[0], abs=1e-3)
    assert left[1] == pytest.approx(-right[1], abs=1e-3)
    assert 0.1 < left[0] < 0.3 and 0.02 < left[1] < 0.12


@pytest.mark.parametrize(("forward", "left"), [(0.03, 0.02), (-0.02, -0.04), (0.0, 0.0)])
def test_a_shuffle_ends_moved_with_the_feet_squared_and_moves_a_foot_only_in_the_air(forward, left):
    stages = shuffle_stages(forward, left)
    last = stages[-1]
    assert last.torso == last.left == last.right == (forward, left)
    before = stages[0]
    for stage in stages[1:]:
        for side in ("left", "right"):
            moved = getattr(stage, side) != getattr(before, side)
            lifted = getattr(stage, f"{side}_lift") > 0 and getattr(before, f"{side}_lift") > 0
            assert not moved or lifted
        # never both feet in the air
        assert not (stage.left_lift > 0 and stage.right_lift > 0)
        before = stage


@pytest.mark.parametrize(("forward", "left", "turn_deg"), [(0.03, -0.02, 10.0), (0.0, 0.0, -8.0)])
def test_a_turning_shuffle_ends_with_both_feet_where_the_turned_stand_puts_them(
    forward, left, turn_deg
):
    stand = {"left": (0.04, 0.055), "right": (0.04, -0.055)}
    turn = math.radians(turn_deg)
    stages = shuffle_stages(forward, left, 0.045, turn, stand)
    last = stages[-1]
    assert last.torso == (forward, left)
    assert last.torso_yaw == last.left_yaw == last.right_yaw == turn
    c, s = math.cos(turn), math.sin(turn)
    for side, (x, y) in stand.items():
        moved = getattr(last, side)
        # the foot's place relative to the turned torso is its stand place
        rx, ry = x + moved[0] - forward, y + moved[1] - left
        assert (c * rx + s * ry, -s * rx + c * ry) == pytest.approx((x, y))
    # the foot on the side of the turn leads (the sideways move is short)
    leading = "left" if turn > 0 else "right"
    assert getattr(stages[1], f"{leading}_lift") > 0
    with pytest.raises(ValueError, match="stand"):
        shuffle_stages(forward, left, 0.045, turn)


def test_a_shuffle_move_keeps_the_ball_where_the_kick_wants_it_after_the_turn():
    """basic_kick's shuffles turn the robot by the heading error about its torso (session 30):
    the move must put the ball, seen off the spot, back on the spot in the turned frame."""
    expected = (0.19, 0.05)
    alignment = basic_kick_module.Alignment(0.02, -0.01, 9.0)
    forward, left, turn = basic_kick_module.shuffle_move(alignment, expected)
    assert turn == pytest.approx(math.radians(9.0))
    bx, by = expected[0] + 0.02 - forward, expected[1] - 0.01 - left
    c, s = math.cos(turn), math.sin(turn)
    assert (c * bx + s * by, -s * bx + c * by) == pytest.approx(expected)
    small = basic_kick_module.Alignment(0.02, -0.01, 1.0)
    assert basic_kick_module.shuffle_move(small, expected) == pytest.approx((0.02, -0.01, 0.0))


def test_a_turning_shuffle_turns_the_standing_robot():
    """Measured when written (session 30): 7.2-8.1 deg of 8 on every type, 0 without the turn."""
    session = Session(SessionConfig(seed=1, beam_noise=False))
    try:
        driver = stand_up(session, 3)
        before = driver.robot.torso_yaw_deg()
        shuffle_in_place(driver, 0.0, 0.0, math.radians(8.0))
        assert driver.is_standing()
        assert driver.robot.torso_yaw_deg() - before == pytest.approx(8.0, abs=2.0)
    finally:
        session.close()


def _shuffle_targets(roll_deg: float, cycles: int) -> dict[str, float]:
    """The leg targets a fresh shuffle (3 cm forward, 1 cm left) writes on its ``cycles``-th
    cycle, every cycle seeing the torso rolled ``roll_deg``."""
    shuffle = FootShuffle(0, 0.03, 0.01)
    commands = JointCommands(0)
    for _ in range(cycles):
        commands.clear()
        shuffle.step(commands, roll_deg)
    return commands.targets()


@pytest.mark.parametrize(("gain", "single_support_only"), [(0.0, False), (0.3, False), (0.3, True)])
def test_the_shuffle_balance_tilts_only_the_support_ankles(monkeypatch, gain, single_support_only):
    """The shuffle's (off by default) balance: a foot on the ground rolls its ankle against the
    torso's roll by ``SHUFFLE_ANKLE_ROLL_GAIN`` (with ``SHUFFLE_SINGLE_SUPPORT_ONLY`` only while
    the other foot is up); a lifted foot does not, and nothing else moves."""
    monkeypatch.setattr(basic_kick_module, "SHUFFLE_ANKLE_ROLL_GAIN", gain)
    monkeypatch.setattr(basic_kick_module, "SHUFFLE_SINGLE_SUPPORT_ONLY", single_support_only)
    shift = round(0.5 * SHUFFLE_SHIFT_S / CYCLE_SECONDS)  # both feet down, the weight moving
    lifted = round((SHUFFLE_SHIFT_S + 0.5 * SHUFFLE_LIFT_S) / CYCLE_SECONDS)  # the left foot rising
    both = () if single_support_only else ("llj6", "rlj6")
    for cycles, moved in ((shift, both), (lifted, ("rlj6",))):
        upright, rolled = _shuffle_targets(0.0, cycles), _shuffle_targets(4.0, cycles)
        for joint, target in upright.items():
            expected = 4.0 * gain if joint in moved else 0.0
            assert rolled[joint] - target == pytest.approx(expected, abs=1e-9), joint


@pytest.mark.parametrize(
    "args", [(1.0, math.nan, "long"), (1.0, 2.0, "short"), (1.0, 2.0, -3.0), (1.0, 2.0, 0.0)]
)
def test_basic_kick_rejects_bad_arguments(args):
    with pytest.raises(ValueError):
        BasicKickSkill().validate(*args)


@pytest.mark.parametrize(("foot", "strength"), [("middle", 1.0), ("left", 1.5), ("right", -0.1)])
def test_kick_rejects_bad_arguments(foot, strength):
    with pytest.raises(ValueError):
        KickSkill().validate(foot, strength)


def test_kick_skill_writes_the_first_frame_and_finishes_after_the_motion():
    state = SimpleNamespace(
        robot_type=0,
        joints_deg=dict(get_pose("stand").joints),
        roll_deg=0.0,
        gyro_deg_s=(0.0, 0.0, 0.0),
    )
    commands = JointCommands(0)
    context = SimpleNamespace(world=SimpleNamespace(robot=state), commands=commands)
    skill = KickSkill()
    cycles = 0
    while True:
        commands.clear()
        cycles += 1
        if skill.step(context, "right", 1.0):
            break
    expected = kick_motion(0).sequence(1.0).duration
    assert cycles == round(expected / 0.02)


@pytest.mark.parametrize("release_s", [0.0, 0.6])
def test_the_one_leg_balance_fades_out_over_the_release_once_the_return_to_the_stand_starts(
    monkeypatch, release_s
):
    """The correction of the last balanced cycle is held at the last frame's start and fades
    linearly to none over BALANCE_RELEASE_S, whatever the torso does then (0: it stops at
    once); the support ankle and hip get it alike."""
    monkeypatch.setattr(kick_module, "BALANCE_RELEASE_S", release_s)
    sequence = kick_motion(0, aligned=True, long=True).sequence(0.3)
    balance = _OneLegBalance(sequence, mirror=False)
    start = sequence.frames[0].total
    end = sequence.duration - sequence.frames[-1].total

    def correction(elapsed: float, roll_deg: float) -> float:
        commands = JointCommands(0)
        commands.set_targets({"rlj6": 10.0, "rlj2": 5.0})
        balance.correct(commands, elapsed, roll_deg)
        targets = commands.targets()
        assert targets["rlj2"] - 5.0 == pytest.approx(targets["rlj6"] - 10.0)
        return targets["rlj6"] - 10.0

    assert correction(start, 1.0) == 0.0  # the reference roll
    last = correction(end - CYCLE_SECONDS, 3.0)
    assert last == pytest.approx(2.0 * BALANCE_GAIN)
    held = correction(end, 30.0)
    assert held == pytest.approx(last if release_s else 0.0)
    assert correction(end + 0.5 * release_s, -30.0) == pytest.approx(0.5 * held)
    assert correction(end + release_s, 30.0) == 0.0


@pytest.fixture(scope="module")
def left_kick():
    return run_trial("left", 1.0, seed=1)


@pytest.fixture(scope="module")
def right_kick():
    return run_trial("right", 1.0, seed=1)


@pytest.mark.parametrize("kick", ["left_kick", "right_kick"])
def test_full_kick_moves_the_ball_forwards_off_the_kicking_foot(kick, request):
    result = request.getfixturevalue(kick)
    assert not result.fell
    assert result.time_to_contact_s is not None
    assert result.distance_m > 1.0
    assert abs(result.direction_deg) < 20.0
    # the ball lay in front of the kicking foot: left of the centre line for the left foot
    assert (result.ball_side_m > 0.03) == (result.foot == "left")
    assert (result.ball_side_m < -0.03) == (result.foot == "right")


@pytest.fixture(scope="module")
def long_kicks() -> dict[str, KickMotion]:
    """Each foot's long kick as its plain kick, so that a stand kick plays it."""
    return {
        KICK_LEFT: kick_motion(0, None, "left", aligned=True, long=True),
        KICK_RIGHT: kick_motion(0, None, "right", aligned=True, long=True),
    }


@pytest.mark.parametrize("foot", FEET)
def test_full_long_kick_reaches_three_metres(foot, long_kicks):
    """The long kick plays after ``basic_kick``'s alignment shuffle (it was searched on such
    starts): after a shuffle of 2 cm forwards and 1 cm left at seed 1 it sends the ball 5.64 m
    with the left foot and 6.03 m with the right (the same motion mirrored, session 29; the right
    foot's own long kick went 4.26 m under 30 solver iterations) without falling, within 10 deg
    of its aim (``aim_deg``, mirrored for the right foot). From the rise alone both fell after
    contact (the left one since its support arm is raised). The plain stand kicks, tuned on the
    soft contacts' pushing foot, go 2.03 / 2.62 m on the bounce contacts (2.98 / 3.09 m before
    session 20)."""
    result = run_trial(foot, 1.0, seed=1, motions=long_kicks, shuffle_m=(0.02, 0.01))
    assert result.time_to_contact_s is not None
    assert not result.fell
    assert result.distance_m >= 3.0
    aim = long_kicks[KICK_LEFT if foot == "left" else KICK_RIGHT].aim_deg
    assert abs(result.direction_deg - (aim if foot == "left" else -aim)) < 10.0


def test_the_kick_search_starts_from_the_packaged_kick():
    """The search's parameterisation must reproduce ``kicks.yaml``, or its scores would not
    say how the packaged kick does."""
    searched, packaged = motions_for(start_parameters())[KICK_LEFT], kick_motion(0)
    assert searched.ball_gap_m == packaged.ball_gap_m
    assert searched.ball_side_m == packaged.ball_side_m
    for strength in (0.0, 1.0):
        pairs = zip(
            searched.sequence(strength).frames, packaged.sequence(strength).frames, strict=True
        )
        for mine, theirs in pairs:
            assert mine.duration == pytest.approx(theirs.duration, abs=2e-3)
            assert mine.hold == theirs.hold
            for joint, angle in theirs.joints.items():
                assert mine.joints[joint] == pytest.approx(angle, abs=0.05)


def test_a_written_candidate_loads_with_the_packaged_calibration(tmp_path):
    """``kick_search --write`` files feed ``benchmarks/kick.py --kicks``: they must load and
    carry the packaged distance table, so ``basic_kick`` asks the same strengths of them."""
    path = tmp_path / "candidate.yaml"
    write_candidate({**start_parameters(), "ball_gap_m": 0.012}, path)
    candidate, packaged = load_kicks(path)[KICK_LEFT], kick_motion(0)
    assert candidate.ball_gap_m == pytest.approx(0.012)
    assert candidate.distances == packaged.distances
    assert candidate.swing_duration(1.0) == pytest.approx(packaged.swing_duration(1.0))


def test_a_right_kick_written_beside_a_left_one_keeps_both(tmp_path):
    """A right-foot search (``kick_search --feet right``) writes its kick as
    ``kick_right_aligned`` into the left search's file (``--write-as``): both entries load and
    ``basic_kick`` then plays each foot's own."""
    path = tmp_path / "candidate.yaml"
    write_candidate({**start_parameters(), "ball_gap_m": 0.012}, path)
    write_candidate({**start_parameters(), "roll": 12.0}, path, "kick_right_aligned")
    kicks = load_kicks(path)
    assert kicks[KICK_LEFT].ball_gap_m == pytest.approx(0.012)
    assert set(kicks) == {KICK_LEFT, "kick_right_aligned"}
    assert kick_motion(0, kicks, "right", aligned=True) is kicks["kick_right_aligned"]
    assert kick_motion(0, kicks, "left", aligned=True) is kicks[KICK_LEFT]


def test_impact_measurement_sees_the_foot_push_the_ball_faster_than_it_moved_before():
    """Measured when written (left, strength 1, seed 1): foot 1.30 m/s the cycle before the
    ball moves, ball 3.14 m/s (the foot keeps pushing and speeds up to about 2.8 m/s), knee at
    its 352 deg/s cap, 2.98 m."""
    result = measure_impact("left", 1.0, seed=1)
    assert result.kick.time_to_contact_s is not None and not result.kick.fell
    assert 0.5 < result.foot_speed_m_s < result.ball_speed_m_s
    assert result.ball_speed_m_s < 2.0 * result.peak_striking_speed_m_s
    knee = result.joint_speeds_deg_s[1]
    assert knee > 300.0  # the knee extends at (about) its speed cap


def test_basic_kick_figures_are_medians_over_the_kicks_and_counts_of_the_rest(monkeypatch):
    outcomes = iter(
        [
            BasicKickResult(3.0, 2.0, -4.0, 8.0, "left"),
            BasicKickResult(3.0, 3.0, 1.0, 10.0, "right", fall_stage="after_contact"),
            BasicKickResult(3.0, 0.0, 0.0, None, None),
            BasicKickResult(3.0, 4.0, 2.0, 9.0, "left"),
        ]
    )
    monkeypatch.setattr(kick_benchmark, "run_basic_trial", lambda *a, **k: next(outcomes))
    figures = kick_benchmark.basic_kick_figures(4, 0, 3.0)
    assert figures == {
        "basic_kick_distance_m": 3.0,
        "basic_kick_distance_error_m": 1.0,  # |2 - 3|, |3 - 3|, |4 - 3|: the median is not 0
        "basic_kick_direction_error_deg": 2.0,
        "basic_kick_time_s": 9.0,
        "basic_kick_falls": 1.0,
        "basic_kick_misses": 1.0,
        "basic_kick_falls_before_kick": 0.0,
        "basic_kick_falls_before_contact": 0.0,
        "basic_kick_falls_after_contact": 1.0,
        "basic_kick_falls_after_kick": 0.0,
    }


@pytest.mark.parametrize(
    ("phase", "contact", "stage"),
    [
        ("approach", False, "before_kick"),
        ("head_up", False, "before_kick"),
        ("kick", False, "before_contact"),
        ("kick", True, "after_contact"),
        ("done", True, "after_kick"),
    ],
)
def test_a_fall_is_placed_by_the_phase_and_whether_the_ball_was_kicked(phase, contact, stage):
    assert kick_benchmark.fall_stage(phase, contact) == stage


def test_a_shuffle_start_moves_the_standing_robot_by_the_asked_amount():
    """Kick trials may start from the alignment shuffle's stance (as after an approach); the
    start is only that if the shuffle really moved the robot and left it standing."""
    session = Session(SessionConfig(seed=1, beam_noise=False))
    try:
        driver = stand_up(session, 0)
        before = driver.robot.torso_position()
        shuffle_in_place(driver, 0.03, -0.02)  # START faces +x: forward = +x, left = +y
        after = driver.robot.torso_position()
        assert driver.is_standing()
        assert after[0] - before[0] == pytest.approx(0.03, abs=0.015)
        assert after[1] - before[1] == pytest.approx(-0.02, abs=0.015)
    finally:
        session.close()


def test_a_basic_trial_lets_a_started_kick_end_after_the_time_limit():
    """The 20 s limit stops the approach, never a kick mid-motion: cut off on one leg, the
    robot fell, and the benchmark counted it as the kick's fall (session 11: 2 of 40 trials)."""
    goes_on = kick_benchmark._basic_trial_goes_on
    limit = kick_benchmark.BASIC_KICK_TIMEOUT_CYCLES
    assert goes_on(limit - 1, "approach") and goes_on(limit - 1, "kick")
    assert not goes_on(limit, "approach") and not goes_on(limit, "head_up")
    assert goes_on(limit, "kick") and goes_on(limit + 100, "kick")
    assert not goes_on(limit + kick_benchmark.BASIC_KICK_FINISH_CYCLES, "kick")


def test_weak_kick_keeps_the_robot_up():
    result = run_trial("left", 0.0, seed=2)
    assert not result.fell
    assert result.time_to_contact_s is not None and math.isfinite(result.distance_m)


#: Basic-kick layouts in the tests: the benchmark's first trials (``benchmarks/kick.py
#: --layout-seed 0``), the ball 0.5-2 m away at a random bearing. Twelve, because one layout
#: says little: which trial falls or lands short is chaotic (numpy's AVX-512 paths round
#: sin/cos differently in the last bit, and on an AVX-512 machine the three hand-picked layouts
#: of sessions 10-14 fell twice after contact where a machine without it had kicked all three).
BASIC_TEST_TRIALS = 12


@pytest.fixture(scope="module")
def basic_kicks() -> list[BasicKickResult]:
    layouts = basic_layouts(BASIC_TEST_TRIALS, seed=0)
    return [run_basic_trial("long", k, *layout) for k, layout in enumerate(layouts)]


def test_basic_kick_walks_lines_up_and_kicks_towards_the_target(basic_kicks):
    """Most layouts end in a kick within the trial's 20 s, and every kick that kept the robot
    up sends the ball towards the target. Measured when written (session 15, layouts of seed
    0): 10 and 11 of 12 kicked on an AVX-512 EPYC with and without numpy's AVX-512 paths; the
    kicks that stayed up erred by at most 8.7 and 13.8 deg."""
    kicked = [r for r in basic_kicks if r.time_to_kick_s is not None]
    assert len(kicked) >= 9, basic_kicks
    for result in kicked:
        if not result.fell:
            assert result.distance_m > 1.8, result
            assert abs(result.direction_error_deg) < 20.0, result


def test_basic_kick_falls_in_fewer_than_half_of_the_trials(basic_kicks):
    """Issue 4 wants no falls; the basic kick falls in about 1 of 4 trials (``python -m
    benchmarks.kick --strengths --basic-trials 20 --basic-distance 3``: 8 and 3 of 20 on layout
    seeds 0 and 1 on this session's machine), mostly after the contact. This asks for what
    holds, so that more falls turn it red: 3 and 5 of 12 when written."""
    assert sum(r.fell for r in basic_kicks) <= BASIC_TEST_TRIALS // 2, basic_kicks


def test_basic_kick_moves_the_ball_three_metres(basic_kicks):
    """Issue 4: a basic kick moves the ball at least 3 m. It does in many trials, not in all:
    the median kick is about 3 m (session 15: 3.01 / 2.75 m over these layouts, with and
    without numpy's AVX-512 paths; the benchmark's 20 layouts 2.94-3.18 m). Here at least a
    third of the layouts go 3 m or more (7 and 5 of 12 when written) and the median kick at
    least 2.5 m."""
    kicked = [r.distance_m for r in basic_kicks if r.time_to_kick_s is not None]
    assert sum(d >= 3.0 for d in kicked) >= BASIC_TEST_TRIALS // 3, basic_kicks
    assert float(np.median(kicked)) >= 2.5, basic_kicks


@pytest.mark.parametrize(("robot_type", "shift"), [(1, -1), (3, 1)])
def test_types_1_and_3_shift_their_weight_differently_and_are_otherwise_type_0s(robot_type, shift):
    """With type 0's weight shift (13.5 deg of hip roll) type 3's basic kicks fell 18 of 20 and
    type 1's 8 of 20 (session 29); type 3 (wider stance) shifts further (16.5 deg: none of 20),
    type 1 (longer legs) less (12.0 deg: 1 of 20). Only the shift differs from type 0's motion;
    their distance tables are their own (session 30)."""
    for long in (False, True):
        common = kick_motion(0, None, "left", aligned=True, long=long)
        own = kick_motion(robot_type, None, "left", aligned=True, long=long)
        assert own.name == f"{common.name}_type{robot_type}"
        difference = own.frames.frames[0].joints["llj2"] - common.frames.frames[0].joints["llj2"]
        assert shift * difference >= 1.0
        assert own.frames.frames[1:] == common.frames.frames[1:]
        assert own.swing_frames == common.swing_frames and own.distances != common.distances
        assert kick_motion(robot_type, None, "right", aligned=True, long=long) is own


@pytest.mark.parametrize("foot", FEET)
def test_type_4_never_plays_the_weak_long_swing_that_it_falls_from(foot):
    """Type 4's long kick fell in 31 / 46 of 80 basic kicks asked 3.5 / 4.0 m at strength 0.1 /
    0.21 of type 0's table, and in none of 200 at 0.25 (session 35): its table starts at 0.25,
    so shorter requests get that swing, and the rest of the table is type 0's."""
    own = kick_motion(4, None, foot, aligned=True, long=True)
    common = kick_motion(0, None, foot, aligned=True, long=True)
    assert min(strength for strength, _ in own.distances) == 0.25
    assert strength_for(own, 3.2) == 0.25
    assert strength_for(common, 3.7) < 0.25
    assert own.distances[1:] == tuple(d for d in common.distances if d[0] > 0.25)


@pytest.mark.parametrize(("foot", "seed"), [("left", 0), ("right", 1)])
def test_type_4_kicks_with_its_toe_flat_and_the_ball_a_toe_further(foot, seed):
    """Type 4's toes stand curled up (70 deg); curled, the toe met the ball and a full-strength
    stand kick went 1.43 m (session 30). Its kicks lay the kicking toe flat through the swing
    (the right foot's by the mirror table) and want the ball a toe's length further ahead:
    2.56 / 2.58 m for these two kicks when written."""
    for aligned, long in ((False, False), (True, False), (True, True)):
        motion = kick_motion(4, None, foot, aligned=aligned, long=long)
        common = kick_motion(0, None, foot, aligned=aligned, long=long)
        assert motion.name == f"{common.name}_type4"
        assert motion.ball_gap_m == pytest.approx(common.ball_gap_m + 0.0355)
        assert motion.frames.frames[1].joints["llj7"] == 0.0
    result = run_trial(foot, 1.0, seed=seed, robot_type=4)
    assert not result.fell
    assert result.distance_m > 2.2, result


def test_type_4_walks_far_enough_in_not_to_back_off():
    """Type 4's walk sets its soles further back than type 0's, so its torso settles further
    back when it stands after the walk; with type 0's overshoot its first settle found the ball
    6-7 cm too far ahead and it backed off to walk in again (8 of 20 layouts, this one among
    them: session 30). Sent further beyond the spot, it only shuffles."""
    phases: set[str] = set()
    layout = basic_layouts(2, seed=0)[1]
    result = run_basic_trial(2.0, 1, *layout, robot_type=4, observe=lambda _, p: phases.add(p))
    assert result.time_to_kick_s is not None and not result.fell, result
    assert "back_off" not in phases and "shuffle" in phases, phases


def test_the_shuffle_shifts_the_weight_as_far_towards_the_support_foot_on_every_type():
    """Type 3 stands on feet 0.146 m apart (the others 0.11 m); with the others' 0.045 m shift
    its weight stayed partly on the foot it lifted and its shuffles moved it by about 40 % of
    what they asked in basic kicks (session 30). Every type now moves its torso the same share
    of the way to the support foot, and the first stage of a shuffle does so."""
    shares = set()
    for robot_type in ROBOT_TYPES:
        feet = basic_kick_module._stand_feet(robot_type)
        half_spacing = abs(feet["left"][0, 3] - feet["right"][0, 3]) / 2.0
        shares.add(round(shuffle_weight_shift(robot_type) / half_spacing, 6))
    assert len(shares) == 1
    shift = shuffle_weight_shift(3)
    assert shift > basic_kick_module.SHUFFLE_WEIGHT_SHIFT_M + 0.01
    assert abs(shuffle_stages(0.03, 0.0, shift)[0].torso[1]) == pytest.approx(shift)


def test_the_long_kick_aims_per_strength_and_bad_aim_tables_are_refused():
    """The long kick's weakest swings send the ball 8-9 deg further out than its full swing
    (session 30): basic_kick faces further away for them (``aims``), and the table is checked
    like the distance tables."""
    long = kick_motion(0, None, "left", aligned=True, long=True)
    assert long.aim_for(0.1) > long.aim_for(1.0) + 5.0
    assert long.aim_for(0.0) == long.aim_for(0.1)  # clipped to the table's ends
    short = kick_motion(0, None, "left", aligned=True)
    assert short.aim_for(0.5) == short.aim_deg
    entry = {
        "frames": [{"duration": 0.2, "pose": "stand"}, {"duration": 0.2, "pose": "stand"}],
        "swing": {"frames": [1], "fast_s": 0.2, "slow_s": 0.4},
        "aims": [[0.5, 10.0], [0.2, 12.0]],
    }
    with pytest.raises(PoseError, match="aims: strengths must increase"):
        parse_kicks({"kick_left": entry}, "test")


def test_the_approach_searches_for_a_ball_not_where_it_was_last_seen():
    """A ball estimate in view that vision does not confirm is stale (the ball was moved while
    out of view): the approach stops walking to it and searches until it sees the ball again
    (session 30: basic kicks asked 3 m, layout seeds 0-1, mean time to kick 13.3 -> 12.2 s,
    the slowest tenth 17.8 -> 14.1 s). Estimates out of view, or at the robot's feet, are
    trusted."""
    skill = BasicKickSkill()

    def world(since_seen: float, bearing: float, distance: float) -> SimpleNamespace:
        ball = SimpleNamespace(time_since_seen=since_seen, position=(1.0, 0.0))
        return SimpleNamespace(
            ball=ball, bearing_to=lambda _: bearing, distance_to=lambda _: distance
        )

    assert not skill._searching(world(0.1, 0.0, 1.0))  # seen lately
    assert not skill._searching(world(5.0, 120.0, 1.0))  # out of view: may be right
    assert not skill._searching(world(5.0, 0.0, 0.3))  # at the feet, below the view
    assert skill._searching(world(5.0, 10.0, 1.0))
    assert skill._searching(world(5.0, 150.0, 1.0))  # keeps searching as it turns away
    assert skill._searching(world(5.0, 150.0, 1.0))
    assert not skill._searching(world(0.05, 150.0, 1.0))  # seen again
    skill.reset()
    assert skill._search_cycles is None
