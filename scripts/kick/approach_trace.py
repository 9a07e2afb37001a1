"""Where a basic kick's approach spends its time: one line every ``--every`` cycles of a
``benchmarks/kick.py`` basic trial with the skill's phase, the true torso pose, the walk's
target (the kicking spot or the detour point), the distance and heading error to it, and the
walk velocity command (``--estimate``: also the localiser's pose and the true ball position).
The spot and heading error are the skill's own (its motion, ball gap and aimed target; before
session 34 the trace left the aim out, and its heading error read 6-10 deg off what the walk
steered by).

Run: ``PYTHONPATH=. python scripts/kick/approach_trace.py --layout-seed 0 --trial 0
[--distance 3] [--every 10] [--robot-type 0] [--estimate]``. Why: the approach is the longest
part of the time from the decision to kick to the ball leaving the foot (2-14 s for a ball
0.5-2 m away)."""

from __future__ import annotations

import argparse
import math

import numpy as np

from behaviors.basic_kick import aimed_motion, detour_point, expected_ball_ego, kick_spot
from benchmarks.kick import random_basic_layout, run_basic_trial
from learning.local_agent import LocalAgent


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--layout-seed", type=int, default=0)
    parser.add_argument("--trial", type=int, default=0)
    parser.add_argument("--distance", default="3")
    parser.add_argument("--every", type=int, default=10)
    parser.add_argument("--robot-type", type=int, default=0)
    parser.add_argument(
        "--estimate",
        action="store_true",
        help="also the localiser's pose and the true ball position",
    )
    args = parser.parse_args()
    rng = np.random.default_rng(args.layout_seed + 1)
    layouts = [random_basic_layout(rng) for _ in range(args.trial + 1)]
    asked = args.distance if args.distance == "long" else float(args.distance)
    cycle = [0]
    target: list[tuple[float, float]] = []
    #: the first second the robot came within 0.2 m of the kicking spot, per phase
    near: dict[str, float] = {}
    phases: dict[str, float] = {}

    def observe(driver: LocalAgent, phase: str) -> None:
        cycle[0] += 1
        phases.setdefault(phase, cycle[0] * 0.02)
        world = driver.world
        skill = driver.behavior.skill("basic_kick")
        robot = driver.robot
        x, y, _ = robot.torso_position()
        h = robot.torso_yaw_deg()
        line = f"{cycle[0] * 0.02:6.2f} s {phase:9s} pose {x:+.2f} {y:+.2f} {h:+6.1f}"
        ball = world.ball.position
        if ball is not None and skill.foot is not None and target:
            # the spot as the skill walks to it: its motion, ball gap and aimed target
            motion, _, aimed = aimed_motion(
                world.robot.robot_type, skill.motions, skill.foot, asked, ball[:2], target[0]
            )
            offset = expected_ball_ego(world.robot.robot_type, skill.foot, motion, asked)
            spot = kick_spot(ball, aimed, offset)
            detour = detour_point(ball, spot, (x, y))
            goal = spot if detour is None else (*detour, float("nan"))
            d = math.dist(goal[:2], (x, y))
            if detour is None and d < 0.2:
                near.setdefault("near", cycle[0] * 0.02)
            herr = (spot[2] - h + 180.0) % 360.0 - 180.0
            if phase == "approach" and world.ball_relative_ego is not None:
                context = driver.behavior._context
                a = skill._alignment(context, motion, aimed)
                line += f" align {a.along_m:+.3f} {a.across_m:+.3f} {a.heading_deg:+.0f}"
                if a.within(0.05, 0.05):
                    near.setdefault("aligned", cycle[0] * 0.02)
            where = "DETOUR" if detour else "spot  "
            line += f" foot {skill.foot:5s} {where} d {d:.2f} herr {herr:+.0f}"
        engine = driver.behavior.skill("walk").gait_engine
        if engine is not None:
            vx, vy, w = engine.velocity
            line += f" v {vx:+.2f} {vy:+.2f} {math.degrees(w):+.0f}"
        if args.estimate:
            pose = world.pose
            if pose is not None:
                line += f" est {pose.x:+.3f} {pose.y:+.3f} {pose.heading_deg:+6.1f}"
            true_ball = driver.session.ball.position()
            line += f" ball {true_ball[0]:+.3f} {true_ball[1]:+.3f}"
        if args.every and cycle[0] % args.every == 0:
            print(line, flush=True)

    layout = layouts[args.trial]
    distance, bearing, direction = layout
    rad = math.radians(bearing)
    bx, by = -1.0 + distance * math.cos(rad), distance * math.sin(rad)
    reach = 10.0 if isinstance(asked, str) else asked
    target.append((bx + reach * math.cos(math.radians(direction)),
                   by + reach * math.sin(math.radians(direction))))  # fmt: skip
    print(f"ball {bx:+.2f} {by:+.2f} target dir {direction:+.0f} deg")
    print(run_basic_trial(asked, args.trial, *layout, robot_type=args.robot_type, observe=observe))
    first = near.get("near", math.nan)
    settle = phases.get("settle", math.nan)
    aligned = near.get("aligned", math.nan)
    starts = " ".join(f"{p}:{t:.2f}" for p, t in phases.items())
    print(
        f"summary: within 0.2 m of the spot at {first:.2f} s, within 5 cm (estimate) at "
        f"{aligned:.2f} s, settle at {settle:.2f} s, creep {settle - first:.2f} s; "
        f"phases start {starts}"
    )


if __name__ == "__main__":
    main()
