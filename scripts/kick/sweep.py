"""Basic-kick figures over several layout seeds with kick/basic_kick module constants changed
for this process only (an experiment runner; the packaged values stay as they are).

Run: ``PYTHONPATH=. nice -n 5 python scripts/kick/sweep.py --layout-seeds 0 1 2
--set kick.TOUCHDOWN_FORCE_N=20 [--kicks FILE] [--distance 3] [--verbose]``. Prints the figures of
``benchmarks.kick.basic_kick_figures`` per seed and the falls / misses summed over the seeds."""

from __future__ import annotations

import argparse
import importlib
from pathlib import Path
from types import ModuleType

from benchmarks.kick import FALL_STAGES, SkillSettings, basic_kick_figures


def parse_change(change: str) -> tuple[ModuleType, str, object]:
    """``module.NAME=value`` (module under ``behaviors``) -> (module, NAME, value), the value of
    the constant's own type: a bool from ``1``/``true``, else a float converted to it."""
    target, value = change.split("=")
    module_name, attribute = target.rsplit(".", 1)
    module = importlib.import_module(f"behaviors.{module_name}")
    old = getattr(module, attribute)  # unknown names fail here
    typed = value.lower() in ("1", "true") if isinstance(old, bool) else type(old)(float(value))
    return module, attribute, typed


def apply(changes: list[str]) -> None:
    """Set each ``module.NAME=value`` (:func:`parse_change`) for the rest of this process."""
    for change in changes:
        setattr(*parse_change(change))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--layout-seeds", type=int, nargs="+", default=[0, 1, 2])
    parser.add_argument("--set", nargs="*", default=[])
    parser.add_argument("--kicks", type=Path)
    parser.add_argument("--distance", default="3")
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument(
        "--verbose", action="store_true", help="print every trial (for scripts/kick/per_foot.py)"
    )
    args = parser.parse_args()
    apply(args.set)
    settings = SkillSettings.with_kicks(args.kicks)
    asked = args.distance if args.distance == "long" else float(args.distance)
    falls = misses = 0
    for seed in args.layout_seeds:
        f = basic_kick_figures(args.trials, 0, asked, seed, args.verbose, settings=settings)
        falls += int(f["basic_kick_falls"])
        misses += int(f["basic_kick_misses"])
        stages = " ".join(f"{stage} {f[f'basic_kick_falls_{stage}']:.0f}" for stage in FALL_STAGES)
        print(
            f"seed {seed}: median {f['basic_kick_distance_m']:.2f} m, dir "
            f"{f['basic_kick_direction_error_deg']:.1f} deg, time {f['basic_kick_time_s']:.2f} s,"
            f" falls {f['basic_kick_falls']:.0f} ({stages}), misses {f['basic_kick_misses']:.0f}",
            flush=True,
        )
    print(f"total falls {falls}, misses {misses} ({' '.join(args.set)} {args.kicks or ''})")


if __name__ == "__main__":
    main()
