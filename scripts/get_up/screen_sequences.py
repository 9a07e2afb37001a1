"""Screen get-up sequence variants on the benchmark's own trials, with its exact outcomes.

Why: a change to one type's keyframes changes only that type's trials, and the benchmark's
trials are cheap one by one (about 0.25 s), but two thirds of each is the fall. Here each
trial falls once (:func:`benchmarks.get_up.fall`, the benchmark's seeds from
:func:`benchmarks.get_up.trial_specs`); then for every variant the process forks and the child
plays the get-up (:func:`benchmarks.get_up.play_get_up`) with the variant's sequences. A fork
copies the simulator bit for bit (contact caches included, unlike ``Session.save_state``), so
the ``base`` variant repeats ``benchmarks/get_up.py``'s outcomes trial for trial (checked with
``--check``) and every variant's figures are what the benchmark would print with its sequences
packaged. Still a screen: a kept variant is written into ``behaviors/data/get_up.yaml`` and
measured with the benchmark itself.

A variant is ``base`` or edits separated by ``;``:

- ``NEW=BASE``: sequence ``NEW`` becomes a copy of the raw entry ``BASE``
  (``get_up_back_type3=get_up_back``);
- ``SEQ:FRAME:KEY=VALUE,...``: in frame FRAME of SEQ set a joint target (a left joint or head
  joint name, ``lj3`` short for ``llj3``; the right twin is set to the mirror value) or
  ``duration`` / ``hold`` / ``track`` / ``pose``; ``-KEY`` drops a joint (and its twin),
  ``!KEY=VALUE`` sets the joint alone (a one-sided motion such as a roll);
- ``SEQ:dup:FRAME``: insert a copy of frame FRAME after it; ``SEQ:del:FRAME``: delete it;
- ``balance=FILE``: the rise's balance corrections from FILE (the format of
  ``behaviors/data/get_up_balance.yaml``) instead of the packaged ones;
- ``knob:NAME=VALUE``: a module constant of ``behaviors/get_up.py`` set in the forked child
  (``knob:RETRY_AT_ONCE_PITCH_DEG=80``, ``None`` for None, ``TYPE:VALUE/TYPE:VALUE`` for a
  per-robot-type mapping), so decision thresholds are screened on the same falls.

``--time-limit`` plays every get-up with another limit than the benchmark's 4 s (how many
trials a variant stands within 5 s says whether it only moves the late ones).

``--save-trials FILE`` writes the trials played (those left after ``--lying-on``) and
``--trials-file FILE`` plays only the listed ones, grouped by the benchmark seed each belongs
to: the falls that end elsewhere are not simulated again (the 114 front trials of seeds 0-5000
are 114 falls instead of 700; session 14 screened its front variants on such lists).

Session 12, shorter back get-ups so that late retries fit into the 4 s (every back sequence,
``--types 0,1,2,3,4 --seed 0 --seed 500``, base 181 of 200): squat frame 0.3 s (was 0.4) 176,
rise 0.4 s (was 0.5) 181 with no trial changed (the early stand check already ends the rise
when the legs are near the stand), both 176. Type 3 (``--types 3``, seeds 0 / 500 / 1000, base
16 / 15 / 15): a ``roll_over_back_type3`` sequence (its back get-up's first two frames, sit-up
0.3-0.8 s, hold 0-0.2 s) played before the retry after a sit-up that rose and tipped back, to
reach the shoulders-over posture from which the retry rocks up: 13 / 13 / 12 for every timing
(a robot lying flat sits up in it instead, and the rock-up saves only 0.2 s of a 4.7-5.2 s
get-up).

Run::

    nice -n 5 .venv/bin/python scripts/get_up/screen_sequences.py --types 3 --seed 0 \\
        --seed 500 --variant base --variant "get_up_back_type3:1:lj4=-40"
"""

from __future__ import annotations

import argparse
import copy
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import behaviors.get_up as get_up
from behaviors.get_up import GetUpSkill, RiseBalance, load_balances
from behaviors.keyframes import KeyframeSequence, default_sequences, parse_sequences
from behaviors.mirror import MIRROR_TABLE
from benchmarks.get_up import TrialResult, fall, play_get_up, run_trial, trial_specs
from learning.falls import FALL_DIRECTIONS
from learning.get_up_search import raw_entries
from scripts.get_up.forking import forked_call
from scripts.get_up.sweep_knobs import parse_variant

_FRAME_FIELDS = {"duration", "hold"}
_BALANCE_EDIT = "balance="
_KNOB_EDIT = "knob:"
_TEXT_FIELDS = {"track", "pose"}


def _joint(key: str) -> str:
    """``lj3`` -> ``llj3``; full perceptor names pass through (checked)."""
    name = key if key in MIRROR_TABLE else "l" + key
    if name not in MIRROR_TABLE:
        raise SystemExit(f"unknown joint {key!r}")
    return name


def _set_frame(frame: dict[str, Any], assignments: str) -> None:
    joints = frame.setdefault("joints", {})
    for item in assignments.split(","):
        if item.startswith("-"):
            name = _joint(item[1:])
            joints.pop(name, None)
            joints.pop(MIRROR_TABLE[name].twin, None)
            continue
        key, value = item.split("=")
        if key.startswith("!"):  # this joint alone, not its twin (one-sided motions)
            joints[_joint(key[1:])] = float(value)
        elif key in _FRAME_FIELDS:
            frame[key] = float(value)
        elif key in _TEXT_FIELDS:
            frame[key] = value
        else:
            name = _joint(key)
            twin = MIRROR_TABLE[name]
            joints[name] = float(value)
            if twin.twin != name:
                joints[twin.twin] = twin.sign * float(value) + 0.0


def apply_variant(entries: dict[str, Any], variant: str) -> dict[str, Any]:
    """A copy of the raw get-up entries with the variant's edits (module docstring)."""
    out = copy.deepcopy(entries)
    if variant == "base":
        return out
    for edit in filter(None, (e.strip() for e in variant.split(";"))):
        if edit.startswith((_BALANCE_EDIT, _KNOB_EDIT)):
            continue
        if ":" not in edit:
            new, base = edit.split("=")
            out[new] = copy.deepcopy(out[base])
            continue
        name, where, what = edit.split(":", 2)
        frames = out[name]["frames"]
        if where == "dup":
            frames.insert(int(what) + 1, copy.deepcopy(frames[int(what)]))
        elif where == "del":
            del frames[int(what)]
        else:
            _set_frame(frames[int(where)], what)
    return out


def variant_sequences(variant: str) -> Mapping[str, KeyframeSequence]:
    """The packaged sequences with the variant's edited entries parsed in their place."""
    if variant == "base":
        return default_sequences()
    sequences = dict(default_sequences())
    sequences.update(parse_sequences(apply_variant(raw_entries(), variant), "variant"))
    return sequences


def variant_balances(variant: str) -> Mapping[str, RiseBalance] | None:
    """The variant's balance corrections (its ``balance=FILE`` edit), None: the packaged."""
    for edit in (e.strip() for e in variant.split(";")):
        if edit.startswith(_BALANCE_EDIT):
            return load_balances(Path(edit[len(_BALANCE_EDIT) :]))
    return None


def variant_knobs(variant: str) -> dict[str, object]:
    """The variant's ``knob:NAME=VALUE`` edits as module constants of behaviors.get_up."""
    knobs: dict[str, object] = {}
    for edit in (e.strip() for e in variant.split(";")):
        if edit.startswith(_KNOB_EDIT):
            knobs.update(parse_variant(edit[len(_KNOB_EDIT) :]))
    return knobs


def _play_forked(
    driver: Any,
    spec: tuple[int, str, int],
    lying_on: str | None,
    sequences: Any,
    balances: Mapping[str, RiseBalance] | None = None,
    knobs: Mapping[str, object] | None = None,
    time_limit: float = 4.0,
) -> TrialResult:
    """The get-up from this fall in a forked child (the parent's simulator stays as it was)."""

    def play() -> TrialResult:
        for name, value in (knobs or {}).items():
            setattr(get_up, name, value)
        skill = driver.behavior.skill("get_up")
        assert isinstance(skill, GetUpSkill)
        skill.sequences = sequences
        return play_get_up(driver, *spec, lying_on, time_limit, balances=balances)

    return forked_call(play)


def read_trials(path: Path) -> list[tuple[int, str, int]]:
    """Trials ``TYPE:DIRECTION:SEED``, one per line (``--save-trials``' format)."""
    out = []
    for line in path.read_text().split():
        robot_type, direction, seed = line.split(":")
        out.append((int(robot_type), direction, int(seed)))
    return out


def benchmark_seed(spec: tuple[int, str, int]) -> int:
    """The ``--seed`` of the benchmark run a trial belongs to (a multiple of 500: trial k of
    type T has seed ``S + 1000 * T + k``, k < 500)."""
    return (spec[2] - 1000 * spec[0]) // 500 * 500


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, action="append")
    parser.add_argument("--types", default="3")
    parser.add_argument("--trials-per-type", type=int, default=20)
    parser.add_argument("--variant", action="append")
    parser.add_argument("--directions", default=",".join(FALL_DIRECTIONS))
    parser.add_argument(
        "--lying-on", help="play only trials whose fall ends on these sides (front,back,...)"
    )
    parser.add_argument(
        "--check", action="store_true", help="also run the base through run_trial and compare"
    )
    parser.add_argument("--time-limit", type=float, default=4.0)
    parser.add_argument(
        "--trials-file",
        type=Path,
        help="play only the trials listed in this file (TYPE:DIRECTION:SEED per line, as "
        "--save-trials writes them) instead of --seed: the falls that end elsewhere are skipped "
        "without being simulated",
    )
    parser.add_argument(
        "--save-trials", type=Path, help="write the trials played (after --lying-on) to this file"
    )
    parser.add_argument("--show-changes", action="store_true", help="trials that differ from base")
    parser.add_argument(
        "--show-failures", action="store_true", help="the trials every variant leaves down"
    )
    args = parser.parse_args()
    types = [int(t) for t in args.types.split(",")]
    variants = args.variant or ["base"]
    all_sequences = {v: variant_sequences(v) for v in variants}
    all_balances = {v: variant_balances(v) for v in variants}
    all_knobs = {v: variant_knobs(v) for v in variants}
    base_sequences = default_sequences()
    totals = dict.fromkeys(variants, 0)
    changes: dict[str, list[str]] = {v: [] for v in variants}
    failures: dict[str, list[str]] = {v: [] for v in variants}
    listed = None if args.trials_file is None else read_trials(args.trials_file)
    saved: list[str] = []
    seeds = args.seed or [0]
    if listed is not None:
        seeds = sorted({benchmark_seed(spec) for spec in listed})
    for seed in seeds:
        ups = dict.fromkeys(variants, 0)
        played = 0
        specs = (
            [spec for spec in listed if benchmark_seed(spec) == seed]
            if listed is not None
            else trial_specs(types, args.trials_per_type, seed, args.directions.split(","))
        )
        for spec in specs:
            session, driver, lying_on = fall(*spec)
            try:
                if args.lying_on and lying_on not in args.lying_on.split(","):
                    continue
                played += 1
                saved.append(f"{spec[0]}:{spec[1]}:{spec[2]}")
                base = _play_forked(
                    driver, spec, lying_on, base_sequences, time_limit=args.time_limit
                ).succeeded
                if args.check and run_trial(*spec, args.time_limit).succeeded != base:
                    print(f"MISMATCH with run_trial: {spec}", flush=True)
                for variant in variants:
                    up = (
                        base
                        if variant == "base"
                        else _play_forked(
                            driver,
                            spec,
                            lying_on,
                            all_sequences[variant],
                            all_balances[variant],
                            all_knobs[variant],
                            args.time_limit,
                        ).succeeded
                    )
                    ups[variant] += up
                    if not up:
                        failures[variant].append(f"{spec[0]}:{spec[1]}:{spec[2]}:{lying_on}")
                    if up != base:
                        changes[variant].append(
                            f"{'+' if up else '-'}{spec[0]}:{spec[1]}:{spec[2]}"
                        )
            finally:
                session.close()
        for variant in variants:
            totals[variant] += ups[variant]
        print(
            f"seed {seed} ({played} trials): " + "  ".join(f"{ups[v]}" for v in variants),
            flush=True,
        )
    if args.save_trials is not None:
        args.save_trials.write_text("".join(f"{trial}\n" for trial in saved))
    for variant in variants:
        line = f"{totals[variant]:4d}  {variant}"
        if args.show_changes and variant != "base":
            line += "  " + " ".join(changes[variant])
        if args.show_failures:
            line += "\n      down: " + " ".join(failures[variant])
        print(line)


if __name__ == "__main__":
    main()
