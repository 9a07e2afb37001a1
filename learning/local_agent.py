"""One agent driven in-process: perception bytes -> world model -> skills -> effector bytes.

Training environments, benchmarks and tests all need to run a skill on one robot of an
in-process :class:`~sim.session.Session` without sockets. :class:`LocalAgent` is that loop, and
it keeps the agent honest: the skills see only what the perception bytes say (through a
:class:`~world.world_model.WorldModel`), and answer through effector bytes, exactly as over TCP.
Ground truth (``robot``, :meth:`LocalAgent.is_standing`) is there for the caller's own checks,
never for the skills.
"""

from __future__ import annotations

import copy
import math

import behaviors  # noqa: F401  (registers the built-in skills)
from behaviors.manager import Behavior
from sim.robot import SimRobot
from sim.session import Session, SessionSnapshot
from world.effectors import EffectorMessage, write_effectors
from world.perception import parse_perception
from world.world_model import WorldModel

#: Ground truth for "standing": torso within this angle of vertical ...
UPRIGHT_DEG = 25.0
#: ... and its centre at least this fraction of the zero-pose torso height.
STANDING_HEIGHT_FRACTION = 0.8
#: Cycles the stand pose is held after rising, so the body stops swaying.
STAND_SETTLE_CYCLES = 25


class LocalAgent:
    """One agent's loop in-process; every :meth:`run` is one 0.02 s cycle of the session.

    Several may share a session, but each :meth:`run` steps the whole session, so a caller
    running several agents should call :meth:`act` on each and step the session itself.
    """

    def __init__(
        self, session: Session, agent: int, robot_type: int, team_name: str | None = None
    ) -> None:
        self.session = session
        self.agent = agent
        self.robot_type = robot_type
        self.world = WorldModel(robot_type, team_name)
        self.behavior = Behavior(self.world, robot_type)

    @classmethod
    def join(
        cls,
        session: Session,
        team_name: str = "Local",
        unum: int = 1,
        robot_type: int = 0,
        beam: tuple[float, float, float] | None = None,
        settle_cycles: int = 2,
    ) -> LocalAgent:
        """Connect a robot (scene, init, optional beam) through the same bytes as a client."""
        agent = session.join(team_name, unum, robot_type, beam=beam, settle_cycles=settle_cycles)
        return cls(session, agent, robot_type, team_name)

    @classmethod
    def from_snapshot(
        cls,
        session: Session,
        agent: int,
        robot_type: int,
        team_name: str | None,
        snapshot: SessionSnapshot,
        world: WorldModel,
    ) -> LocalAgent:
        """Put ``session`` back to ``snapshot`` (``Session.save_state``) and return agent
        ``agent`` with a copy of ``world`` (its world model saved with the snapshot) and new
        skills, as a robot whose behaviour starts now: how fall banks, saved benchmark falls
        and training episodes start again from a saved moment (a restored fall continues
        exactly as the original: tests/test_get_up_env.py)."""
        session.restore_state(snapshot)
        local = cls(session, agent, robot_type, team_name)
        local.world = copy.deepcopy(world)
        local.behavior = Behavior(local.world, robot_type)
        return local

    # ------------------------------------------------------------------ the loop
    @property
    def commands(self):
        """This cycle's joint commands (a :class:`~behaviors.joint_control.JointCommands`)."""
        return self.behavior.commands

    @property
    def state(self):
        """The robot's own state as perceived (a :class:`~world.robot_state.RobotState`)."""
        return self.world.robot

    def perceive(self) -> None:
        """Read this cycle's perception bytes into the world model."""
        self.world.update(parse_perception(self.session.perception(self.agent)))

    def act(self, name: str, *args: object) -> bool:
        """Perceive, execute skill ``name`` and queue its effector bytes, without stepping;
        True when the skill has finished."""
        self.perceive()
        return self.decide(name, *args)

    def decide(self, name: str, *args: object) -> bool:
        """Execute skill ``name`` on what was last perceived and queue its effector bytes,
        without perceiving or stepping; True when the skill has finished."""
        self.behavior.begin_cycle()
        finished = self.behavior.execute(name, *args)
        self.queue(self.behavior.effector_speeds())
        return finished

    def queue(self, speeds: dict[str, float]) -> None:
        """Send joint speeds (rad/s by effector name) plus ``(syn)`` as effector bytes."""
        message = EffectorMessage(joint_speeds=speeds, syn=True)
        self.session.handle_message(self.agent, write_effectors(message))

    def send(self, speeds: dict[str, float]) -> None:
        """Send joint speeds and step the session one cycle."""
        self.queue(speeds)
        self.session.step()

    def run(self, name: str, *args: object) -> bool:
        """One cycle of ``Behavior.execute(name, *args)`` and a session step; True when the
        skill has finished."""
        finished = self.act(name, *args)
        self.session.step()
        return finished

    def rise_to_stand(self) -> LocalAgent:
        """From the beam's zero pose rise slowly into ``stand`` and hold it half a second:
        jumping into the stand's bent knees at once tips the robot over."""
        while not self.run("keyframe", "stand_up_slowly"):
            pass
        for _ in range(STAND_SETTLE_CYCLES):
            self.run("pose", "stand")
        return self

    def trainer(self, text: str) -> None:
        """Queue trainer commands (monitor-port syntax) on the session."""
        self.session.trainer(text)

    # ------------------------------------------------------------------ ground truth
    @property
    def robot(self) -> SimRobot:
        """The simulated robot: ground truth for checks, never for skills."""
        return self.session.agents[self.agent].robot

    def is_standing(self) -> bool:
        """Ground truth: upright torso at standing height, both feet on the ground."""
        robot = self.robot
        upright = robot.torso_up()[2] > math.cos(math.radians(UPRIGHT_DEG))
        height = robot.torso_position()[2] > STANDING_HEIGHT_FRACTION * robot.spec.sole_height()
        feet = robot.force_resistance()
        return bool(upright and height and "lf" in feet and "rf" in feet)
