"""Evolution-strategy search over one get-up sequence's frames and a rise balance.

Why: hand screens of single knobs (``screen_sequences.py``) move a type's back get-up by a
trial or two either way, and the coordinate search (``learning/get_up_search.py``) over 12
falls fitted its bank and not fresh falls. This searches many parameters at once with a
separable natural evolution strategy (SNES: a mean and a spread per parameter, moved by the
rank-weighted samples) on a larger bank of falls, every candidate played on the same falls
(common random numbers: the falls are made once and each play is a fork of the fallen
simulator, so a candidate's score is exactly what the benchmark's get-up would do from there).

Parameters: the ``--joints`` targets (left joints; the right twins follow by mirroring) and the
durations of the ``--frames`` of ``--sequence`` (default: the sit-up, fold, crouch and squat of
a back get-up) and a :class:`behaviors.get_up.RiseBalance` from ``--balance-from`` (setpoint,
hip and ankle gains; 0 gains: off; -1: none). Score of a candidate: falls standing within 4 s
plus a quarter of those that stood with their first attempt and half the first attempt's peak
closeness (torso height times uprightness: a signal where candidates fail the same falls).

Every generation prints the mean's score and writes the mean to ``--out`` (JSON: a screen
variant string for ``screen_sequences.py`` and the balance as YAML text), so a run can be
validated on the benchmark's own trials at any time::

    nice -n 5 .venv/bin/python scripts/get_up/es_search.py --type 3 \\
        --sequence get_up_back_type3 --falls 40 --seed 20000 --budget-s 2400 --out /tmp/es3.json
    .venv/bin/python scripts/get_up/es_search.py --show /tmp/es3.json   # the variant to screen
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from behaviors.get_up import RISE_BALANCE, GetUpSkill, RiseBalance
from behaviors.keyframes import KeyframeSequence
from behaviors.poses import default_poses
from benchmarks.get_up import TrialResult, fall, play_get_up
from learning.falls import FALL_DIRECTIONS
from learning.get_up_search import closeness, raw_entries
from learning.snes import utilities
from scripts.get_up.forking import forked_map
from scripts.get_up.screen_sequences import variant_sequences
from world.nao_model import robot_spec

#: Weights of a fall's stood, stood-at-first-attempt and first-attempt peak closeness: the
#: closeness separates candidates that fail the same falls (without it whole generations tied).
SCORE_WEIGHTS = np.array([1.0, 0.25, 0.5])


@dataclass(frozen=True)
class Dimension:
    """One searched number: a frame field (``frame`` >= 0: ``key`` is a left joint or
    ``duration``) or a balance field (``frame`` -1: ``setpoint``, ``hip``, ``ankle``)."""

    frame: int
    key: str
    start: float
    spread: float
    low: float
    high: float


def frame_dimensions(
    entry: Mapping[str, Any],
    frames: Sequence[int],
    robot_type: int,
    joints: Sequence[str] = ("llj3", "llj4", "llj5", "laj1"),
) -> list[Dimension]:
    """``joints`` (left ones: hip, knee and ankle pitch and shoulder pitch by default) and the
    duration of each of ``frames``, starting from the raw entry's values (a frame's pose
    fills what its joints leave out)."""
    poses = default_poses()
    limits = {j.perceptor: (j.min_deg, j.max_deg) for j in robot_spec(robot_type).joints}
    out = []
    for index in frames:
        frame = entry["frames"][index]
        targets = dict(poses[frame["pose"]].joints) if "pose" in frame else {}
        targets.update(frame.get("joints", {}))
        for key in joints:
            low, high = limits[key]
            out.append(Dimension(index, key, float(targets.get(key, 0.0)), 2.0, low, high))
        out.append(Dimension(index, "duration", float(frame["duration"]), 0.015, 0.1, 0.8))
    return out


BALANCE_DIMENSIONS = (
    Dimension(-1, "setpoint", -3.0, 2.0, -20.0, 10.0),
    Dimension(-1, "hip", 0.0, 0.5, -4.0, 8.0),
    Dimension(-1, "ankle", 0.0, 0.5, -4.0, 8.0),
)


def candidate_variant(sequence: str, dims: Sequence[Dimension], values: np.ndarray) -> str:
    """The frame values as a ``screen_sequences.py`` variant string."""
    edits: dict[int, list[str]] = {}
    for dim, value in zip(dims, values):
        if dim.frame < 0:
            continue
        key = dim.key[1:] if dim.key.startswith("l") else dim.key
        edits.setdefault(dim.frame, []).append(f"{key}={value:.2f}")
    return ";".join(f"{sequence}:{f}:{','.join(items)}" for f, items in sorted(edits.items()))


def candidate_balance(
    dims: Sequence[Dimension], values: np.ndarray, from_frame: int
) -> RiseBalance | None:
    """The balance part of a candidate (None when both gains are near zero)."""
    named = {d.key: float(v) for d, v in zip(dims, values) if d.frame < 0}
    if not named or (abs(named["hip"]) < 0.05 and abs(named["ankle"]) < 0.05):
        return None
    gains = {
        "llj3": named["hip"],
        "rlj3": named["hip"],
        "llj5": named["ankle"],
        "rlj5": named["ankle"],
    }
    return RiseBalance(
        from_frame=from_frame,
        setpoint_deg=named["setpoint"],
        gains=MappingProxyType(gains),
        max_offset_deg=40.0,
        horizon_s=0.1,
    )


def balance_yaml(sequence: str, balance: RiseBalance | None) -> str:
    """The packaged balances plus the candidate's, in ``get_up_balance.yaml``'s format."""
    entries: dict[str, Any] = {}
    for name, b in {**RISE_BALANCE, **({sequence: balance} if balance else {})}.items():
        entries[name] = {
            "description": "es_search candidate" if name == sequence else "packaged",
            "from_frame": b.from_frame,
            "setpoint_deg": b.setpoint_deg,
            "gains": dict(b.gains),
            "max_offset_deg": b.max_offset_deg,
            "horizon_s": b.horizon_s,
        }
    return yaml.safe_dump(entries, sort_keys=False)


@dataclass
class Bank:
    """Fallen robots kept alive in this process, each played by forked children."""

    falls: list[tuple[Any, Any, tuple[int, str, int], str | None]]

    @classmethod
    def make(cls, robot_type: int, count: int, seed: int, lying_on: set[str]) -> Bank:
        falls = []
        k = 0
        while len(falls) < count:
            spec = (robot_type, FALL_DIRECTIONS[k % len(FALL_DIRECTIONS)], seed + k)
            k += 1
            session, driver, side = fall(*spec)
            if side in lying_on:
                falls.append((session, driver, spec, side))
            else:
                session.close()
        return cls(falls)


def play_one(
    driver: Any,
    spec: tuple[int, str, int],
    side: str | None,
    sequences: Mapping[str, KeyframeSequence],
    balances: Mapping[str, RiseBalance],
) -> tuple[TrialResult, float]:
    """The benchmark's get-up from this fall with a candidate's sequences and balances, and
    the peak closeness of its first attempt."""
    skill = driver.behavior.skill("get_up")
    assert isinstance(skill, GetUpSkill)
    skill.sequences = sequences
    peak = 0.0

    def first_peak(agent: Any, _cycle: int) -> None:
        nonlocal peak
        if skill.get_up_attempts <= 1:
            peak = max(peak, closeness(agent))

    result = play_get_up(driver, *spec, side, balances=balances, observer=first_peak)
    return result, peak


def play_all(
    bank: Bank,
    candidates: Sequence[tuple[Mapping[str, KeyframeSequence], Mapping[str, RiseBalance]]],
    jobs: int,
) -> np.ndarray:
    """Scores of every candidate on every fall: (candidates, falls, 3) of stood, stood with
    the first attempt, and the first attempt's peak closeness (height times uprightness)."""
    cells = [(f, c) for f in range(len(bank.falls)) for c in range(len(candidates))]

    def task(f: int, c: int) -> Callable[[], tuple[TrialResult, float]]:
        _, driver, spec, side = bank.falls[f]
        sequences, balances = candidates[c]
        return lambda: play_one(driver, spec, side, sequences, balances)

    out = np.zeros((len(candidates), len(bank.falls), 3))
    played = forked_map((task(f, c) for f, c in cells), jobs)
    for (f, c), (result, peak) in zip(cells, played, strict=True):
        out[c, f] = (result.succeeded, result.stood_first, peak)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--type", type=int, default=3)
    parser.add_argument("--sequence", default="get_up_back_type3")
    parser.add_argument("--frames", type=int, nargs="+", default=[1, 2, 3, 4])
    parser.add_argument("--joints", nargs="+", default=["llj1", "llj3", "llj4", "llj5", "laj1"])
    parser.add_argument("--balance-from", type=int, default=3, help="-1: no balance")
    parser.add_argument("--falls", type=int, default=40)
    parser.add_argument("--lying-on", default="back")
    parser.add_argument("--seed", type=int, default=20000)
    parser.add_argument("--pairs", type=int, default=5, help="antithetic pairs per generation")
    parser.add_argument("--budget-s", type=float, default=1800.0)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--rng", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("/tmp/es_search.json"))
    parser.add_argument("--show", type=Path, help="print a saved result's variant and exit")
    args = parser.parse_args()
    if args.show is not None:
        saved = json.loads(args.show.read_text())
        print(saved["variant"])
        print(saved["balance_yaml"])
        return
    entry = raw_entries()[args.sequence]
    dims = frame_dimensions(entry, args.frames, args.type, args.joints)
    if args.balance_from >= 0:
        dims += list(BALANCE_DIMENSIONS)
    low = np.array([d.low for d in dims])
    high = np.array([d.high for d in dims])
    mean = np.array([d.start for d in dims])
    spread = np.array([d.spread for d in dims])
    rng = np.random.default_rng(args.rng)
    bank = Bank.make(args.type, args.falls, args.seed, set(args.lying_on.split(",")))
    print(f"# {len(bank.falls)} falls, {len(dims)} parameters", flush=True)
    eta_spread = (3 + math.log(len(dims))) / (5 * math.sqrt(len(dims)))
    started = time.monotonic()
    generation = 0

    def build(
        values: np.ndarray,
    ) -> tuple[Mapping[str, KeyframeSequence], Mapping[str, RiseBalance]]:
        sequences = variant_sequences(candidate_variant(args.sequence, dims, values))
        balance = candidate_balance(dims, values, args.balance_from)
        balances = dict(RISE_BALANCE)
        if balance is not None:
            balances[args.sequence] = balance
        return sequences, balances

    while time.monotonic() - started < args.budget_s:
        noise = rng.standard_normal((args.pairs, len(dims)))
        noise = np.concatenate([noise, -noise])
        samples = np.clip(mean + spread * noise, low, high)
        values = np.concatenate([mean[None], samples])
        scores = play_all(bank, [build(v) for v in values], args.jobs)
        fitness = (scores @ SCORE_WEIGHTS).sum(axis=1)
        order = np.argsort(-fitness[1:])
        u = utilities(len(order))
        used = (samples - mean) / spread  # the clipped steps
        mean = np.clip(mean + spread * (u @ used[order]), low, high)
        spread = spread * np.exp(0.5 * eta_spread * (u @ (used[order] ** 2 - 1)))
        generation += 1
        print(
            f"gen {generation} {time.monotonic() - started:.0f}s mean-before "
            f"{scores[0, :, 0].sum():.0f} stood ({scores[0, :, 1].sum():.0f} first, "
            f"score {fitness[0]:.2f}) "
            f"samples best {fitness[1:].max():.2f} median {np.median(fitness[1:]):.2f}",
            flush=True,
        )
        args.out.write_text(
            json.dumps(
                {
                    "generation": generation,
                    "values": {f"{d.frame}:{d.key}": float(v) for d, v in zip(dims, mean)},
                    "variant": candidate_variant(args.sequence, dims, mean),
                    "balance_yaml": balance_yaml(
                        args.sequence, candidate_balance(dims, mean, args.balance_from)
                    ),
                },
                indent=1,
            )
        )
    for session, *_ in bank.falls:
        session.close()


if __name__ == "__main__":
    main()
