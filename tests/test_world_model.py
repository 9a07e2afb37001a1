"""The world model fed by the stand-in server's perception bytes: game state, the ball (rolling,
velocity, where it stops), other robots, frame helpers. Ground truth is read from the session
here only; the model itself sees nothing but perceptions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.monitor import parse_trainer_commands
from sim.session import Session, SessionConfig
from world.ball_model import BallModel
from world.kinematics import body_transforms
from world.perception import GameState, Perception, parse_perception
from world.players import PlayerTracker
from world.world_model import WorldModel

SCENE = b"(scene rsg/agent/nao/nao_hetero.rsg 0)"
STANDING_Z = 0.38


def _trainer(session: Session, text: str) -> None:
    commands, errors = parse_trainer_commands(text.encode())
    assert not errors, errors
    session.trainer_command(commands)


def _connect(session: Session, team: str, unum: int) -> int:
    agent = session.add_agent()
    session.handle_message(agent, SCENE)
    session.step()
    session.handle_message(agent, f"(init (unum {unum})(teamname {team}))(syn)".encode())
    return agent


def _place(session: Session, team: str, unum: int, x: float, y: float, heading: float) -> None:
    """Stand a robot at a world position facing ``heading`` (deg, 0 = world +x)."""
    _trainer(
        session, f"(agent (unum {unum}) (team {team}) (move {x} {y} {STANDING_Z} {heading - 90}))"
    )


@pytest.fixture
def session():
    s = Session(SessionConfig(seed=11))
    yield s
    s.close()


def _run(session: Session, models: dict[int, WorldModel], cycles: int, each=None) -> None:
    for cycle in range(cycles):
        session.step()
        for agent, model in models.items():
            model.update(parse_perception(session.perception(agent)))
        if each is not None:
            each(cycle)


# ------------------------------------------------------------------------------ game state
def test_game_state_identity_and_score_for_the_right_team():
    model = WorldModel()
    model.update(Perception(time=1.0, game_state=GameState(unum=4, team="right", score_left=2)))
    model.update(
        Perception(time=1.02, game_state=GameState(game_time=3.5, play_mode="PlayOn", score_left=2))
    )
    assert (model.side, model.unum) == ("right", 4), "kept after the one GS carrying them"
    assert (model.score_own, model.score_opponent) == (0, 2)
    assert (model.play_mode, model.game_time, model.time) == ("PlayOn", 3.5, 1.02)
    assert model.localizer.side == "right"


def test_body_transforms_are_this_cycles_kinematics():
    model = WorldModel(robot_type=4)
    joints = {"hj1": 20.0, "rlj3": 30.0, "rlj4": -60.0, "rlj7": 10.0}
    model.update(Perception(time=0.02, joints=joints))
    expected = body_transforms(model.robot.spec, joints)
    for name, matrix in expected.items():
        np.testing.assert_allclose(model.body_transforms[name], matrix)
    np.testing.assert_allclose(model.camera_transform, expected["head"])
    # standing straight, the torso centre is a sole height above the ground
    model.update(Perception(time=0.04, joints={}))
    assert model.torso_height == pytest.approx(model.robot.spec.sole_height())


# ------------------------------------------------------------------------------ the ball
def test_rolling_ball_position_velocity_and_stop(session):
    agent = _connect(session, "Alpha", 1)
    model = WorldModel(0, "Alpha")
    _run(session, {agent: model}, 3)
    _place(session, "Left", 1, -4.0, 0.0, 0.0)
    _trainer(session, "(playMode PlayOn)")
    _run(session, {agent: model}, 40)
    _trainer(session, "(ball (pos -2.5 1.5 0.042) (vel 2.5 -1.0 0))")
    position_errors, velocity_errors, stops = [], [], []

    def compare(cycle: int) -> None:
        if cycle < 8:
            return  # the first sightings of the moved ball
        truth = session.ball.position()
        truth_v = session.ball.velocity()
        x, y = model.ball.position
        vx, vy = model.ball.velocity
        position_errors.append(math.hypot(x - truth[0], y - truth[1]))
        velocity_errors.append(math.hypot(vx - truth_v[0], vy - truth_v[1]))
        if cycle in (20, 40, 80):
            stops.append(model.ball.predicted_stop())

    _run(session, {agent: model}, 350, compare)
    rest = session.ball.position()
    assert np.median(position_errors) < 0.05
    assert np.median(velocity_errors) < 0.15
    assert max(velocity_errors[10:]) < 0.6
    for stop in stops:  # seen from 2-4 m away while it still rolls over a metre
        assert math.hypot(stop[0] - rest[0], stop[1] - rest[1]) < 0.3
    assert model.ball.speed < 0.1
    assert model.ball.time_since_seen <= 0.06 + 1e-9
    # the relative position agrees with the field position through the helpers
    relative = model.to_relative((*model.ball.position, 0.042))
    np.testing.assert_allclose(model.to_field(relative)[:2], model.ball.position, atol=1e-9)
    torso = session.agents[agent].robot.torso_position()
    assert model.distance_to(model.ball.position) == pytest.approx(
        math.hypot(rest[0] - torso[0], rest[1] - torso[1]), abs=0.05
    )


def test_ball_model_follows_the_servers_rolling_law():
    """Noisy sightings every 0.06 s of a ball rolling as the server's does (exponential decay,
    tau 0.94 s): the velocity and the rest point come out right, and with no more sightings
    the prediction rolls on to that rest point."""
    rng = np.random.default_rng(4)
    tau, v0 = 0.94, 3.0
    ball = BallModel()
    for k in range(12):
        t = 0.06 * k
        x = v0 * tau * (1.0 - math.exp(-t / tau)) + rng.normal(0.0, 0.01)
        ball.observe((x, 1.0 + rng.normal(0.0, 0.01)), 2.0, time=t)
    t_last = 0.06 * 11
    speed = v0 * math.exp(-t_last / tau)
    assert ball.velocity[0] == pytest.approx(speed, abs=0.15)
    assert abs(ball.velocity[1]) < 0.15
    stop = ball.predicted_stop()
    assert stop[0] == pytest.approx(v0 * tau, abs=0.15)
    assert stop[1] == pytest.approx(1.0, abs=0.1)
    ball.predict(t_last + 10.0)
    assert ball.position[0] == pytest.approx(stop[0], abs=1e-3)
    assert ball.time_since_seen == pytest.approx(10.0)


def test_a_kicked_ball_restarts_the_filter():
    ball = BallModel()
    for k in range(5):
        ball.observe((1.0, 0.0), 1.0, time=0.06 * k)  # lying still
    assert ball.speed < 0.05
    ball.observe((1.3, 0.0), 1.0, time=0.30)  # 5 m/s: far outside a lying ball's noise
    assert ball.velocity[0] == pytest.approx(5.0, rel=0.01)
    assert ball.position == pytest.approx((1.3, 0.0))


# ------------------------------------------------------------------------------ other robots
def test_teammates_and_opponents_on_the_field(session):
    mate = _connect(session, "Alpha", 2)
    rival = _connect(session, "Beta", 3)
    me = _connect(session, "Alpha", 1)  # last: its model reads every message after init
    model = WorldModel(0)  # no team name: learnt from the own arms
    _run(session, {me: model}, 3)
    _place(session, "Left", 1, -3.0, 0.0, 0.0)
    _place(session, "Left", 2, -0.5, 1.5, 90.0)
    _place(session, "Right", 3, 1.0, -1.0, 180.0)
    _run(session, {me: model}, 40)
    assert model.team_name == "Alpha"
    assert 1 not in model.teammates, "the own arms are not a teammate"
    for tracker, agent, number in ((model.teammates, mate, 2), (model.opponents, rival, 3)):
        seen = tracker[number]
        truth = session.agents[agent].robot.torso_position()
        assert math.hypot(seen.position[0] - truth[0], seen.position[1] - truth[1]) < 0.15
        assert seen.is_fallen is False
        assert seen.age(model.time) <= 0.06 + 1e-9
        assert {"head", "lfoot", "rfoot"} <= set(seen.parts)
    assert model.opponents[3].team == "Beta"
    assert model.teammates.nearest((0.0, 2.0), model.time).unum == 2


def test_player_tracker_keeps_the_latest_sighting():
    tracker = PlayerTracker()
    tracker.observe("Beta", 5, {"lfoot": (1.0, 0.0, 0.0), "rfoot": (1.2, 0.0, 0.0)}, 1.0)
    tracker.observe("Beta", 5, {"head": (2.0, 1.0, 0.1)}, 2.0)
    tracker.observe("Beta", 6, {}, 2.0)  # nothing seen: ignored
    assert len(tracker) == 1
    assert tracker[5].position == (2.0, 1.0)
    assert tracker[5].is_fallen is True
    assert tracker.recent(now=5.0, max_age=2.0) == []


# ------------------------------------------------------------------------------ helpers
def test_helpers_need_a_pose_and_invert_each_other(session):
    agent = _connect(session, "Alpha", 1)
    model = WorldModel(0, "Alpha")
    with pytest.raises(ValueError, match="does not know"):
        model.to_field((0.0, 1.0, 0.0))
    _run(session, {agent: model}, 3)
    _place(session, "Left", 1, -5.0, 2.0, 30.0)
    _run(session, {agent: model}, 30)
    for point in ((1.0, 2.0, 0.0), (-4.0, 2.5, 0.3)):
        np.testing.assert_allclose(model.to_field(model.to_relative(point)), point, atol=1e-9)
    # a ground point 1 m along the heading is 1 m ahead in the ego frame, at the feet's level
    pose = model.pose
    h = math.radians(pose.heading_deg)
    ahead = (pose.x + math.cos(h), pose.y + math.sin(h), 0.0)
    np.testing.assert_allclose(
        model.to_ego(model.to_relative(ahead)), (1.0, 0.0, -model.torso_height), atol=1e-9
    )
    # the feet, through kinematics, tilt and pose, land where the simulator has them
    truth = session.agents[agent].robot.body_world_transforms()
    for foot in ("lfoot", "rfoot"):
        ours = model.to_field(model.body_transforms[foot][:3, 3])
        np.testing.assert_allclose(ours, truth[foot][:3, 3], atol=0.06)
    assert model.bearing_to((pose.x, pose.y + 1.0)) == pytest.approx(90.0 - pose.heading_deg)
