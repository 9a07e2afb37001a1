"""Basic kicks of one foot only: rerun just the trials that a reference log shows kicked with
``--foot`` (an experiment runner for a change to one foot's kick).

Run: ``PYTHONPATH=. nice -n 5 python scripts/kick/one_foot.py --log REF.log --foot left
--layout-seeds 0 1 2 [--kicks FILE] [--set module.NAME=value ...] [--distance 3]``, where
``REF.log`` is a ``scripts/kick/sweep.py --verbose`` log of the packaged kicks over the same
layout seeds. Why: the approach and the choice of foot do not depend on the kick motions
(every aligned motion wants the ball at the same spot), so a change to the left kick alone
leaves every right-footed trial byte for byte as it was; running only the left-footed trials
halves an experiment's cost. Prints each trial (as ``sweep.py --verbose``) and per seed the
foot's median distance, falls and misses; ``scripts/kick/per_foot.py`` reads the output."""

from __future__ import annotations

import argparse
import re
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from sweep import apply

from benchmarks.kick import SkillSettings, basic_kick_figures

TRIAL = re.compile(r"^# trial (\d+): .*?foot='(\w+)'")
SEED = re.compile(r"^seed (\d+):")


def trials_by_seed(log: Path, foot: str) -> dict[int, list[int]]:
    """Trial numbers per layout seed whose basic kick chose ``foot`` in a sweep log (the
    trial lines come before their seed's summary line)."""
    found: dict[int, list[int]] = {}
    pending: list[int] = []
    for line in log.read_text().splitlines():
        match = TRIAL.match(line)
        if match and match.group(2) == foot:
            pending.append(int(match.group(1)))
        seed = SEED.match(line)
        if seed:
            found[int(seed.group(1))] = pending
            pending = []
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--log", type=Path, required=True)
    parser.add_argument("--foot", choices=("left", "right"), required=True)
    parser.add_argument("--layout-seeds", type=int, nargs="+", default=[0, 1, 2])
    parser.add_argument("--set", nargs="*", default=[])
    parser.add_argument("--kicks", type=Path)
    parser.add_argument("--distance", default="3")
    parser.add_argument("--trials", type=int, default=20)
    args = parser.parse_args()
    apply(args.set)
    settings = SkillSettings.with_kicks(args.kicks)
    asked = args.distance if args.distance == "long" else float(args.distance)
    chosen = trials_by_seed(args.log, args.foot)
    medians, falls = [], 0
    for seed in args.layout_seeds:
        if seed not in chosen:
            raise SystemExit(f"{args.log} has no summary line for layout seed {seed}")
        only = chosen[seed]
        f = basic_kick_figures(args.trials, 0, asked, seed, True, only, settings)
        falls += int(f["basic_kick_falls"])
        medians.append(f["basic_kick_distance_m"])
        print(
            f"seed {seed}: {args.foot} trials {len(only)}, median "
            f"{f['basic_kick_distance_m']:.2f} m, falls {f['basic_kick_falls']:.0f}, misses "
            f"{f['basic_kick_misses']:.0f}",
            flush=True,
        )
    print(f"total {args.foot} falls {falls}; medians {' '.join(f'{m:.2f}' for m in medians)}")
    print(f"median of medians {statistics.median(medians):.2f} ({' '.join(args.set)})")


if __name__ == "__main__":
    main()
