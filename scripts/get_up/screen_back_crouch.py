"""Screen back-crouch variants of ``get_up_back`` on the benchmark's saved falls.

Why: types 0 and 2 tip backwards in the back squat with hip, knee and ankle pitch at their
limits, so the crouch itself (arms, ankle, hip targets of the crouch and squat frames) must put
the centre of mass further over the feet. Each variant edits the raw ``get_up_back`` entry and
plays every saved fall of the chosen types (``learning.get_up_eval``: the benchmark's falls,
replayed from saved states; a screen only, the benchmark decides).

Run::

    nice -n 5 .venv/bin/python scripts/get_up/screen_back_crouch.py --seed 0 --types 0,2 \\
        --variant base --variant arms90
"""

from __future__ import annotations

import argparse
import copy
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from behaviors.get_up import GetUpSkill
from learning.get_up_eval import close, evaluate, saved_falls
from learning.get_up_search import candidate_sequences, raw_entries

Edit = Callable[[dict[str, Any]], None]
CROUCH, SQUAT = 3, 4


def _set(frame: int, **joints: float) -> Edit:
    """An edit that sets mirrored leg/arm pitch targets (lj3, lj4, lj5, aj1) of one frame."""

    def edit(entry: dict[str, Any]) -> None:
        target = entry["frames"][frame].setdefault("joints", {})
        for key, value in joints.items():
            if key == "duration":
                entry["frames"][frame]["duration"] = value
                continue
            target["l" + key] = value
            target["r" + key] = value

    return edit


def _both(*edits: Edit) -> Edit:
    def edit(entry: dict[str, Any]) -> None:
        for e in edits:
            e(entry)

    return edit


_SQUAT = {"lj1": 0, "lj2": 0, "lj3": 100, "lj4": -130, "lj5": 60, "aj1": -90}


def _squat(**changes: float) -> Edit:
    joints = dict(_SQUAT, **changes)
    return _set(SQUAT, **joints)


VARIANTS: dict[str, Edit] = {
    "base": lambda entry: None,
    "crouch_arms90": _set(CROUCH, aj1=-90),
    "crouch_arms60": _set(CROUCH, aj1=-60),
    "squat_ankle75": _squat(lj5=75),
    "squat_ankle70": _squat(lj5=70),
    "crouch_hip90": _set(CROUCH, lj3=90),
    "crouch_hip100": _set(CROUCH, lj3=100),
    "arms90_ankle75": _both(_set(CROUCH, aj1=-90), _squat(lj5=75)),
    "hip90_ankle75": _both(_set(CROUCH, lj3=90), _squat(lj5=75)),
    "squat_arms60": _squat(aj1=-60),
    "crouch_hip70": _set(CROUCH, lj3=70),
    "crouch_hip65": _set(CROUCH, lj3=65),
    "crouch_ankle65": _set(CROUCH, lj5=65),
    "crouch_arms105": _set(CROUCH, aj1=-105),
    "squat_ankle55": _squat(lj5=55),
    "squat_hip95": _squat(lj3=95),
    "crouch_slow": _set(CROUCH, duration=0.5),
    "arms90_hip70": _set(CROUCH, aj1=-90, lj3=70),
    "arms90_squat_ankle55": _both(_set(CROUCH, aj1=-90), _squat(lj5=55)),
    "arms90_squat_hip95": _both(_set(CROUCH, aj1=-90), _squat(lj3=95)),
    "crouch_hip60": _set(CROUCH, lj3=60),
    "crouch_hip55": _set(CROUCH, lj3=55),
    "arms90_hip65": _set(CROUCH, aj1=-90, lj3=65),
    "arms90_hip60": _set(CROUCH, aj1=-90, lj3=60),
    "hip65_ankle70": _set(CROUCH, lj3=65, lj5=70),
}


def candidate(name: str, variant: str) -> Callable[[GetUpSkill], None]:
    entry = copy.deepcopy(raw_entries()[name])
    VARIANTS[variant](entry)
    sequences = candidate_sequences(name, entry)

    def apply(skill: GetUpSkill) -> None:
        skill.sequences = sequences

    return apply


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, action="append")
    parser.add_argument("--types", default="0,2")
    parser.add_argument("--trials-per-type", type=int, default=20)
    parser.add_argument("--sequence", default="get_up_back")
    parser.add_argument("--variant", action="append", choices=sorted(VARIANTS))
    args = parser.parse_args()
    types = [int(t) for t in args.types.split(",")]
    totals: dict[str, int] = {}
    for seed in args.seed or [0]:
        falls = saved_falls(seed, types, args.trials_per_type)
        for variant in args.variant or ["base"]:
            results = evaluate(falls, candidate(args.sequence, variant))
            up = [r.succeeded for r in results]
            per_type = {t: sum(u for u, f in zip(up, falls) if f.robot_type == t) for t in types}
            totals[variant] = totals.get(variant, 0) + sum(up)
            print(f"seed {seed} {variant}: {sum(up)}/{len(up)} {per_type}", flush=True)
        close(falls)
    print("totals", totals)


if __name__ == "__main__":
    main()
