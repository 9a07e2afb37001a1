"""The agent loop, the team launcher and the embedded match."""

from __future__ import annotations

import socket
import threading

import numpy as np
import pytest

from agent.agent import Agent, AgentConfig
from agent.match import run_match
from agent.team import DEFAULT_ROBOT_TYPES, TeamConfig, check_robot_types, run_team_tcp
from sim.server import SoccerServer
from sim.session import Session, SessionConfig
from world.framing import FrameDecoder, frame


def _world_snapshot(agent: Agent) -> dict:
    world = agent.world
    return {
        "time": world.time,
        "play_mode": world.play_mode,
        "side": world.side,
        "unum": world.unum,
        "joints": dict(world.robot.joints_deg),
        "up": tuple(np.round(world.robot.up, 12)),
        "pose": world.pose,
        "ball": (world.ball.position, world.ball.velocity),
    }


@pytest.mark.parametrize("pipeline", [False, True])
def test_tcp_and_in_process_agents_see_identical_worlds(pipeline: bool):
    """Also with a pipelined server, which simulates the next cycle while the agent thinks."""
    cycles = 120

    # in-process: the agent answers inside the server's cycle, no socket
    local_session = Session(SessionConfig(seed=11))
    local_server = SoccerServer(local_session, "127.0.0.1", 0, 0, sync=True)
    local = Agent(AgentConfig("Same", 1, 2))
    local_server.add_local_agent(local)
    for _ in range(cycles):
        local_server.run_cycle()
    local_server.close()
    local_session.close()

    # TCP: the same agent code over a real socket, server in sync mode
    tcp_session = Session(SessionConfig(seed=11))
    tcp_server = SoccerServer(tcp_session, "127.0.0.1", 0, 0, sync=True, pipeline=pipeline)
    remote = Agent(AgentConfig("Same", 1, 2))
    sock = socket.create_connection(("127.0.0.1", tcp_server.port))
    sock.sendall(frame(remote.greeting()))
    while not any(s.robot for s in tcp_session.agents.values()):
        tcp_server.poll(0.05)  # no cycle runs before the robot exists, as in-process

    def play() -> None:
        decoder = FrameDecoder()
        answered = 0
        while answered < cycles:
            for message in decoder.feed(sock.recv(1 << 20)):
                sock.sendall(frame(remote.think(message)))
                answered += 1

    client = threading.Thread(target=play, daemon=True)
    client.start()
    thread = threading.Thread(target=tcp_server.serve_forever, args=(cycles,), daemon=True)
    thread.start()
    client.join(timeout=60)
    tcp_server.stop()
    thread.join(timeout=10)
    sock.close()
    tcp_server.close()
    tcp_session.close()

    assert remote.cycles == local.cycles == cycles
    assert _world_snapshot(remote) == _world_snapshot(local)


def test_robot_type_rules():
    check_robot_types(DEFAULT_ROBOT_TYPES)
    with pytest.raises(ValueError, match="at least 3"):
        check_robot_types((0,) * 6 + (1,) * 5)
    with pytest.raises(ValueError, match="at most 7"):
        check_robot_types((0,) * 8 + (1, 2, 3))
    with pytest.raises(ValueError, match="0-4"):
        check_robot_types((0, 1, 5))


def test_team_of_eleven_joins_over_tcp_and_stops_cleanly_when_the_server_goes():
    session = Session(SessionConfig(seed=4))
    server = SoccerServer(session, "127.0.0.1", 0, 0, sync=True)
    team = TeamConfig("Eleven")
    result: dict = {}

    def play() -> None:
        result["returned"] = run_team_tcp(team, "127.0.0.1", server.port)

    client = threading.Thread(target=play, daemon=True)
    client.start()
    server.serve_forever(max_cycles=150)  # sync mode: paced by the team's answers
    joined = [s for s in session.agents.values() if s.unum is not None]
    server.close()  # the server goes away: the team must notice and return
    client.join(timeout=20)
    session.close()
    assert sorted(s.unum for s in joined) == list(range(1, 12))
    assert sorted(s.robot_type for s in joined) == sorted(DEFAULT_ROBOT_TYPES)
    assert {s.side for s in joined} == {"left"}
    assert not client.is_alive() and result["returned"] == 0


def test_no_server_gives_a_clear_error():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    with pytest.raises(ConnectionError, match="no server answers"):
        run_team_tcp(TeamConfig("Lonely"), "127.0.0.1", port)


def test_short_match_kicks_off_and_reports_the_score():
    lines: list[str] = []
    small = (0, 1, 2)
    result = run_match(
        1.0,
        seed=5,
        left=TeamConfig("Reds", robot_types=small),
        right=TeamConfig("Blues", robot_types=small),
        on_event=lines.append,
    )
    assert result.game_time >= 1.0
    assert any("KickOff" in line or "kick" in line.lower() for line in lines), lines
    assert result.score_line() == f"score: Reds {result.score_left} - {result.score_right} Blues"
    assert all(agent.world.side in ("left", "right") for agent in result.agents)


def test_opponents_restart_keeps_our_players_back():
    from agent.strategy import opponents_restart

    assert opponents_restart("KickOff_Right", "left")
    assert opponents_restart("corner_kick_left", "right")
    assert not opponents_restart("KickOff_Left", "left")
    assert not opponents_restart("PlayOn", "left")
    assert not opponents_restart("BeforeKickOff", "right")
    assert not opponents_restart("KickIn_Left", None)


def test_agents_in_a_worker_process_play_the_same_game_as_in_one_process():
    # the server simulates the next cycle while the worker's agents think (pipeline): the
    # answers still reach the motors at the same cycles, so every agent ends in the same state
    teams = {
        "left": TeamConfig("Reds", robot_types=(0, 1, 2)),
        "right": TeamConfig("Blues", robot_types=(3, 4, 0)),
    }
    here = run_match(3.0, seed=6, **teams, on_event=lambda _: None)
    worker = run_match(3.0, seed=6, **teams, on_event=lambda _: None, agent_worker=True)
    assert worker.cycles == here.cycles and len(worker.agents) == len(here.agents) == 6
    for a, b in zip(here.agents, worker.agents, strict=True):
        assert a.cycles == b.cycles and a.cycles > 100
        assert _world_snapshot(b) == _world_snapshot(a)
    assert worker.score_line() == here.score_line()
