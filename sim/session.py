"""One simulated game stepped in-process: physics, referee, perceptors and effectors.

A :class:`Session` is the server without sockets. Agents talk to it with the very bytes they
would send over TCP (``handle_message``) and read back the very perception bytes the server
would send (``perception``), so training, tests and the networked server share one code path.
Many sessions live in one process: each owns its own PyBullet client.

Timing follows rcssserver3d: one :meth:`Session.step` is one 0.02 s cycle, and an action sent in
answer to perception ``k`` first shows in perception ``k + 2`` (received actions wait one cycle
in a staging slot before they reach the motors). ``init`` follows the same path, which is why the
``GS`` perceptor carries the unum and side exactly two messages after ``init``.
"""

from __future__ import annotations

import copy
import logging
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from sim.contact_models import (
    CONTACT_MODELS,
    DEFAULT_CONTACT_MODEL,
    ContactPhysics,
    contact_physics,
)
from sim.field import DEFAULT_SUBSTEPS, Ball, build_field
from sim.hearing import Ear, Listener, broadcast
from sim.monitor import (
    DropBall,
    KickOff,
    KillAgent,
    MoveAgent,
    MoveBall,
    RequestFullState,
    SetPlayMode,
    TrainerCommand,
    parse_trainer_commands,
)
from sim.physics import CYCLE_SECONDS, PhysicsWorld
from sim.referee import (
    BallInfo,
    Event,
    MovePlayer,
    PlaceBall,
    PlayerInfo,
    Referee,
    RefereeConfig,
)
from sim.robot import SimRobot
from sim.scene_graph import MonitorHeader, SceneGraph
from sim.vision import VisibleRobot, VisionSensor
from world.effectors import EffectorMessage, parse_effectors
from world.field_geometry import BALL_RADIUS
from world.perception import GameState, Perception, Vision, write_perception
from world.yaml_config import load_yaml_config

log = logging.getLogger(__name__)

#: The scene every NAO client asks for; other scenes are refused.
NAO_SCENE = "rsg/agent/nao/nao_hetero.rsg"
#: Torso height at which beam places a robot (the real server's AgentRadius).
BEAM_HEIGHT = 0.4
#: Parts of a robot that other robots' vision reports.
VISIBLE_PARTS = ("head", "rlowerarm", "llowerarm", "rfoot", "lfoot")
MAX_SAY_LENGTH = 20
#: Substeps of an ordinary cycle: the robot stands and matches the real server's motions
#: (benchmarks/fidelity.py) at 2; at 1 it is unstable.
BASE_SUBSTEPS = 2
#: How far a striking body may travel in one substep: sim.field shows that DEFAULT_SUBSTEPS
#: substeps catch every contact up to 10 m/s, i.e. this travel per substep.
SAFE_TRAVEL_PER_SUBSTEP = 10.0 * CYCLE_SECONDS / DEFAULT_SUBSTEPS
#: Robots whose torso is this close to the ball (m) are checked for fast feet.
NEAR_BALL = 0.8
#: Headroom for a foot that speeds up during the cycle.
SPEED_MARGIN = 1.5


@dataclass(frozen=True)
class SessionConfig:
    """Settings of a simulated game (``config/server.yaml`` holds the defaults)."""

    #: physics substeps per 0.02 s cycle; 0 = adaptive: ``BASE_SUBSTEPS``, refined up to
    #: ``sim.field.DEFAULT_SUBSTEPS`` in cycles where a fast foot is near the ball
    substeps: int = 0
    seed: int = 0
    vision_noise: bool = True
    beam_noise: bool = True
    #: a new image every this many cycles, counted per robot (the real server: 3)
    see_interval: int = 3
    beam_noise_xy: float = 0.05
    beam_noise_angle_deg: float = 10.0
    #: contact model (``sim.contact_models``): "bounce" (the default: the tuned soft springs with
    #: the real server's bounces, the ball off a foot at 0.8), "soft" (no bounces, the foot
    #: pushes the ball) or "strike" (the ground carries the softness, the foot strikes the ball)
    contact: str = DEFAULT_CONTACT_MODEL
    #: False: no contacts between a robot's own parts, as on the real server
    self_collision: bool = True
    referee: RefereeConfig = field(default_factory=RefereeConfig)

    def __post_init__(self) -> None:
        if self.substeps < 0:
            raise ValueError(f"substeps must be >= 0, got {self.substeps}")
        if self.contact not in CONTACT_MODELS:
            raise ValueError(
                f"contact must be one of {', '.join(CONTACT_MODELS)}, got {self.contact!r}"
            )
        if self.see_interval < 1:
            raise ValueError(f"see_interval must be >= 1, got {self.see_interval}")

    @classmethod
    def from_yaml(cls, path: str | Path) -> SessionConfig:
        return load_yaml_config(cls, path)


@dataclass
class AgentSlot:
    """One connected agent: its robot (after ``scene``), identity (after ``init``) and queues."""

    agent_id: int
    robot: SimRobot | None = None
    robot_type: int = 0
    team_name: str | None = None
    side: str | None = None
    unum: int | None = None
    vision: VisionSensor | None = None
    perceptions_sent: int = 0
    #: effector messages received since the last step
    pending: list[EffectorMessage] = field(default_factory=list)
    #: messages received one cycle earlier: they reach the motors at the next step
    staged: list[EffectorMessage] = field(default_factory=list)
    announce_identity: bool = False
    perception_bytes: bytes | None = None
    #: hearing capacity and messages waiting for the next perception (sim.hearing)
    ear: Ear = field(default_factory=Ear)

    @property
    def robot_id(self) -> str:
        return f"agent{self.agent_id}"


@dataclass(frozen=True)
class SessionSnapshot:
    """Everything needed to continue a session exactly from a saved cycle."""

    physics: object
    python_state: dict


def default_contacts() -> ContactPhysics:
    """The contacts a session built with the default ``SessionConfig`` plays (since session 20
    the ``bounce`` model), for worlds built outside a session (fidelity replays, ball rolls).
    ``contact_physics`` is looked up in this module at call time, so a benchmark variant that
    sets what sessions play (``benchmarks/physics.py``) sets it here too."""
    config = SessionConfig()
    return contact_physics(config.contact, config.self_collision)


class Session:
    """A game without sockets: agents exchange wire-format bytes with it, cycle by cycle."""

    def __init__(self, config: SessionConfig | None = None) -> None:
        self.config = config or SessionConfig()
        self.contact = contact_physics(self.config.contact, self.config.self_collision)
        self.world = PhysicsWorld(
            substeps=self.config.substeps or BASE_SUBSTEPS,
            min_bounce_speed=self.contact.min_bounce_speed,
        )
        self.field = build_field(self.world, self.contact.ground, self.contact.post_restitution)
        self.ball = Ball.create(self.world, (0.0, 0.0, BALL_RADIUS), self.contact.ball)
        self.referee = Referee(self.config.referee, seed=self.config.seed)
        self.scene = SceneGraph()
        self.rng = np.random.default_rng(self.config.seed)
        self.time = 0.0
        self.cycle = 0
        self.agents: dict[int, AgentSlot] = {}
        self.events: list[Event] = []
        self._next_agent_id = 1
        self._trainer_queue: list[TrainerCommand] = []
        self._said: list[tuple[AgentSlot, str]] = []
        self._full_state_requested = True

    # ------------------------------------------------------------------ connections
    def add_agent(self) -> int:
        """Register a new connection; its robot appears when it sends ``scene``."""
        agent_id = self._next_agent_id
        self._next_agent_id += 1
        slot = AgentSlot(agent_id)
        self.agents[agent_id] = slot
        # the real server shows a connected agent without a robot as an empty node
        self.scene.add_pending_robot(slot.robot_id)
        self._full_state_requested = True
        return agent_id

    def remove_agent(self, agent_id: int) -> None:
        """Drop a connection and its robot (a client vanishing, or the trainer's kill)."""
        slot = self.agents.pop(agent_id, None)
        if slot is None:
            return
        if slot.robot is not None:
            self.scene.remove_robot(slot.robot_id)
            slot.robot.remove()
        log.info("agent %d (%s %s) left", agent_id, slot.team_name, slot.unum)

    def handle_message(self, agent_id: int, payload: bytes) -> list[str]:
        """Take one effector message from an agent; returns the errors found (also logged).

        ``scene`` creates the robot at once; every other effector waits for the next step and
        then one more cycle, as on the real server.
        """
        slot = self.agents.get(agent_id)
        if slot is None:
            raise KeyError(f"no agent {agent_id}; connected: {sorted(self.agents)}")
        message, errors = parse_effectors(payload)
        if message.scene is not None:
            errors += self._create_robot(slot, *message.scene)
            message.scene = None
        if slot.robot is None and _has_actions(message):
            errors.append("effectors before scene are ignored")
        else:
            errors += self._check_joint_effectors(slot, message)
            slot.pending.append(message)
        for error in errors:
            log.warning("agent %d: %s", agent_id, error)
        return errors

    def join(
        self,
        team_name: str,
        unum: int = 0,
        robot_type: int = 0,
        beam: tuple[float, float, float] | None = None,
        settle_cycles: int = 0,
    ) -> int:
        """Connect an in-process agent as a client does (``scene``, ``init``, optionally
        ``beam``), through the same bytes, then step ``settle_cycles``; returns its id.
        A convenience for tests, benchmarks and training set-ups."""
        agent = self.add_agent()
        self.handle_message(agent, f"(scene {NAO_SCENE} {robot_type})".encode())
        self.step()
        self.handle_message(agent, f"(init (unum {unum})(teamname {team_name}))(syn)".encode())
        self.step()
        if beam is not None:
            x, y, deg = beam
            self.handle_message(agent, f"(beam {x} {y} {deg})(syn)".encode())
        for _ in range(settle_cycles):
            self.step()
        return agent

    def trainer(self, text: str | bytes) -> None:
        """Queue trainer commands written as on the monitor port, e.g.
        ``"(ball (pos 0 0 0.042) (vel 4 0 0))"``; ValueError lists any bad command."""
        payload = text.encode() if isinstance(text, str) else text
        commands, errors = parse_trainer_commands(payload)
        if errors:
            raise ValueError("; ".join(errors))
        self.trainer_command(commands)

    def syn_received(self, payload: bytes) -> bool:
        """Whether a raw message contains ``(syn)`` (the sync-mode server counts these)."""
        return b"(syn)" in payload

    # ------------------------------------------------------------------ trainer
    def trainer_command(self, commands: list[TrainerCommand]) -> None:
        """Queue trainer commands; like the real server they act on the next cycle."""
        self._trainer_queue.extend(commands)

    # ------------------------------------------------------------------ stepping
    def step(self, perceive: bool = True) -> None:
        """Advance one 0.02 s cycle and prepare every agent's perception.

        ``perceive=False`` skips writing perception messages (for benchmarks and for
        fast-forwarding a scripted part where nobody reads them).
        """
        self.advance(perceive)
        self.stage_answers()

    def advance(self, perceive: bool = True) -> None:
        """The physics half of :meth:`step`: apply the staged effectors, simulate the cycle,
        judge it and write the perceptions, without touching the answers received since.

        The answers to a perception reach the motors only a cycle later (``staged``), so this
        does not depend on them: a server may run it while the agents still think about the
        previous perception, then call :meth:`stage_answers` once every answer is in.
        """
        for slot in list(self.agents.values()):
            self._apply_staged(slot)
        self._broadcast_said()
        self._apply_trainer_commands()
        self.world.step_cycle(self._substeps_for_cycle())
        self.time = round(self.time + CYCLE_SECONDS, 10)
        self.cycle += 1
        robots = [s for s in self.agents.values() if s.robot is not None]
        for slot in robots:
            slot.robot.update_sensors()
        self._run_referee(robots)
        if not perceive:
            return
        seen_by_all = _LazyVisibleRobots(robots)
        for slot in robots:
            slot.perception_bytes = self._perceive(slot, seen_by_all)

    def _substeps_for_cycle(self) -> int:
        """Adaptive substepping: a foot may not jump over the ball within one substep.

        Ordinary cycles use ``BASE_SUBSTEPS``; when a robot near the ball moves a foot or shank
        fast, the cycle is split finely enough that it travels at most
        ``SAFE_TRAVEL_PER_SUBSTEP`` per substep (the figure the fast-contact tests establish),
        up to ``DEFAULT_SUBSTEPS``. A fixed ``SessionConfig.substeps`` turns this off.
        """
        if self.config.substeps:
            return self.config.substeps
        bx, by, _ = self.ball.position()
        fastest = 0.0
        for slot in self.agents.values():
            if slot.robot is None:
                continue
            x, y, _ = slot.robot.torso_position()
            if math.hypot(x - bx, y - by) < NEAR_BALL:
                fastest = max(fastest, slot.robot.striking_speed())
        needed = math.ceil(fastest * SPEED_MARGIN * CYCLE_SECONDS / SAFE_TRAVEL_PER_SUBSTEP)
        return min(max(BASE_SUBSTEPS, needed), DEFAULT_SUBSTEPS)

    def perception(self, agent_id: int) -> bytes | None:
        """The perception message of the last step for this agent (None before its scene)."""
        return self.agents[agent_id].perception_bytes

    # ------------------------------------------------------------------ monitor
    def monitor_message(self) -> bytes:
        """The next monitor message: a full state when the scene changed, else an update."""
        header = self._monitor_header()
        ball = self.ball.world_transform()
        robots = {
            s.robot_id: s.robot.body_world_transforms()
            for s in self.agents.values()
            if s.robot is not None
        }
        if self._full_state_requested:
            self._full_state_requested = False
            return self.scene.full_state(header, ball, robots)
        return self.scene.update(header, ball, robots)

    def request_full_state(self) -> None:
        self._full_state_requested = True

    # ------------------------------------------------------------------ save / restore
    def save_state(self) -> SessionSnapshot:
        """Capture the whole simulator (physics, referee, agents' queues, random streams)."""
        python_state = copy.deepcopy(
            {
                "referee": self.referee,
                "rng": self.rng.bit_generator.state,
                "time": self.time,
                "cycle": self.cycle,
                "trainer": self._trainer_queue,
                "agents": {aid: _slot_state(s) for aid, s in self.agents.items()},
                "robots": {
                    aid: s.robot.python_state() for aid, s in self.agents.items() if s.robot
                },
            }
        )
        return SessionSnapshot(self.world.save_state(), python_state)

    def restore_state(self, snapshot: SessionSnapshot) -> None:
        """Return to a snapshot taken from this session (same agents connected)."""
        state = copy.deepcopy(snapshot.python_state)
        if set(state["agents"]) != set(self.agents):
            raise ValueError(
                f"snapshot has agents {sorted(state['agents'])}, session has {sorted(self.agents)}"
            )
        self.world.restore_state(snapshot.physics)
        self.referee = state["referee"]
        self.rng.bit_generator.state = state["rng"]
        self.time = state["time"]
        self.cycle = state["cycle"]
        self._trainer_queue = state["trainer"]
        for aid, slot_state in state["agents"].items():
            slot = self.agents[aid]
            for name, value in slot_state.items():
                setattr(slot, name, value)
            if slot.robot is not None:
                slot.robot.restore_python_state(state["robots"][aid])

    def close(self) -> None:
        self.world.close()

    # ------------------------------------------------------------------ internals
    def _create_robot(self, slot: AgentSlot, scene: str, robot_type: int) -> list[str]:
        if slot.robot is not None:
            return ["scene sent twice: ignored"]
        if scene != NAO_SCENE:
            return [f"unknown scene {scene!r}: only {NAO_SCENE} exists"]
        if robot_type not in range(5):
            return [f"unknown robot type {robot_type}: valid types are 0-4"]
        x, y = self._spawn_point(slot.agent_id)
        slot.robot = SimRobot(self.world, robot_type, self.contact.robot)
        slot.robot.place(x, y, BEAM_HEIGHT, yaw_deg=90.0)
        slot.robot_type = robot_type
        seed = int(self.rng.integers(2**63))
        slot.vision = VisionSensor(np.random.default_rng(seed), add_noise=self.config.vision_noise)
        self.scene.add_robot(slot.robot_id, robot_type)
        self._full_state_requested = True
        log.info("agent %d created a type %d robot", slot.agent_id, robot_type)
        return []

    def _spawn_point(self, agent_id: int) -> tuple[float, float]:
        """New robots stand outside the side line, apart, until they beam in."""
        column = (agent_id - 1) % 24
        return -14.0 + 1.2 * column, -11.0 - 1.2 * ((agent_id - 1) // 24)

    def _check_joint_effectors(self, slot: AgentSlot, message: EffectorMessage) -> list[str]:
        """Drop joint effectors the robot does not have (toes exist only on type 4)."""
        if slot.robot is None:
            return []
        valid = slot.robot.effector_names
        bad = [name for name in message.joint_speeds if name not in valid]
        for name in bad:
            del message.joint_speeds[name]
        return [f"robot type {slot.robot_type} has no effector {name!r}" for name in bad]

    def _apply_staged(self, slot: AgentSlot) -> None:
        for message in slot.staged:
            if message.init is not None:
                self._init_agent(slot, *message.init)
            if message.beam is not None:
                self._beam(slot, *message.beam)
            if message.joint_speeds and slot.robot is not None:
                slot.robot.set_joint_speeds(message.joint_speeds)
            if message.say is not None:
                self._say(slot, message.say)
        slot.staged = []

    def stage_answers(self) -> None:
        """The effector messages received since the last cycle wait for the next one."""
        for slot in self.agents.values():
            slot.staged, slot.pending = slot.pending, []

    def _init_agent(self, slot: AgentSlot, unum: int, team_name: str) -> None:
        if slot.side is not None:
            log.warning("agent %d: init sent twice: ignored", slot.agent_id)
            return
        try:
            side = self.referee.register_team(team_name)
        except ValueError as exc:
            log.warning("agent %d: %s", slot.agent_id, exc)
            return
        taken = {s.unum for s in self.agents.values() if s.side == side}
        if unum == 0:
            unum = next(n for n in range(1, 100) if n not in taken)
        elif unum in taken:
            log.warning("agent %d: unum %d of %s is taken: init ignored", slot.agent_id, unum, side)
            return
        slot.team_name, slot.side, slot.unum = team_name, side, unum
        slot.announce_identity = True
        if slot.robot is not None:
            self.scene.set_robot_identity(slot.robot_id, side, unum)
        self._full_state_requested = True
        log.info("agent %d is %s %s #%d", slot.agent_id, team_name, side, unum)

    def _beam(self, slot: AgentSlot, x: float, y: float, deg: float) -> None:
        if slot.robot is None or slot.side is None:
            return
        if not self.referee.may_beam(slot.side):
            return
        # the beam is given in the team's own frame; clamp_beam answers in world coordinates
        x, y, deg = self.referee.clamp_beam(slot.side, x, y, deg)
        if self.config.beam_noise:
            noise_xy = self.config.beam_noise_xy
            x += float(self.rng.uniform(-noise_xy, noise_xy))
            y += float(self.rng.uniform(-noise_xy, noise_xy))
            deg += float(self.rng.uniform(-1, 1) * self.config.beam_noise_angle_deg)
        slot.robot.place(x, y, BEAM_HEIGHT, yaw_deg=deg)

    def _say(self, slot: AgentSlot, message: str) -> None:
        if len(message) > MAX_SAY_LENGTH or any(c in message for c in "() "):
            log.warning(
                "agent %d: say %r refused (<= 20 chars, no spaces or parentheses)",
                slot.agent_id,
                message,
            )
            return
        self._said.append((slot, message))

    def _apply_trainer_commands(self) -> None:
        commands, self._trainer_queue = self._trainer_queue, []
        for command in commands:
            self._apply_trainer_command(command)

    def _apply_trainer_command(self, command: TrainerCommand) -> None:
        if isinstance(command, SetPlayMode):
            self.referee.set_play_mode(command.mode)
        elif isinstance(command, MoveBall):
            position = command.position or self.ball.position()
            self.ball.place(position, command.velocity or (0.0, 0.0, 0.0))
        elif isinstance(command, MoveAgent):
            slot = self._find_agent(command.team, command.unum)
            if slot is not None and slot.robot is not None:
                self._move_agent(slot, command)
        elif isinstance(command, KillAgent):
            slot = self._find_agent(command.team, command.unum)
            if slot is not None:
                self.remove_agent(slot.agent_id)
        elif isinstance(command, KickOff):
            side = None if command.side == "None" else command.side.lower()
            self.referee.kick_off(side)
        elif isinstance(command, DropBall):
            self.referee.drop_ball()
        elif isinstance(command, RequestFullState):
            self.request_full_state()
        else:
            log.warning("trainer command %r is not implemented", command)

    def _move_agent(self, slot: AgentSlot, command: MoveAgent) -> None:
        robot = slot.robot
        x, y, z = command.position if command.position is not None else robot.torso_position()
        if command.rotation_deg is not None:
            yaw = command.rotation_deg + 90.0  # the trainer's angle is raw: 0 faces world +y
            robot.place(x, y, z, yaw_deg=yaw, joint_angles_deg=robot.joint_angles_deg())
        else:
            robot.translate(x, y, z)

    def _find_agent(self, team: str, unum: int) -> AgentSlot | None:
        side = team.lower()
        for slot in self.agents.values():
            if slot.side == side and slot.unum == unum:
                return slot
        log.warning("trainer: no agent %s #%d", team, unum)
        return None

    def _run_referee(self, robots: list[AgentSlot]) -> None:
        players = [
            PlayerInfo(s.side, s.unum, s.robot.torso_position(), s.robot.has_fallen())
            for s in robots
            if s.side is not None
        ]
        ball = BallInfo(self.ball.position(), self.ball.velocity())
        actions = self.referee.step(CYCLE_SECONDS, ball, players, self._ball_touches(robots))
        for action in actions:
            if isinstance(action, PlaceBall):
                self.ball.place(action.position)
            elif isinstance(action, MovePlayer):
                self._apply_referee_move(action)
            elif isinstance(action, Event):
                self.events.append(action)
                log.info("referee: %s", action.text)

    def _apply_referee_move(self, move: MovePlayer) -> None:
        """The referee's MoveAgent: the robot's torso goes to the new place with its orientation
        and joint angles, and the base is stopped, as the trainer's ``move`` without an angle
        does (no velocity is given to it). The robot sees the move in its next perception."""
        for slot in self.agents.values():
            if slot.robot is not None and (slot.side, slot.unum) == move.key:
                slot.robot.translate(*move.position)
                log.debug("referee moved %s %d: %s", move.team, move.unum, move.reason)
                return

    def _ball_touches(self, robots: list[AgentSlot]) -> list[tuple[str, int]]:
        touching = self.ball.touching_bodies()
        return [
            (s.side, s.unum) for s in robots if s.side is not None and s.robot.body_id in touching
        ]

    def _perceive(self, slot: AgentSlot, visible: _LazyVisibleRobots) -> bytes:
        robot = slot.robot
        game_state = GameState(
            game_time=self.referee.game_time,
            play_mode=self.referee.play_mode,
            score_left=self.referee.score_left,
            score_right=self.referee.score_right,
        )
        if slot.announce_identity:
            game_state.unum, game_state.team = slot.unum, slot.side
            slot.announce_identity = False
        perception = Perception(
            time=self.time,
            game_state=game_state,
            gyro=robot.gyro_deg_s(),
            accelerometer=robot.accelerometer(),
            joints=robot.joint_angles_deg(),
            force_resistance=robot.force_resistance(),
            heard=slot.ear.take(slot.team_name or "", self.referee.game_time),
        )
        if slot.perceptions_sent % self.config.see_interval == 0:
            perception.vision = self._see(slot, visible)
        slot.perceptions_sent += 1
        return write_perception(perception)

    def _see(self, slot: AgentSlot, visible: _LazyVisibleRobots) -> Vision:
        others = [robot for other, robot in visible.items() if other is not slot and other.side]
        return slot.vision.see(
            slot.robot.camera_world_transform(), self.ball.position(), others, visible[slot]
        )

    def _broadcast_said(self) -> None:
        """Deliver the ``say`` messages applied this cycle under the real server's hearing
        rules (:mod:`sim.hearing`), from the speakers' positions before the physics step."""
        said, self._said = self._said, []
        if not said:
            return
        listeners = {
            slot.agent_id: self._listener(slot)
            for slot in self.agents.values()
            if slot.robot is not None and slot.team_name is not None and slot.side is not None
        }
        speakers = [(listeners[s.agent_id], m) for s, m in said if s.agent_id in listeners]
        broadcast(speakers, list(listeners.values()))

    @staticmethod
    def _listener(slot: AgentSlot) -> Listener:
        x, y, _ = slot.robot.torso_position()
        return Listener(slot.ear, slot.team_name or "", slot.side or "", x, y)

    def _monitor_header(self) -> MonitorHeader:
        """The monitor's header; the rule settings come from the referee actually in use, so
        a viewer shows the game's own half time and pauses, not a second copy of defaults."""
        team_left, team_right = self.referee.team_names
        rules = self.referee.config
        return MonitorHeader(
            free_kick_distance=rules.free_kick_distance,
            wait_before_kick_off=rules.wait_before_kick_off,
            rule_goal_pause_time=rules.goal_pause_time,
            rule_kick_in_pause_time=rules.kick_in_pause_time,
            rule_half_time=rules.half_time,
            time=self.time,
            half=self.referee.half,
            score_left=self.referee.score_left,
            score_right=self.referee.score_right,
            play_mode=self.referee.play_mode,
            team_left=team_left,
            team_right=team_right,
        )


class _LazyVisibleRobots:
    """What vision can see of every robot this cycle, computed once and only if someone looks
    (a new image comes every third cycle per robot, so most cycles nobody does)."""

    def __init__(self, robots: list[AgentSlot]) -> None:
        self._robots = robots
        self._visible: dict[int, VisibleRobot] | None = None

    def _compute(self) -> dict[int, VisibleRobot]:
        if self._visible is None:
            self._visible = {
                s.agent_id: VisibleRobot(
                    s.team_name or "", s.unum or 0, s.robot.body_positions(VISIBLE_PARTS)
                )
                for s in self._robots
            }
        return self._visible

    def __getitem__(self, slot: AgentSlot) -> VisibleRobot:
        return self._compute()[slot.agent_id]

    def items(self) -> list[tuple[AgentSlot, VisibleRobot]]:
        visible = self._compute()
        return [(s, visible[s.agent_id]) for s in self._robots]


def _slot_state(slot: AgentSlot) -> dict:
    """The per-agent Python state a snapshot keeps (the robot itself lives in the physics)."""
    return {
        "team_name": slot.team_name,
        "side": slot.side,
        "unum": slot.unum,
        "vision": slot.vision,
        "perceptions_sent": slot.perceptions_sent,
        "pending": slot.pending,
        "staged": slot.staged,
        "announce_identity": slot.announce_identity,
        "perception_bytes": slot.perception_bytes,
        "ear": slot.ear,
    }


def _has_actions(message: EffectorMessage) -> bool:
    return bool(message.init or message.beam or message.joint_speeds or message.say is not None)
