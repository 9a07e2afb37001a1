"""Agent speed figures, one ``name: value`` line each.

    python benchmarks/agent.py             # 20 s of game time
    python benchmarks/agent.py --quick     # 4 s

- ``think_ms_median`` / ``think_ms_p99``: one agent cycle (parse the perception, update the
  world model, strategy and behaviours, write the effectors), over all 22 agents of a match;
- ``match_realtime_factor``: game seconds per wall second of an 11 vs 11 match in one process
  (server, physics and all 22 agents) on this machine, joining excluded;
- ``match_realtime_factor[team_processes]``: the same with each team in its own process over
  TCP, so the agents think on the second core while the server steps physics.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from agent.match import run_match


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    duration = 4.0 if args.quick else 20.0
    result = run_match(duration, seed=0, on_event=lambda _: None)
    times = np.concatenate([np.asarray(a.think_times) for a in result.agents]) * 1000
    print(f"think_ms_median: {np.median(times):.3f}")
    print(f"think_ms_p99: {np.percentile(times, 99):.3f}")
    print(f"match_realtime_factor: {result.realtime_factor:.2f}")
    split = run_match(duration, seed=0, on_event=lambda _: None, team_processes=True)
    print(f"match_realtime_factor[team_processes]: {split.realtime_factor:.2f}")
    print(f"cpu_count: {os.cpu_count()}")


if __name__ == "__main__":
    main()
