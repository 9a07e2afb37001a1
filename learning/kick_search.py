"""Search over a few keyframe parameters of the left-foot kick, scored on distance without a fall.

Why a search: with the joints' speed cap (6.14 rad/s) and the two-cycle action delay, how far
the ball goes depends on how the wind-up, the swing of the kicking leg and the lean of the
support leg overlap, which is hard to set by hand. The kick is described by
:data:`PARAMETERS` (degrees, seconds, metres); :func:`kick_entry` turns a parameter set into a
``kicks.yaml`` entry (the swing frames keep the structure of ``behaviors/kick.py``: the shift onto
the support leg, a lift, the wind-up, two predictive swing frames, a recovery, the stand). The
support leg extends during the swing (hip and knee straighten), which leans the torso back and
adds its rotation to the kicking leg's swing, as a human kick does.

Scoring (:func:`evaluate`) runs ``benchmarks.kick.run_trial`` at full strength on both feet with
the ball on its expected place and off it by about a centimetre (:data:`OFFSETS`): the score is
the mean distance (m) minus 5 per fall.
The search is a (1 + lambda) evolution strategy from the packaged kick's parameters with the
step size halved after each generation without improvement.

Run: ``nice -n 5 .venv/bin/python learning/kick_search.py --generations 10 --offspring 6``; it
prints every improvement and at the end the best entry as YAML, to paste into ``kicks.yaml``.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.kick import FEET, KICK_LEFT, KickMotion, kick_motion, parse_kicks
from benchmarks.kick import KickResult, run_trial
from world.nao_model import robot_spec

#: Penalty (m of score) for a trial in which the robot fell.
FALL_PENALTY = 5.0


@dataclass(frozen=True)
class Parameter:
    low: float
    high: float
    start: float


#: name -> range and start value. Angles in degrees (left kick; support = right leg). The start
#: values are the packaged kick of the second round (``kicks.yaml``: 3.0-3.1 m from a stand, the
#: swing at ``fast_s`` 0.41 s); ``arm_swing`` moves the arms against the kicking leg during the
#: swing (the right arm forward, the left back, degrees of shoulder pitch), for balance.
PARAMETERS: dict[str, Parameter] = {
    "roll": Parameter(8, 20, 13.6),  # hip and ankle roll moving the weight onto the support foot
    "wind_s": Parameter(0.15, 0.5, 0.2),  # duration of the wind-up frame
    "wind_hip": Parameter(-25, 10, -20.5),  # kicking leg at the end of the wind-up
    "wind_knee": Parameter(-130, -70, -110.5),
    "wind_ankle": Parameter(0, 70, 55.4),
    "wind_support_hip": Parameter(-10, 50, 12.7),  # support leg at the end of the wind-up
    "wind_support_knee": Parameter(-70, 0, -39.5),
    "contact_hip": Parameter(10, 70, 41.6),  # kicking leg at the end of the first swing frame
    "contact_knee": Parameter(-110, -10, -95.0),
    "contact_ankle": Parameter(-30, 60, 20.5),
    "end_hip": Parameter(40, 100, 74.3),  # kicking leg at the end of the swing
    "end_knee": Parameter(-60, 0, -12.2),
    "end_ankle": Parameter(-45, 30, -18.7),
    "end_support_hip": Parameter(-25, 40, 2.0),  # support leg at the end of the swing
    "end_support_knee": Parameter(-60, 0, -31.6),
    "end_support_ankle": Parameter(-20, 60, 19.8),
    "swing_s": Parameter(0.2, 0.5, 0.41),  # both swing frames together at full strength
    "contact_share": Parameter(0.3, 0.8, 0.70),  # share of the swing spent on the first frame
    "recover_s": Parameter(0.2, 0.8, 0.3),  # back from the swing to the bent knee
    "stand_s": Parameter(0.4, 1.2, 0.6),  # from there to the stand
    # below 0.05: none; else seconds to put the kicking foot down beside the support foot,
    # the weight still on the support leg, before the return to the stand shifts it back
    "land_s": Parameter(0.0, 0.6, 0.3),
    "arm_swing": Parameter(-40, 40, 0.0),
    "ball_gap_m": Parameter(-0.02, 0.1, 0.024),
    "ball_side_m": Parameter(-0.04, 0.04, -0.003),
}

#: Shorter ``land_s`` means no landing frame.
LAND_MIN_S = 0.05
#: Swing duration (s) at strength 0 written into every entry (as the packaged kick's).
SLOW_S = 0.8
#: Ball placement errors (m along, m outwards) and cycles in the stand before the kick that
#: every candidate is scored on, each with both feet. Why: after walking and shuffling the ball
#: lies up to about a centimetre off, and a kick tuned on the exact spot lost 0.7 m with the
#: ball 1.6 cm further away; the packaged kick went 2.3-3.7 m (one fall) instead of 3.0-3.1 m
#: when it started 30 or 65 cycles later, while the robot's sway after rising had changed.
#: (The session seed changes nothing here: without beam noise a trial is deterministic.)
START_STATES: tuple[tuple[float, float, int], ...] = (
    (0.0, 0.0, 1),
    (-0.01, 0.008, 30),
    (0.012, -0.008, 65),
    (0.006, -0.005, 15),
    (-0.006, 0.005, 45),
    (0.0, 0.0, 90),
)
#: The searches score on the first three start states (6 kicks); ``--starts 6`` for scans.
SEARCH_STARTS = 3
#: With ``--shuffle`` every start state first plays ``basic_kick``'s alignment shuffle by
#: these (forward, left) m, one per start state (``benchmarks.kick.shuffle_in_place``). Why: a
#: kick that never fell in 12 stand kicks fell 12 of 20 basic kicks, and the packaged kick's
#: right foot fell 2 of 2 after a shuffle (seed 1, 15 cycles' wait) and 0 of 1 without.
SHUFFLES: tuple[tuple[float, float], ...] = (
    (0.03, 0.02),
    (-0.02, -0.03),
    (0.04, -0.01),
    (0.01, 0.03),
    (-0.01, 0.01),
    (0.02, -0.02),
)


def start_parameters() -> dict[str, float]:
    return {name: p.start for name, p in PARAMETERS.items()}


def clip(params: Mapping[str, float]) -> dict[str, float]:
    return {n: float(min(max(v, PARAMETERS[n].low), PARAMETERS[n].high)) for n, v in params.items()}


def kick_entry(p: Mapping[str, float]) -> dict[str, Any]:
    """A ``kicks.yaml`` entry (plain data) for the parameter set ``p``."""
    r = round(p["roll"], 1)

    def support(hip: float, knee: float, ankle: float | None = None) -> dict[str, float]:
        # ankle None: keep the support foot parallel to the torso's level (flat when upright)
        ankle = -(hip + knee) + 2.0 if ankle is None else ankle
        return _within_limits({"rlj3": hip, "rlj4": knee, "rlj5": ankle})

    def kicking(hip: float, knee: float, ankle: float) -> dict[str, float]:
        return _within_limits({"llj3": hip, "llj4": knee, "llj5": ankle})

    swing, share = p["swing_s"], p["contact_share"]
    shift = {"rlj2": r, "llj2": r, "rlj6": -r, "llj6": -r, **support(15, -30, 17)}
    shift.update(kicking(15, -30, 17))
    predictive = {"interpolation": "linear", "track": "predictive"}
    frames = [
        {"duration": 0.5, "hold": 0.15, "pose": "stand", "joints": shift},
        {"duration": 0.2, "joints": kicking(30, -100, 60)},
        {
            "duration": round(p["wind_s"], 3),
            "hold": 0.04,
            "joints": {
                **kicking(p["wind_hip"], p["wind_knee"], p["wind_ankle"]),
                **support(p["wind_support_hip"], p["wind_support_knee"]),
            },
        },
        {
            "duration": round(swing * share, 3),
            **predictive,
            "joints": kicking(p["contact_hip"], p["contact_knee"], p["contact_ankle"]),
        },
        {
            "duration": round(swing * (1 - share), 3),
            **predictive,
            "joints": {
                **kicking(p["end_hip"], p["end_knee"], p["end_ankle"]),
                **support(p["end_support_hip"], p["end_support_knee"], p["end_support_ankle"]),
                **_arms(p.get("arm_swing", 0.0)),
            },
        },
        {
            "duration": round(p["recover_s"], 3),
            "joints": {**kicking(40, -90, 45), **support(15, -30, 17), **_arms(0.0)},
        },
        {"duration": round(p["stand_s"], 3), "hold": 0.3, "pose": "stand"},
    ]
    if p.get("land_s", 0.0) >= LAND_MIN_S:
        land = {"joints": {**kicking(15, -30, 17), **support(15, -30, 17)}}
        frames.insert(-1, {"duration": round(p["land_s"], 3), "hold": 0.1, **land})
    return {
        "description": "left-foot kick found by learning/kick_search.py",
        "ball_gap_m": round(p["ball_gap_m"], 3),
        "ball_side_m": round(p["ball_side_m"], 3),
        "frames": frames,
        "swing": {"frames": [3, 4], "fast_s": round(swing, 3), "slow_s": SLOW_S},
    }


def _arms(swing: float) -> dict[str, float]:
    """Shoulder pitches of the stand (-90) with the right arm ``swing`` deg forward and the
    left one back (a left kick: arms against the legs, as a person kicks)."""
    return _within_limits({"raj1": -90.0 + swing, "laj1": -90.0 - swing})


def _within_limits(angles: Mapping[str, float]) -> dict[str, float]:
    """Angles clipped into the joints' ranges (type 0's, the narrowest) and rounded."""
    limits = {j.perceptor: (j.min_deg, j.max_deg) for j in robot_spec(0).joints}
    return {n: round(min(max(a, limits[n][0]), limits[n][1]), 1) for n, a in angles.items()}


def motions_for(p: Mapping[str, float]) -> dict[str, KickMotion]:
    return parse_kicks({KICK_LEFT: kick_entry(p)}, "kick_search")


def evaluate(
    p: Mapping[str, float],
    starts: int = SEARCH_STARTS,
    robot_type: int = 0,
    shuffle: bool = False,
    fall_penalty: float = FALL_PENALTY,
    feet: tuple[str, ...] = FEET,
) -> tuple[float, list[KickResult]]:
    """Score of full-strength kicks with ``feet`` (default both; the right foot plays the
    mirror image), from the first ``starts`` of :data:`START_STATES`: the mean distance (a kick
    that misses counts 0) minus ``fall_penalty`` (:data:`FALL_PENALTY`) per fall. The mean
    rather than the median, so that a kick that only works from one start scores low.
    ``shuffle``: each start first plays the alignment shuffle of :data:`SHUFFLES`."""
    motions = motions_for(p)
    results = [
        run_trial(
            foot,
            1.0,
            1,
            robot_type,
            gap,
            motions,
            side_error=side,
            wait_cycles=wait,
            shuffle_m=moved if shuffle else None,
        )
        for (gap, side, wait), moved in zip(START_STATES[:starts], SHUFFLES, strict=False)
        for foot in feet
    ]
    distances = [r.distance_m if r.time_to_contact_s is not None else 0.0 for r in results]
    score = statistics.mean(distances) - fall_penalty * sum(r.fell for r in results)
    return score, results


def search(
    generations: int,
    offspring: int,
    step: float,
    seed: int,
    robot_type: int,
    minutes: float = math.inf,
    starts: int = SEARCH_STARTS,
    shuffle: bool = False,
    base: Mapping[str, float] | None = None,
    fall_penalty: float = FALL_PENALTY,
    feet: tuple[str, ...] = FEET,
) -> dict[str, float]:
    """(1 + lambda) evolution from ``base`` (default :func:`start_parameters`), every
    candidate scored on the first ``starts`` start states with ``fall_penalty`` per fall;
    returns the best set found once the generations are done or ``minutes`` have passed
    (checked after every candidate)."""
    deadline = time.monotonic() + 60.0 * minutes
    rng = np.random.default_rng(seed)
    best = clip(start_parameters() if base is None else base)
    best_score, results = evaluate(best, starts, robot_type, shuffle, fall_penalty, feet)
    print(f"start: {best_score:.2f} ({_shown(results)})", flush=True)
    for generation in range(generations):
        improved = False
        for _ in range(offspring):
            if time.monotonic() > deadline:
                return best
            child = clip(
                {
                    n: v + rng.normal() * step * (PARAMETERS[n].high - PARAMETERS[n].low)
                    for n, v in best.items()
                }
            )
            score, results = evaluate(child, starts, robot_type, shuffle, fall_penalty, feet)
            if score > best_score:
                best, best_score, improved = child, score, True
                print(f"gen {generation}: {best_score:.2f} ({_shown(results)})", flush=True)
                print(f"  parameters: {json.dumps(best)}", flush=True)
        if not improved:
            step /= 2
    return best


def scan(
    changes: list[str],
    starts: int,
    robot_type: int,
    base: Mapping[str, float],
    shuffle: bool = False,
    fall_penalty: float = FALL_PENALTY,
    feet: tuple[str, ...] = FEET,
) -> None:
    """Coordinate scan: score ``base`` with each ``name=value[,value...]`` change applied on
    its own (``a=1+b=2`` changes two at once) and print one ``scan[...]: score`` line each.
    Why besides the evolution: the score is noisy (the kick is sensitive to its start), and a
    (1 + lambda) search keeps a lucky candidate; a scan shows a lever's trend."""
    score, results = evaluate(base, starts, robot_type, shuffle, fall_penalty, feet)
    _report("scan[base]", score, results)
    for change in changes:
        for values in _expand(change):
            params = clip({**base, **values})
            label = ",".join(f"{n}={v:g}" for n, v in values.items())
            score, results = evaluate(params, starts, robot_type, shuffle, fall_penalty, feet)
            _report(f"scan[{label}]", score, results)


def _expand(change: str) -> list[dict[str, float]]:
    """``"a=1,2"`` -> [{a: 1}, {a: 2}]; ``"a=1+b=2"`` -> [{a: 1, b: 2}]."""
    if "+" in change:
        return [_changes(change)]
    name, values = change.split("=")
    if name not in PARAMETERS:
        raise SystemExit(f"unknown parameter {name!r}; known: {', '.join(PARAMETERS)}")
    return [{name: float(v)} for v in values.split(",")]


def _changes(text: str) -> dict[str, float]:
    """``"a=1+b=2"`` -> {a: 1, b: 2}, or a JSON object as the search prints its best
    (``{"a": 1, ...}``); names checked against :data:`PARAMETERS`."""
    if text.lstrip().startswith("{"):
        values = {n: float(v) for n, v in json.loads(text).items()}
    else:
        values = {n: float(v) for n, v in (part.split("=") for part in text.split("+"))}
    unknown = sorted(set(values) - set(PARAMETERS))
    if unknown:
        raise SystemExit(f"unknown parameters {unknown}; known: {', '.join(PARAMETERS)}")
    return values


def write_candidate(p: Mapping[str, float], path: Path, name: str = KICK_LEFT) -> None:
    """Write ``p`` as a kick file for ``benchmarks/kick.py --kicks``: its entry named ``name``
    (``kick_right_aligned``: the right foot's own kick, written for the left foot and played
    mirrored; an entry already in the file under another name is kept, so a left and a right
    search can share one file) with the packaged kick's distance table, so ``basic_kick``
    picks the same strengths (full strength at 3 m) and only the motion differs."""
    entry = {**kick_entry(p), "distances": [list(pair) for pair in kick_motion(0).distances]}
    data = yaml.safe_load(path.read_text()) if path.exists() else {}
    data = {**(data or {}), name: entry}
    path.write_text(yaml.safe_dump(data, sort_keys=False, width=100))


def _shown(results: list[KickResult]) -> str:
    """Each kick's distance, ``F`` after a fall: ``2.41, 3.10F, ...``."""
    return ", ".join(f"{r.distance_m:.2f}{'F' if r.fell else ''}" for r in results)


def _report(label: str, score: float, results: list[KickResult]) -> None:
    falls = sum(r.fell for r in results)
    print(f"{label}: {score:.2f} (falls {falls} of {len(results)}: {_shown(results)})", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--generations", type=int, default=10)
    parser.add_argument("--offspring", type=int, default=6)
    parser.add_argument("--step", type=float, default=0.15, help="share of each range")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--robot-type", type=int, default=0)
    parser.add_argument("--minutes", type=float, default=math.inf, help="time budget")
    parser.add_argument(
        "--scan", nargs="+", metavar="NAME=V1,V2", help="score single changes instead of searching"
    )
    parser.add_argument(
        "--starts", type=int, default=SEARCH_STARTS, help="start states per score, 1-6"
    )
    parser.add_argument(
        "--shuffle",
        action="store_true",
        help="start every kick after basic_kick's alignment shuffle (as after an approach)",
    )
    parser.add_argument(
        "--base",
        metavar="A=1+B=2",
        help="start (search) or scan from the packaged kick with these changes",
    )
    parser.add_argument(
        "--fall-penalty",
        type=float,
        default=FALL_PENALTY,
        help="score lost per fall (m of mean distance)",
    )
    parser.add_argument(
        "--write",
        type=Path,
        metavar="FILE",
        help="write --base as a kick file (for benchmarks/kick.py --kicks) and stop",
    )
    parser.add_argument(
        "--write-as",
        default=KICK_LEFT,
        metavar="NAME",
        help="--write: the entry's name (kick_right_aligned: the right foot's own kick)",
    )
    parser.add_argument(
        "--feet",
        nargs="+",
        choices=FEET,
        default=list(FEET),
        help="the feet every candidate kicks with (right: the left kick mirrored)",
    )
    args = parser.parse_args()
    base = {**start_parameters(), **(_changes(args.base) if args.base else {})}
    feet = tuple(args.feet)
    if args.write:
        write_candidate(clip(base), args.write, args.write_as)
        return
    if args.scan:
        scan(args.scan, args.starts, args.robot_type, base, args.shuffle, args.fall_penalty, feet)
        return
    best = search(
        args.generations,
        args.offspring,
        args.step,
        args.seed,
        args.robot_type,
        args.minutes,
        args.starts,
        args.shuffle,
        base,
        args.fall_penalty,
        feet,
    )
    print(yaml.safe_dump({"parameters": best}, sort_keys=False))
    print(yaml.safe_dump({KICK_LEFT: kick_entry(best)}, sort_keys=False, width=100))


if __name__ == "__main__":
    main()
