"""Per-foot figures of basic-kick logs: trials, falls, kicks, medians.

Run: ``python scripts/kick/trial_summary.py LOG [LOG ...] [--asked D] [--pool]``. Reads the
trial lines of ``scripts/kick/fall_stages.py`` logs and the ``# trial k: BasicKickResult(...)``
lines of ``python -m benchmarks.kick`` logs. For each log, one line per foot and one for all
trials: trials, falls, trials that kicked, the median distance (m), the tenth and ninetieth
percentile distances, the median absolute direction error (deg), kicks more than 15 deg off
line, and the median time to kick (s) over the trials that kicked; with ``--asked`` (the
distance the logs asked for, m) also the median ``|distance - D|`` and the share of kicks
within 0.5 m of D; with ``--pool`` the same lines over all the logs together (one benchmark
run per layout seed, pooled).

Why: calibrating a kick by its ball gap needs each foot's median distance (the feet play
different motions), which the fall_stages summary line does not give.
"""

from __future__ import annotations

import argparse
import re
import statistics
from dataclasses import dataclass
from pathlib import Path

TRIAL = re.compile(
    r"^seed \d+ trial +\d+ foot (?P<foot>\S+) fall (?P<fall>\S+) "
    r"distance (?P<distance>\S+) direction (?P<direction>\S+) time (?P<time>\S+)"
)
#: a trial of ``benchmarks/kick.py``'s log (its repr of ``BasicKickResult``)
BENCHMARK_TRIAL = re.compile(
    r"^# trial \d+: BasicKickResult\(asked=[^,]+, distance_m=(?P<distance>[^,]+), "
    r"direction_error_deg=(?P<direction>[^,]+), time_to_kick_s=(?P<time>[^,]+), "
    r"foot=(?P<foot>[^,]+), .*fall_stage=(?P<fall>[^)]+)\)"
)
#: a kick further off line than this (deg) counts as wide
WIDE_DEG = 15.0


@dataclass(frozen=True)
class Trial:
    foot: str
    fell: bool
    distance_m: float
    direction_deg: float
    time_s: float | None


def read_trials(path: Path) -> list[Trial]:
    """The trial lines of a fall_stages or benchmarks/kick.py log (other lines are skipped)."""
    trials = []
    for line in path.read_text().splitlines():
        match = TRIAL.match(line) or BENCHMARK_TRIAL.match(line)
        if match:
            time = match["time"]
            trials.append(
                Trial(
                    foot=match["foot"].strip("'"),
                    fell=match["fall"] not in ("none", "None"),
                    distance_m=float(match["distance"]),
                    direction_deg=float(match["direction"]),
                    time_s=None if time in ("-", "None") else float(time),
                )
            )
    return trials


def _median(values: list[float]) -> str:
    return f"{statistics.median(values):.2f}" if values else "-"


def _percentile(values: list[float], share: float) -> str:
    """The nearest-rank percentile (``share`` in 0..1), or - for no values."""
    if not values:
        return "-"
    ordered = sorted(values)
    return f"{ordered[min(len(ordered) - 1, int(share * len(ordered)))]:.2f}"


def summary(label: str, trials: list[Trial], asked_m: float | None = None) -> str:
    """One line of figures over ``trials`` (``asked_m``: add the distance error figures)."""
    kicked = [t for t in trials if t.time_s is not None]
    errors = [abs(t.direction_deg) for t in kicked]
    distances = [t.distance_m for t in kicked]
    line = (
        f"{label}: trials {len(trials)} falls {sum(t.fell for t in trials)} kicked {len(kicked)}"
        f" distance_median_m {_median(distances)}"
        f" p10-p90 {_percentile(distances, 0.1)}-{_percentile(distances, 0.9)}"
        f" direction_error_median_deg {_median(errors)}"
        f" wide_over_{WIDE_DEG:.0f}deg {sum(e > WIDE_DEG for e in errors)}"
        f" time_median_s {_median([t.time_s for t in kicked if t.time_s is not None])}"
    )
    if asked_m is not None:
        misses = [abs(d - asked_m) for d in distances]
        within = sum(m <= 0.5 for m in misses) / len(misses) if misses else 0.0
        line += f" distance_error_median_m {_median(misses)} within_0.5m {within:.2f}"
    return line


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", type=Path, nargs="+")
    parser.add_argument("--asked", type=float, help="the distance the logs asked for (m)")
    parser.add_argument("--pool", action="store_true", help="one set of lines over all logs")
    args = parser.parse_args()
    if args.pool:
        groups = [("pooled", [t for path in args.logs for t in read_trials(path)])]
    else:
        groups = [(path.name, read_trials(path)) for path in args.logs]
    for label, trials in groups:
        for foot in sorted({t.foot for t in trials}):
            mine = [t for t in trials if t.foot == foot]
            print(summary(f"{label} [{foot}]", mine, args.asked))
        print(summary(f"{label} [all]", trials, args.asked))


if __name__ == "__main__":
    main()
