"""One playing agent: perception bytes in, effector bytes out.

:meth:`Agent.think` is the whole cycle: parse the message, update the world model, let the
strategy pick behaviours, collect the joint speeds they command and write the effectors with
``(syn)``. It knows nothing of sockets, so the same agent runs over TCP against any
SimSpark-protocol server (ours or a real rcssserver3d), or in-process against a ``sim`` session
with the very same bytes (training, tests, the embedded match).

Handshake, as real agents do it: ``scene`` first (:meth:`Agent.greeting`), then ``init`` in
answer to the first perception; the server announces side and uniform number two messages later.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass

from behaviors.manager import Behavior
from world.effectors import EffectorMessage, write_effectors
from world.perception import parse_perception
from world.world_model import WorldModel

NAO_SCENE = "rsg/agent/nao/nao_hetero.rsg"
#: How many recent think() durations an agent keeps (for benchmarks and logs).
THINK_TIME_WINDOW = 10_000


@dataclass(frozen=True)
class AgentConfig:
    """Who an agent is: team name, uniform number (0: the server chooses), robot type."""

    team_name: str
    unum: int = 0
    robot_type: int = 0

    def __post_init__(self) -> None:
        if not self.team_name or any(c in self.team_name for c in "() "):
            raise ValueError(f"team name {self.team_name!r}: non-empty, no spaces or parentheses")
        if not 0 <= self.unum <= 11:
            raise ValueError(f"unum {self.unum}: 1-11, or 0 to let the server choose")
        if self.robot_type not in range(5):
            raise ValueError(f"robot type {self.robot_type}: valid types are 0-4")


class Agent:
    """World model + behaviour manager + strategy, driven one perception at a time."""

    def __init__(self, config: AgentConfig, strategy=None) -> None:
        from agent.strategy import Strategy  # the strategy imports behaviours lazily too

        self.config = config
        self.world = WorldModel(config.robot_type, config.team_name)
        self.behavior = Behavior(self.world, config.robot_type)
        self.strategy = strategy if strategy is not None else Strategy()
        self.cycles = 0
        #: seconds spent in think() for each cycle (parse + world + behaviour + writing)
        self.think_times: deque[float] = deque(maxlen=THINK_TIME_WINDOW)
        self._initialised = False

    def greeting(self) -> bytes:
        """The first message to the server: which robot this agent plays."""
        return write_effectors(EffectorMessage(scene=(NAO_SCENE, self.config.robot_type)))

    def think(self, payload: bytes) -> bytes:
        """One cycle: a perception message in, the answering effector message out."""
        start = time.perf_counter()
        perception = parse_perception(payload)
        self.world.update(perception)
        message = EffectorMessage(syn=True)
        if not self._initialised:
            message.init = (self.config.unum, self.config.team_name)
            self._initialised = True
        else:
            self.behavior.begin_cycle()
            decision = self.strategy.decide(self.world, self.behavior)
            message.beam = decision.beam
            message.say = decision.say
            message.joint_speeds = self.behavior.effector_speeds()
        self.cycles += 1
        reply = write_effectors(message)
        self.think_times.append(time.perf_counter() - start)
        return reply
