"""Sum the per-seed lines of several ``screen_sequences.py`` logs (``screen_fanout.sh``).

Prints every variant's trials up over all seeds found, and its mean per-seed difference from
the base with the standard error of that mean: the paired comparison that says whether a
variant's gain is more than the spread of its falls.

Run: ``python scripts/get_up/sum_screens.py OUT_DIR [--names NAME ...]``.
"""

from __future__ import annotations

import argparse
import math
import re
import statistics
from pathlib import Path

SEED_LINE = re.compile(r"^seed (-?\d+) \((\d+) trials\):((?:\s+\d+)+)\s*$")


def read_rows(folder: Path) -> list[tuple[int, list[int]]]:
    """(trials, ups per variant) for every completed seed in the folder's ``*.log`` files."""
    rows = []
    for log in sorted(folder.glob("*.log")):
        for line in log.read_text().splitlines():
            match = SEED_LINE.match(line)
            if match:
                rows.append((int(match.group(2)), [int(v) for v in match.group(3).split()]))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--names", nargs="*", default=[], help="variant names after the base")
    args = parser.parse_args()
    rows = read_rows(args.folder)
    if not rows:
        raise SystemExit(f"no 'seed S (N trials): ...' lines in {args.folder}/*.log")
    trials = sum(n for n, _ in rows)
    width = min(len(ups) for _, ups in rows)
    names = ["base", *args.names] + [f"variant {i}" for i in range(len(args.names) + 1, width)]
    print(f"{len(rows)} seeds, {trials} trials per variant")
    for index in range(width):
        up = sum(ups[index] for _, ups in rows)
        line = f"{names[index]}: {up} up ({up / trials:.3f})"
        if index:
            diffs = [ups[index] - ups[0] for _, ups in rows]
            error = statistics.stdev(diffs) / math.sqrt(len(diffs)) if len(diffs) > 1 else 0.0
            line += f", per seed {statistics.mean(diffs):+.2f} +- {error:.2f} against the base"
        print(line)


if __name__ == "__main__":
    main()
