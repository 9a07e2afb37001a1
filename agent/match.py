"""A whole match in one process: the embedded stand-in server plus two teams.

The agents are in-process clients of the server (``SoccerServer.add_local_agent``): they exchange
the same perception and effector bytes as TCP agents, without sockets. The server still opens
its monitor port when asked, so RoboViz can watch, and its agent port, so outside agents could
join. Kick-off is given by the match runner, as a trainer would, once every player has joined
and beamed in.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import dataclass

from agent.agent import Agent
from agent.team import TeamConfig

log = logging.getLogger(__name__)

#: Seconds of game setup (joining, beaming, settling) before the runner kicks off.
SETTLE_S = 1.0


@dataclass(frozen=True)
class MatchResult:
    left: str
    right: str
    score_left: int
    score_right: int
    game_time: float
    cycles: int
    wall_seconds: float
    agents: tuple[Agent, ...]

    @property
    def realtime_factor(self) -> float:
        return self.cycles * 0.02 / self.wall_seconds if self.wall_seconds else 0.0

    def score_line(self) -> str:
        return f"score: {self.left} {self.score_left} - {self.score_right} {self.right}"


def run_match(
    duration_s: float,
    seed: int = 0,
    left: TeamConfig | None = None,
    right: TeamConfig | None = None,
    monitor_port: int | None = None,
    real_time: bool = False,
    on_event: Callable[[str], None] = print,
    on_cycle: Callable[[object], None] | None = None,
) -> MatchResult:
    """Play ``duration_s`` seconds of game time; events go to ``on_event`` as they happen and
    ``on_cycle(session)`` runs after every played cycle (renderers, recorders)."""
    from sim.server import SoccerServer
    from sim.session import Session, SessionConfig

    left = left or TeamConfig("NaoLeft")
    right = right or TeamConfig("NaoRight")
    if left.name == right.name:
        raise ValueError(f"the two teams need different names, both are {left.name!r}")
    session = Session(SessionConfig(seed=seed))
    server = SoccerServer(session, "127.0.0.1", 0, monitor_port or 0, sync=True)
    if monitor_port is not None:
        on_event(f"monitor port {server.monitor_port} (RoboViz can connect)")
    start = time.perf_counter()
    try:
        agents = _join_teams(server, [*left.agents(), *right.agents()])
        _play(server, duration_s, real_time, on_event, on_cycle)
    finally:
        server.close()
        session.close()
    referee_state = session.referee
    return MatchResult(
        left.name,
        right.name,
        referee_state.score_left,
        referee_state.score_right,
        referee_state.game_time,
        session.cycle,
        time.perf_counter() - start,
        tuple(agents),
    )


def _join_teams(server, agents: list[Agent]) -> list[Agent]:
    """Agents join one at a time: the next one connects once the last knows its number."""
    joined: list[Agent] = []
    for agent in agents:
        server.add_local_agent(agent)
        joined.append(agent)
        for _ in range(50):
            server.run_cycle()
            server.poll(0.0)
            if agent.world.unum is not None:
                break
        else:
            raise RuntimeError(f"agent {agent.config} got no side and number from the server")
    return joined


def _play(
    server,
    duration_s: float,
    real_time: bool,
    on_event: Callable[[str], None],
    on_cycle: Callable[[object], None] | None,
) -> None:
    """Run cycles until ``duration_s`` of game time; kick off whenever the game waits for it
    (the start, and the second half), after the players had ``SETTLE_S`` to beam in."""
    session = server.session
    referee = session.referee
    printed = 0
    waiting = 0
    next_cycle = time.monotonic()
    while referee.game_time < duration_s and referee.play_mode != "GameOver":
        server.run_cycle()
        server.poll(0.0)
        waiting = waiting + 1 if referee.play_mode == "BeforeKickOff" else 0
        if waiting * 0.02 >= SETTLE_S:
            referee.kick_off(None)
        for event in session.events[printed:]:
            on_event(f"[{referee.game_time:7.2f}] {event.text}")
        printed = len(session.events)
        if on_cycle is not None:
            on_cycle(session)
        if real_time:
            next_cycle += 0.02
            time.sleep(max(0.0, next_cycle - time.monotonic()))
