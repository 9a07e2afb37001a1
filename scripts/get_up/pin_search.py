"""Find falls that pin one get-up detail: the packaged skill stands, the variant without that
detail stays down.

Why: ``tests/test_get_up.py`` keeps each tuned detail of the get-up (a type's own crouch, the
front abort's pitch prediction, a knee fold, a roll's arm swing) alive with one fall on which
the detail makes the difference. Such a fall is a single trajectory; a change of physics (the
contact model, session 20) flips it, and the test needs a new fall that shows the same thing.
This script replays falls of one type and fall direction, keeps those that end lying on the
test's side and that the packaged skill brings up within 4 s, and plays the variant on them
until ``--want`` falls stay down with it. Each case is named after its test; the variant is
the test's own (built from the test module's helpers).

Run::

    nice -n 5 .venv/bin/python scripts/get_up/pin_search.py --case front_fold_2 \\
        --seeds 0:2000:50 [--want 2]
"""

from __future__ import annotations

import argparse
import contextlib
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import behaviors.get_up as get_up_module
import tests.test_get_up as pins
from benchmarks.get_up import run_trial

Variant = Callable[[pytest.MonkeyPatch], None]


@dataclass(frozen=True)
class Case:
    robot_type: int
    direction: str
    lying_on: str
    #: applied for the packaged run and the variant alike
    base: Variant | None
    variant: Variant
    #: a physics variant of benchmarks/physics.py both runs play under
    physics: str | None = None


def _without(name: str) -> Variant:
    return lambda mp: pins._package_without(mp, name)


def _set(attribute: str, value: object) -> Variant:
    return lambda mp: mp.setattr(get_up_module, attribute, value)


def _both(*variants: Variant) -> Variant:
    def apply(mp: pytest.MonkeyPatch) -> None:
        for variant in variants:
            variant(mp)

    return apply


def _front_fold(robot_type: int) -> Variant:
    return _both(_set("EARLY_STAND_DEG", None), lambda mp: pins._front_fold(mp, robot_type, -116.7))


CASES: dict[str, Case] = {
    "type0_back_crouch": Case(0, "back", "back", None, _without("get_up_back_type0")),
    "front_abort_horizon": Case(2, "front", "front", None, _set("FRONT_ABORT_HORIZON_S", 0.0)),
    "type3_roll": Case(3, "right", "right", None, _without("roll_left_to_back_type3")),
    **{f"front_fold_{t}": Case(t, "front", "front", None, _front_fold(t)) for t in (1, 2, 3, 4)},
    "late_retry": Case(
        3,
        "front",
        "front",
        _without("get_up_front_retry_type3"),
        _set("EARLY_STAND_DEG", None),
    ),
    "type3_front_retry": Case(3, "front", "front", None, _without("get_up_front_retry_type3")),
    "type1_back_noself": Case(
        1, "back", "back", None, pins._type1_back_before_session11, physics="noself"
    ),
    **{
        f"roll_upper_arm_{t}": Case(
            t, "front", "right", None, lambda mp, t=t: pins._roll_upper_arm(mp, t, -120.0)
        )
        for t in (3, 4)
    },
}


@contextlib.contextmanager
def _played(case: Case, variant: bool) -> Iterator[None]:
    with pytest.MonkeyPatch.context() as mp, contextlib.ExitStack() as stack:
        if case.physics:
            from benchmarks.physics import VARIANTS

            stack.enter_context(VARIANTS[case.physics]())
        if case.base:
            case.base(mp)
        if variant:
            case.variant(mp)
        yield


def search(case: Case, seeds: range, want: int) -> list[int]:
    """Seeds whose fall the packaged skill brings up and the variant does not."""
    found = []
    for seed in seeds:
        with _played(case, variant=False):
            result = run_trial(case.robot_type, case.direction, seed)
        if result.lying_on != case.lying_on or not result.succeeded:
            continue
        with _played(case, variant=True):
            pinned = not run_trial(case.robot_type, case.direction, seed).succeeded
        print(f"seed {seed}: packaged {result.time_s:.2f} s, variant {'down' if pinned else 'up'}")
        if pinned:
            found.append(seed)
            if len(found) >= want:
                break
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", required=True, choices=sorted(CASES))
    parser.add_argument("--seeds", default="0:1000:1", help="start:stop:step added to 1000*type")
    parser.add_argument("--want", type=int, default=1)
    args = parser.parse_args()
    case = CASES[args.case]
    start, stop, step = (int(x) for x in args.seeds.split(":"))
    offset = 1000 * case.robot_type
    found = search(case, range(offset + start, offset + stop, step), args.want)
    print(f"{args.case}: {found}")


if __name__ == "__main__":
    main()
