"""Fall detection and the get_up skill: perception-only decisions checked against the simulator.

The back get-up (predictive tracking, tuned per type for types 1, 3, 4; a failed sit-up is
retried at once, without waiting for the body to settle when it lies flat), the front one
(abandoned for a back get-up as soon as the robot tips back over or lies on its back; types 1-4
keep the arms down while the torso comes up) and the side roll (the lower arm levers the chest
up) bring most robots back on their feet within 4 s (``benchmarks/get_up.py`` under 60
solver iterations with session 28's front corrections of types 0 and 3: 95 of 100, ``--seed
500`` 97, ``--seed 1000`` 97, ``--seed 2000`` 96; ``runs/kick_abort/s28_get_up_t3_seed*.txt``).
Type 4's rise from the squat and the front get-ups of types 0 and 3 have a hip-pitch balance
correction from the IMU's torso pitch (``RISE_BALANCE``).
The trial test below asks for both sides, of types 0 and 3 (type 3's back fall of that seed
stayed down under 30 solver iterations, a strict xfail until session 27).
The tests that keep a tuned detail alive do it on one fall on which the detail makes the
difference; a change of physics flips such falls, and the tests then need new ones
(``scripts/get_up/pin_search.py``). The falls pinned here are those of 60 solver iterations
(session 27).
The search that tunes the sequences (``learning/get_up_search.py``) is checked here for what it
writes into the packaged file.
"""

from __future__ import annotations

import numpy as np
import pytest
import yaml

import behaviors.get_up as get_up_module
from behaviors.get_up import (
    FLIPPED_AFTER_S,
    FRONT_UP_FRAMES,
    RISE_BALANCE,
    SAT_UP_FRAMES,
    SETTLED_CYCLES,
    GetUpSkill,
    RiseBalance,
    _legs_risen,
    load_balances,
    parse_balances,
    robot_stands,
    sequence_for,
)
from behaviors.joint_control import CYCLE_SECONDS, JointCommands
from behaviors.keyframes import (
    Keyframe,
    KeyframePlayer,
    KeyframeSequence,
    PredictiveTracker,
    parse_sequences,
)
from behaviors.poses import PoseError, get_pose, support_margin
from behaviors.skill import SkillContext
from world.perception import ForceResistance, Perception
from world.robot_state import RobotState
from world.world_model import WorldModel

pytest.importorskip("pybullet")

from benchmarks.get_up import run_trial
from learning.falls import FALL_DIRECTIONS, knock_over
from learning.falls import join_at_random_spot as join
from learning.get_up_eval import close, evaluate, saved_falls
from learning.get_up_search import (
    Parameter,
    candidate_sequences,
    dump_entries,
    parameters,
    raw_entries,
)
from sim.session import Session, SessionConfig


def _state(accelerometer, feet_newton: float) -> RobotState:
    state = RobotState(0)
    feet = {
        name: ForceResistance(name, (0.0, 0.0, 0.0), (0.0, 0.0, feet_newton / 2))
        for name in ("lf", "rf")
    }
    perception = Perception(accelerometer=accelerometer, force_resistance=feet)
    for _ in range(200):  # let the tilt filter converge on the accelerometer
        state.update(perception)
    return state


def test_the_rise_ends_once_the_legs_are_near_the_stand_in_the_last_frame(monkeypatch):
    """The last frame (the rise) counts as done once hips, knees and ankles are within
    EARLY_STAND_DEG of its targets, not before the last frame and not with the knees still
    bent further (lower than standing height: the benchmark's ground truth fails those)."""
    monkeypatch.setattr(get_up_module, "EARLY_STAND_DEG", 12.0)
    sequence = sequence_for("get_up_back", 0)
    commands = JointCommands(0)
    stand = dict.fromkeys(commands.joint_names, 0.0)
    stand.update((n, v) for n, v in sequence.frames[-1].joints.items() if n in stand)

    def state(**offsets: float) -> RobotState:
        robot = RobotState(0)
        joints = {n: v + offsets.get(n, 0.0) for n, v in stand.items()}
        robot.update(Perception(accelerometer=(0.0, 0.0, 9.81), joints=joints))
        return robot

    player = KeyframePlayer(sequence, 0)
    last_start = sequence.duration - sequence.frames[-1].total
    while player.elapsed < last_start - CYCLE_SECONDS / 2:
        assert not _legs_risen(player, state())
        player.step(commands, stand)
    player.step(commands, stand)  # the first cycle of the last frame
    assert _legs_risen(player, state(llj4=-10.0, rlj3=8.0))
    assert not _legs_risen(player, state(llj4=-15.0))
    assert not _legs_risen(player, state(rlj5=-15.0))
    monkeypatch.setattr(get_up_module, "EARLY_STAND_DEG", None)
    assert not _legs_risen(player, state())


def test_standing_needs_upright_torso_and_loaded_feet():
    assert robot_stands(_state((0.0, 0.0, 9.81), 45.0))
    assert not robot_stands(_state((0.0, 0.0, 9.81), 10.0))  # held up by something else
    assert not robot_stands(_state((0.0, 6.0, 7.8), 45.0))  # 37 deg forward


def _second_attempt_s(side: str, up_frames: int) -> float | None:
    """Seconds into the first attempt at which a robot that never comes up (the perceived
    torso keeps lying on ``side``) starts its second one; asserts it started early enough:
    right after the first ``up_frames`` frames plus the settle wait, not after the whole
    sequence (that is what lets a retry fit into the 4 s)."""
    world = WorldModel(0)
    commands = JointCommands(0)
    skill = GetUpSkill()
    sequence = sequence_for(f"get_up_{side}", 0)
    gravity_y = 9.81 if side == "back" else -9.81
    lying = Perception(
        accelerometer=(0.0, gravity_y, 0.0), joints=dict.fromkeys(commands.joint_names, 0.0)
    )
    for cycle in range(200):  # let the tilt filter converge on the accelerometer
        lying.time = cycle * CYCLE_SECONDS
        world.update(lying)
    second_attempt_s = None
    for cycle in range(round(sequence.duration / CYCLE_SECONDS)):
        lying.time = (200 + cycle) * CYCLE_SECONDS
        world.update(lying)
        commands.clear()
        assert not skill.step(SkillContext(world, commands, None))
        if skill.attempts == 2:
            second_attempt_s = cycle * CYCLE_SECONDS
            break
    assert skill.lying_on == side
    up_s = sum(frame.total for frame in sequence.frames[:up_frames])
    assert second_attempt_s is not None and second_attempt_s < up_s + 0.3
    return second_attempt_s


def test_a_back_attempt_that_stays_down_after_the_sit_up_is_retried_at_once():
    _second_attempt_s("back", SAT_UP_FRAMES)


def test_a_front_attempt_that_lies_again_once_upright_is_retried_at_once():
    """Traces showed front attempts that had the torso upright at 0.76 s tip back over in
    the squat and wait out the 2.8 s sequence; now they retry (from the back) at once."""
    _second_attempt_s("front", FRONT_UP_FRAMES)


def test_a_robot_lying_flat_after_a_failed_attempt_retries_without_waiting(monkeypatch):
    """The settle wait (quiet gyro for SETTLED_CYCLES) is skipped once an attempt has failed and
    the torso lies flat: the second attempt starts cycles earlier than with the wait."""
    at_once = _second_attempt_s("back", SAT_UP_FRAMES)
    monkeypatch.setattr(get_up_module, "RETRY_AT_ONCE_PITCH_DEG", None)
    waiting = _second_attempt_s("back", SAT_UP_FRAMES)
    assert at_once is not None and waiting is not None
    assert waiting - at_once > (SETTLED_CYCLES - 1.5) * CYCLE_SECONDS


def test_the_retry_without_settling_brings_a_benchmark_fall_up(monkeypatch):
    """Fall type 2 seed 2436 (ends on the back; under 60 solver iterations (session 27) the
    only fall of type 2's seeds 2000-2999 thrown backwards on which the retry's start made the
    difference; benchmark seed 2009 until then): its first back get-up tips back over;
    starting the retry at once (1.22 s) has the robot standing within 4 s (3.26 s), waiting
    for the gyro to quiet first (as before; 1.52 s) its retry fails too and the third
    attempt (3.52 s) runs out of time."""
    assert run_trial(2, "back", 2436).succeeded
    monkeypatch.setattr(get_up_module, "RETRY_AT_ONCE_PITCH_DEG", None)
    assert not run_trial(2, "back", 2436).succeeded


def _front_attempt_after_a_roll_over_the_head_s() -> float:
    """Seconds into a front get-up at which the back get-up starts when the perceived torso
    rolls over the head onto its back in 0.4 s (IMU and gyro as the roll would give them)."""
    world = WorldModel(0)
    commands = JointCommands(0)
    skill = GetUpSkill()
    joints = dict.fromkeys(commands.joint_names, 0.0)
    cycle = 0

    def step(pitch_deg: float, rate_deg_s: float = 0.0, act: bool = True) -> None:
        nonlocal cycle
        pitch = np.radians(pitch_deg)
        up = (0.0, -9.81 * np.sin(pitch), 9.81 * np.cos(pitch))
        perception = Perception(
            time=cycle * CYCLE_SECONDS, gyro=(rate_deg_s, 0.0, 0.0), accelerometer=up, joints=joints
        )
        world.update(perception)
        cycle += 1
        if act:
            commands.clear()
            skill.step(SkillContext(world, commands, None))

    for _ in range(200):  # let the tilt filter converge on the accelerometer
        step(90.0, act=False)
    while skill.attempts == 0:
        step(90.0)
    assert skill.lying_on == "front"
    started = cycle
    for k in range(1, 21):  # over the head: pitch 90 -> 180 -> 270 (-90) in 0.4 s
        step(90.0 + 9.0 * k, 450.0)
    while skill.attempts == 1 and cycle - started < 100:
        step(270.0)
    assert skill.attempts == 2 and skill.lying_on == "back"
    return (cycle - started) * CYCLE_SECONDS


def test_a_front_get_up_that_rolled_onto_the_back_is_abandoned_early(monkeypatch):
    """A retry from the face (hips up) often goes over the head onto the back in 0.3-0.4 s:
    the back get-up then starts as soon as the torso lies on its back, not only after the
    front's upright frames (0.75 s) as before."""
    early = _front_attempt_after_a_roll_over_the_head_s()
    up_s = sum(frame.total for frame in sequence_for("get_up_front", 0).frames[:FRONT_UP_FRAMES])
    assert FLIPPED_AFTER_S < early < up_s - 0.1
    monkeypatch.setattr(get_up_module, "FLIPPED_PITCH_DEG", (0.0, 0.0))  # never flipped
    assert _front_attempt_after_a_roll_over_the_head_s() >= up_s


def test_saved_benchmark_falls_replay_the_same_get_up_and_take_candidates():
    """learning/get_up_eval.py: a saved fall replays to the same outcome every time, and a
    candidate reaches the fresh skill of each replay (here one that never finds the robot
    settled: it never starts an attempt)."""
    falls = saved_falls(0, robot_types=[2], trials_per_type=1)
    try:
        assert [(f.robot_type, f.direction, f.seed) for f in falls] == [(2, "front", 2000)]
        first, again = evaluate(falls), evaluate(falls)
        assert first == again and first[0].succeeded

        def never_settled(skill: GetUpSkill) -> None:
            skill._settled = lambda state: False

        stuck = evaluate(falls, never_settled)
        assert not stuck[0].succeeded
    finally:
        close(falls)


def test_sequences_are_looked_up_per_type_then_shared():
    assert sequence_for("get_up_front", 3).name in ("get_up_front_type3", "get_up_front")
    with pytest.raises(KeyError):
        sequence_for("no_such_motion", 0)


def test_the_skill_plays_injected_sequences_type_variant_first():
    """A search hands candidates to the real skill; the type's own variant wins over the
    common one, in the injected set as in the packaged one."""
    entry = raw_entries()["get_up_back"]
    sequences = candidate_sequences("get_up_back_type2", entry)
    assert sequence_for("get_up_back", 2, sequences).name == "get_up_back_type2"
    assert sequence_for("get_up_back", 2).name == "get_up_back"
    assert GetUpSkill(sequences).sequences is sequences
    assert GetUpSkill().sequences["get_up_front"].frames


def test_the_rise_balance_acts_only_past_its_setpoint_and_is_clipped():
    balance = RiseBalance(from_frame=4, setpoint_deg=-3.0, gains={"llj3": 4.0}, max_offset_deg=40)
    assert balance.offsets(10.0) == {"llj3": 0.0}  # leaning forwards: no correction
    assert balance.offsets(-3.0) == {"llj3": 0.0}
    assert balance.offsets(-8.0) == pytest.approx({"llj3": 20.0})
    assert balance.offsets(-60.0) == {"llj3": 40.0}


def test_the_balance_corrects_both_ways_and_acts_early_on_a_fast_lean():
    """A torso leaning forward past ``forward_setpoint_deg`` moves the joints the other way;
    the pitch rate predicts the lean ``horizon_s`` ahead, so a torso still upright but tipping
    fast is corrected before it has gone far."""
    balance = RiseBalance(
        from_frame=2,
        setpoint_deg=None,
        gains={"llj3": 2.0},
        max_offset_deg=30.0,
        forward_setpoint_deg=20.0,
        horizon_s=0.1,
    )
    assert balance.offsets(-60.0) == {"llj3": 0.0}  # no backward setpoint: never
    assert balance.offsets(25.0) == pytest.approx({"llj3": -10.0})
    assert balance.offsets(15.0) == {"llj3": 0.0}
    assert balance.offsets(15.0, 100.0) == pytest.approx({"llj3": -10.0})  # 25 deg in 0.1 s
    assert balance.offsets(90.0) == {"llj3": -30.0}


def test_balance_files_are_validated_with_the_entry_named(tmp_path):
    good = {"description": "d", "from_frame": 4, "gains": {"llj3": 4}, "max_offset_deg": 40}
    assert parse_balances({"x": good}, "f")["x"].setpoint_deg is None
    for bad in (
        {**good, "gains": {"llj3": "four"}},
        {**good, "max_offset_deg": 0},
        {**good, "from_frame": -1},
        {**good, "setpoint": -3},  # misspelt key
        {key: value for key, value in good.items() if key != "gains"},
    ):
        with pytest.raises(PoseError, match="f: x"):
            parse_balances({"x": bad}, "f")
    path = tmp_path / "balance.yaml"
    path.write_text(yaml.safe_dump({"get_up_back": {**good, "setpoint_deg": -3.0}}))
    assert load_balances(path)["get_up_back"].offsets(-8.0) == {"llj3": 20.0}


def test_rise_balance_only_for_sequences_that_exist():
    """A misspelt name in RISE_BALANCE would silently switch the correction off."""
    for name, balance in RISE_BALANCE.items():
        sequence = sequence_for(name, 0)
        assert sequence.name == name
        assert 0 < balance.from_frame < len(sequence.frames)


def test_search_parameters_move_mirror_twins_within_the_joint_range():
    entry = {"frames": [{"duration": 0.3, "joints": {"llj2": 10.0, "rlj2": -10.0, "laj1": -90}}]}
    Parameter(0, "llj2", 15.0).set(entry, 25.0)
    assert entry["frames"][0]["joints"] == {"llj2": 25.0, "rlj2": -25.0, "laj1": -90}
    Parameter(0, "llj2", 15.0).set(entry, 500.0)  # clipped to the hip roll's range
    assert entry["frames"][0]["joints"]["llj2"] < 90.0
    assert entry["frames"][0]["joints"]["rlj2"] == -entry["frames"][0]["joints"]["llj2"]
    Parameter(0, "duration", 0.08).set(entry, -1.0)
    assert entry["frames"][0]["duration"] > 0.0


def test_search_parameters_cover_one_sided_joints_of_a_roll():
    """A roll moves each side differently: with ``one_sided`` every joint is searched on its
    own and moving it leaves its twin alone; otherwise pairs move together, by the left joint,
    and a right joint without its twin in the frame is still searched."""
    entry = {"frames": [{"duration": 0.3, "joints": {"raj1": -120, "rlj3": -25, "llj3": 0}}]}
    one_sided = parameters(entry, frames=1, joint_step=15.0, time_step=0.08, one_sided=True)
    assert {p.key for p in one_sided} == {"duration", "raj1", "rlj3", "llj3"}
    paired = parameters(entry, frames=1, joint_step=15.0, time_step=0.08)
    assert {p.key for p in paired} == {"duration", "raj1", "llj3"}
    next(p for p in one_sided if p.key == "llj3").set(entry, 30.0)
    assert entry["frames"][0]["joints"] == {"raj1": -120, "rlj3": -25, "llj3": 30.0}
    next(p for p in paired if p.key == "llj3").set(entry, 15.0)
    assert entry["frames"][0]["joints"] == {"raj1": -120, "rlj3": 15.0, "llj3": 15.0}


def test_the_search_writes_the_get_up_file_back_unchanged():
    """What the search writes (one flow-style line per frame) reads back as the same data."""
    entries = raw_entries()
    assert yaml.safe_load(dump_entries(entries)) == entries
    entries["get_up_back"]["description"] = "type 4: knees 'straight' (lj4 +1) # search"
    assert yaml.safe_load(dump_entries(entries)) == entries


def test_predictive_speed_subtracts_the_command_still_in_flight():
    tracker = PredictiveTracker(0)
    first = tracker.speeds({"raj1": 5.0}, {"raj1": 0.0})
    assert first["raj1"] == pytest.approx(np.radians(5.0) / CYCLE_SECONDS)
    # the joint has not moved yet (the command shows two perceptions later): nothing more to ask
    assert tracker.speeds({"raj1": 5.0}, {"raj1": 0.0})["raj1"] == pytest.approx(0.0)
    # far targets are clipped to the joint's maximum speed, targets to the joint's range
    far = tracker.speeds({"raj1": 500.0}, {"raj1": 0.0})["raj1"]
    assert far == pytest.approx(6.1395, abs=1e-3)


def test_predictive_frames_need_the_robot_type_and_a_known_mode():
    sequences = parse_sequences(
        {"m": {"frames": [{"duration": 0.1, "joints": {"hj1": 10}, "track": "predictive"}]}}, "t"
    )
    assert sequences["m"].predictive
    with pytest.raises(ValueError):
        KeyframePlayer(sequences["m"])
    with pytest.raises(PoseError):
        parse_sequences({"m": {"frames": [{"duration": 0.1, "joints": {}, "track": "fast"}]}}, "t")


def test_predictive_tracking_follows_a_ramp_two_cycles_behind():
    """A free arm follows a 225 deg/s ramp with only the transport delay (two cycles), where
    the gain-0.25 controller lags four cycles more."""
    session = Session(SessionConfig(seed=1, beam_noise=False))
    try:
        driver = join(session, 0, np.random.default_rng(1))
        ramp = Keyframe({"raj1": 0.0}, 0.4, "linear", 0.1, track="predictive")
        player = KeyframePlayer(KeyframeSequence("ramp", (ramp,)), 0)
        sent, measured = [], []
        finished = False
        while not finished:
            driver.perceive()
            driver.behavior.begin_cycle()
            measured.append(driver.state.joints_deg["raj1"])
            sent.append(player.targets(driver.state.joints_deg)[0]["raj1"])
            finished = player.step(driver.commands, driver.state.joints_deg)
            driver.send(driver.commands.effector_speeds(driver.state.joints_deg))
        assert isinstance(driver.commands, JointCommands)
        errors = [abs(m - t) for m, t in zip(measured[2:], sent, strict=False)]
        assert max(errors) < 1.0, errors
    finally:
        session.close()


@pytest.mark.parametrize("robot_type", range(5))
def test_stand_and_squat_keep_the_centre_of_mass_over_the_feet(robot_type):
    for name in ("stand", "squat"):
        assert support_margin(get_pose(name).joints, robot_type) > 0.03, name
    leaning_back = {"rlj5": -40.0, "llj5": -40.0}  # straight legs, torso 40 deg backwards
    assert support_margin(leaning_back, robot_type) < 0.0


@pytest.mark.parametrize("robot_type", range(5))
def test_the_stand_pose_is_held_upright(robot_type):
    """Risen slowly into ``stand``, the torso stays within a few degrees of upright."""
    session = Session(SessionConfig(seed=3, beam_noise=False))
    try:
        driver = join(session, robot_type, np.random.default_rng(3))
        robot = session.agents[driver.agent].robot
        tilts = []
        for _ in range(75):
            driver.run("pose", "stand")
            tilts.append(np.degrees(np.arccos(min(1.0, robot.torso_up()[2]))))
        assert max(tilts) < 8.0, tilts
    finally:
        session.close()


@pytest.mark.parametrize("robot_type", [0, 4])
def test_a_standing_robot_finishes_at_once(robot_type):
    session = Session(SessionConfig(seed=2, beam_noise=False))
    try:
        driver = join(session, robot_type, np.random.default_rng(2))
        assert driver.run("get_up")
    finally:
        session.close()


@pytest.mark.parametrize("direction", FALL_DIRECTIONS)
def test_fall_side_from_perception_matches_the_simulator(direction):
    """Knocked over by physics, the robot's own tilt estimate names the side facing the ground
    as the simulator's torso orientation does, and get_up picks that side's sequence."""
    session = Session(SessionConfig(seed=11, beam_noise=False))
    try:
        rng = np.random.default_rng(11)
        driver = join(session, 0, rng)
        assert knock_over(driver, direction, rng)
        for _ in range(30):  # lie still and let the tilt filter settle
            driver.perceive()
            driver.send({})
        robot = session.agents[driver.agent].robot
        rotation = robot.torso_world_transform()[:3, :3]
        down = {  # torso axis pointing most nearly at the ground -> side lying on
            "front": -rotation[2, 1],
            "back": rotation[2, 1],
            "right": -rotation[2, 0],
            "left": rotation[2, 0],
        }
        truth = max(down, key=down.get)
        assert driver.state.is_fallen
        assert driver.state.lying_on == truth
        driver.run("get_up")
        for _ in range(5):
            driver.run("get_up")
        skill = driver.behavior._skills["get_up"]
        assert isinstance(skill, GetUpSkill)
        assert skill.lying_on == truth
    finally:
        session.close()


@pytest.mark.parametrize("robot_type", [0, 3])
def test_get_up_after_a_physical_fall(robot_type):
    """One physical fall towards the front and one towards the back, each up within 4 s and
    still up half a second later (the benchmark's rule; deterministic for a seed). Type 3's
    back fall of seed 7 stayed down under 30 solver iterations (a strict xfail until then);
    under 60 (session 27) it stands at 2.48 s, its front fall at 3.60 s."""
    results = [run_trial(robot_type, direction, seed=7) for direction in ("front", "back")]
    assert all(r.succeeded for r in results), results


@pytest.mark.parametrize(
    ("robot_type", "direction", "seed"), [(4, "front", 4015), (1, "right", 1015)]
)
def test_the_side_roll_turns_the_body_within_a_second(robot_type, direction, seed):
    """Two falls that end on a side (type 4 seed 4015 on its left under 60 solver iterations
    (session 27), the first of type 4's falls towards the front from seed 4000 on that does;
    seed 4000, which now lands on its back, until then; type 1 seed 1015 on its right): the
    roll has the robot on its back or front and its get-up started within 1.2 s (0.96 s on
    both). On the falls of 30 solver iterations (4000 and 1015), the roll swinging the upper
    arm and leg back alone left the first one on its side for the whole 4 s and the second
    one until 1.4 s."""
    started: list[tuple[float, str | None]] = []

    def observe(agent, cycle: int) -> None:
        skill = agent.behavior.skill("get_up")
        if skill.attempts == 2 and not started:
            started.append((cycle * CYCLE_SECONDS, skill.lying_on))

    result = run_trial(robot_type, direction, seed, observer=observe)
    assert result.lying_on in ("left", "right")
    assert started, "the robot was still on its side after the first roll"
    second_attempt_s, side = started[0]
    assert side in ("back", "front") and second_attempt_s < 1.2, started


def test_type4_back_get_up_keeps_a_once_tipping_robot_up(monkeypatch):
    """Benchmark fall type 4 seed 4016 (ends on the back): before the fold with less foot pitch
    (lj5 15.4) the rise from the squat tipped backwards unless the hip correction caught it;
    now the robot stands within 4 s with the correction and without it."""
    assert run_trial(4, "front", 4016).succeeded
    monkeypatch.setattr(get_up_module, "RISE_BALANCE", {})
    assert run_trial(4, "front", 4016).succeeded


def test_type0_front_get_up_is_kept_up_by_its_hip_correction(monkeypatch):
    """Benchmark fall type 0 seed 6004 (ends on the front; session 28): its first attempt
    stalls 40 deg forward and tips onto the face, and without the hip correction of
    ``get_up_front`` the retry swings through upright to -15 deg and sits back down, so
    the robot is still down at 4 s; with it the retry stands (3.52 s)."""
    assert "get_up_front" in RISE_BALANCE
    assert run_trial(0, "front", 6004).succeeded
    monkeypatch.setattr(get_up_module, "RISE_BALANCE", {})
    assert not run_trial(0, "front", 6004).succeeded


def test_a_robot_tipping_back_after_an_abandoned_attempt_does_not_count_as_standing(
    monkeypatch,
):
    """Benchmark fall type 0 seed 33004 (ends on the front; session 29): the front get-up
    comes up over the knees and tips back in its squat; the attempt is abandoned at a 40 deg
    predicted lean, when the torso is still within 20 deg of vertical with the weight on the
    feet but falling back at 200-300 deg/s. Counted as standing there, the skill reported
    success and the robot lay on its back half a second later; now it waits for the fall to
    end and the back get-up stands it up within 4 s (3.78 s)."""
    result = run_trial(0, "front", 33004)
    assert result.succeeded and result.attempts == 2
    monkeypatch.setattr(get_up_module, "STANDS_AFTER_ATTEMPT_MAX_GYRO_DEG_S", None)
    result = run_trial(0, "front", 33004)
    assert not result.succeeded and result.attempts == 1


def test_front_get_up_of_types_1_to_4_keeps_the_arms_down(monkeypatch):
    """Fall type 3 seed 3007 (ends on the front; under 60 solver iterations (session 27) the
    first of type 3's seeds from 3000 on where the own variant stands at its first attempt
    and the common one does not; benchmark seed 3008 until then): with its own front variant
    (arms kept down and forward while the torso comes up over the knees) the robot stands
    within 4 s (2.56 s); with the common front get-up, tuned on type 0, it tips onto its face
    again, and after the retry it lies on its back, whose get-up (from 2.00 s) runs out of
    time."""
    own = sequence_for("get_up_front", 3)
    assert own.name == "get_up_front_type3"
    assert (
        own.frames[2].joints["laj1"] < 0 < sequence_for("get_up_front", 0).frames[2].joints["laj1"]
    )
    assert run_trial(3, "front", 3007).succeeded
    common = {
        name: sequence
        for name, sequence in get_up_module.default_sequences().items()
        if not name.startswith("get_up_front_type")
    }
    monkeypatch.setattr(get_up_module, "default_sequences", lambda: common)
    assert not run_trial(3, "front", 3007).succeeded


def test_type0_back_crouch_with_less_hip_flexion_brings_a_benchmark_fall_up(monkeypatch):
    """Fall type 0 seed 910 (ends on the back; ``scripts/get_up/pin_search.py --case
    type0_back_crouch`` under 60 solver iterations (session 27): the only one in seeds 0-910):
    with type 0's own back get-up (crouch lj3 65 instead of the common 75) the robot stands
    within 4 s (2.10 s, its first attempt); with the common back get-up the first attempt
    ends lying back again and the retry runs out of time. (Seed 73 from session 20's bounce
    contacts, 517 before them.)"""
    own = sequence_for("get_up_back", 0)
    assert own.name == "get_up_back_type0"
    assert own.frames[3].joints["llj3"] < sequence_for("get_up_back", 2).frames[3].joints["llj3"]
    assert run_trial(0, "back", 910).succeeded
    _package_without(monkeypatch, "get_up_back_type0")
    assert not run_trial(0, "back", 910).succeeded


def _package_without(monkeypatch, sequence_name: str) -> None:
    """The skill's packaged sequences without ``sequence_name`` (the common one plays)."""
    common = {
        name: sequence
        for name, sequence in get_up_module.default_sequences().items()
        if name != sequence_name
    }
    monkeypatch.setattr(get_up_module, "default_sequences", lambda: common)


def test_a_front_get_up_tipping_back_is_caught_from_its_pitch_rate(monkeypatch):
    """Fall type 2 seed 2693 (ends on the front; ``scripts/get_up/pin_search.py --case
    front_abort_horizon`` under 60 solver iterations (session 27): the only one in seeds
    2000-2693): its front get-up tips back in the squat; abandoned from the pitch predicted
    0.1 s ahead (at 1.16 s, pitch -22 deg) the back get-up that follows stands at 3.34 s,
    abandoned from the pitch alone (1.24 s, -43 deg) it tips back and the retry runs out of
    time. (Seed 2023 from session 20's bounce contacts, 3.14 s; before them seed 2019, whose
    front get-up tipped back in its squat at 1.4 s; until session 11 type 1 seed 1500 with
    its old front fold.)"""
    assert get_up_module.FRONT_ABORT_HORIZON_S > 0
    assert run_trial(2, "front", 2693).succeeded
    monkeypatch.setattr(get_up_module, "FRONT_ABORT_HORIZON_S", 0.0)
    assert not run_trial(2, "front", 2693).succeeded


def test_type3_side_roll_with_less_shoulder_push_brings_a_benchmark_fall_up(monkeypatch):
    """Fall type 3 seed 3086 (ends on the right side; ``scripts/get_up/pin_search.py --case
    type3_roll`` under 60 solver iterations (session 27)): with type 3's own roll (the lower
    arm pushes through 40 deg of shoulder roll instead of 95) the robot is on its back at
    0.96 s and stands within 4 s (3.38 s); after the common roll it is on its back as early,
    but its back get-ups fail (three attempts) and it stays down. (Seed 3050 from session 20's
    bounce contacts; 3019 before them: there the common roll left the robot twisted and its
    sit-ups tipped back over the shoulders.)"""
    own = sequence_for(get_up_module.ROLL_FROM_LEFT, 3)
    assert own.name == "roll_left_to_back_type3"
    assert (
        own.frames[1].joints["laj2"] < sequence_for("roll_left_to_back", 0).frames[1].joints["laj2"]
    )
    assert run_trial(3, "right", 3086).succeeded
    _package_without(monkeypatch, "roll_left_to_back_type3")
    assert not run_trial(3, "right", 3086).succeeded


@pytest.mark.parametrize(("robot_type", "seed"), [(1, 1001), (2, 2025), (3, 3007), (4, 4019)])
def test_front_get_up_with_the_knees_folded_less_brings_a_benchmark_fall_up(
    monkeypatch, robot_type, seed
):
    """Falls of types 1-4 ending on the front (``scripts/get_up/pin_search.py --case
    front_fold_T`` under 60 solver iterations (session 27), type 3 the first from 3000 on
    that stands at its first attempt; 1504 / 2015 / 3011 / 4001 from session 20's bounce
    contacts, before them 2504 / 3516 / 4516): with the knees folded to -80 / -90 / -100 deg
    in the second frame the robot stands within 4 s (2.56 s, its first attempt, on all
    four); with the fold of type 0 (-116.7) the torso tips over the knees or back out of the
    squat (type 2's onto its side) and it stays down (measured before EARLY_STAND_DEG, which
    brings type 2's retry up in time)."""
    own = sequence_for("get_up_front", robot_type)
    assert own.frames[1].joints["llj4"] > sequence_for("get_up_front", 0).frames[1].joints["llj4"]
    assert run_trial(robot_type, "front", seed).succeeded
    monkeypatch.setattr(get_up_module, "EARLY_STAND_DEG", None)
    _front_fold(monkeypatch, robot_type, -116.7)
    assert not run_trial(robot_type, "front", seed).succeeded


def _front_fold(monkeypatch, robot_type: int, knee_deg: float) -> None:
    """The skill plays the type's front get-up with the knees folded to ``knee_deg`` in its
    second frame."""
    name = sequence_for("get_up_front", robot_type).name
    entry = raw_entries()[name]
    for side in "lr":
        entry["frames"][1]["joints"][f"{side}lj4"] = knee_deg
    folded = candidate_sequences(name, entry)
    monkeypatch.setattr(get_up_module, "default_sequences", lambda: folded)


def test_a_late_retry_that_has_risen_counts_before_its_last_hold(monkeypatch):
    """Fall type 3 seed 3001 (front; ``scripts/get_up/pin_search.py --case late_retry`` after
    session 28's hip correction of type 3's front get-up, which stands 3136 earlier; 3136
    under session 27's 60 solver iterations, 3041 on session 20's bounce contacts, 3504
    before them): the third attempt has the legs near the stand at 3.98 s, when the last
    frame's full time has not passed yet; reported once the legs are near the stand
    (EARLY_STAND_DEG) it counts, waiting for the hold it does not. Played without type 3's
    front retry version."""
    _package_without(monkeypatch, "get_up_front_retry_type3")
    assert run_trial(3, "front", 3001).succeeded
    monkeypatch.setattr(get_up_module, "EARLY_STAND_DEG", None)
    assert not run_trial(3, "front", 3001).succeeded


def test_type1_back_get_up_stands_without_self_collision(monkeypatch):
    """Fall type 1 seed 1000 (ends on the back; ``scripts/get_up/pin_search.py --case
    type1_back_noself`` under 60 solver iterations (session 27), which bring seed 1002 down
    with self-collision; 1002 from session 20's bounce contacts, which brought 1001 down with
    self-collision, 1001 before them) under the real server's rule that a robot's parts never
    touch each other (``benchmarks/physics.py --variant noself``): with type 1's back get-up
    of session 11 (arms straight back at once, a slower sit-up with less hip flexion) it
    stands within 4 s (2.96 s, at its retry); with the one before (arms back only during the
    sit-up, whose torso rose only while the forearms pressed the thighs) it stays down. With
    self-collision both stand (2.22 s and 3.08 s)."""
    from benchmarks.physics import VARIANTS

    assert run_trial(1, "back", 1000).succeeded
    with VARIANTS["noself"]():
        assert run_trial(1, "back", 1000).succeeded
        _type1_back_before_session11(monkeypatch)
        assert not run_trial(1, "back", 1000).succeeded
    assert run_trial(1, "back", 1000).succeeded


def _type1_back_before_session11(monkeypatch) -> None:
    """The skill plays type 1's back get-up as before session 11: arms back only during the
    sit-up (0.2 s, shoulder -70.7), a faster sit-up (0.53 s) with more hip flexion (100)."""
    name = sequence_for("get_up_back", 1).name
    entry = raw_entries()[name]
    frames = entry["frames"]
    frames[0].update(duration=0.2)
    frames[0]["joints"].update(laj1=-70.7, raj1=-70.7)
    frames[1].update(duration=0.53)
    frames[1]["joints"].update(llj3=100.0, rlj3=100.0)
    frames[2].update(duration=0.3)
    old = candidate_sequences(name, entry)
    monkeypatch.setattr(get_up_module, "default_sequences", lambda: old)


def test_the_search_scores_each_contact_rule_on_its_own_bank():
    """``--rules current,noself``: one bank per rule, the robots of the second built without
    self-collision, and the trials indexed over both banks in turn."""
    from learning.get_up_search import make_rule_banks

    banks = make_rule_banks(["current", "noself"], 1, ["back"], 1, 7)
    try:
        first, second = banks.banks
        assert len(banks.states) == len(first.states) + len(second.states) == 2
        collide = [b.session.agents[b.agent].robot.physics.self_collision for b in banks.banks]
        assert collide == [True, False]
        sequences = get_up_module.default_sequences()
        assert banks.trial(1, sequences) == pytest.approx(second.trial(0, sequences))
        with pytest.raises(IndexError):
            banks.trial(2, sequences)
    finally:
        banks.close()


def test_a_retry_version_plays_only_after_an_attempt_that_never_rose():
    """``get_up_back_retry_type3`` replaces type 3's back get-up once an attempt has failed
    without the torso coming within RETRY_NEVER_UP_TILT_DEG of vertical; types without a
    retry version play their own sequence again."""
    skill = GetUpSkill()
    assert skill._get_up_sequence("back", 3).name == "get_up_back_type3"
    skill.get_up_attempts = 1
    assert skill._get_up_sequence("back", 3).name == "get_up_back_type3"
    skill.last_never_up = True
    assert skill._get_up_sequence("back", 3).name == "get_up_back_retry_type3"
    assert skill._get_up_sequence("back", 0).name == "get_up_back_retry_type0"
    assert skill._get_up_sequence("back", 2).name == "get_up_back_retry_type2"
    assert skill._get_up_sequence("back", 4).name == "get_up_back_type4"
    assert skill._get_up_sequence("front", 3).name == "get_up_front_retry_type3"
    skill.reset()
    assert skill._get_up_sequence("back", 3).name == "get_up_back_type3"


def test_a_front_retry_version_plays_after_any_failed_attempt():
    """``get_up_front_retry_type3`` replaces type 3's front get-up after any failed attempt
    (no never-up condition: a front attempt that fails has come up and tipped over); types
    without one play their own front get-up again."""
    skill = GetUpSkill()
    assert skill._get_up_sequence("front", 3).name == "get_up_front_type3"
    skill.get_up_attempts = 1
    assert not skill.last_never_up
    assert skill._get_up_sequence("front", 3).name == "get_up_front_retry_type3"
    assert skill._get_up_sequence("front", 1).name == "get_up_front_type1"
    assert skill._get_up_sequence("front", 0).name == "get_up_front"
    retry = skill._get_up_sequence("front", 3).frames[0].joints
    assert retry["laj1"] == retry["raj1"] == -40.0  # the hands stay planted


def test_type3_front_retry_with_the_hands_planted_brings_a_benchmark_fall_up(monkeypatch):
    """Fall type 3 seed 3000 (ends on the front; ``scripts/get_up/pin_search.py --case
    type3_front_retry`` after session 28's hip correction of type 3's front get-up, which
    stands benchmark fall 3512 at its first attempt): the first attempt sags onto the face
    from its knees; the retry with the arms kept at -40 rises from the front again and stands
    within 4 s (3.74 s), the common first frame (arms overhead) vaults it over the head onto
    the back and it stays down."""
    assert run_trial(3, "front", 3000).succeeded
    _package_without(monkeypatch, "get_up_front_retry_type3")
    assert not run_trial(3, "front", 3000).succeeded


def test_type3_back_retry_stands_without_self_collision(monkeypatch):
    """Benchmark fall type 3 seed 3001 (``--seed 0``, ends on the back) without self-collision
    (``benchmarks/physics.py --variant noself``): the first sit-up rolls back over the
    shoulders, the retry version rocks up from there and the robot stands within 4 s; playing
    type 3's back get-up again it stays down. With self-collision the first attempt stands."""
    from benchmarks.physics import VARIANTS

    assert run_trial(3, "back", 3001).succeeded
    with VARIANTS["noself"]():
        assert run_trial(3, "back", 3001).succeeded
        _package_without(monkeypatch, "get_up_back_retry_type3")
        assert not run_trial(3, "back", 3001).succeeded


def test_the_never_up_limit_is_per_type():
    """Type 0's sit-up without self-collision stalls 40-50 deg short of upright, type 3's rolls
    back: each type's retry waits for its own failure."""
    assert get_up_module._never_up_tilt_deg(0) < get_up_module._never_up_tilt_deg(3)
    assert get_up_module._never_up_tilt_deg(3) == get_up_module.RETRY_NEVER_UP_DEFAULT_DEG


def test_a_gain_frame_shift_uses_the_gain_of_the_frame_just_played():
    """``_shift_gain_targets`` re-sets a cycle's targets with ``frame_at(elapsed)`` after the
    player's step: that must be the frame whose targets the step sent, at frame boundaries
    too (else a residual's offsets would go out with the next frame's gain)."""
    joints = {name: 0.0 for name in JointCommands(0).joint_names}
    checked = 0
    for name, sequence in get_up_module.default_sequences().items():
        if not name.startswith("get_up"):
            continue
        player = KeyframePlayer(sequence, 0)
        finished = False
        while not finished:
            _, played = player.targets(joints)
            finished = player.step(JointCommands(0), joints)
            assert player.frame_at(player.elapsed) is played, (name, player.elapsed)
            checked += 1
    assert checked > 1000


def test_the_never_up_flag_is_left_by_the_attempt_that_ends():
    """The retry version is picked from how the last get-up attempt ended: a back attempt whose
    torso stayed further from vertical than the type's limit sets the flag, a roll leaves it."""
    skill = GetUpSkill()
    state = RobotState(0)
    limit = get_up_module._never_up_tilt_deg(0)
    skill.lying_on = "back"
    skill._attempt = get_up_module._Attempt(least_tilt_deg=limit + 1.0)
    skill._end_attempt(state)
    assert skill.last_never_up
    skill._attempt = get_up_module._Attempt(rolling=True, least_tilt_deg=limit - 1.0)
    skill._end_attempt(state)
    assert skill.last_never_up  # a roll does not say whether a sit-up rose
    skill._attempt = get_up_module._Attempt(least_tilt_deg=limit - 1.0)
    skill._end_attempt(state)
    assert not skill.last_never_up


@pytest.mark.parametrize("robot_type", [0, 1, 2, 3, 4])
def test_lying_on_the_right_plays_the_mirror_image_of_the_left_roll(robot_type):
    """A robot on its right side must do exactly what one on its left does, mirrored: the
    side is read the same way from the mirrored IMU (world up x -> -x) and the roll played is
    the left roll with every joint target moved to its twin with the mirror sign, frame for
    frame. (Session 13: the benchmark's right-side trials stood less often, 10 of 16 against
    19 of 20 on the left at seeds 0-3000; on 51 side falls of seeds 10000-30000,
    ``scripts/get_up/side_falls.py``, right 21 of 29 and left 18 of 22, the failures on
    either side type-3 sit-ups after the roll and diagonal postures that rolled onto the
    front: no asymmetry in the skill.)"""
    from behaviors.mirror import MIRROR_TABLE

    played = {}
    for side, x in (("left", 0.95), ("right", -0.95)):
        state = RobotState(robot_type)
        state.up = np.array([x, 0.1, 0.3]) / np.linalg.norm([x, 0.1, 0.3])
        assert state.lying_on == side
        skill = GetUpSkill()
        skill._start(state)
        assert skill.lying_on == side and skill._attempt.rolling
        assert skill._attempt.player is not None
        played[side] = skill._attempt.player.sequence
    left, right = played["left"], played["right"]
    assert left.name == sequence_for(get_up_module.ROLL_FROM_LEFT, robot_type).name
    assert len(left.frames) == len(right.frames)
    for frame_left, frame_right in zip(left.frames, right.frames):
        assert (frame_left.duration, frame_left.hold) == (frame_right.duration, frame_right.hold)
        for name, target in frame_left.joints.items():
            twin = MIRROR_TABLE[name]
            assert frame_right.joints[twin.twin] == pytest.approx(twin.sign * target), name


def _roll_upper_arm(monkeypatch, robot_type: int, shoulder_deg: float) -> None:
    """The skill plays the type's side roll with the upper (right) arm swung back to
    ``shoulder_deg`` in its second frame."""
    name = sequence_for(get_up_module.ROLL_FROM_LEFT, robot_type).name
    entry = raw_entries()[name]
    entry["frames"][1]["joints"]["raj1"] = shoulder_deg
    rolled = candidate_sequences(name, entry)
    monkeypatch.setattr(get_up_module, "default_sequences", lambda: rolled)


@pytest.mark.parametrize(("robot_type", "seed"), [(4, 4051), (3, 3018)])
def test_the_side_roll_with_the_upper_arm_swung_back_less_brings_a_benchmark_fall_up(
    monkeypatch, robot_type, seed
):
    """Falls ending on the right side (type 4 seed 4051, type 3 seed 3018:
    ``scripts/get_up/pin_search.py --case roll_upper_arm_T`` under 60 solver iterations
    (session 27); type 4 seed 4131 and type 3 seed 3004 from session 20's bounce contacts,
    before them type 4 seed 4012, lying half on its front, and type 3 seed 8004): with the
    upper arm swung back to -90 deg in the roll's second frame the robot is on its back at
    0.96 s and stands within 4 s (3.06 s, 3.38 s); swung back to -120 (before session 13;
    then the first of 4012 / 8004 rolled onto its front and the second came to lie twisted)
    both are on their backs as early but their back get-ups fail and they stay down."""
    assert sequence_for(get_up_module.ROLL_FROM_LEFT, robot_type).frames[1].joints["raj1"] == -90
    assert run_trial(robot_type, "front", seed).succeeded
    _roll_upper_arm(monkeypatch, robot_type, -120.0)
    assert not run_trial(robot_type, "front", seed).succeeded
