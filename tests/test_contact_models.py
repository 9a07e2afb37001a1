"""The server's contact options (``contact`` and ``self_collision`` in ``config/server.yaml``,
``sim.contact_models``): the default is ``bounce``, which gives the soft contacts tuned before
the real server's bounces (a ball off a foot at 0.8) and leaves robots standing as they were;
``soft`` builds exactly the physics tuned before; ``strike`` makes a driven foot strike the ball
at 1 + 0.8 times its speed; ``self_collision: false`` keeps a robot's own parts from touching,
as on the real server."""

from __future__ import annotations

from pathlib import Path

import pybullet
import pytest

import sim.field
import sim.robot
from sim.contact_models import STRIKE_MIN_BOUNCE_SPEED, contact_physics
from sim.field import BALL_RADIUS, DEFAULT_SUBSTEPS, Ball, foot_strike_speed
from sim.physics import PhysicsWorld
from sim.robot import SimRobot
from sim.session import Session, SessionConfig
from world.yaml_config import ConfigError, config_from_mapping

CONFIG = Path(__file__).resolve().parents[1] / "config" / "server.yaml"
FOOT_SPEED = 2.0
#: Hip rolls that cross the legs (each leg swung inwards), so the feet and shanks overlap.
CROSSED_LEGS_DEG = {"llj2": -40.0, "rlj2": 40.0}


def _strike_ratio(model: str) -> float:
    """Ball launch speed over the speed of a driven foot box touching the ball as a robot's
    foot does under contact model ``model``."""
    physics = contact_physics(model)
    launch = foot_strike_speed(
        FOOT_SPEED,
        DEFAULT_SUBSTEPS,
        foot_dynamics=physics.robot.collider_dynamics(),
        ball_physics=physics.ball,
        min_bounce_speed=physics.min_bounce_speed,
    )
    return launch / FOOT_SPEED


def _self_contacts(self_collision: bool) -> int:
    """Contact points between parts of one robot whose legs are set crossed in the air."""
    world = PhysicsWorld(substeps=2)
    try:
        physics = contact_physics("soft", self_collision).robot
        robot = SimRobot(world, 0, physics, position=(0.0, 0.0, 1.0))
        robot.place(0.0, 0.0, 1.0, 0.0, CROSSED_LEGS_DEG)
        pybullet.setGravity(0.0, 0.0, 0.0, physicsClientId=world.client)
        world.step_cycle()
        contacts = pybullet.getContactPoints(
            bodyA=robot.body_id, bodyB=robot.body_id, physicsClientId=world.client
        )
        return len(contacts)
    finally:
        world.close()


def test_server_yaml_plays_the_real_servers_bounces() -> None:
    """Since session 20 the server's default is ``bounce``: the soft springs of the tuned
    physics, the real server's restitutions and minimum bounce speed."""
    config = SessionConfig.from_yaml(CONFIG)
    assert (config.contact, config.self_collision) == ("bounce", True)
    assert SessionConfig().contact == "bounce"
    session = Session(config)
    try:
        assert session.contact == contact_physics()
        assert session.contact == contact_physics("bounce")
        assert session.contact.min_bounce_speed == STRIKE_MIN_BOUNCE_SPEED
        assert (
            session.contact.robot.contact_stiffness == sim.robot.DEFAULT_PHYSICS.contact_stiffness
        )
        assert session.contact.ball.restitution > sim.field.DEFAULT_BALL.restitution
    finally:
        session.world.close()


def test_soft_contact_keeps_the_frozen_physics() -> None:
    """``contact: soft`` builds exactly the physics tuned before the contact options existed."""
    session = Session(SessionConfig(contact="soft"))
    try:
        assert session.contact.robot is sim.robot.DEFAULT_PHYSICS
        assert session.contact.ball is sim.field.DEFAULT_BALL
        assert session.contact.min_bounce_speed is None
    finally:
        session.world.close()


def test_unknown_contact_model_is_a_clear_error() -> None:
    with pytest.raises(ConfigError, match="contact must be one of soft, strike, bounce"):
        config_from_mapping(SessionConfig, {"contact": "bouncy"}, source="server.yaml")


def test_soft_foot_pushes_and_strike_foot_strikes() -> None:
    assert _strike_ratio("soft") == pytest.approx(1.0, abs=0.1)
    assert _strike_ratio("strike") == pytest.approx(1.8, abs=0.1)


def test_strike_restitution_products_are_the_real_servers() -> None:
    """Bullet multiplies the bodies' restitutions: foot-ball, ball-ground and ball-post 0.8
    (the ball's bounce), robot-robot and robot-ground at most 0.01."""
    physics = contact_physics("strike")
    robot, ball = physics.robot.restitution, physics.ball.restitution
    ground = physics.ground.restitution
    assert robot * ball == pytest.approx(0.8)
    assert ball * ground == pytest.approx(0.8)
    assert ball * physics.post_restitution == pytest.approx(0.8)
    assert max(robot * robot, robot * ground) <= 0.0101
    assert physics.ground.contact_stiffness == contact_physics().robot.contact_stiffness


def test_without_self_collision_a_robots_parts_pass_through_each_other() -> None:
    assert _self_contacts(True) > 0
    assert _self_contacts(False) == 0


def test_strike_session_without_self_collision_stands_a_robot() -> None:
    """The option reaches the robots a session creates, and a robot stands on the strike
    model's ground as on today's (the same robot-ground spring)."""
    heights = {}
    for contact in ("soft", "strike"):
        config = SessionConfig(seed=1, beam_noise=False, contact=contact, self_collision=False)
        session = Session(config)
        try:
            agent = session.add_agent()
            session.handle_message(agent, b"(scene rsg/agent/nao/nao_hetero.rsg 0)")
            session.step()
            robot = session.agents[agent].robot
            assert robot is not None and not robot.physics.self_collision
            for _ in range(100):
                session.step()
            assert not robot.has_fallen()
            heights[contact] = robot.torso_position()[2]
        finally:
            session.world.close()
    assert heights["strike"] == pytest.approx(heights["soft"], abs=0.002)


#: Speed (m/s) at which a ball is sent against a robot's toe.
THROW_SPEED = 2.0


def _standing_robot(contact: str) -> tuple[Session, int]:
    """A session of contact model ``contact`` with one type-0 robot standing at the origin,
    facing +x, the ball out of the way."""
    session = Session(SessionConfig(seed=1, beam_noise=False, contact=contact))
    agent = session.add_agent()
    session.handle_message(agent, b"(scene rsg/agent/nao/nao_hetero.rsg 0)")
    session.step()
    robot = session.agents[agent].robot
    assert robot is not None
    robot.place(0.0, 0.0, robot.spec.sole_height() - 0.005, 0.0)
    session.ball.place((3.0, 3.0, BALL_RADIUS))
    for _ in range(50):
        session.step()
    return session, agent


def _floating_robot_and_ball(contact: str) -> tuple[PhysicsWorld, SimRobot, Ball]:
    """Without gravity, a type-0 robot held in its zero pose 1 m up, facing +x, and a ball of
    contact model ``contact`` level with the middle of its left foot, 0.1 m ahead of the toe."""
    physics = contact_physics(contact)
    world = PhysicsWorld(substeps=DEFAULT_SUBSTEPS, min_bounce_speed=physics.min_bounce_speed)
    robot = SimRobot(world, 0, physics.robot, position=(0.0, 0.0, 1.0))
    robot.place(0.0, 0.0, 1.0, 0.0)
    pybullet.setGravity(0.0, 0.0, 0.0, physicsClientId=world.client)
    foot = robot.body_world_transforms()["lfoot"]
    toe_x = foot[0, 3] + robot.spec.body("lfoot").size[1] / 2
    ball = Ball.create(world, (toe_x + 0.1 + BALL_RADIUS, foot[1, 3], foot[2, 3]), physics.ball)
    return world, robot, ball


def _rebound_ratio(world: PhysicsWorld, ball: Ball) -> float:
    """Send ``ball`` at :data:`THROW_SPEED` straight at the toe (-x) and return the speed it
    comes back with (+x, largest over 0.3 s) over the speed it was sent at."""
    ball.place(ball.position(), (-THROW_SPEED, 0.0, 0.0))
    away = 0.0
    for _ in range(15):
        world.step_cycle()
        away = max(away, ball.velocity()[0])
    return away / THROW_SPEED


def test_bounce_sends_the_ball_back_off_a_foot_and_soft_stops_it() -> None:
    """A ball sent at a foot: with today's restitutions (the robot's 0 times the ball's 0.8)
    the soft foot stops it dead; with ``bounce``'s (0.1 times 8) it comes back. Not at the
    full 0.8: within the impact the motors hold the foot with a bounded force, so the ball
    meets little more than the foot's own mass: (0.8 M - m) / (M + m) is 0.56 for M = 0.17 kg
    of the 0.2 kg foot and the ball's m = 0.026 kg."""
    ratios = {}
    for contact in ("soft", "bounce"):
        world, _, ball = _floating_robot_and_ball(contact)
        try:
            ratios[contact] = _rebound_ratio(world, ball)
        finally:
            world.close()
    assert ratios["soft"] < 0.2
    assert 0.45 < ratios["bounce"] < 0.8


def test_bounce_leaves_a_standing_robot_as_it_was() -> None:
    """Only restitutions change (robot-ground 0.01 and no bounce below 0.8 m/s): a robot
    stands at the same height and its foot pressure sensors read the same load."""
    figures = {}
    for contact in ("soft", "bounce"):
        session, agent = _standing_robot(contact)
        try:
            robot = session.agents[agent].robot
            load = sum(r.force[2] for r in robot.force_resistance().values())
            figures[contact] = (robot.torso_position()[2], load)
        finally:
            session.world.close()
    assert figures["bounce"][0] == pytest.approx(figures["soft"][0], abs=1e-4)
    assert figures["bounce"][1] == pytest.approx(figures["soft"][1], rel=0.01)
