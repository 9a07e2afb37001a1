"""The get-up benchmark's own trials, fallen once and replayed for many candidates.

Why: ``benchmarks/get_up.py`` makes every fall anew (two thirds of a trial's time is the fall),
so comparing ten candidates on the same 100 trials costs ten times the falls. Here the falls of
the benchmark's trials (:func:`benchmarks.get_up.trial_specs`, the same seeds) are made once,
each saved with ``Session.save_state`` and the agent's world model, and every candidate plays
only the get-up itself from each of them, through the real skill and
:func:`benchmarks.get_up.play_get_up`. Saving normalises the simulator (contact caches
dropped), so a replayed trial continues as a restored one does, not exactly as the benchmark's
never-saved run: the falls are the benchmark's, the outcomes a statistically equal sample
(the skill of session 7's start, seed 0: 0.81 here against the benchmark's 0.83,
other trials failing). Use it to screen
candidates; only the benchmark's figures are quoted as results.

A candidate is a function that adjusts the fresh ``get_up`` skill of each trial (its
sequences, balance corrections, thresholds). Memory: one open session per trial (about 25 MB
each), so one seed set of 100 trials at a time.

Run (the packaged skill, as the benchmark would score it)::

    nice -n 5 .venv/bin/python -m learning.get_up_eval --seed 0 --seed 500
"""

from __future__ import annotations

import argparse
import copy
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.get_up import GetUpSkill
from benchmarks.get_up import TrialResult, fall, play_get_up, summary, trial_specs
from learning.falls import FALL_DIRECTIONS
from learning.local_agent import LocalAgent
from sim.session import Session, SessionSnapshot
from world.nao_model import ROBOT_TYPES
from world.world_model import WorldModel

#: Adjusts the fresh get_up skill of a trial before it plays (a candidate).
Candidate = Callable[[GetUpSkill], None]


@dataclass
class SavedFall:
    """One benchmark trial's fall at rest: its session (kept open) and what to restore."""

    robot_type: int
    direction: str
    seed: int
    lying_on: str | None
    session: Session
    agent: int
    team_name: str | None
    snapshot: SessionSnapshot
    world: WorldModel

    def replay(self) -> LocalAgent:
        """The session back at the fall's end and a fresh agent with the world model as it
        was (new skills, as a robot whose get_up starts now)."""
        return LocalAgent.from_snapshot(
            self.session, self.agent, self.robot_type, self.team_name, self.snapshot, self.world
        )


def saved_falls(
    seed: int,
    robot_types: list[int] | None = None,
    trials_per_type: int = 20,
    directions: list[str] | None = None,
) -> list[SavedFall]:
    """The falls of ``benchmarks/get_up.py --seed SEED`` (same trials, same order)."""
    out = []
    specs = trial_specs(
        list(ROBOT_TYPES) if robot_types is None else robot_types,
        trials_per_type,
        seed,
        list(FALL_DIRECTIONS) if directions is None else directions,
    )
    for robot_type, direction, trial_seed in specs:
        session, driver, lying_on = fall(robot_type, direction, trial_seed)
        out.append(
            SavedFall(
                robot_type,
                direction,
                trial_seed,
                lying_on,
                session,
                driver.agent,
                driver.world.team_name,
                session.save_state(),
                copy.deepcopy(driver.world),
            )
        )
    return out


def evaluate(
    falls: list[SavedFall], candidate: Candidate | None = None, time_limit: float = 4.0
) -> list[TrialResult]:
    """Every saved fall's get-up with the candidate applied to its skill."""
    return list(play_all(falls, candidate, time_limit))


def play_all(
    falls: list[SavedFall], candidate: Candidate | None, time_limit: float
) -> Iterator[TrialResult]:
    for saved in falls:
        driver = saved.replay()
        skill = driver.behavior.skill("get_up")
        assert isinstance(skill, GetUpSkill)
        if candidate is not None:
            candidate(skill)
        yield play_get_up(
            driver, saved.robot_type, saved.direction, saved.seed, saved.lying_on, time_limit
        )


def close(falls: list[SavedFall]) -> None:
    for saved in falls:
        saved.session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, action="append", default=None)
    parser.add_argument("--types", default=",".join(map(str, ROBOT_TYPES)))
    parser.add_argument("--trials-per-type", type=int, default=20)
    parser.add_argument("--show-failures", action="store_true")
    args = parser.parse_args()
    robot_types = [int(t) for t in args.types.split(",")]
    for seed in args.seed or [0]:
        falls = saved_falls(seed, robot_types, args.trials_per_type)
        print(f"seed {seed}")
        print(summary(evaluate(falls), robot_types, args.show_failures))
        close(falls)


if __name__ == "__main__":
    main()
