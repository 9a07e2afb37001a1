"""Agent speed figures, one ``name: value`` line each.

    python benchmarks/agent.py                 # 20 s of game time
    python benchmarks/agent.py --quick         # 4 s
    python benchmarks/agent.py --think-only    # replay a recorded match: think time only

- ``think_ms_median`` / ``think_ms_p99``: one agent cycle (parse the perception, update the
  world model, strategy and behaviours, write the effectors), over all 22 agents of a match;
- ``match_realtime_factor``: game seconds per wall second of an 11 vs 11 match in one process
  (server, physics and all 22 agents) on this machine, joining excluded;
- ``match_realtime_factor[agent_worker]``: the same game with the agents thinking in a second
  process while the server simulates the next cycle (``run_match(agent_worker=True)``);
- ``match_realtime_factor[team_processes]``: the same with each team in its own process over
  TCP (pipelined too), so the agents think on the second core while the server steps physics.

``--think-only`` plays the match once while recording every perception each agent received,
then feeds the recordings to fresh agents with the same configuration and times only their
``think`` (an agent's answers depend on its perceptions alone, so the replay repeats the match's
decisions exactly, without the physics). ``--recording FILE`` keeps the recording, so repeated
measurements (and ``--profile``) skip the match; these print ``think_ms_median[replay]`` and
``think_ms_p99[replay]`` (wall clock per cycle, as in the match) and the same figures in this
thread's CPU time per cycle (``..._cpu[replay]``: steadier on a shared, busy machine, where the
wall clock also counts the time other processes had the core).
"""

from __future__ import annotations

import argparse
import cProfile
import os
import pickle
import pstats
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from agent.agent import Agent, AgentConfig
from agent.match import run_match
from agent.strategy import Strategy
from agent.strategy_config import StrategyConfig
from agent.team import TeamConfig


class _RecordingAgent(Agent):
    """An agent that keeps every perception it is given (for the replay)."""

    def __init__(self, config: AgentConfig, strategy: Strategy) -> None:
        super().__init__(config, strategy)
        self.payloads: list[bytes] = []

    def think(self, payload: bytes) -> bytes:
        self.payloads.append(bytes(payload))
        return super().think(payload)


@dataclass(frozen=True)
class _RecordingTeam(TeamConfig):
    """A team whose agents record their perceptions."""

    def agents(self) -> list[Agent]:
        return [
            _RecordingAgent(AgentConfig(self.name, unum, robot_type), Strategy(self.strategy))
            for unum, robot_type in enumerate(self.robot_types, start=1)
        ]


#: one recorded agent: (team name, unum, robot type, its perceptions in order)
Recording = list[tuple[str, int, int, list[bytes]]]


def record_match(duration: float) -> Recording:
    """Play a match in one process and return every agent's perceptions."""
    result = run_match(
        duration,
        seed=0,
        left=_RecordingTeam("NaoLeft"),
        right=_RecordingTeam("NaoRight"),
        on_event=lambda _: None,
    )
    return [
        (a.config.team_name, a.config.unum, a.config.robot_type, a.payloads)
        for a in result.agents
        if isinstance(a, _RecordingAgent)
    ]


def replay(recording: Recording) -> tuple[np.ndarray, np.ndarray]:
    """Think times (ms) of fresh agents fed the recorded perceptions: wall clock (as the agent
    records it) and this thread's CPU time per cycle (unaffected by other processes)."""
    wall, cpu = [], []
    for team, unum, robot_type, payloads in recording:
        agent = Agent(AgentConfig(team, unum, robot_type), Strategy(StrategyConfig()))
        for payload in payloads:
            start = time.thread_time()
            agent.think(payload)
            cpu.append(time.thread_time() - start)
        wall.append(np.asarray(agent.think_times))
    return np.concatenate(wall) * 1000, np.asarray(cpu) * 1000


def _load_or_record(path: str | None, duration: float) -> Recording:
    if path and os.path.exists(path):
        with open(path, "rb") as handle:
            return pickle.load(handle)
    recording = record_match(duration)
    if path:
        with open(path, "wb") as handle:
            pickle.dump(recording, handle)
    return recording


def think_only(args: argparse.Namespace, duration: float) -> None:
    recording = _load_or_record(args.recording, duration)
    if args.profile:
        profiler = cProfile.Profile()
        profiler.runcall(replay, recording)
        pstats.Stats(profiler).sort_stats(args.profile).print_stats(40)
        return
    runs = [replay(recording) for _ in range(args.repeats)]
    wall = np.concatenate([w for w, _ in runs])
    cpu = np.concatenate([c for _, c in runs])
    print(f"think_ms_median[replay]: {np.median(wall):.3f}")
    print(f"think_ms_p99[replay]: {np.percentile(wall, 99):.3f}")
    print(f"think_ms_median_cpu[replay]: {np.median(cpu):.3f}")
    print(f"think_ms_p99_cpu[replay]: {np.percentile(cpu, 99):.3f}")
    print(f"think_ms_mean_cpu[replay]: {cpu.mean():.3f}")
    print(f"think_cycles[replay]: {len(cpu)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="4 s of game time instead of 20")
    parser.add_argument("--think-only", action="store_true", help="replay a recorded match")
    parser.add_argument("--recording", help="file keeping the --think-only recording")
    parser.add_argument("--repeats", type=int, default=1, help="--think-only replays")
    parser.add_argument(
        "--profile", metavar="SORT", help="--think-only: cProfile one replay (tottime, ...)"
    )
    args = parser.parse_args()
    duration = 4.0 if args.quick else 20.0
    if args.think_only:
        think_only(args, duration)
        return
    result = run_match(duration, seed=0, on_event=lambda _: None)
    times = np.concatenate([np.asarray(a.think_times) for a in result.agents]) * 1000
    print(f"think_ms_median: {np.median(times):.3f}")
    print(f"think_ms_p99: {np.percentile(times, 99):.3f}")
    print(f"match_realtime_factor: {result.realtime_factor:.2f}")
    worker = run_match(duration, seed=0, on_event=lambda _: None, agent_worker=True)
    print(f"match_realtime_factor[agent_worker]: {worker.realtime_factor:.2f}")
    split = run_match(duration, seed=0, on_event=lambda _: None, team_processes=True)
    print(f"match_realtime_factor[team_processes]: {split.realtime_factor:.2f}")
    print(f"cpu_count: {os.cpu_count()}")


if __name__ == "__main__":
    main()
