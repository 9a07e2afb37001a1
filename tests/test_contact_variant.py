"""The opt-in contact variant ``strike`` of ``benchmarks/physics.py``: softness on the ground
instead of the robot links, so a foot strikes the ball (bounce 0.8) instead of pushing it.

The defaults must stay exactly as they were (others tune skills on them); the variant must
keep the robot-ground contact and the ball's roll, and make the foot-ball contact bounce.
"""

from __future__ import annotations

import dataclasses

import pytest

import sim.field
import sim.robot
from benchmarks.physics import VARIANTS, idle_stance
from sim.contact_models import contact_physics
from sim.field import BallPhysics, GroundPhysics, foot_strike_speed
from sim.physics import PhysicsWorld
from sim.robot import RobotPhysics, SimRobot
from sim.session import Session, SessionConfig

FOOT_SPEED = 2.0


def _strike_ratio() -> float:
    """Ball launch speed over the speed of a rigidly driven foot box with the current robot
    physics hitting a resting ball of the current ball physics."""
    return _strike_ratio_of(sim.robot.DEFAULT_PHYSICS.collider_dynamics())


def _strike_ratio_of(foot_dynamics: dict[str, float]) -> float:
    """The same for a foot box with the collider settings ``foot_dynamics``."""
    launch = foot_strike_speed(
        FOOT_SPEED, sim.field.DEFAULT_SUBSTEPS, foot_dynamics=foot_dynamics, ball_physics=None
    )
    return launch / FOOT_SPEED


def test_defaults_are_the_frozen_physics() -> None:
    """The hooks' defaults build exactly what the field and robots built before them."""
    assert GroundPhysics().dynamics() == {
        "lateralFriction": 1.0,
        "restitution": 1.0,
        "rollingFriction": 0.0,
    }
    assert GroundPhysics() == sim.field.DEFAULT_GROUND
    assert BallPhysics() == sim.field.DEFAULT_BALL
    assert RobotPhysics() == sim.robot.DEFAULT_PHYSICS
    assert RobotPhysics().soft_contacts
    world = PhysicsWorld(substeps=2)
    try:
        assert SimRobot(world, 0).physics is sim.robot.DEFAULT_PHYSICS
    finally:
        world.close()


def test_strike_variant_is_undone_on_exit() -> None:
    with VARIANTS["strike"]():
        assert not sim.robot.DEFAULT_PHYSICS.soft_contacts
        assert sim.field.DEFAULT_GROUND.contact_stiffness == RobotPhysics().contact_stiffness
    assert RobotPhysics() == sim.robot.DEFAULT_PHYSICS
    assert GroundPhysics() == sim.field.DEFAULT_GROUND
    assert BallPhysics() == sim.field.DEFAULT_BALL
    assert sim.field.POST_RESTITUTION == 1.0


def test_restitution_products_match_the_real_server() -> None:
    """Bullet multiplies restitutions: foot-ball, ball-ground and ball-post 0.8, robot-robot
    and robot-ground at most 0.01."""
    with VARIANTS["strike"]():
        robot = sim.robot.DEFAULT_PHYSICS.restitution
        ball = sim.field.DEFAULT_BALL.restitution
        ground = sim.field.DEFAULT_GROUND.restitution
        post = sim.field.POST_RESTITUTION
    assert robot * ball == pytest.approx(0.8)
    assert ball * ground == pytest.approx(0.8)
    assert ball * post == pytest.approx(0.8)
    assert robot * robot <= 0.0101 and robot * ground <= 0.0101


def test_default_foot_pushes_and_strike_foot_bounces() -> None:
    """Today's soft, inelastic foot gives the ball the foot's own speed; under ``strike`` the
    ball leaves at about 1 + 0.8 times the foot's speed, as off a rigid foot on the real
    server."""
    assert _strike_ratio() == pytest.approx(1.0, abs=0.1)
    with VARIANTS["strike"]():
        assert _strike_ratio() == pytest.approx(1.8, abs=0.1)
    with VARIANTS["rigid"]():
        assert _strike_ratio() == pytest.approx(1.0, abs=0.1)


def test_strike_keeps_the_standing_robot_on_the_ground_as_tuned() -> None:
    """The robot-ground contact is the same spring either way, so an idle robot stands at the
    same height (the fidelity benchmark's stand figures depend on it)."""
    drop_default, tilt_default = idle_stance(0, seconds=1.0)
    with VARIANTS["strike"]():
        drop_strike, tilt_strike = idle_stance(0, seconds=1.0)
    assert drop_strike == pytest.approx(drop_default, abs=1e-3)
    assert tilt_strike == pytest.approx(tilt_default, abs=0.5)


def test_strike_ball_physics_only_changes_restitution() -> None:
    with VARIANTS["strike"]():
        ball = sim.field.DEFAULT_BALL
    assert dataclasses.replace(ball, restitution=BallPhysics().restitution) == BallPhysics()


@pytest.mark.parametrize("name", ["noself", "strike_noself"])
def test_no_self_collision_variants_reach_sessions(name: str) -> None:
    """Benchmarks build sessions with the default ``self_collision: true``; the variants must
    still take a robot's self-contacts away there (a first version did not)."""
    from sim.session import Session, SessionConfig

    with VARIANTS[name]():
        session = Session(SessionConfig())
    try:
        assert not session.contact.robot.self_collision
    finally:
        session.world.close()
    session = Session(SessionConfig())
    try:
        assert session.contact.robot.self_collision
    finally:
        session.world.close()


def test_strike_feet_keeps_other_links_soft_and_feet_striking() -> None:
    with VARIANTS["strike_feet"]():
        physics = sim.robot.DEFAULT_PHYSICS
        foot_ratio = _strike_ratio_of(physics.collider_dynamics("lfoot"))
        assert "contactStiffness" in physics.collider_dynamics("lthigh")
        assert "contactStiffness" not in physics.collider_dynamics("rfoot")
    assert foot_ratio == pytest.approx(1.8, abs=0.1)


@pytest.mark.parametrize(
    ("variant", "model"),
    [("current", "bounce"), ("bounce", "bounce"), ("soft", "soft"), ("strike", "strike")],
)
def test_a_session_inside_a_contact_variant_plays_exactly_its_contacts(variant, model) -> None:
    """A session plays the variant's contacts, not its configured model on top of them (with
    ``bounce`` the default, the bounces applied twice put ball-ground restitution at 8)."""
    with VARIANTS[variant]():
        session = Session(SessionConfig(beam_noise=False))
        try:
            contact = session.contact
        finally:
            session.world.close()
    assert contact == contact_physics(model)
    ball_ground = contact.ball.restitution * contact.ground.restitution
    assert ball_ground == pytest.approx(
        0.8 if model != "soft" else sim.field.DEFAULT_BALL.restitution
    )
