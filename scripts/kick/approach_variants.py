"""``benchmarks/kick.py`` with basic_kick's approach or foot choice changed: experiments on
the approaches that never reach their kick (type 2 crept round its kicking spot for 12 s in
session 34, stepping sideways at the walk's 0.2 m/s floor with 10-20 deg foot spins, until the
20 s limit) and on the foot a long kick prefers.

Run: ``PYTHONPATH=. python scripts/kick/approach_variants.py [--overshoot TYPE=M ...]
[--min-speed V] [--creep-stop-s S] [--stop-before-leaving] -- --robot-type 2 --strengths
--basic-trials 20 --basic-distance 5.0 --layout-seed 2`` (after ``--``: benchmarks/kick.py's own
arguments). The variants patch the running process only; none of them is packaged (figures in
runs/kick_abort/README.md, session 34):

- ``--overshoot TYPE=M``: ``basic_kick.TYPE_WALK_OVERSHOOT_M`` for that type (how far beyond
  the kicking spot the walk is sent);
- ``--min-speed V``: the walk's slowest go-to speed (``GoToGains.min_speed``, 0.2 m/s);
- ``--creep-stop-s S``: once the coarse alignment (within the shuffle's reach) has held for S
  seconds of the approach without the walk arriving, the walk is sent to the pose of that
  moment (it stops on its own engine) and the settle measures and shuffles from there;
- ``--stop-before-leaving``: the walk inside skills steps out its stop before it tests whether
  it has left its target (``go_to_stop_before_leaving``, a copy of walk.yaml).
- ``--foot-credit TYPE=FOOT:M``: ``basic_kick.TYPE_LONG_KICK_FOOT_CREDIT_M`` for that type (the
  foot a long kick prefers within M metres of extra walking).
- ``--set module.NAME=value``: any constant of a ``behaviors`` module, as
  ``scripts/kick/sweep.py --set`` (the kick's own knobs, e.g. ``kick.BALANCE_RELEASE_S=0.3``).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path
from types import MappingProxyType

import yaml

import behaviors.basic_kick as basic_kick
import behaviors.walk as walk
from benchmarks import kick
from world.perception import CYCLE_SECONDS

sys.path.insert(0, str(Path(__file__).resolve().parent))
from sweep import apply


def overshoot(specs: list[str]) -> None:
    table = dict(basic_kick.TYPE_WALK_OVERSHOOT_M)
    for spec in specs:
        robot_type, metres = spec.split("=")
        table[int(robot_type)] = float(metres)
    basic_kick.TYPE_WALK_OVERSHOOT_M = MappingProxyType(table)


def foot_credit(specs: list[str]) -> None:
    table = dict(basic_kick.TYPE_LONG_KICK_FOOT_CREDIT_M)
    for spec in specs:
        robot_type, credit = spec.split("=")
        foot, metres = credit.split(":")
        table[int(robot_type)] = (foot, float(metres))
    basic_kick.TYPE_LONG_KICK_FOOT_CREDIT_M = MappingProxyType(table)


def min_speed(speed: float) -> None:
    original = walk.WalkSkill.__init__

    def init(self: walk.WalkSkill) -> None:
        original(self)
        self.gains = walk.GoToGains(min_speed=speed)

    walk.WalkSkill.__init__ = init  # type: ignore[method-assign]


def creep_stop(seconds: float) -> None:
    cycles = round(seconds / CYCLE_SECONDS)
    approach = basic_kick.BasicKickSkill._approach

    def patched(self, context, motion, target) -> None:
        stop = getattr(self, "_creep_stop", None)
        if stop is not None:
            if context.manager.execute_sub_behavior("walk", *stop):
                self._creep_stop, self._creep, self.phase = None, 0, "settle"
            return
        if self.phase == "approach" and context.world.ball_relative_ego is not None:
            aligned = self._alignment(context, motion, target).within_shuffle
            self._creep = getattr(self, "_creep", 0) + 1 if aligned else 0
            if self._creep >= cycles:
                pose = context.world.pose
                self._creep_stop = (pose.x, pose.y, pose.heading_deg)
                context.manager.execute_sub_behavior("walk", *self._creep_stop)
                return
        approach(self, context, motion, target)

    basic_kick.BasicKickSkill._approach = patched  # type: ignore[method-assign]


def stop_before_leaving() -> None:
    data = yaml.safe_load(walk.WALK_FILE.read_text())
    data["inside_skills"]["go_to_stop_before_leaving"] = True
    copy = Path(tempfile.mkdtemp()) / "walk.yaml"
    copy.write_text(yaml.safe_dump(data, sort_keys=False))
    walk.WALK_FILE = copy


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--overshoot", nargs="*", default=[], metavar="TYPE=M")
    parser.add_argument("--foot-credit", nargs="*", default=[], metavar="TYPE=FOOT:M")
    parser.add_argument("--min-speed", type=float)
    parser.add_argument("--creep-stop-s", type=float)
    parser.add_argument("--stop-before-leaving", action="store_true")
    parser.add_argument("--set", nargs="*", default=[], metavar="MODULE.NAME=VALUE")
    parser.add_argument("benchmark", nargs=argparse.REMAINDER, help="-- benchmarks/kick.py args")
    args = parser.parse_args()
    overshoot(args.overshoot)
    foot_credit(args.foot_credit)
    if args.min_speed is not None:
        min_speed(args.min_speed)
    if args.creep_stop_s is not None:
        creep_stop(args.creep_stop_s)
    if args.stop_before_leaving:
        stop_before_leaving()
    apply(args.set)
    print(f"# variants: {' '.join(sys.argv[1:])}", flush=True)
    rest = args.benchmark[1:] if args.benchmark[:1] == ["--"] else args.benchmark
    sys.argv = ["benchmarks/kick.py", *rest]
    kick.main()


if __name__ == "__main__":
    main()
