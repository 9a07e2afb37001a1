"""Per-foot figures of ``scripts/kick/fall_stages.py`` logs: trials, falls, kicks, medians.

Run: ``python scripts/kick/trial_summary.py LOG [LOG ...]``. For each log, one line per foot and
one for all trials: trials, falls, trials that kicked, the median distance (m), the median
absolute direction error (deg), kicks more than 15 deg off line, and the median time to kick
(s) over the trials that kicked.

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
    """The trial lines of a fall_stages log (other lines are skipped)."""
    trials = []
    for line in path.read_text().splitlines():
        match = TRIAL.match(line)
        if match:
            time = match["time"]
            trials.append(
                Trial(
                    foot=match["foot"],
                    fell=match["fall"] != "none",
                    distance_m=float(match["distance"]),
                    direction_deg=float(match["direction"]),
                    time_s=None if time == "-" else float(time),
                )
            )
    return trials


def _median(values: list[float]) -> str:
    return f"{statistics.median(values):.2f}" if values else "-"


def summary(label: str, trials: list[Trial]) -> str:
    """One line of figures over ``trials``."""
    kicked = [t for t in trials if t.time_s is not None]
    errors = [abs(t.direction_deg) for t in kicked]
    return (
        f"{label}: trials {len(trials)} falls {sum(t.fell for t in trials)} kicked {len(kicked)}"
        f" distance_median_m {_median([t.distance_m for t in kicked])}"
        f" direction_error_median_deg {_median(errors)}"
        f" wide_over_{WIDE_DEG:.0f}deg {sum(e > WIDE_DEG for e in errors)}"
        f" time_median_s {_median([t.time_s for t in kicked if t.time_s is not None])}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", type=Path, nargs="+")
    for path in parser.parse_args().logs:
        trials = read_trials(path)
        for foot in sorted({t.foot for t in trials}):
            print(summary(f"{path.name} [{foot}]", [t for t in trials if t.foot == foot]))
        print(summary(f"{path.name} [all]", trials))


if __name__ == "__main__":
    main()
