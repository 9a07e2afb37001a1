"""The networked server over real TCP sockets: handshake, message shape, joints, bad input."""

from __future__ import annotations

import itertools
import logging
import socket
import struct
import threading
import time
from pathlib import Path

import pytest

from sim.server import SoccerServer
from sim.session import Session, SessionConfig
from world.framing import FrameDecoder, frame
from world.perception import parse_perception
from world.sexp import parse

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"
SCENE = b"(scene rsg/agent/nao/nao_hetero.rsg 0)"


class Client:
    """A bare-bones blocking agent connection for tests."""

    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=20)
        self.decoder = FrameDecoder()
        self.ready: list[bytes] = []

    def send(self, payload: bytes) -> None:
        self.sock.sendall(frame(payload))

    def receive(self) -> bytes:
        while not self.ready:
            data = self.sock.recv(65536)
            if not data:
                raise ConnectionError("server closed the connection")
            self.ready.extend(self.decoder.feed(data))
        return self.ready.pop(0)

    def join(self, team: str, unum: int, beam: str = "-2 0 0") -> bytes:
        self.send(SCENE)
        self.receive()
        self.send(f"(init (unum {unum})(teamname {team}))(syn)".encode())
        self.receive()
        self.send(f"(beam {beam})(syn)".encode())
        return self.receive()

    def close(self) -> None:
        self.sock.close()


@pytest.fixture
def server():
    session = Session(SessionConfig(seed=1, beam_noise=False))
    srv = SoccerServer(session, "127.0.0.1", 0, 0, sync=True)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    yield srv
    srv.stop()
    thread.join(timeout=10)
    srv.close()
    session.close()


def _tags(message: bytes) -> list[str]:
    """Top-level perceptor tags with their names: 'HJ hj1', 'FRP lf', 'GYR', ..."""
    return [
        f"{expr[0]} {expr[1][1]}" if expr[0] in ("HJ", "FRP") else expr[0]
        for expr in parse(message)
    ]


def _normalised(tags: list[str]) -> list[str]:
    return [t for t in tags if not t.startswith(("See", "FRP", "hear"))]


def test_handshake_and_message_shape_match_the_real_server(server):
    client = Client(server.port)
    try:
        client.send(SCENE)
        first = client.receive()
        assert b"(See " in first
        client.send(b"(init (unum 1)(teamname Probe))(syn)")
        client.receive()
        client.send(b"(beam -3 0 0)(syn)")
        third = client.receive()
        assert b"(GS (unum 1) (team left) (sl 0) (sr 0) (t 0.00) (pm BeforeKickOff))" in third
        if TRACES.is_dir():
            real = (TRACES / "01_first_msg_after_scene_type0.txt").read_bytes()
            assert _normalised(_tags(first)) == _normalised(_tags(real))
            real_ident = (TRACES / "02_msg_after_init_with_unum_team.txt").read_bytes()
            assert _normalised(_tags(third)) == _normalised(_tags(real_ident))
    finally:
        client.close()


def test_see_on_every_third_cycle_only(server):
    client = Client(server.port)
    try:
        client.join("Probe", 1)
        flags = []
        for _ in range(24):
            client.send(b"(syn)")
            flags.append(b"(See " in client.receive())
        first = flags.index(True)
        assert flags == [((i - first) % 3 == 0) for i in range(24)]
    finally:
        client.close()


def test_one_joint_speed_moves_that_joint_only_within_limits(server):
    client = Client(server.port)
    try:
        client.join("Probe", 1)
        for _ in range(30):
            client.send(b"(syn)")
            client.receive()
        client.send(b"(syn)")
        start = parse_perception(client.receive()).joints
        client.send(b"(rae1 -2.0)(syn)")
        angles = []
        for _ in range(60):
            angles.append(parse_perception(client.receive()).joints)
            client.send(b"(syn)")
        # after the two-cycle latency the shoulder turns at -2 rad/s = -2.29 deg per cycle
        rates = [b["raj1"] - a["raj1"] for a, b in itertools.pairwise(angles[2:21])]
        assert sum(rates) / len(rates) == pytest.approx(-2.29, abs=0.25)
        # the other joints hold: the arm's swing and its stop at the limit jolt the body, so
        # loaded leg joints give a little (the motors hold with at most 10 N m), no more
        drift = sorted(abs(v - start[n]) for n, v in angles[-1].items() if n != "raj1")
        assert drift[-1] < 3.0
        assert drift[len(drift) // 2] < 0.5  # the real server too: knees give 3 deg on landing
        # raj1 stops at its lower limit of -120 deg (soft, a few degrees of give)
        assert -126 < angles[-1]["raj1"] < -114
    finally:
        client.close()


def _good_agent_keeps_cycling(server, bad_action) -> None:
    """Run ``bad_action`` while a well-behaved agent keeps answering every cycle (in a thread);
    the good agent must get every cycle, before, during and after the misbehaviour."""
    good = Client(server.port)
    good.join("Good", 1)
    times: list[float] = []
    done = threading.Event()

    def keep_cycling() -> None:
        while not done.is_set():
            good.send(b"(syn)")
            times.append(parse_perception(good.receive()).time)

    thread = threading.Thread(target=keep_cycling, daemon=True)
    thread.start()
    try:
        bad_action()
        count = len(times)
        deadline = time.monotonic() + 20
        while len(times) < count + 15 and time.monotonic() < deadline:
            time.sleep(0.01)
    finally:
        done.set()
        thread.join(timeout=10)
        good.close()
    assert len(times) >= count + 15, "the good agent stopped getting cycles"
    assert all(b == pytest.approx(a + 0.02) for a, b in itertools.pairwise(times))


def test_garbage_and_unknown_effectors_are_logged_and_ignored(server, caplog):
    bad = Client(server.port)

    def misbehave():
        bad.join("Bad", 2, beam="-4 1 0")
        bad.send(b"\x00\xffgarbage((((")
        bad.send(b"(he1 1.0)(xyz 3)(lle7 1.0)(beam 1)(syn)")
        bad.receive()
        bad.close()

    with caplog.at_level(logging.WARNING):
        _good_agent_keeps_cycling(server, misbehave)
    text = caplog.text
    assert "xyz" in text and "lle7" in text


def test_oversized_length_prefix_drops_that_client(server, caplog):
    def misbehave():
        bad = socket.create_connection(("127.0.0.1", server.port))
        bad.sendall(struct.pack(">I", 500_000_000) + b"(syn)")
        time.sleep(0.3)
        bad.close()

    with caplog.at_level(logging.ERROR):
        _good_agent_keeps_cycling(server, misbehave)
    assert "dropped" in caplog.text


def test_client_vanishing_mid_frame_is_dropped(server, caplog):
    def misbehave():
        bad = Client(server.port)
        bad.join("Bad", 3, beam="-5 2 0")
        bad.sock.sendall(struct.pack(">I", 100) + b"(he1 1")
        bad.close()
        time.sleep(0.2)

    with caplog.at_level(logging.INFO):
        _good_agent_keeps_cycling(server, misbehave)
    assert "mid-frame" in caplog.text


def test_monitor_gets_full_state_then_updates_and_trainer_moves_ball(server):
    monitor = Client(server.monitor_port)
    agent = Client(server.port)
    try:
        agent.join("Probe", 1)
        first = monitor.receive()
        assert first.startswith(b"((FieldLength 30)")
        assert b"(RSG 0 1)" in first
        # the referee keeps the ball on the centre spot before kick-off, as the real server
        monitor.send(b"(playMode PlayOn)(ball (pos 1 2 0.042) (vel 0 0 0))")
        for _ in range(6):
            agent.send(b"(syn)")
            agent.receive()
        update = monitor.receive()
        assert b"(RDS 0 1)" in update or b"(RSG 0 1)" in update
        x, y, _ = server.session.ball.position()
        assert (x, y) == pytest.approx((1.0, 2.0), abs=0.02)
    finally:
        agent.close()
        monitor.close()


def test_real_time_mode_runs_without_waiting_for_syn():
    session = Session(SessionConfig(seed=2))
    srv = SoccerServer(session, "127.0.0.1", 0, 0, sync=False)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    client = Client(srv.port)
    try:
        client.send(SCENE)
        times = [parse_perception(client.receive()).time for _ in range(10)]  # never syncs
        assert times == sorted(times) and len(set(times)) == 10
    finally:
        client.close()
        srv.stop()
        thread.join(timeout=10)
        srv.close()
        session.close()
