"""Roll traces of basic kicks (analysis aid): for each trial, the torso roll every few cycles
from the kick motion's first cycle, with the cycle the ball moved and whether it fell.

Run: ``PYTHONPATH=. python scripts/kick/trace_rolls.py --layout-seed 0 --trials 0 2 4``."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import pybullet

from benchmarks.kick import MOVING_SPEED, SkillSettings, random_basic_layout, run_basic_trial

sys.path.insert(0, str(Path(__file__).resolve().parent))
from sweep import apply


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--layout-seed", type=int, default=0)
    parser.add_argument("--trials", type=int, nargs="+", required=True)
    parser.add_argument("--every", type=int, default=3)
    parser.add_argument("--distance", default="3")
    parser.add_argument("--set", nargs="*", default=[], help="as scripts/kick/sweep.py")
    parser.add_argument("--kicks", type=Path, help="kick file instead of the packaged one")
    parser.add_argument("--robot-type", type=int, default=0)
    args = parser.parse_args()
    apply(args.set)
    rng = np.random.default_rng(args.layout_seed + 1)
    layouts = [random_basic_layout(rng) for _ in range(max(args.trials) + 1)]
    asked = args.distance if args.distance == "long" else float(args.distance)
    settings = SkillSettings.with_kicks(args.kicks)
    for k in args.trials:
        rows: list[tuple[float, float, float, float, bool]] = []

        def observe(driver, phase, rows=rows):
            if phase != "kick":
                return
            state = driver.world.robot
            ball = driver.session.ball.speed() > MOVING_SPEED
            robot = driver.robot
            skill = driver.behavior.skill("basic_kick")
            link = robot.link_index("lfoot" if skill.foot == "left" else "rfoot")
            ball_id = driver.session.ball._body_id
            touching = [
                c
                for c in pybullet.getContactPoints(
                    bodyA=robot.body_id, linkIndexA=link, physicsClientId=robot.world.client
                )
                if c[2] not in (ball_id, robot.body_id)
            ]
            rows.append(
                (
                    state.roll_deg,
                    state.pitch_deg,
                    float(state.gyro_deg_s[1]),
                    robot.has_fallen(),
                    ball,
                    bool(touching),
                )
            )

        result = run_basic_trial(
            asked, k, *layouts[k], robot_type=args.robot_type, observe=observe, settings=settings
        )
        contact = next((i for i, r in enumerate(rows) if r[4]), None)
        fall = next((i for i, r in enumerate(rows) if r[3]), None)
        print(
            f"trial {k} foot {result.foot} dist {result.distance_m:.2f} stage "
            f"{result.fall_stage} contact@{contact} fall@{fall}"
        )
        sign = 1.0 if result.foot == "left" else -1.0  # + = towards the support foot
        onset = next((i for i, r in enumerate(rows) if abs(r[0]) > 20 or abs(r[1]) > 20), None)
        side = None
        if onset is not None:
            r = rows[onset]
            if abs(r[1]) > abs(r[0]):
                side = "pitch+" if r[1] > 0 else "pitch-"
            else:
                side = "support" if sign * r[0] > 0 else "kicking"
        ground = "".join("g" if r[5] else "." for r in rows[:130])
        print(f"  onset@{onset} towards {side}")
        print(f"  kick foot on ground: {ground}")
        if args.every:
            print("  roll " + " ".join(f"{r[0]:+.0f}" for r in rows[:: args.every]))
            print("  pitch " + " ".join(f"{r[1]:+.0f}" for r in rows[:: args.every]))


if __name__ == "__main__":
    main()
