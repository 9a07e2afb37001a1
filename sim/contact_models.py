"""Contact models of the stand-in: where the ground's softness sits, how the ball bounces off a
foot, and whether a robot's own parts touch each other.

Bullet makes a contact soft when EITHER body carries soft-contact parameters (stiffness in
series, damping summed) and multiplies the two bodies' restitutions. The real server's contacts
are set per pair (ODE surface parameters), so one model cannot match every pair at once:

* ``soft`` (the default until session 20, tuned against the real server's traces): every robot
  collider carries the ground contact's spring (1000 N/m, 80 N s/m per contact point), so
  foot-ball and robot-robot contacts are that spring too; a foot pushes the ball (ball speed =
  foot speed).
* ``strike``: the spring sits on the ground instead. Robot-ground contacts stay the same spring
  (1000 N/m in series with a rigid body, 80 + 0 N s/m); foot-ball and robot-robot contacts
  become rigid. Restitutions are chosen so the products match the real server: foot-ball,
  ball-ground and ball-post 0.8 (the ball's bounce), robot-robot and robot-ground 0.01; no
  contact closing slower than 0.8 m/s bounces (the real server's minimum bounce velocity). A
  driven foot then gives the ball 1.8x its speed, as off a rigid foot on the real server.

* ``bounce`` (the default since session 20): every spring and damper as ``soft``, with the
  restitutions of ``strike`` (foot-ball, ball-ground, ball-post 0.8; robot-ground, robot-robot
  0.01) and its 0.8 m/s minimum bounce speed. This is how the real server builds a foot-ball
  contact: SimSpark's ``ContactJointHandler`` mixes the two colliders' surfaces, so the robot's
  soft ERP / CFM (averaged with the ball's) and the ball's bounce 0.8 (the robot's is off) both
  apply; a bounce is a velocity target, which a 26 g ball meets nearly in full through a soft
  contact too. A foot then gives the ball about 2x its speed (``benchmarks/kick.py --impact``
  under ``benchmarks/physics.py --variant bounce``), as off the real server's foot, while
  robot-ground contacts and a robot's self-contacts keep their springs (which ``strike`` could
  not: its rigid robot links made the get-up and the kicks fall).

``self_collision`` False lets no two parts of one robot touch, as on the real server
(``nao_hetero.rsg``: each NAO is a ``Space`` with ``disableInnerCollision true``); see
``sim/robot.py``.

The session builds its world from :func:`contact_physics` (``contact`` and ``self_collision``
in ``config/server.yaml``); ``contact: soft`` gives exactly the physics built before these
options, the default ``bounce`` that physics with the real server's bounces.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import sim.field
import sim.robot
from sim.field import BallPhysics, GroundPhysics
from sim.robot import RobotPhysics

#: The contact models :func:`contact_physics` knows.
CONTACT_MODELS = ("soft", "strike", "bounce")
#: The model a session uses unless ``config/server.yaml`` names another.
DEFAULT_CONTACT_MODEL = "bounce"
#: Restitution of robot links under ``strike``: with robot r, ball 0.8 / r and ground r, the
#: products foot-ball and ball-ground are 0.8 while robot-robot and robot-ground are r^2
#: (0.01: no bounce). Bullet does not clamp one body's value above 1, only products matter.
STRIKE_ROBOT_RESTITUTION = 0.1
#: The real server's minimum bounce velocity of the ball's contacts (nao-model-facts.md);
#: Bullet's own threshold is 0.2 m/s and applies to every contact.
STRIKE_MIN_BOUNCE_SPEED = 0.8


@dataclass(frozen=True)
class ContactPhysics:
    """Everything a world needs to build its contacts: robot, ground and ball materials, the
    goal posts' restitution and the world's minimum bounce speed (None: Bullet's own)."""

    robot: RobotPhysics
    ground: GroundPhysics
    ball: BallPhysics
    post_restitution: float
    min_bounce_speed: float | None = None


def soft_contact() -> ContactPhysics:
    """Today's tuned contacts, read from the module defaults when called (benchmark variants
    patch those defaults, and a session built inside a variant must follow them)."""
    return ContactPhysics(
        robot=sim.robot.DEFAULT_PHYSICS,
        ground=sim.field.DEFAULT_GROUND,
        ball=sim.field.DEFAULT_BALL,
        post_restitution=sim.field.POST_RESTITUTION,
    )


def _with_restitutions(
    base: ContactPhysics, robot_r: float, ball_r: float, min_bounce_speed: float | None
) -> ContactPhysics:
    """``base`` with restitution ``robot_r`` on the robots and ``ball_r`` on the ball, the
    ground's set so that ball-ground keeps the ball's own bounce (Bullet multiplies the two
    bodies'), the posts scaled alike, and the world's minimum bounce speed."""
    ground_r = base.ball.restitution / ball_r
    return dataclasses.replace(
        base,
        robot=dataclasses.replace(base.robot, restitution=robot_r),
        ground=dataclasses.replace(base.ground, restitution=ground_r),
        ball=dataclasses.replace(base.ball, restitution=ball_r),
        post_restitution=base.post_restitution * ground_r,
        min_bounce_speed=min_bounce_speed,
    )


def bounce_contact(
    base: ContactPhysics, robot_restitution: float = STRIKE_ROBOT_RESTITUTION
) -> ContactPhysics:
    """``base`` with the restitutions of the real server's contacts: foot-ball (every robot
    collider with the ball), ball-ground and ball-post 0.8, robot-robot and robot-ground the
    square of ``robot_restitution`` (Bullet multiplies the two bodies'; the robot r, the ball
    0.8 / r and the ground r, as ``strike``'s with r = 0.1: 0.01), and the ball's 0.8 m/s
    minimum bounce speed. Every spring and damper stays as in ``base``."""
    ball_r = base.ball.restitution / robot_restitution
    return _with_restitutions(base, robot_restitution, ball_r, STRIKE_MIN_BOUNCE_SPEED)


def strike_contact(base: ContactPhysics, bounce: bool = True) -> ContactPhysics:
    """``base`` with the robots' soft-contact parameters moved onto the ground (see the module
    docstring) and ``bounce``'s restitutions. Without ``bounce`` the robot links keep
    restitution 0 (a rigid foot-ball contact that does not bounce), the ball and ground their
    own."""
    if bounce:
        physics = bounce_contact(base)
    else:
        physics = _with_restitutions(base, 0.0, base.ball.restitution, STRIKE_MIN_BOUNCE_SPEED)
    return dataclasses.replace(
        physics,
        robot=dataclasses.replace(physics.robot, soft_contacts=False),
        ground=dataclasses.replace(
            physics.ground,
            contact_stiffness=base.robot.contact_stiffness,
            contact_damping=base.robot.contact_damping,
        ),
    )


def with_self_collision(physics: ContactPhysics, self_collision: bool) -> ContactPhysics:
    """``physics`` with or without contacts between a robot's own parts."""
    if physics.robot.self_collision == self_collision:
        return physics
    robot = dataclasses.replace(physics.robot, self_collision=self_collision)
    return dataclasses.replace(physics, robot=robot)


def contact_physics(
    model: str = DEFAULT_CONTACT_MODEL, self_collision: bool = True
) -> ContactPhysics:
    """The contacts of contact model ``model`` (one of :data:`CONTACT_MODELS`), with or without
    contacts between a robot's own parts."""
    if model not in CONTACT_MODELS:
        raise ValueError(f"unknown contact model {model!r}; valid: {', '.join(CONTACT_MODELS)}")
    physics = soft_contact()
    if model == "strike":
        physics = strike_contact(physics)
    elif model == "bounce":
        physics = bounce_contact(physics)
    return with_self_collision(physics, self_collision)
