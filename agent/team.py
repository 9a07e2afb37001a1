"""A team of agents: its configuration, and running it over TCP in one process.

Eleven agents, robot types following the rules (at least 3 different types, at most 7 robots of
one type), one TCP connection each, served by one ``selectors`` loop in one process. Agents join
one at a time, each finishing its handshake (until the server has announced its side and
number) before the next connects, as real clients do (the real server can hang otherwise).
"""

from __future__ import annotations

import logging
import selectors
import socket
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from agent.agent import Agent, AgentConfig
from agent.strategy import Strategy
from agent.strategy_config import StrategyConfig
from world.framing import FrameDecoder, FrameError, frame
from world.yaml_config import load_yaml_config

log = logging.getLogger(__name__)

#: 11 robots: all five types, at most 4 of one.
DEFAULT_ROBOT_TYPES: tuple[int, ...] = (0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4)
MIN_DISTINCT_TYPES = 3
MAX_OF_ONE_TYPE = 7


def check_robot_types(robot_types: tuple[int, ...]) -> None:
    """Raise ValueError unless the team's robot types follow the rules."""
    counts = Counter(robot_types)
    if any(t not in range(5) for t in counts):
        raise ValueError(f"robot types must be 0-4, got {sorted(counts)}")
    if len(robot_types) == 11 and len(counts) < MIN_DISTINCT_TYPES:
        raise ValueError(
            f"a team of 11 fields at least {MIN_DISTINCT_TYPES} robot types, got {dict(counts)}"
        )
    worst, count = counts.most_common(1)[0]
    if count > MAX_OF_ONE_TYPE:
        raise ValueError(f"at most {MAX_OF_ONE_TYPE} robots of one type: type {worst} has {count}")


@dataclass(frozen=True)
class TeamConfig:
    """A team: its name, the robot type of each player (unum 1, 2, ...), its strategy."""

    name: str = "NaoSoccer"
    robot_types: tuple[int, ...] = DEFAULT_ROBOT_TYPES
    strategy: StrategyConfig = field(default_factory=StrategyConfig)

    def __post_init__(self) -> None:
        if not 1 <= len(self.robot_types) <= 11:
            raise ValueError(f"a team has 1-11 players, got {len(self.robot_types)}")
        check_robot_types(self.robot_types)
        AgentConfig(self.name)  # validates the name

    @classmethod
    def from_yaml(cls, path: str | Path) -> TeamConfig:
        return load_yaml_config(cls, path)

    def agents(self) -> list[Agent]:
        """One agent per player, unums 1..n."""
        return [
            Agent(AgentConfig(self.name, unum, robot_type), Strategy(self.strategy))
            for unum, robot_type in enumerate(self.robot_types, start=1)
        ]


class _Connection:
    def __init__(self, agent: Agent, host: str, port: int) -> None:
        self.agent = agent
        self.sock = socket.create_connection((host, port), timeout=30)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.decoder = FrameDecoder()
        self.sock.sendall(frame(agent.greeting()))

    def serve(self) -> bool:
        """Answer every complete perception; False when the server has gone."""
        try:
            data = self.sock.recv(1 << 20)
        except OSError:
            return False
        if not data:
            return False
        try:
            messages = self.decoder.feed(data)
        except FrameError as exc:
            log.error("agent %s: %s", self.agent.config.unum, exc)
            return False
        try:
            for message in messages:
                self.sock.sendall(frame(self.agent.think(message)))
        except OSError:
            return False
        return True


def run_team_tcp(team: TeamConfig, host: str = "127.0.0.1", port: int = 3100) -> int:
    """Connect the team's agents one at a time and play until the server goes away.

    Returns the number of cycles the first agent played. Raises ConnectionError with a clear
    message when no server answers at ``host:port``.
    """
    selector = selectors.DefaultSelector()
    pending = list(team.agents())
    connections: list[_Connection] = []
    try:
        while pending or connections:
            if pending and (not connections or connections[-1].agent.world.unum is not None):
                try:
                    connection = _Connection(pending.pop(0), host, port)
                except OSError as exc:
                    if not connections:
                        raise ConnectionError(
                            f"no server answers at {host}:{port}: {exc}"
                        ) from None
                    log.error("agent could not connect: %s", exc)
                    continue
                selector.register(connection.sock, selectors.EVENT_READ, connection)
                connections.append(connection)
            for key, _ in selector.select(timeout=1.0):
                connection = key.data
                if not connection.serve():
                    selector.unregister(connection.sock)
                    connection.sock.close()
                    connections.remove(connection)
                    if not connections:
                        log.info("the server closed the connections: team %s stops", team.name)
                        pending.clear()
        return 0
    finally:
        for connection in connections:
            connection.sock.close()
        selector.close()
