"""Per-foot figures from the trial lines that ``benchmarks/kick.py`` prints for basic kicks
(``# trial k: BasicKickResult(...)``): kicks, median distance, falls and misses per foot.

Run: ``python scripts/kick/per_foot.py [--asked D] LOG [LOG ...]``; ``--asked D`` also prints
the median miss ``|distance - D|``. Why: the left and right kicks after the
approach are different motions with different distances and falls, and the benchmark's
figures mix them."""

from __future__ import annotations

import re
import statistics
import sys

PATTERN = re.compile(
    r"distance_m=([\d.]+).*?time_to_kick_s=([\d.]+|None), foot=(?:'(\w+)'|None).*?"
    r"fall_stage=(?:'(\w+)'|None)"
)


def _median_miss(distances: list[float], asked: float | None) -> str:
    """``, median miss X m`` (|distance - asked|), or nothing without ``asked`` or kicks."""
    if asked is None or not distances:
        return ""
    return f", median miss {statistics.median(abs(d - asked) for d in distances):.2f} m"


def main() -> None:
    args = sys.argv[1:]
    asked = None
    if args[:1] == ["--asked"]:
        asked, args = float(args[1]), args[2:]
    rows: dict[str, list[tuple[float, bool, str | None]]] = {"left": [], "right": [], "-": []}
    for path in args:
        with open(path) as log:
            for line in log:
                if not line.startswith("# trial"):
                    continue
                match = PATTERN.search(line)
                if match is None:
                    continue
                distance, time, foot, stage = match.groups()
                rows[foot or "-"].append((float(distance), time != "None", stage))
    for foot, trials in rows.items():
        kicked = [d for d, k, _ in trials if k]
        falls = sum(stage is not None for *_, stage in trials)
        median = statistics.median(kicked) if kicked else float("nan")
        over3 = sum(d >= 3.0 for d in kicked)
        print(
            f"{foot:5s}: trials {len(trials)}, kicked {len(kicked)}, median {median:.2f} m, "
            f">=3 m {over3}, falls {falls}{_median_miss(kicked, asked)}"
        )
    every = [d for trials in rows.values() for d, k, _ in trials if k]
    if every:
        miss = _median_miss(every, asked)
        print(f"all  : median {statistics.median(every):.2f} m over {len(every)} kicks{miss}")


if __name__ == "__main__":
    main()
