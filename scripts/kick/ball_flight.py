"""Where a kick sends the ball: per cycle after contact, the ball's height, velocity and spin
and the kicking foot's height and pitch (a diagnostic for lofted kicks).

Run: ``PYTHONPATH=. nice -n 5 python scripts/kick/ball_flight.py [--foot left] [--strength 1]
[--kicks FILE] [--wait 30] [--cycles 40]``. Why: on the ground the ball rolls about 0.68 m
per m/s of its start speed, while in the air its drag is tiny and it bounces at 0.8, so a
ball leaving upwards carries its speed further; this shows whether a kick lifts the ball.

``--launch 2.8 0 2.8 1.0 ...`` (pairs of horizontal and vertical m/s) instead puts the ball
just above the ground with that velocity (trainer command, no spin) and prints where it comes
to rest: what a lofted kick would gain, without a kick."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import pybullet

from behaviors.kick import load_kicks
from benchmarks.kick import foot_link_state, run_trial
from sim.robot import SimRobot
from sim.session import Session, SessionConfig
from world.field_geometry import BALL_RADIUS

#: Cycles a launched ball is left to roll out (8 s).
LAUNCH_CYCLES = 400


def launches(pairs: list[float]) -> None:
    """Print the rest distance of a ball launched at each (horizontal, vertical) m/s pair."""
    session = Session(SessionConfig(seed=0, beam_noise=False))
    try:
        for vx, vz in zip(pairs[::2], pairs[1::2], strict=True):
            session.trainer(
                f"(playMode PlayOn)(ball (pos 0 0 {BALL_RADIUS + 0.005}) (vel {vx} 0 {vz}))"
            )
            for _ in range(LAUNCH_CYCLES + 1):
                session.step()
            x, y, _ = session.ball.position()
            print(f"launch {vx:.2f} / {vz:+.2f} m/s: rests {math.hypot(x, y):.2f} m away")
    finally:
        session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--foot", default="left")
    parser.add_argument("--strength", type=float, default=1.0)
    parser.add_argument("--kicks", type=Path)
    parser.add_argument("--wait", type=int, default=30)
    parser.add_argument("--cycles", type=int, default=40, help="cycles shown after contact")
    parser.add_argument("--gap", type=float, default=0.0, help="ball placement error along (m)")
    parser.add_argument("--launch", type=float, nargs="+", help="vx vz pairs (m/s)")
    args = parser.parse_args()
    if args.launch:
        launches(args.launch)
        return
    motions = None if args.kicks is None else load_kicks(args.kicks)
    rows: list[str] = []
    state = {"contact": None, "cycle": 0}

    def observe(session: Session, robot: SimRobot) -> None:
        state["cycle"] += 1
        ball = session.ball
        if state["contact"] is None and ball.speed() > 0.1:
            state["contact"] = state["cycle"]
        if state["contact"] is None or state["cycle"] - state["contact"] > args.cycles:
            return
        link = foot_link_state(robot, args.foot)
        pitch = math.degrees(pybullet.getEulerFromQuaternion(link[1])[0])
        z = ball.position()[2]
        vx, vy, vz = ball.velocity()
        fv = link[6]
        rows.append(
            f"c{state['cycle']:3d} ball z {z:.3f} v {math.hypot(vx, vy):.2f}/{vz:+.2f} "
            f"launch {ball.launch_speed():.2f} | foot z {link[0][2]:.3f} pitch {pitch:+.0f} "
            f"v {math.hypot(fv[0], fv[1]):.2f}/{fv[2]:+.2f}"
        )

    result = run_trial(
        args.foot, args.strength, 1, 0, args.gap, motions, observe, wait_cycles=args.wait
    )
    print("\n".join(rows))
    print(result)


if __name__ == "__main__":
    main()
