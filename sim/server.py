"""The networked stand-in server: agent port (3100) and monitor/trainer port (3200) over TCP.

A single-threaded ``selectors`` loop wraps one :class:`~sim.session.Session`. Every message in
both directions is length-prefixed (4-byte big-endian) S-expressions, as rcssserver3d speaks.

Pacing:
- sync mode (``--sync``): a cycle runs as soon as every agent with a robot has sent ``(syn)``
  for the previous perception, so the game runs as fast as the slowest agent allows;
- real-time mode: a cycle every 0.02 s whatever the agents do.

Bad input never stops the server: a message that does not parse is logged and ignored (as the
real server does), a frame whose length prefix exceeds the limit or a client that vanishes
mid-frame is logged and that client dropped; every other agent keeps getting its cycles.
"""

from __future__ import annotations

import contextlib
import errno
import logging
import selectors
import socket
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

from sim.monitor import parse_trainer_commands
from sim.session import Session
from world.framing import FrameDecoder, FrameError, frame
from world.perception import CYCLE_SECONDS

log = logging.getLogger(__name__)

#: Largest message an agent or a monitor may send us (effectors and trainer commands are small).
MAX_INPUT_FRAME = 64 * 1024
#: Monitors get a scene update every this many cycles, as the real server.
MONITOR_INTERVAL = 2
#: A sync-mode server gives up waiting for an agent's (syn) after this long and drops it.
SYNC_TIMEOUT_S = 30.0


class LocalAgent(Protocol):
    """An agent living in the server's process (see ``agent.agent.Agent``)."""

    def greeting(self) -> bytes: ...

    def think(self, payload: bytes) -> bytes: ...


class AgentWorker(Protocol):
    """Agents thinking in another process (``agent.agent_pool.AgentPool``), addressed by the
    server's agent ids: the server submits their perceptions, simulates the next cycle while
    they think (with ``pipeline``) and then collects their answers."""

    def submit(self, perceptions: dict[int, bytes]) -> None: ...

    def collect(self) -> dict[int, bytes]: ...


@dataclass
class _Client:
    sock: socket.socket
    address: str
    kind: str  # "agent" or "monitor"
    decoder: FrameDecoder = field(default_factory=lambda: FrameDecoder(MAX_INPUT_FRAME))
    outbox: bytearray = field(default_factory=bytearray)
    agent_id: int | None = None
    synced: bool = True
    #: whether the selector also waits for this socket to take more output
    watching_writes: bool = False


class SoccerServer:
    """Serve one :class:`Session` to agents and monitors over TCP."""

    def __init__(
        self,
        session: Session,
        host: str = "127.0.0.1",
        port: int = 3100,
        monitor_port: int = 3200,
        sync: bool = False,
        pipeline: bool = False,
    ) -> None:
        self.session = session
        self.sync = sync
        self.pipeline = pipeline
        #: whether the session already simulated the cycle after the last perceptions sent
        self._ahead = False
        self.selector = selectors.DefaultSelector()
        self.agent_listener = self._listen(host, port, "agent")
        self.monitor_listener = self._listen(host, monitor_port, "monitor")
        self.clients: dict[socket.socket, _Client] = {}
        #: in-process agents (anything with ``think(bytes) -> bytes``): same bytes, no socket
        self.local_agents: dict[int, LocalAgent] = {}
        #: agents of worker processes, by agent id (same bytes again, answered a little later)
        self.worker_agents: dict[int, AgentWorker] = {}
        self._running = False

    # ------------------------------------------------------------------ public
    @property
    def port(self) -> int:
        return self.agent_listener.getsockname()[1]

    @property
    def monitor_port(self) -> int:
        return self.monitor_listener.getsockname()[1]

    def serve_forever(
        self,
        max_cycles: int | None = None,
        until: Callable[[], bool] | None = None,
        on_cycle: Callable[[], None] | None = None,
    ) -> None:
        """Run until :meth:`stop` is called (from a callback or a signal), the session reaches
        ``max_cycles``, or ``until()`` is true; ``on_cycle()`` runs after every cycle, once its
        perceptions are out.

        In sync mode the server waits for every TCP agent's ``(syn)``; in-process agents answer
        inside the cycle, so with only those it runs as fast as it can. With ``pipeline`` the
        session is a cycle ahead of the perceptions sent while this runs (``max_cycles`` and
        ``until()`` see that cycle); on return its perceptions have gone out too, so the agents
        end where they would have without the pipeline.
        """
        self._running = True
        next_cycle = time.monotonic()
        waiting_since = time.monotonic()
        while self._running:
            finished = (max_cycles is not None and self.session.cycle >= max_cycles) or (
                until is not None and until()
            )
            if finished and not self._ahead:
                break
            if self.sync and (
                self._agents_with_robots() or self.local_agents or self.worker_agents
            ):
                self._poll(0.05 if not self._all_synced() else 0.0)
                if not self._all_synced():
                    if time.monotonic() - waiting_since > SYNC_TIMEOUT_S:
                        self._drop_unsynced()
                    continue
                waiting_since = next_cycle = time.monotonic()
            else:  # real time, and sync mode with nobody to wait for
                self._poll(max(0.0, next_cycle - time.monotonic()))
                if time.monotonic() < next_cycle:
                    continue
                next_cycle += CYCLE_SECONDS
                if time.monotonic() - next_cycle > 1.0:  # fell far behind: do not try to catch up
                    next_cycle = time.monotonic()
            self.run_cycle(on_cycle, simulate_next=not finished)

    def stop(self) -> None:
        self._running = False

    def close(self) -> None:
        for client in list(self.clients.values()):
            self._drop(client, None)
        for listener in (self.agent_listener, self.monitor_listener):
            self.selector.unregister(listener)
            listener.close()
        self.selector.close()

    def add_worker_agent(self, worker: AgentWorker, greeting: bytes) -> int:
        """Connect an agent that thinks in ``worker``'s process; ``greeting`` is its first
        message (``scene``). Returns the agent id the worker's perceptions are keyed by."""
        agent_id = self._greet(greeting)
        self.worker_agents[agent_id] = worker
        return agent_id

    def add_local_agent(self, agent: LocalAgent) -> int:
        """Connect an in-process agent: it gets its perception and answers inside
        :meth:`run_cycle`, with the very bytes a TCP agent would exchange."""
        agent_id = self._greet(agent.greeting())
        self.local_agents[agent_id] = agent
        return agent_id

    def _greet(self, greeting: bytes) -> int:
        """A new session agent that has sent ``greeting`` (its ``scene``): its agent id."""
        agent_id = self.session.add_agent()
        self.session.handle_message(agent_id, greeting)
        return agent_id

    def poll(self, timeout: float = 0.0) -> None:
        """Serve socket traffic (connections, effectors, trainer commands) for up to timeout."""
        self._poll(timeout)

    def run_cycle(
        self, on_cycle: Callable[[], None] | None = None, simulate_next: bool = True
    ) -> None:
        """Step the game once and send every agent its perception (and monitors their update);
        then ``on_cycle()``.

        With ``pipeline`` (and ``simulate_next``) the next cycle's physics runs right after
        that, while the agents think in their own processes (TCP clients, agent workers): it
        does not depend on their answers, which reach the motors a cycle later anyway
        (:meth:`Session.advance`), so the agents see exactly the same game. Only trainer
        commands from monitors act a cycle later than without it (``on_cycle`` still acts in
        time). This is what lets a match use both cores.
        """
        if not self._ahead:
            self.session.advance()
        self.session.stage_answers()
        self._ahead = False
        for agent_id, agent in self.local_agents.items():
            payload = self.session.perception(agent_id)
            if payload is not None:
                self.session.handle_message(agent_id, agent.think(payload))
        workers = self._submit_to_workers()
        for client in list(self.clients.values()):
            if client.kind == "agent" and client.agent_id is not None:
                payload = self.session.perception(client.agent_id)
                if payload is not None:
                    client.synced = False
                    self._send(client, payload)
        if self.session.cycle % MONITOR_INTERVAL == 0 and self._monitors():
            message = self.session.monitor_message()
            for client in self._monitors():
                self._send(client, message)
        if on_cycle is not None:
            on_cycle()
        if self.pipeline and simulate_next:
            self.session.advance()
            self._ahead = True
        for worker in workers:
            for agent_id, answer in sorted(worker.collect().items()):
                self.session.handle_message(agent_id, answer)

    def _submit_to_workers(self) -> list[AgentWorker]:
        """Hand every worker its agents' perceptions; returns the workers that got some."""
        batches: dict[int, tuple[AgentWorker, dict[int, bytes]]] = {}
        for agent_id, worker in self.worker_agents.items():
            payload = self.session.perception(agent_id)
            if payload is not None:
                batches.setdefault(id(worker), (worker, {}))[1][agent_id] = payload
        for worker, perceptions in batches.values():
            worker.submit(perceptions)
        return [worker for worker, _ in batches.values()]

    # ------------------------------------------------------------------ sockets
    def _listen(self, host: str, port: int, kind: str) -> socket.socket:
        listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            listener.bind((host, port))
        except OSError as exc:
            listener.close()
            raise OSError(exc.errno, f"cannot listen for {kind}s on {host}:{port}: {exc}") from None
        listener.listen(64)
        listener.setblocking(False)
        self.selector.register(listener, selectors.EVENT_READ, kind)
        log.info("listening for %ss on %s:%d", kind, host, listener.getsockname()[1])
        return listener

    def _poll(self, timeout: float) -> None:
        for key, events in self.selector.select(timeout):
            if key.data in ("agent", "monitor"):
                self._accept(key.fileobj, key.data)
                continue
            client = key.data
            if events & selectors.EVENT_READ:
                self._read(client)
            if events & selectors.EVENT_WRITE and client.sock in self.clients:
                self._flush(client)

    def _accept(self, listener: socket.socket, kind: str) -> None:
        try:
            sock, address = listener.accept()
        except BlockingIOError:
            return
        sock.setblocking(False)
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        client = _Client(sock, f"{address[0]}:{address[1]}", kind)
        self.clients[sock] = client
        self.selector.register(sock, selectors.EVENT_READ, client)
        if kind == "agent":
            client.agent_id = self.session.add_agent()
            log.info("agent %d connected from %s", client.agent_id, client.address)
        else:
            log.info("monitor connected from %s", client.address)
            self.session.request_full_state()

    def _read(self, client: _Client) -> None:
        try:
            data = client.sock.recv(65536)
        except (ConnectionError, OSError) as exc:
            self._drop(client, f"connection error: {exc}")
            return
        if not data:
            reason = None
            if client.decoder.pending:
                reason = f"vanished mid-frame ({client.decoder.pending} bytes of a message unread)"
            self._drop(client, reason)
            return
        try:
            payloads = client.decoder.feed(data)
        except FrameError as exc:
            self._drop(client, str(exc))
            return
        for payload in payloads:
            self._dispatch(client, payload)

    def _dispatch(self, client: _Client, payload: bytes) -> None:
        if client.kind == "monitor":
            commands, errors = parse_trainer_commands(payload)
            for error in errors:
                log.warning("monitor %s: %s", client.address, error)
            self.session.trainer_command(commands)
            return
        try:
            self.session.handle_message(client.agent_id, payload)
        except Exception:  # a bug must not take the other agents down with it
            log.exception(
                "agent %d: message %r could not be handled", client.agent_id, payload[:80]
            )
        if self.session.syn_received(payload):
            client.synced = True

    def _send(self, client: _Client, payload: bytes) -> None:
        client.outbox += frame(payload)
        self._flush(client)

    def _flush(self, client: _Client) -> None:
        try:
            sent = client.sock.send(client.outbox)
        except BlockingIOError:
            sent = 0
        except OSError as exc:
            if exc.errno not in (errno.EAGAIN, errno.EWOULDBLOCK):
                self._drop(client, f"send failed: {exc}")
                return
            sent = 0
        del client.outbox[:sent]
        pending = bool(client.outbox)
        if pending != client.watching_writes:  # a system call only when interest changes
            events = selectors.EVENT_READ | (selectors.EVENT_WRITE if pending else 0)
            self.selector.modify(client.sock, events, client)
            client.watching_writes = pending

    def _drop(self, client: _Client, reason: str | None) -> None:
        if reason:
            log.error("%s %s dropped: %s", client.kind, client.address, reason)
        else:
            log.info("%s %s disconnected", client.kind, client.address)
        self.clients.pop(client.sock, None)
        with contextlib.suppress(KeyError, ValueError):
            self.selector.unregister(client.sock)
        client.sock.close()
        if client.agent_id is not None:
            self.session.remove_agent(client.agent_id)

    # ------------------------------------------------------------------ sync
    def _agents_with_robots(self) -> list[_Client]:
        return [
            c
            for c in self.clients.values()
            if c.kind == "agent" and self.session.perception(c.agent_id) is not None
        ]

    def _all_synced(self) -> bool:
        return all(c.synced for c in self._agents_with_robots())

    def _drop_unsynced(self) -> None:
        for client in self._agents_with_robots():
            if not client.synced:
                self._drop(client, f"no (syn) for {SYNC_TIMEOUT_S:.0f} s in sync mode")

    def _monitors(self) -> list[_Client]:
        return [c for c in self.clients.values() if c.kind == "monitor"]
