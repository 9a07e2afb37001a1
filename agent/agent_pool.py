"""Agents that think in a second process while the server simulates: one match, two cores.

In a match in one process the server's physics and the 22 agents' thinking take turns on one
core. An :class:`AgentPool` moves the agents into a worker process: each cycle the server hands
them their perceptions, simulates the next cycle while they think (``SoccerServer(pipeline=
True)``) and then collects their answers. The bytes, their order and the cycles at which the
answers reach the motors are those of the one-process match, so a seed plays the same game
(tested); only the wall clock differs. Agents join one at a time through the server, as the
in-process agents of ``agent.match`` do, which is what keeps the game reproducible (agents of a
team process over TCP join whenever their process gets to it).
"""

from __future__ import annotations

import copyreg
import io
import multiprocessing
import pickle
import types
from multiprocessing.connection import Connection

from agent.agent import Agent

#: Seconds the server waits for the worker's answers before it calls the worker dead.
ANSWER_TIMEOUT_S = 60.0


class AgentPool:
    """A worker process holding ``agents``; the server addresses them by its agent ids."""

    def __init__(self, agents: list[Agent]) -> None:
        self._greetings = [agent.greeting() for agent in agents]
        self._index: dict[int, int] = {}  # server agent id -> position in ``agents``
        self._unums: dict[int, int | None] = {}
        context = multiprocessing.get_context("spawn")
        self._connection, worker_end = context.Pipe()
        self._process = context.Process(target=_serve, args=(worker_end, agents), daemon=True)
        self._process.start()
        worker_end.close()
        self._waiting = False

    def join(self, server, position: int) -> int:
        """Connect the agent at ``position`` to ``server``; returns its agent id."""
        agent_id = server.add_worker_agent(self, self._greetings[position])
        self._index[agent_id] = position
        self._unums[agent_id] = None
        return agent_id

    def unum(self, agent_id: int) -> int | None:
        """The uniform number the agent has learnt from the server (None until it has)."""
        return self._unums[agent_id]

    def submit(self, perceptions: dict[int, bytes]) -> None:
        """Hand the agents their perceptions; they think while the caller goes on."""
        if self._waiting:
            raise RuntimeError("collect() the last answers before submitting new perceptions")
        batch = [(self._index[agent_id], payload) for agent_id, payload in perceptions.items()]
        self._connection.send(batch)
        self._waiting = True

    def collect(self) -> dict[int, bytes]:
        """The answers to the last perceptions submitted, by agent id."""
        if not self._waiting:
            return {}
        if not self._connection.poll(ANSWER_TIMEOUT_S):
            raise RuntimeError(f"the agents' worker gave no answer for {ANSWER_TIMEOUT_S:.0f} s")
        self._waiting = False
        agent_ids = {position: agent_id for agent_id, position in self._index.items()}
        try:
            answers = self._connection.recv()
        except EOFError:
            raise RuntimeError(
                "the agents' worker process ended (its traceback is above)"
            ) from None
        result = {}
        for position, (answer, unum) in answers:
            agent_id = agent_ids[position]
            result[agent_id], self._unums[agent_id] = answer, unum
        return result

    def close(self) -> list[Agent]:
        """Stop the worker and return its agents as they ended (think times, world models)."""
        try:
            self.collect()
            self._connection.send(None)
            agents = self._connection.recv() if self._connection.poll(ANSWER_TIMEOUT_S) else []
        except (BrokenPipeError, EOFError, OSError):
            agents = []
        self._connection.close()
        self._process.join(timeout=10)
        if self._process.is_alive():
            self._process.terminate()
        return agents


def _dumps(obj: object) -> bytes:
    """Pickle ``obj``, read-only mappings (``MappingProxyType``, which skills use for tables
    they must not change) included: pickle cannot take them, their contents it can."""
    buffer = io.BytesIO()
    pickler = pickle.Pickler(buffer)
    pickler.dispatch_table = copyreg.dispatch_table.copy()
    pickler.dispatch_table[types.MappingProxyType] = lambda m: (_read_only, (dict(m),))
    pickler.dump(obj)
    return buffer.getvalue()


def _read_only(mapping: dict) -> types.MappingProxyType:
    return types.MappingProxyType(mapping)


def _serve(connection: Connection, agents: list[Agent]) -> None:
    """The worker: think about each batch of perceptions, answer with effectors and unums; on
    ``None`` send the agents back and stop."""
    while True:
        try:
            batch = connection.recv()
        except EOFError:
            return
        if batch is None:
            connection.send_bytes(_dumps(agents))
            return
        answers = []
        for position, payload in batch:
            agent = agents[position]
            answers.append((position, (agent.think(payload), agent.world.unum)))
        connection.send(answers)
