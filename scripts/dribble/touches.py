"""Where in the step the dribbles touch the ball, and how hard: one line per touch and a table
by phase.

A touch is a cycle in which the ball's ground speed rises by more than ``--jump`` m/s (the ball
gains speed only from contacts; rolling only slows it). Per touch: the phase (t, left_active)
of the cycle before, the ball's distance ahead of the torso before the touch, the ball's speed
before and after, the robot's forward speed (ground truth). The table gives, per phase t and
swinging leg, the number of touches and the median speed after.

Why: under the bounce contacts (restitution 0.8 as on the real server) a toe meeting the ball at
mid-swing, when the swing foot moves at about twice the walking speed, sends it 1 m and more
ahead and the dribble loses it; a toe that meets it as the swing ends (the foot slowing to land)
pushes it gently. This says which touches the gaits make. Diagnostic only (reads the
simulator's truth).

Run: ``PYTHONPATH=. python scripts/dribble/touches.py --kind lfdl --type 0 --seeds 0 1 2
[--set dotted.key=value ...]``
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from benchmarks.dribble import (
    CYCLE,
    DRIBBLE_FILE,
    TOUCH_JUMP,
    start_dribble_episode,
    with_settings,
)


def touches(
    kind: str,
    robot_type: int,
    seed: int,
    data_file: Path,
    seconds: float,
    jump: float,
    foot: str = "left",
) -> list[dict[str, float | int | bool | str]]:
    """Every touch of one straight 0 deg dribble of ``seconds``."""
    session, agent = start_dribble_episode(robot_type, 0.0, seed)
    skill = agent.behavior.skill("dribble")
    skill.data_file = data_file
    found = []
    try:
        before_speed = 0.0
        before_phase = skill.phase
        before_ahead = 0.3
        last_torso = agent.robot.torso_position()
        for cycle in range(round(seconds / CYCLE)):
            agent.run("dribble", kind, 0.0, foot)
            vx, vy, _ = session.ball.velocity()
            speed = math.hypot(vx, vy)
            torso = agent.robot.torso_position()
            robot_speed = (torso[0] - last_torso[0]) / CYCLE
            last_torso = torso
            if speed - before_speed > jump:
                found.append(
                    {
                        "by": _touching_links(session, agent),
                        "cycle": cycle,
                        "t": before_phase[0],
                        "left": before_phase[1],
                        "ahead": before_ahead,
                        "before": before_speed,
                        "after": speed,
                        "robot": robot_speed,
                    }
                )
            bx, by, _ = session.ball.position()
            yaw = math.radians(agent.robot.torso_yaw_deg())
            before_ahead = math.cos(yaw) * (bx - torso[0]) + math.sin(yaw) * (by - torso[1])
            before_speed, before_phase = speed, skill.phase
            if agent.robot.has_fallen():
                break
    finally:
        session.close()
    return found


def _touching_links(session, agent) -> str:
    """The robot links within 2 cm of the ball (a touch may end within the cycle's substeps)."""
    import pybullet

    near = pybullet.getClosestPoints(
        session.ball.body_id, agent.robot.body_id, 0.02, physicsClientId=session.world.client
    )
    return "+".join(sorted({agent.robot.link_name(c[4]) for c in near})) or "-"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--kind", default="lfdl")
    parser.add_argument("--type", type=int, default=0)
    parser.add_argument("--foot", default="left", choices=("left", "right"))
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--jump", type=float, default=TOUCH_JUMP)
    parser.add_argument("--set", action="append", default=[], metavar="DOTTED.KEY=VALUE")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        data_file = with_settings(args.set, Path(tmp)) if args.set else DRIBBLE_FILE
        table: dict[tuple[int, bool], list[float]] = defaultdict(list)
        for seed in args.seeds:
            for touch in touches(
                args.kind, args.type, seed, data_file, args.seconds, args.jump, args.foot
            ):
                table[(int(touch["t"]), bool(touch["left"]))].append(float(touch["after"]))
                print(
                    f"seed {seed} {touch['cycle'] * CYCLE:6.2f}s phase ({touch['t']},"
                    f"{'L' if touch['left'] else 'R'}) ahead {touch['ahead']:+.2f} ball "
                    f"{touch['before']:.2f} -> {touch['after']:.2f} m/s robot "
                    f"{touch['robot']:+.2f} m/s by {touch['by']}",
                    flush=True,
                )
    print("phase   touches  median speed after (m/s)")
    for (t, left), speeds in sorted(table.items(), key=lambda kv: (not kv[0][1], kv[0][0])):
        print(f"({t},{'L' if left else 'R'})  {len(speeds):7d}  {statistics.median(speeds):.2f}")


if __name__ == "__main__":
    main()
