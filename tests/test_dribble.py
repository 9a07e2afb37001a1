"""The dribble-long gaits: controller law, parameters, mirror, and short runs in the simulator."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, replace

import numpy as np
import pytest

from behaviors.dribble import (
    DRIBBLE_KINDS,
    DribbleGait,
    DribbleInputs,
    DribbleSkill,
    _mirrored_robot,
    ball_in_front,
    ball_within_reach,
    dribble_gait,
    dribble_velocity,
    dribble_walk_parameters,
    recovery_velocity,
    still_turning,
    touch_step_cap,
)
from behaviors.joint_control import JointCommands
from behaviors.mirror import mirror_joint_angles
from behaviors.skill import SkillContext
from world.nao_model import ROBOT_TYPES
from world.perception import CYCLE_SECONDS
from world.robot_state import RobotState

GAIT = DribbleGait()


def _inputs(x=0.2, y=0.0, heading_error=0.0) -> DribbleInputs:
    return DribbleInputs(x, y, 0.0, 0.0, heading_error)


# ------------------------------------------------------------------ the control law
def test_ball_on_the_line_walks_straight_at_the_gait_speed():
    vx, vy, turn = dribble_velocity(_inputs(GAIT.ball_ahead, GAIT.ball_side), GAIT)
    assert vx == pytest.approx(GAIT.speed)
    assert vy == pytest.approx(0.0)
    assert turn == pytest.approx(0.0)


@pytest.mark.parametrize("sign", (1.0, -1.0))
def test_ball_off_the_line_steps_towards_it_and_slows_down(sign):
    vx, vy, _ = dribble_velocity(_inputs(GAIT.ball_ahead, sign * 0.05), GAIT)
    assert vy * sign > 0.0
    assert vx < GAIT.speed


def test_ball_rolled_ahead_speeds_up_and_out_of_reach_only_catches_up():
    near, _, _ = dribble_velocity(_inputs(GAIT.ball_ahead), GAIT)
    ahead, _, _ = dribble_velocity(_inputs(GAIT.ball_ahead + 0.1), GAIT)
    assert ahead > near
    gone = _inputs(GAIT.reach_max_ahead + 0.5)
    assert not ball_within_reach(gone, GAIT)
    far_vx, _, _ = dribble_velocity(gone, GAIT)
    assert far_vx == pytest.approx(min(GAIT.max_speed, GAIT.ahead_gain * (gone.ball_x - 0.2)))


def test_catch_up_ahead_slows_for_a_near_ball_and_keeps_the_ball_place():
    """``catch_up_ahead`` (LFDL since session 20): the catch-up term aims for a ball that far
    ahead, so a ball at ``ball_ahead`` slows the robot by ``ahead_gain`` per metre short of it,
    while the place the ball is lined up at (and walked round to) stays ``ball_ahead``."""
    slowing = dataclasses.replace(GAIT, ahead_gain=1.0, catch_up_ahead=GAIT.ball_ahead + 0.15)
    plain, _, _ = dribble_velocity(_inputs(GAIT.ball_ahead, GAIT.ball_side), GAIT)
    slowed, _, _ = dribble_velocity(_inputs(GAIT.ball_ahead, GAIT.ball_side), slowing)
    assert slowed == pytest.approx(max(plain - 0.15, slowing.min_speed))
    assert dataclasses.replace(GAIT, catch_up_ahead=None) == GAIT
    assert dribble_gait("lfdl", 0).catch_up_ahead == pytest.approx(0.4)
    assert dribble_gait("lfdl", 0).ball_ahead < dribble_gait("lfdl", 0).catch_up_ahead


def test_ball_behind_never_walks_on_over_it():
    """A ball behind the torso is walked round: backwards, never forwards away from it."""
    vx, _, _ = dribble_velocity(_inputs(-0.1), GAIT)
    assert vx < 0.0


@pytest.mark.parametrize("sign", (1.0, -1.0))
def test_ball_beside_is_walked_round_on_its_own_side(sign):
    """A ball beside the robot (level with the torso): the robot steps back and away from it,
    so that its feet pass the ball with room to spare, then comes in behind it."""
    beside = _inputs(0.0, sign * 0.12)
    assert not ball_in_front(beside, GAIT)
    vx, vy, turn = dribble_velocity(beside, GAIT)
    assert vx < 0.0
    assert vy * sign < 0.0  # away from the ball's side
    assert turn == pytest.approx(0.0)
    behind_it = _inputs(0.15, sign * 0.2)  # off to the side, a little ahead: step in behind it
    assert not ball_in_front(behind_it, GAIT)
    vx, vy, _ = recovery_velocity(behind_it, GAIT)
    assert -0.15 < vx <= 0.0
    assert vy * sign > 0.0


def test_a_ball_far_behind_is_walked_to_facing_the_way():
    """Half a metre and more away, the robot turns towards its way round the ball and walks
    it forwards (sidestepping that far takes seconds); it does not step off before facing it."""
    vx, vy, turn = recovery_velocity(_inputs(-0.8, 0.0), GAIT)
    assert turn == pytest.approx(GAIT.max_turn_deg)  # the way lies behind-left: turn left
    assert vx == pytest.approx(0.0, abs=1e-9)
    assert vy == pytest.approx(0.0, abs=1e-9)
    # the direction to dribble lies behind, the ball 0.8 m ahead: walk on to pass it by its
    # side (here its right), nearly straight ahead
    vx, vy, turn = recovery_velocity(DribbleInputs(0.8, 0.0, 0.0, 0.0, 180.0), GAIT)
    assert vx > 0.8 * GAIT.recover_speed
    assert vy == pytest.approx(0.0, abs=1e-9)
    assert -30.0 < turn < 0.0


def test_a_far_ball_is_fetched_when_the_direction_turns_sharply():
    """The ball rolled 0.8 m ahead and the direction turns round: with fetch_distance set, the
    robot walks to the ball's side (recovery law) instead of turning on the spot, where the
    ball drifted out of the front and the two laws took turns (LFDL stalled for 12 s)."""
    far = DribbleInputs(0.8, 0.0, 0.0, 0.0, 170.0)
    fetching = replace(GAIT, fetch_distance=0.5)
    assert dribble_velocity(far, fetching) == pytest.approx(recovery_velocity(far, fetching))
    vx, _, _ = dribble_velocity(far, fetching)
    assert vx > 0.5 * GAIT.recover_speed  # walks on towards it
    orbiting = replace(GAIT, ahead_gain=0.0)  # LFDL's law: no catch-up, it turns on the spot
    assert dribble_velocity(far, orbiting)[0] == pytest.approx(GAIT.min_speed)
    # near, or with the heading about right, the dribble law as before
    near = DribbleInputs(0.3, 0.0, 0.0, 0.0, 170.0)
    assert dribble_velocity(near, fetching) == pytest.approx(dribble_velocity(near, GAIT))
    ahead = DribbleInputs(0.8, 0.0, 0.0, 0.0, 10.0)
    assert dribble_velocity(ahead, fetching) == pytest.approx(dribble_velocity(ahead, GAIT))


def test_ball_in_front_window():
    assert ball_in_front(_inputs(GAIT.ball_ahead, GAIT.ball_side), GAIT)
    assert not ball_in_front(_inputs(GAIT.reach_min_ahead - 0.01), GAIT)
    # off the line, the ball must lie further ahead to count as in front
    off = GAIT.reach_side + 0.1
    assert not ball_in_front(_inputs(GAIT.reach_min_ahead + 0.05, off), GAIT)
    assert ball_in_front(_inputs(GAIT.reach_min_ahead + 0.15, off), GAIT)


def test_turning_left_steps_right_to_orbit_the_ball():
    vx, vy, turn = dribble_velocity(_inputs(GAIT.ball_ahead, 0.0, 20.0), GAIT)
    assert turn > 0.0
    assert vy < 0.0
    assert vx < GAIT.speed


def test_a_sharp_turn_circles_the_ball_instead_of_walking_through_it():
    """Dribbling on at 90 degrees to the left of the heading: the ball belongs ahead-left, so
    the robot turns left and steps right around the ball; it never heads straight at it."""
    vx, vy, turn = dribble_velocity(_inputs(GAIT.ball_ahead, 0.0, 90.0), GAIT)
    assert turn > 0.0
    assert vy < 0.0
    assert abs(vy) > 0.5 * abs(vx)


def test_pursuit_turns_towards_a_ball_off_the_line_instead_of_stepping_sideways():
    """With pursuit on, a ball ahead-left turns the robot left (no orbit step to the right
    for it); with it off the robot only steps left."""
    ball_left = _inputs(0.3, 0.05)
    _, vy_off, turn_off = dribble_velocity(ball_left, GAIT)
    assert turn_off == pytest.approx(0.0) and vy_off > 0.0
    gait = replace(GAIT, pursuit_share=1.0, pursuit_max_deg=5.0)
    _, vy_on, turn_on = dribble_velocity(ball_left, gait)
    assert turn_on == pytest.approx(GAIT.turn_gain * 5.0)  # capped at pursuit_max_deg
    assert vy_on == pytest.approx(vy_off)
    # turning to a new direction (beyond the dead band) has its own law: no pursuit
    turning = DribbleInputs(0.3, 0.05, 0.0, 0.0, 40.0)
    assert dribble_velocity(turning, gait) == pytest.approx(dribble_velocity(turning, GAIT))


def test_a_near_rolling_ball_is_not_chased():
    """A ball nearer than ball_ahead is not followed at its speed: the robot would tread on it."""
    gait = replace(GAIT, follow_gain=1.0)
    still = dribble_velocity(_inputs(0.15), gait)[0]
    rolling = dribble_velocity(DribbleInputs(0.15, 0.0, 0.8, 0.0, 0.0), gait)[0]
    ahead_rolling = dribble_velocity(DribbleInputs(0.22, 0.0, 0.1, 0.0, 0.0), gait)[0]
    assert rolling == pytest.approx(still)
    assert ahead_rolling > dribble_velocity(_inputs(0.22), gait)[0]


def test_a_ball_within_the_corridor_counts_as_on_the_line():
    """DFDL's ball swings between the feet: within ball_corridor of the line the robot walks
    on at full speed without sidestepping or turning; beyond it only the excess counts."""
    gait = replace(GAIT, ball_corridor=0.03, pursuit_share=1.0, pursuit_max_deg=10.0)
    on_line = dribble_velocity(_inputs(GAIT.ball_ahead, 0.0), gait)
    for side in (0.03, -0.025):
        assert dribble_velocity(_inputs(GAIT.ball_ahead, side), gait) == pytest.approx(on_line)
    _, vy, turn = dribble_velocity(_inputs(GAIT.ball_ahead, 0.05), gait)
    _, vy_plain, _ = dribble_velocity(
        _inputs(GAIT.ball_ahead, 0.02), replace(gait, ball_corridor=0)
    )
    assert vy == pytest.approx(vy_plain) and vy > 0.0 and turn > 0.0
    # turning to a new direction: no corridor (a ball beside the line tripped the robot)
    turning = DribbleInputs(0.3, 0.03, 0.0, 0.0, 40.0)
    assert dribble_velocity(turning, gait) == pytest.approx(
        dribble_velocity(turning, replace(gait, ball_corridor=0.0))
    )


def test_coming_out_of_a_sharp_turn_is_slower_until_settled():
    gait = replace(GAIT, speed=0.9, max_speed=0.9, turning_max_speed=0.6, turn_settled_deg=5.0)
    near = DribbleInputs(0.2, 0.0, 0.0, 0.0, 8.0)
    assert not still_turning(False, near, gait)  # never turned: a small error is no turn
    assert still_turning(False, replace(near, heading_error_deg=25.0), gait)
    assert still_turning(True, near, gait)  # 8 deg: not yet settled
    aligned_near = replace(near, heading_error_deg=2.0)
    assert still_turning(True, aligned_near, gait)  # the ball still near: not yet
    assert not still_turning(True, replace(aligned_near, ball_x=0.3), gait)
    on_line = DribbleInputs(GAIT.ball_ahead + 0.1, 0.0, 0.0, 0.0, 0.0)
    assert dribble_velocity(on_line, gait)[0] > 0.6
    assert dribble_velocity(replace(on_line, turning=True), gait)[0] == pytest.approx(0.6)


def test_a_tilting_robot_calms_down():
    gait = replace(GAIT, tilt_calm_deg=8.0, tilt_calm_range_deg=10.0, calm_min_share=0.3)
    upright = dribble_velocity(DribbleInputs(0.2, 0.05, 0.0, 0.0, 10.0, 2.0), gait)
    rocking = dribble_velocity(DribbleInputs(0.2, 0.05, 0.0, 0.0, 10.0, 30.0), gait)
    assert rocking == pytest.approx(tuple(0.3 * v for v in upright))


def test_the_touch_planner_lands_the_toe_just_past_the_ball_and_is_off_by_default():
    """``touch_step_cap``: the touching leg's step is capped so that its toe, landing
    ``touch_reach + 1.5 step`` ahead of the torso, meets the ball's back (plus the push) only as
    the swing ends; a rolling ball is met where it will be; never below the shortest step; off
    (None) unless set, for a ball off the toe's line and while turning."""
    assert touch_step_cap(_inputs(0.25, 0.0), GAIT, 0.16) is None  # default: off
    gait = replace(GAIT, touch_reach=0.14, touch_push=0.01, touch_min_step=0.05)
    cap = touch_step_cap(_inputs(0.4, 0.0), gait, 0.16)
    assert cap is not None
    assert gait.touch_reach + 1.5 * cap == pytest.approx(0.4 - 0.042 + 0.01)
    rolling = DribbleInputs(0.4, 0.0, 0.5, 0.0, 0.0)
    assert touch_step_cap(rolling, gait, 0.16) == pytest.approx(cap + 0.5 * 0.16 / 1.5)
    assert touch_step_cap(_inputs(0.2, 0.0), gait, 0.16) == gait.touch_min_step
    off_line = _inputs(0.4, gait.ball_side + gait.reach_side + 0.02)
    assert touch_step_cap(off_line, gait, 0.16) is None
    turning = _inputs(0.4, 0.0, heading_error=gait.placement_deadband_deg + 5.0)
    assert touch_step_cap(turning, gait, 0.16) is None
    assert touch_step_cap(replace(_inputs(0.4, 0.0), turning=True), gait, 0.16) is None


def test_touch_legs_must_be_left_or_both(tmp_path):
    from benchmarks.dribble import with_settings

    path = with_settings(["lfdl.controller.default.touch_legs=right"], tmp_path)
    with pytest.raises(ValueError, match="touch_legs"):
        dribble_gait("lfdl", 0, path)
    assert dribble_gait("dfdl", 0).touch_legs == "both"
    assert dribble_gait("lfdl", 0).touch_legs == "left"


def test_within_reach_window():
    assert ball_within_reach(_inputs(0.2, 0.0), GAIT)
    assert not ball_within_reach(_inputs(0.05, 0.0), GAIT)
    assert not ball_within_reach(_inputs(0.2, GAIT.reach_side + 0.01), GAIT)
    lfdl = dribble_gait("lfdl", 0)
    assert ball_within_reach(_inputs(lfdl.ball_ahead, lfdl.ball_side), lfdl)


def test_inputs_mirror_is_an_involution_and_negates_lateral_values():
    inputs = DribbleInputs(0.2, 0.03, 0.4, -0.1, 12.0)
    assert inputs.mirrored().mirrored() == inputs
    assert inputs.mirrored() == DribbleInputs(0.2, -0.03, 0.4, 0.1, -12.0)


# ------------------------------------------------------------------ parameters
@pytest.mark.parametrize("kind", DRIBBLE_KINDS)
@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_every_type_and_kind_has_parameters(kind, robot_type):
    gait = dribble_gait(kind, robot_type)
    walk = dribble_walk_parameters(kind, robot_type)
    assert gait.reach_min_ahead < gait.ball_ahead < gait.reach_max_ahead
    assert gait.min_speed <= gait.speed <= gait.max_speed
    assert walk.step.step_cycles == 8  # the 16 phases of the thesis
    # the dribbles keep the ball beyond the 2023 holding radius (0.12 m) by design
    assert gait.ball_ahead > 0.12


def test_lfdl_keeps_the_ball_further_out_and_to_the_left():
    """LFDL's ball lies out in front of the left foot; DFDL's between the feet's paths, since
    the sixth round as far ahead as LFDL's (0.24 m: clear of the landing toes)."""
    dfdl, lfdl = dribble_gait("dfdl", 0), dribble_gait("lfdl", 0)
    assert lfdl.ball_ahead >= dfdl.ball_ahead
    assert lfdl.ball_side > 0.0 == dfdl.ball_side


def test_unknown_kind_foot_and_type_are_rejected():
    skill = DribbleSkill()
    with pytest.raises(ValueError, match="kind"):
        skill.validate("cfdl", 0.0)
    with pytest.raises(ValueError, match="foot"):
        skill.validate("dfdl", 0.0, "middle")
    with pytest.raises(ValueError, match="finite"):
        skill.validate("dfdl", math.nan)
    with pytest.raises(ValueError, match="robot type"):
        dribble_gait("dfdl", 7)


# ------------------------------------------------------------------ the mirror
@dataclass
class _Pose:
    x: float
    y: float
    heading_deg: float


@dataclass
class _Ball:
    velocity: tuple[float, float]


@dataclass
class _World:
    """The parts of a world model the dribble reads."""

    robot: RobotState
    pose: _Pose
    ball: _Ball
    ball_relative_ego: np.ndarray
    localizer: None = None


def _robot(rng: np.random.Generator) -> RobotState:
    robot = RobotState(0)
    names = JointCommands(0).joint_names
    robot.joints_deg = {n: float(rng.uniform(-20, 20)) for n in names}
    robot.gyro_deg_s = rng.normal(0, 10, 3)
    robot.up = np.array([0.05, -0.08, 0.99]) / np.linalg.norm([0.05, -0.08, 0.99])
    return robot


def _world(robot, heading, ball_y, ball_vy) -> _World:
    return _World(robot, _Pose(0.0, 0.0, heading), _Ball((0.3, ball_vy)), np.array([0.2, ball_y]))


def test_right_footed_dribble_is_the_mirror_image_of_the_left_footed_one():
    """Same situation mirrored (body readings, ball, heading and direction): the right-footed
    LFDL sends exactly the mirrored joint speeds of the left-footed one, cycle after cycle."""
    rng = np.random.default_rng(3)
    left, right = DribbleSkill(), DribbleSkill()
    for _ in range(20):
        robot = _robot(rng)
        heading, ball_y, ball_vy = rng.uniform(-30, 30), rng.uniform(0, 0.1), rng.normal(0, 0.2)
        commands = {foot: JointCommands(0) for foot in ("left", "right")}
        world_left = _world(robot, heading, ball_y, ball_vy)
        world_right = _world(_mirrored_robot(robot), -heading, -ball_y, -ball_vy)
        left.step(SkillContext(world_left, commands["left"], None), "lfdl", 10.0, "left")
        right.step(SkillContext(world_right, commands["right"], None), "lfdl", -10.0, "right")
        expected = mirror_joint_angles(commands["left"].speeds())
        assert commands["right"].speeds() == pytest.approx(expected, abs=1e-9)
        t, left_active = left.phase
        assert right.phase == (t, not left_active)
        assert right.gait_phase == left.phase


def test_mirrored_robot_state_is_an_involution():
    robot = _robot(np.random.default_rng(0))
    twice = _mirrored_robot(_mirrored_robot(robot))
    assert twice.joints_deg == pytest.approx(robot.joints_deg)
    assert twice.gyro_deg_s == pytest.approx(robot.gyro_deg_s)
    assert twice.up == pytest.approx(robot.up)
    assert _mirrored_robot(robot).roll_deg == pytest.approx(-robot.roll_deg)
    assert _mirrored_robot(robot).pitch_deg == pytest.approx(robot.pitch_deg)


# ------------------------------------------------------------------ in the simulator
pybullet = pytest.importorskip("pybullet")

from benchmarks.dribble import dribble_to_phase, start_dribble_episode  # noqa: E402

#: One second and a half: the robot reaches the ball (0.3 m) and touches it a few times.
SHORT_RUN_CYCLES = 90
#: A ball this close to a robot body (m) at the end of a cycle touched it during the cycle.
NEAR_CONTACT = 0.02


@dataclass
class _ShortRun:
    phases: list[tuple[int, bool]]
    ball_start: np.ndarray
    ball_end: np.ndarray
    #: robot link names that touched the ball
    touched: set[str]
    #: cycles where the ball sped up, and whether the robot touched it then
    speed_ups: list[bool]
    fell: bool


def _short_run(
    kind: str,
    foot: str,
    skill_name: str = "dribble",
    cycles: int = SHORT_RUN_CYCLES,
    seed: int = 0,
) -> _ShortRun:
    session, agent = start_dribble_episode(0, 0.0, seed=seed)
    try:
        ball = session.ball
        client = session.world.client
        start = np.array(ball.position())
        phases, touched, speed_ups = [], set(), []
        speed = ball.speed()
        for _ in range(cycles):
            if skill_name == "dribble":
                agent.run("dribble", kind, 0.0, foot)
            else:
                agent.run("walk_velocity", 0.3, 0.0, 0.0)
            phases.append(agent.behavior.skill(skill_name).phase)
            contacts = pybullet.getContactPoints(
                bodyA=ball.body_id, bodyB=agent.robot.body_id, physicsClientId=client
            )
            touched |= {agent.robot.link_name(c[4]) for c in contacts}
            # a touch may end within the cycle's physics substeps: "touching" here is within
            # NEAR_CONTACT of a robot body at the cycle's end, plus the way the ball can have
            # rolled since (its speed for one cycle: session 23's faster LFDL swing sends it
            # off at up to 2 m/s, 4 cm in a cycle)
            new_speed = ball.speed()
            reach = NEAR_CONTACT + new_speed * CYCLE_SECONDS
            near = pybullet.getClosestPoints(
                ball.body_id, agent.robot.body_id, reach, physicsClientId=client
            )
            if new_speed > speed + 0.02:
                speed_ups.append(bool(near))
                # under the bounce contacts a push can begin and end inside one cycle: the
                # links near the ball in a cycle where it sped up pushed it
                touched |= {agent.robot.link_name(c[4]) for c in near}
            speed = new_speed
        return _ShortRun(
            phases, start, np.array(ball.position()), touched, speed_ups, agent.robot.has_fallen()
        )
    finally:
        session.close()


def _assert_phase_sequence(phases: list[tuple[int, bool]]) -> None:
    """t runs 0..7 cycle by cycle and the swinging leg changes with every step."""
    steps = [phases[i : i + 8] for i in range(0, len(phases) - len(phases) % 8, 8)]
    assert len(steps) >= 8
    for k, step in enumerate(steps):
        assert [t for t, _ in step] == list(range(8))
        assert len({left for _, left in step}) == 1
        if k:
            assert step[0][1] != steps[k - 1][0][1]


def test_walk_phase_sequence():
    run = _short_run("", "left", skill_name="walk_velocity")
    _assert_phase_sequence(run.phases)


def test_dribble_turns_with_the_ball_to_a_new_direction():
    """One second straight on, then the direction turns 90 degrees to the left: the robot
    walks around the ball and takes it along the new direction, without falling. Within 9 s:
    at session 7's full DFDL speed the ball lies 0.5 m ahead when the direction turns and
    rolls on to 1.1 m, and orbiting it takes longer (0.57 m along the new direction after
    9 s on seed 0, -0.03 after 6 s; session 6's slower gait: 1.22 m and 0.37 m)."""
    session, agent = start_dribble_episode(0, 0.0, seed=0)
    try:
        for _ in range(50):
            agent.run("dribble", "dfdl", 0.0, "left")
        turned_from = np.array(session.ball.position())
        for _ in range(450):
            agent.run("dribble", "dfdl", 90.0, "left")
            assert not agent.robot.has_fallen()
        moved = np.array(session.ball.position()) - turned_from
        assert moved[1] > 0.3
        assert agent.robot.torso_yaw_deg() == pytest.approx(90.0, abs=30.0)
        tx, ty, _ = agent.robot.torso_position()
        bx, by, _ = session.ball.position()
        assert math.hypot(bx - tx, by - ty) < 1.0  # still within the dribble's reach
    finally:
        session.close()


@pytest.mark.parametrize(("kind", "foot"), [("dfdl", "left"), ("lfdl", "left"), ("lfdl", "right")])
def test_short_dribble_moves_the_ball_forward_by_contact_only(kind, foot):
    run = _short_run(kind, foot)
    assert not run.fell
    _assert_phase_sequence(run.phases)
    assert run.phases[0] == (0, foot == "left")  # the chosen foot's leg swings first
    moved = run.ball_end - run.ball_start
    assert moved[0] > 0.15  # forward ...
    assert abs(moved[1]) < moved[0]  # ... more than sideways
    assert run.speed_ups and all(run.speed_ups)  # it sped up only while touching the robot
    feet = {name for name in run.touched if "foot" in name or "toe" in name}
    if kind == "lfdl":  # only the chosen foot touches the ball
        assert feet == {"lfoot" if foot == "left" else "rfoot"}, feet
    else:  # a foot (both take turns over a longer run: the next test)
        assert feet, feet


def test_dfdl_pushes_the_ball_with_both_feet():
    """DFDL's ball swings between the feet's lines (``ball_corridor``): over 8 s both feet
    push it (session 7, type 0, seeds 0-3: the right foot first after 4.7-6.7 s, then both
    3-7 times each over 10 m). Three seeds, at most one fall: DFDL still falls now and then
    (issue 4's "no falls" is not met), and which seed falls is chaotic across CPUs (session 15,
    an AVX-512 EPYC: seed 0 fell after 7.2 s, having pushed with both feet; seeds 1-7 stayed
    up). Under the bounce contacts (session 20) seed 1 pushed with the left foot only at up to
    0.9 m/s; capped at 0.7 m/s (the ball bouncing off the toes less hard) every seed pushes with
    both. Session 21 (the touch planner): seed 0's right-foot push at 2.5 s began and ended
    inside one cycle, so the pushes are now also read from the links near the ball when it
    speeds up (``_short_run``)."""
    runs = [_short_run("dfdl", "left", cycles=400, seed=seed) for seed in (0, 1, 2)]
    assert sum(run.fell for run in runs) <= 1
    for run in runs:
        feet = {name for name in run.touched if "foot" in name or "toe" in name}
        assert {"lfoot", "rfoot"} <= feet, feet


def _episode_end(seed: int, phase: tuple[int, bool]) -> tuple[int, tuple, tuple]:
    session, agent = start_dribble_episode(0, 30.0, seed=seed)
    try:
        cycles = dribble_to_phase(agent, "lfdl", 30.0, 0.5, phase)
        assert agent.behavior.skill("dribble").phase == phase
        return cycles, session.ball.position(), agent.robot.torso_position()
    finally:
        session.close()


def test_episode_start_is_reproducible_and_stops_at_the_chosen_phase():
    """The next issue's episodes: the same seed gives the same dribble to the last bit, and a
    caller can hand over at a chosen phase of either leg."""
    first = _episode_end(4, (6, True))
    assert _episode_end(4, (6, True)) == first
    cycles, _, _ = _episode_end(4, (2, False))
    assert 25 <= cycles < 25 + 16


@pytest.mark.parametrize("kind", DRIBBLE_KINDS)
def test_a_ball_that_rolled_behind_is_walked_round_and_dribbled_on(kind):
    """The ball rolls at the standing robot from 0.6 m ahead, passes its side and stops about
    0.3 m behind it (seen on its way, so the world model knows where it went). Dribbling on
    towards 0 deg, the robot walks round it and takes it forward again, without falling
    (before, the dribble only ever walked forwards and left the ball behind)."""
    session, agent = start_dribble_episode(0, 0.0, seed=0)
    try:
        tx, ty, _ = agent.robot.torso_position()
        agent.trainer(f"(ball (pos {tx + 0.6:.3f} {ty + 0.15:.3f} 0.042) (vel -1.4 0 0))")
        for _ in range(150):  # it rolls 1.3 m in all, 0.06 m/s left after 3 s
            agent.run("pose", "stand")
        rest = np.array(session.ball.position())
        assert rest[0] < tx - 0.1  # it lies behind the torso
        in_front = False
        for _ in range(250):
            agent.run("dribble", kind, 0.0, "left")
            assert not agent.robot.has_fallen()
            bx, _, _ = session.ball.position()
            in_front = in_front or bx > agent.robot.torso_position()[0] + 0.1
        assert in_front
        assert session.ball.position()[0] - rest[0] > 0.1  # taken forward again
    finally:
        session.close()


def test_type4_dribble_keeps_the_ball_rolling():
    """Type 4 with its toes curled up (the plain walk's 70 deg) pushed the ball along at its
    own pace and stalled against it (0.3 m in 3 s); with flat toes a toe kicks it ahead (about
    1.2 m in 3 s)."""
    assert dribble_walk_parameters("dfdl", 4).toe_deg == pytest.approx(0.0)
    session, agent = start_dribble_episode(4, 0.0, seed=0)
    try:
        start = session.ball.position()
        for _ in range(150):
            agent.run("dribble", "dfdl", 0.0, "left")
        assert not agent.robot.has_fallen()
        assert session.ball.position()[0] - start[0] > 0.7
    finally:
        session.close()


def test_benchmark_settings_override_changes_only_the_named_keys(tmp_path):
    """``benchmarks.dribble --set`` tries a setting on a copy of dribble.yaml: the named key
    changes (also a new one), everything else reads as in the real file."""
    from benchmarks.dribble import with_settings

    path = with_settings(
        ["dfdl.controller.type0.speed=0.7", "lfdl.walk.type2={step: {max_forward: 0.13}}"],
        tmp_path,
    )
    assert dribble_gait("dfdl", 0, path).speed == pytest.approx(0.7)
    assert replace(dribble_gait("dfdl", 0, path), speed=0.0) == replace(
        dribble_gait("dfdl", 0), speed=0.0
    )
    assert dribble_walk_parameters("lfdl", 2, path).step.max_forward == pytest.approx(0.13)
    assert dribble_walk_parameters("lfdl", 0, path) == dribble_walk_parameters("lfdl", 0)
    with pytest.raises(ValueError, match="dotted"):
        with_settings(["no-equals-sign"], tmp_path)


@pytest.mark.parametrize(("kind", "angle", "seed"), [("lfdl", 45.0, 1), ("dfdl", 90.0, 1)])
def test_a_start_at_an_angle_turns_the_ball_round_without_falling(kind, angle, seed):
    """The next issue's episodes dribble at a random direction from the robot's first heading.
    These two starts fell before the fifth round (LFDL's 20 deg of pursuit swung it past the
    ball coming out of the turn; DFDL asked for full speed forwards and sideways at once)."""
    from benchmarks.dribble import run_dribble

    run = run_dribble(kind, 0, distance=2.0, seed=seed, start_angle_deg=angle, max_seconds=12.0)
    assert not run.fell  # before: LFDL fell after 3.1 s, DFDL after 5.6 s
    assert run.reached  # the ball went 2 m along the new direction within 12 s


def test_benchmark_trace_keeps_the_last_seconds_and_shows_them_for_a_fall():
    """``benchmarks.dribble --trace S``: a run keeps its last S seconds (one sample per 0.1 s,
    ground truth next to what the skill perceived), and the per-run lines show the trace only
    for a run that fell or lost the ball (the falls must be explained, not only counted)."""
    from benchmarks.dribble import run_dribble, run_lines

    run = run_dribble("dfdl", 0, distance=5.0, seed=0, max_seconds=1.0, trace_seconds=0.5)
    assert len(run.trace) == 5  # 0.5 s at one sample per 0.1 s, the run's last cycle newest
    assert run.trace[-1].lstrip().startswith("1.00s")
    assert all("phase" in line and "feet-ball" in line for line in run.trace)
    assert run_lines(run)[0].startswith("run[dfdl][type0][seed=0][angle=0]: timeout")
    assert len(run_lines(run)) == 1 + len(run.trace) * (run.fell or run.ball_losses > 0)
    run.fell = True
    assert run_lines(run)[1:] == [f"trace[dfdl][type0][seed=0][angle=0]: {s}" for s in run.trace]


def test_benchmark_counts_touches_and_reports_the_ball_speed_after_them():
    """``benchmarks.dribble`` records the ball's speed after every touch (a one-cycle rise of its
    speed: only a contact speeds it up) and reports their median and 90th percentile."""
    from benchmarks.dribble import TOUCH_JUMP, report_lines, run_dribble

    run = run_dribble("lfdl", 0, distance=5.0, seed=0, max_seconds=3.0)
    assert run.touch_speeds  # the toe met the ball within 3 s
    assert all(speed > TOUCH_JUMP for speed in run.touch_speeds)
    lines = dict(line.split(": ") for line in report_lines([run]))
    median = float(lines["lfdl_touch_ball_speed_mps[type0]"])
    assert min(run.touch_speeds) <= median <= float(lines["lfdl_touch_ball_speed_mps_p90[type0]"])
