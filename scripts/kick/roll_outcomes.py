"""The torso's roll through each basic kick, with how the kick ended: data for fall predictors.

Run: ``PYTHONPATH=. python scripts/kick/roll_outcomes.py --layout-seeds 0 1 --distance 3.5
--out runs/kick_abort/rolls_3.5_L0-1.npz [--set kick.NAME=value] [--kicks FILE]``, then
``python scripts/kick/roll_outcomes.py --summary FILE...`` prints, per outcome (stayed up, fell
before the ball moved, fell after), the roll at fixed times of the kick motion.

Each trial is ``benchmarks/kick.py``'s basic trial (same layouts, same seeds). From the kick
motion's first cycle until the trial's skill loop ends the script keeps, per cycle (the
benchmark's roll-out in ``stand`` after that is not traced; a fall there shows only as the
``after_kick`` stage): the motion's elapsed
time (s; NaN once the kick skill has finished), the torso roll seen from the kicking foot
(degrees, + = leaning over the support foot: the world model's ``roll_deg``, as the skill sees
it), its rate (deg/s, same sign), the two feet's FRP forces (support, kicking; N), whether the
ball moves and whether the robot has fallen.

Why: session 25 found 30 of 40 basic-kick falls inside the kick, 11 of them before contact with the
torso 9-12 deg over the support foot before the swing; a kick that can still stop (put the foot
down and try again) needs a signal, seen before the swing commits, that tells the falls apart.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from benchmarks.kick import (
    DEFAULT_SETTINGS,
    MOVING_SPEED,
    SkillSettings,
    random_basic_layout,
    run_basic_trial,
)
from learning.local_agent import LocalAgent

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fall_stages import trial_arguments
from sweep import apply

#: times of the long kick motion (s from its start) at which the summary reads the roll: the
#: weight shift's end, the lift's, the wind-up's (the swing starts), contact, the landing
SUMMARY_TIMES = (0.3, 0.5, 0.65, 0.75, 0.85, 0.95, 1.06, 1.2, 1.36, 1.6, 1.9, 2.2, 2.6)


def record_trial(
    asked: float | str,
    seed: int,
    layout: tuple[float, float, float],
    settings: SkillSettings = DEFAULT_SETTINGS,
) -> dict:
    """One basic trial with its per-cycle kick trace (see the module docstring)."""
    rows: list[tuple[float, ...]] = []
    foot: list[str] = []

    def observe(driver: LocalAgent, phase: str) -> None:
        skill = driver.behavior.skill("basic_kick")
        if phase != "kick" and not rows:
            return
        if not foot:
            foot.append(skill.foot or "left")
        sign = 1.0 if foot[0] == "left" else -1.0  # + = over the support foot
        kick = driver.behavior.skill("kick")
        player = kick._player  # analysis aid: the motion's elapsed time
        elapsed = player.elapsed if phase == "kick" and player is not None else float("nan")
        robot = driver.world.robot
        pressure = robot.foot_pressure
        support, kicking = ("rf", "lf") if foot[0] == "left" else ("lf", "rf")
        forces = [
            float(pressure[name].force[2]) if name in pressure else 0.0
            for name in (support, kicking)
        ]
        rows.append(
            (
                elapsed,
                sign * robot.roll_deg,
                sign * float(robot.gyro_deg_s[1]),
                *forces,
                float(driver.session.ball.speed() > MOVING_SPEED),
                float(driver.robot.has_fallen()),
            )
        )

    result = run_basic_trial(asked, seed, *layout, observe=observe, settings=settings)
    return {
        "trace": np.array(rows, dtype=float).reshape(-1, 7),
        "stage": result.fall_stage or "none",
        "foot": result.foot or "-",
        "distance": result.distance_m,
        "direction": result.direction_error_deg,
    }


def outcome(trial: dict) -> str:
    """The benchmark's fall stage (``before_contact``, ``after_contact``, ``after_kick``,
    ``before_kick``), ``up`` for a kick that stayed up, ``no_kick`` for none."""
    if trial["stage"] != "none":
        return trial["stage"]
    return "up" if len(trial["trace"]) else "no_kick"


def roll_at(trace: np.ndarray, time_s: float) -> float:
    """The roll at the first cycle whose elapsed time reaches ``time_s`` (NaN if none)."""
    index = np.flatnonzero(trace[:, 0] >= time_s - 1e-9)
    return float(trace[index[0], 1]) if len(index) else float("nan")


def summary(paths: list[Path]) -> None:
    trials: list[dict] = []
    for path in paths:
        data = np.load(path, allow_pickle=True)
        trials.extend(data["trials"].tolist())
    groups: dict[str, list[dict]] = {}
    for trial in trials:
        groups.setdefault(outcome(trial), []).append(trial)
    print("counts " + " ".join(f"{k}:{len(v)}" for k, v in sorted(groups.items())))
    header = "outcome   " + " ".join(f"{t:>6.2f}" for t in SUMMARY_TIMES)
    for quantile in (0.1, 0.5, 0.9):
        print(f"-- roll (deg, + over the support foot), quantile {quantile}")
        print(header)
        for name, members in sorted(groups.items()):
            if name in ("no_kick", "before_kick"):
                continue
            cells = []
            for t in SUMMARY_TIMES:
                values = [roll_at(m["trace"], t) for m in members]
                values = [v for v in values if not np.isnan(v)]
                cells.append(f"{np.quantile(values, quantile):6.1f}" if values else "     -")
            print(f"{name:9s} " + " ".join(cells))


def main() -> None:
    parser = trial_arguments(__doc__)
    parser.add_argument("--out", type=Path)
    parser.add_argument("--summary", type=Path, nargs="+", help="print the summary of files")
    args = parser.parse_args()
    if args.summary:
        summary(args.summary)
        return
    apply(args.set)
    settings = SkillSettings.with_kicks(args.kicks)
    asked = args.distance if args.distance == "long" else float(args.distance)
    trials: list[dict] = []
    for seed in args.layout_seeds:
        rng = np.random.default_rng(seed + 1)
        layouts = [random_basic_layout(rng) for _ in range(args.trials)]
        for index, layout in enumerate(layouts):
            trial = record_trial(asked, index, layout, settings)
            trial.update(layout_seed=seed, trial=index)
            trials.append(trial)
            print(
                f"seed {seed} trial {index:2d} foot {trial['foot']} {outcome(trial)} "
                f"stage {trial['stage']} distance {trial['distance']:.2f}",
                flush=True,
            )
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(args.out, trials=np.array(trials, dtype=object))
        summary([args.out])


if __name__ == "__main__":
    main()
