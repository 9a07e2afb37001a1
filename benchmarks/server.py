"""Server speed figures, one ``name: value`` line each.

    python benchmarks/server.py            # full run (about a minute)
    python benchmarks/server.py --quick    # fewer cycles

Figures:
- ``inprocess_cycles_per_s``: one robot moving its joints and a ball, in-process session, with
  the perception message written every cycle (what training pays);
- ``inprocess_cycles_per_s_no_perception``: the same without writing perceptions (physics,
  sensors and referee only);
- ``inprocess_cpu_cycles_per_s`` (and ``..._no_perception``): the same runs measured in this
  process's CPU time instead of wall time: steadier where other programs share the cores;
- ``networked22_cycles_per_s`` and ``networked22_realtime_factor``: 22 agents (11 a side, robot
  types mixed as the rules allow) in sync mode over TCP, each parsing its perception and answering
  with new joint speeds every cycle; the server runs as its own process (``naosoccer server
  --sync``), all 22 clients in this one, so on a 2-core machine each side has about one core;
- ``networked22_server_cpu_ms_per_cycle``: CPU time the server process spent per cycle in that
  run (Linux only: read from /proc);
- ``parse_us`` / ``write_us``: one full perception message (with a ``See``) parsed / written.
"""

from __future__ import annotations

import argparse
import math
import os
import selectors
import socket
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.codec import measure_parse_us, measure_write_us  # noqa: E402
from world.framing import FrameDecoder, frame  # noqa: E402
from world.perception import parse_perception  # noqa: E402

SCENE = "(scene rsg/agent/nao/nao_hetero.rsg {})"
#: 11 robots of one team: 5 types, at most 7 (here 4) of one type, as the rules ask
TEAM_TYPES = (0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4)


def _joint_command(cycle: int, offset: float) -> bytes:
    s = 1.5 * math.sin(cycle / 8.0 + offset)
    return (
        f"(rae1 {s:.3f})(lae1 {-s:.3f})(rae2 {s / 2:.3f})(lle3 {s / 3:.3f})(rle3 {-s / 3:.3f})"
        f"(lle4 {s / 4:.3f})(he1 {s / 2:.3f})(syn)"
    ).encode()


def inprocess_cycles_per_s(cycles: int, with_perception: bool) -> float:
    return inprocess_rates(cycles, with_perception)[0]


def inprocess_rates(cycles: int, with_perception: bool) -> tuple[float, float]:
    """Cycles per second of wall time and of this process's CPU time."""
    from sim.session import Session, SessionConfig

    session = Session(SessionConfig(seed=0))
    agent = session.join("Bench", 1, beam=(-2.0, 0.0, 0.0), settle_cycles=20)
    start, start_cpu = time.perf_counter(), time.process_time()
    for i in range(cycles):
        session.handle_message(agent, _joint_command(i, 0.0))
        session.step(perceive=with_perception)
        session.perception(agent)
    elapsed, elapsed_cpu = time.perf_counter() - start, time.process_time() - start_cpu
    session.close()
    return cycles / elapsed, cycles / elapsed_cpu


def _cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` (Linux /proc; NaN elsewhere)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return math.nan
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _start_server(port: int, monitor_port: int) -> subprocess.Popen:
    command = [
        sys.executable,
        "-m",
        "agent.cli",
        "--log-level",
        "warning",
        "server",
        "--sync",
        "--port",
        str(port),
        "--monitor-port",
        str(monitor_port),
    ]
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            return process
        except OSError:
            time.sleep(0.2)
    process.kill()
    raise RuntimeError("the server did not start")


class _Agent:
    """One scripted client: answers every perception, as a real agent process would."""

    def __init__(self, port: int, robot_type: int, team: str, unum: int, index: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port))
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.decoder = FrameDecoder()
        self.robot_type, self.team, self.unum, self.index = robot_type, team, unum, index
        self.perceptions = 0
        self.ready = False  # its identity has arrived and it has beamed
        self.send(SCENE.format(robot_type).encode())

    def send(self, payload: bytes) -> None:
        self.sock.sendall(frame(payload))

    def answer(self, message: bytes, moving: bool) -> None:
        self.perceptions += 1
        if self.perceptions == 1:
            self.send(f"(init (unum {self.unum})(teamname {self.team}))(syn)".encode())
        elif not self.ready and b"(unum " in message:
            self.ready = True
            self.send(f"(beam {-1 - self.unum} {self.unum % 4 - 2} 0)(syn)".encode())
        elif moving:
            parse_perception(message)  # what an agent does with every message
            self.send(_joint_command(self.perceptions, self.index))
        else:
            self.send(b"(syn)")


def networked22(cycles: int) -> float:
    """Cycles per second with 22 agents joining one at a time, then all moving their joints."""
    return networked22_figures(cycles)[0]


def networked22_figures(cycles: int) -> tuple[float, float]:
    """(cycles per second, server CPU milliseconds per cycle) of :func:`networked22`'s run."""
    port, monitor_port = _free_port(), _free_port()
    server = _start_server(port, monitor_port)
    selector = selectors.DefaultSelector()
    roster = [(team, unum, t) for team in ("Left", "Right") for unum, t in enumerate(TEAM_TYPES, 1)]
    agents: list[_Agent] = []
    start_at = end_at = None
    start = start_cpu = 0.0
    try:
        while end_at is None or agents[0].perceptions < end_at:
            if len(agents) < len(roster) and (not agents or agents[-1].ready):
                team, unum, robot_type = roster[len(agents)]
                agent = _Agent(port, robot_type, team, unum, len(agents))
                selector.register(agent.sock, selectors.EVENT_READ, agent)
                agents.append(agent)
            if start_at is None and len(agents) == len(roster) and agents[-1].ready:
                start_at = agents[0].perceptions + 20  # let everyone land from the beam
                end_at = start_at + cycles
            moving = start_at is not None and agents[0].perceptions >= start_at
            if moving and not start:
                start, start_cpu = time.perf_counter(), _cpu_seconds(server.pid)
            for key, _ in selector.select(timeout=10):
                agent = key.data
                data = agent.sock.recv(1 << 20)
                if not data:
                    raise RuntimeError("the server closed a connection")
                for message in agent.decoder.feed(data):
                    agent.answer(message, moving)
        rate = cycles / (time.perf_counter() - start)
        return rate, 1000.0 * (_cpu_seconds(server.pid) - start_cpu) / cycles
    finally:
        # the server goes first: closing sockets it still writes to would reset them, and the
        # server would rightly log every agent as dropped
        server.terminate()
        server.wait(timeout=10)
        for agent in agents:
            agent.sock.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer cycles (noisier)")
    args = parser.parse_args()
    n = 300 if args.quick else 2000
    wall, cpu = inprocess_rates(n, True)
    print(f"inprocess_cycles_per_s: {wall:.0f}", flush=True)
    wall_np, cpu_np = inprocess_rates(n, False)
    print(f"inprocess_cycles_per_s_no_perception: {wall_np:.0f}")
    print(f"inprocess_cpu_cycles_per_s: {cpu:.0f}")
    print(f"inprocess_cpu_cycles_per_s_no_perception: {cpu_np:.0f}", flush=True)
    rate, server_ms = networked22_figures(100 if args.quick else 500)
    print(f"networked22_cycles_per_s: {rate:.1f}")
    print(f"networked22_realtime_factor: {rate * 0.02:.2f}")
    print(f"networked22_server_cpu_ms_per_cycle: {server_ms:.1f}")
    print(f"parse_us: {measure_parse_us():.1f}")
    print(f"write_us: {measure_write_us():.1f}")
    print(f"cpu_count: {os.cpu_count()}")


if __name__ == "__main__":
    main()
