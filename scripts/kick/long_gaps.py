"""Stand kicks of each foot's long kick with the ball lined up further ahead of the toe: how far
it goes, per foot and ball gap.

Why: under the bounce contacts (session 20) the long kicks go 4-6.5 m at full strength, and
their weaker swings go no shorter (4.3-5.1 m from a stand, with falls). A ball met later in the
swing, further ahead of the toe, meets a foot that has passed the bottom of its arc; if that
shortens the kick smoothly without more falls, ``gap_distances`` (``behaviors/kick.py``)
calibrates the long kick by ball gap for the distances between the short kick's ~3 m and the
long kick's full reach.

Run::

    nice -n 5 .venv/bin/python scripts/kick/long_gaps.py --extra 0 0.03 0.06 0.09 --starts 6
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from behaviors.kick import FEET, KICK_LEFT, KICK_RIGHT, kick_motion
from benchmarks.kick import STAND_KICK_WAITS, run_trial


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--extra", type=float, nargs="+", default=[0.0, 0.03, 0.06, 0.09])
    parser.add_argument("--starts", type=int, default=6)
    parser.add_argument("--shuffle", action="store_true", help="start after a small shuffle")
    args = parser.parse_args()
    long = {foot: kick_motion(0, None, foot, aligned=True, long=True) for foot in FEET}
    for extra in args.extra:
        for foot in FEET:
            motion = dataclasses.replace(long[foot], ball_gap_m=long[foot].ball_gap_m + extra)
            motions = {KICK_LEFT: motion, KICK_RIGHT: motion}
            results = [
                run_trial(
                    foot,
                    1.0,
                    seed=seed,
                    motions=motions,
                    wait_cycles=STAND_KICK_WAITS[seed % len(STAND_KICK_WAITS)],
                    shuffle_m=(0.03, 0.0) if args.shuffle else None,
                )
                for seed in range(args.starts)
            ]
            distances = sorted(round(r.distance_m, 2) for r in results)
            falls = sum(r.fell for r in results)
            median = statistics.median(distances)
            print(
                f"gap={motion.ball_gap_m:.3f} {foot}: median {median:.2f} m, falls {falls} of "
                f"{len(results)}, {distances}",
                flush=True,
            )


if __name__ == "__main__":
    main()
