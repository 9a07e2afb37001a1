"""Where basic kicks fall, and how far the torso rolls in each phase: one line per trial.

Run: ``PYTHONPATH=. python scripts/kick/fall_stages.py --layout-seeds 0 1 --distance 3.5
[--set basic_kick.SHUFFLE_ANKLE_ROLL_GAIN=0] [--kicks FILE]``. Each trial is
``benchmarks/kick.py``'s basic trial (same layouts, same seeds); a fall before the kick is split
by the phase it came in (``approach`` or ``shuffle``, which the benchmark counts together), each
trial prints its distance, direction error and time to kick (s, - when it never kicked), the
largest torso roll (true, degrees, in the torso's own frame:
:func:`learning.get_up_trace.torso_pitch_roll_deg`) per skill phase. The last line
sums the falls per stage and gives the shuffle's largest rolls (median, 90th percentile, max).

Why: the benchmark's fall stages lump the approach, the alignment shuffle and the settle
together as ``before_kick``; session 25 traced falls there to the open-loop shuffle tipping
over a foot's edge, and this is how its roll feedback was measured.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
from collections import Counter
from pathlib import Path

import numpy as np

from benchmarks.kick import SkillSettings, random_basic_layout, run_basic_trial
from learning.get_up_trace import torso_pitch_roll_deg
from learning.local_agent import LocalAgent

sys.path.insert(0, str(Path(__file__).resolve().parent))
from sweep import apply


def _placement(error: tuple[float, float] | None) -> str:
    """The ball's place against the kick's spot when it started (m, along and across), or -."""
    return "-" if error is None else f"{error[0]:+.3f} {error[1]:+.3f}"


def _seconds(time_s: float | None) -> str:
    """Seconds from the skill's first cycle to the kick's contact, or - when it never kicked."""
    return "-" if time_s is None else f"{time_s:.2f}"


def trial_arguments(description: str | None) -> argparse.ArgumentParser:
    """A parser with the options that pick basic trials as ``benchmarks/kick.py`` plays them
    (layout seeds, trials per seed, distance asked) and ``--set`` for module constants."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--layout-seeds", type=int, nargs="+", default=[0, 1])
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--distance", default="3.5")
    parser.add_argument("--set", nargs="*", default=[], help="module.NAME=value (behaviors)")
    parser.add_argument("--kicks", type=Path, help="kick file instead of the packaged one")
    return parser


def main() -> None:
    args = trial_arguments(__doc__).parse_args()
    apply(args.set)
    settings = SkillSettings.with_kicks(args.kicks)
    asked = args.distance if args.distance == "long" else float(args.distance)
    stages: Counter[str] = Counter()
    shuffle_rolls: list[float] = []
    for seed in args.layout_seeds:
        rng = np.random.default_rng(seed + 1)
        layouts = [random_basic_layout(rng) for _ in range(args.trials)]
        for trial, layout in enumerate(layouts):
            rolls: dict[str, float] = {}

            def observe(driver: LocalAgent, phase: str, rolls: dict[str, float] = rolls) -> None:
                rolls[phase] = max(rolls.get(phase, 0.0), abs(torso_pitch_roll_deg(driver)[1]))

            result = run_basic_trial(asked, trial, *layout, observe=observe, settings=settings)
            stage = result.fall_stage or "none"
            if stage == "before_kick":
                stage = "shuffle" if "shuffle" in rolls else "approach"
            stages[stage] += 1
            if "shuffle" in rolls:
                shuffle_rolls.append(rolls["shuffle"])
            phases = " ".join(f"{phase}:{roll:.1f}" for phase, roll in rolls.items())
            print(
                f"seed {seed} trial {trial:2d} foot {result.foot} fall {stage} "
                f"distance {result.distance_m:.2f} direction {result.direction_error_deg:+.1f} "
                f"time {_seconds(result.time_to_kick_s)} "
                f"placement {_placement(result.placement_error_m)} | max roll {phases}",
                flush=True,
            )
    falls = sum(count for stage, count in stages.items() if stage != "none")
    largest = sorted(shuffle_rolls)
    summary = "no shuffle"
    if largest:
        p90 = largest[max(0, math.ceil(0.9 * len(largest)) - 1)]
        summary = (
            f"shuffle max roll median {statistics.median(largest):.1f} p90 {p90:.1f} "
            f"max {largest[-1]:.1f} deg"
        )
    print(f"trials {sum(stages.values())}, falls {falls} {dict(stages)}; {summary}")


if __name__ == "__main__":
    main()
