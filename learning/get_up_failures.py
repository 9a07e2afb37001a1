"""One line per get-up trial: each attempt's sequence, how high it got and how it ended.

Why: ``learning/get_up_trace.py`` prints a trial cycle by cycle, which is what one needs to see
one failure, but twenty failures need a classification first: did the sit-up stall (low peak
height), did the robot come up and tip over in the squat or the stand (high peak, then down),
did a front attempt turn into a back one, did the time run out during a retry? Each attempt is
summarised by the skill's own view (sequence, seconds played) and the simulator's ground truth
(peak torso height as a fraction of standing height, the torso pitch when it peaked and at the
attempt's end), which the benchmark may read to measure.

Run (trials from ``benchmarks/get_up.py --show-failures``, ``TYPE:DIRECTION:SEED``)::

    .venv/bin/python learning/get_up_failures.py 1:front:1016 3:left:3010
    .venv/bin/python learning/get_up_failures.py --time-limit 8 0:back:13

With ``--time-limit 8`` a trial that stands only after the benchmark's 4 s shows where its
time went: each attempt's start (after the wait for the body to settle), how long it played
before it was abandoned or ended, and when the robot stood.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.get_up import GetUpSkill
from behaviors.joint_control import CYCLE_SECONDS
from benchmarks.get_up import run_trial
from learning.get_up_trace import torso_pitch_roll_deg
from learning.local_agent import LocalAgent


@dataclass
class AttemptSummary:
    """What one attempt did, from its first to its last cycle."""

    number: int
    sequence: str = "-"
    started_s: float = 0.0
    played_s: float = 0.0
    peak_height: float = 0.0
    pitch_at_peak: float = 0.0
    peak_at_s: float = 0.0
    end_height: float = 0.0
    end_pitch: float = 0.0
    end_roll: float = 0.0

    def line(self) -> str:
        return (
            f"#{self.number} {self.sequence} @{self.started_s:.2f}s played {self.played_s:.2f}s "
            f"peak h {self.peak_height:.2f} at {self.peak_at_s:.2f}s "
            f"(pitch {self.pitch_at_peak:+.0f}) end h {self.end_height:.2f} "
            f"pitch {self.end_pitch:+.0f} roll {self.end_roll:+.0f}"
        )


@dataclass
class TrialRecorder:
    """An observer for :func:`benchmarks.get_up.run_trial` that fills attempt summaries."""

    attempts: list[AttemptSummary] = field(default_factory=list)

    def __call__(self, agent: LocalAgent, cycle: int) -> None:
        skill = agent.behavior.skill("get_up")
        assert isinstance(skill, GetUpSkill)
        if skill.attempts == 0:
            return
        if not self.attempts or self.attempts[-1].number != skill.attempts:
            self.attempts.append(AttemptSummary(skill.attempts, started_s=cycle * CYCLE_SECONDS))
        attempt = self.attempts[-1]
        if skill.playing is not None:
            attempt.sequence, attempt.played_s = skill.playing
        pitch, roll = torso_pitch_roll_deg(agent)
        height = float(agent.robot.torso_position()[2]) / agent.robot.spec.sole_height()
        if height > attempt.peak_height:
            attempt.peak_height, attempt.pitch_at_peak = height, pitch
            attempt.peak_at_s = cycle * CYCLE_SECONDS - attempt.started_s
        attempt.end_height, attempt.end_pitch, attempt.end_roll = height, pitch, roll


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("trials", nargs="+", help="TYPE:DIRECTION:SEED")
    parser.add_argument(
        "--time-limit",
        type=float,
        default=4.0,
        help="seconds the get-up may take (longer: when does a late trial stand)",
    )
    args = parser.parse_args()
    for spec in args.trials:
        robot_type, direction, seed = spec.split(":")
        recorder = TrialRecorder()
        result = run_trial(
            int(robot_type), direction, int(seed), args.time_limit, observer=recorder
        )
        outcome = f"UP at {result.time_s:.2f}s" if result.succeeded else "DOWN"
        print(f"type {robot_type} {direction} seed {seed} lying {result.lying_on}: {outcome}")
        for attempt in recorder.attempts:
            print("   ", attempt.line())


if __name__ == "__main__":
    main()
