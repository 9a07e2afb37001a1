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
from agent.agent_pool import AgentPool
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
    #: cycles and wall seconds of play, after every agent had joined
    play_cycles: int = 0
    play_wall_seconds: float = 0.0

    @property
    def realtime_factor(self) -> float:
        """Simulated seconds per wall second while playing (joining excluded)."""
        if not self.play_wall_seconds:
            return 0.0
        return self.play_cycles * 0.02 / self.play_wall_seconds

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
    team_processes: bool = False,
    agent_worker: bool = False,
) -> MatchResult:
    """Play ``duration_s`` seconds of game time; events go to ``on_event`` as they happen and
    ``on_cycle(session)`` runs after every cycle (renderers, recorders).

    ``agent_worker`` lets all agents think in a second process while the server simulates the
    next cycle (:mod:`agent.agent_pool`): the same game as in one process, seed for seed, on
    two cores. ``team_processes`` runs each team in its own process, talking TCP to the server;
    those agents join whenever their process gets to it, so that game is not reproducible.
    Otherwise all agents answer inside the server's cycle in this process. The left team joins
    first, one agent at a time.
    """
    if agent_worker and team_processes:
        raise ValueError("choose agent_worker or team_processes, not both")
    from sim.server import SoccerServer
    from sim.session import Session, SessionConfig

    left = left or TeamConfig("NaoLeft")
    right = right or TeamConfig("NaoRight")
    if left.name == right.name:
        raise ValueError(f"the two teams need different names, both are {left.name!r}")
    session = Session(SessionConfig(seed=seed))
    server = SoccerServer(session, "127.0.0.1", 0, monitor_port or 0, sync=not real_time)
    if monitor_port is not None:
        on_event(f"monitor port {server.monitor_port} (RoboViz can connect)")
    start = time.perf_counter()
    processes = []
    agents: list[Agent] = []
    pool = AgentPool(left.agents() + right.agents()) if agent_worker else None
    try:
        for team in (left, right):
            if team_processes:
                processes.append(_start_team_process(team, server.port))
            elif pool is not None:
                first = 0 if team is left else len(left.robot_types)
                _join_pool(server, pool, range(first, first + len(team.robot_types)))
            else:
                agents += _join_local(server, team.agents())
            server.serve_forever(
                until=lambda team=team: _joined(session, team) == len(team.robot_types)
            )
        # the pipeline starts after joining: a robot joining a pipelined server would enter
        # a cycle later than in one process (the next cycle is simulated before it connects)
        server.pipeline = team_processes or agent_worker
        play_start, first_cycle = time.perf_counter(), session.cycle
        _play(server, duration_s, on_event, on_cycle)
        play_wall, play_cycles = time.perf_counter() - play_start, session.cycle - first_cycle
    finally:
        if pool is not None:
            agents = pool.close()
        server.close()
        session.close()
        for process in processes:
            process.join(timeout=10)
            if process.is_alive():
                process.terminate()
    return MatchResult(
        left.name,
        right.name,
        session.referee.score_left,
        session.referee.score_right,
        session.referee.game_time,
        session.cycle,
        time.perf_counter() - start,
        tuple(agents),
        play_cycles,
        play_wall,
    )


def _joined(session, team: TeamConfig) -> int:
    """How many of the team's players the server has given a side and number."""
    return sum(1 for s in session.agents.values() if s.team_name == team.name and s.unum)


def _join_local(server, agents: list[Agent]) -> list[Agent]:
    """In-process agents join one at a time: the next once the last knows its number."""
    for agent in agents:
        server.add_local_agent(agent)
        _await_number(server, lambda a=agent: a.world.unum is not None, f"agent {agent.config}")
    return agents


def _join_pool(server, pool: AgentPool, positions: range) -> None:
    """The pool's agents at ``positions`` (one team's) join as in-process agents do, one at a
    time, each once the last knows its number."""
    for position in positions:
        agent_id = pool.join(server, position)
        _await_number(
            server, lambda a=agent_id: pool.unum(a) is not None, f"agent {position} of the pool"
        )


def _await_number(server, has_number: Callable[[], bool], who: str) -> None:
    """Run cycles (50 at most) until a joining agent knows its side and number."""
    server.serve_forever(max_cycles=server.session.cycle + 50, until=has_number)
    if not has_number():
        raise RuntimeError(f"{who} got no side and number from the server")


def _start_team_process(team: TeamConfig, port: int):
    import multiprocessing

    process = multiprocessing.get_context("spawn").Process(
        target=_team_process_main, args=(team, port), daemon=True
    )
    process.start()
    return process


def _team_process_main(team: TeamConfig, port: int) -> None:
    from agent.team import run_team_tcp

    logging.basicConfig(level=logging.WARNING)
    run_team_tcp(team, "127.0.0.1", port)


def _play(
    server, duration_s: float, on_event: Callable[[str], None], on_cycle: Callable | None
) -> None:
    """Run cycles until ``duration_s`` of game time; kick off whenever the game waits for it
    (the start, and the second half), after the players had ``SETTLE_S`` to beam in."""
    session = server.session
    referee = session.referee
    state = {"printed": 0, "waiting": 0}

    def after_cycle() -> None:
        for event in session.events[state["printed"] :]:
            on_event(f"[{referee.game_time:7.2f}] {event.text}")
        state["printed"] = len(session.events)
        state["waiting"] = state["waiting"] + 1 if referee.play_mode == "BeforeKickOff" else 0
        if state["waiting"] * 0.02 >= SETTLE_S:
            referee.kick_off(None)
        if on_cycle is not None:
            on_cycle(session)

    server.serve_forever(
        until=lambda: referee.game_time >= duration_s or referee.play_mode == "GameOver",
        on_cycle=after_cycle,
    )
