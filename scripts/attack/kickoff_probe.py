"""Does the kick-off taker take the kick-off? Traces the taker of a k v k match cycle by cycle.

A diagnostic, not a benchmark (it reads the simulator's ground truth to report, never to act):
the match is ``benchmarks.match``'s, same seeds and teams. For every seed it prints when the
ball first moved (the kick-off taken), whether the taker fell before, and with ``--trace`` the
taker's skill, torso tilt, heading and the ball in its torso frame every ``--every`` seconds.

Run: ``python scripts/attack/kickoff_probe.py --players 11 --seeds 1 2 3 [--duration 4]
[--trace] [--set KEY=VALUE ...]``
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from agent.match import run_match
from agent.team import TeamConfig
from benchmarks.match import (
    DEFAULT_TEAM_FILE,
    LINEUP_ORDER,
    _recorded,
    add_set_option,
    small_team,
    team_with_overrides,
)

#: the kick-off taker's formation place (the centre forward) and the ball counts as moved
TAKER_PLACE = 10
MOVED_M = 0.05


def probe(
    players: int, seed: int, duration: float, base: TeamConfig | None, trace_every: float
) -> tuple[float | None, float | None]:
    """(when the ball first moved, when the taker first fell) in seconds of game time, each
    None if it did not happen within ``duration``."""
    left = _recorded(small_team("NaoLeft", players, base))
    right = _recorded(small_team("NaoRight", players, base))
    places = sorted(LINEUP_ORDER[:players])
    taker_unum = places.index(TAKER_PLACE) + 1
    state = {"moved": None, "fell": None}
    every = max(1, round(trace_every / 0.02))

    def on_cycle(session) -> None:
        slot = next(
            (
                s
                for s in session.agents.values()
                if s.team_name == "NaoLeft" and s.unum == taker_unum and s.robot is not None
            ),
            None,
        )
        if slot is None:
            return
        t = session.referee.game_time
        bx, by, _ = session.ball.position()
        if state["moved"] is None and math.hypot(bx, by) > MOVED_M:
            state["moved"] = t
        if state["fell"] is None and slot.robot.has_fallen():
            state["fell"] = t
        if trace_every and session.cycle % every == 0:
            x, y, _ = slot.robot.torso_position()
            yaw = slot.robot.torso_yaw_deg()
            tilt = math.degrees(math.acos(max(-1.0, min(1.0, slot.robot.torso_up()[2]))))
            agent = next(a for a in left.made if a.config.unum == taker_unum)
            run = agent.behavior.current
            dx, dy = bx - x, by - y
            c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))
            print(
                f"  t {t:5.2f} {session.referee.play_mode:14s} {run.name if run else '-':10s} "
                f"torso ({x:5.2f},{y:5.2f}) yaw {yaw:6.1f} tilt {tilt:5.1f} "
                f"ball_ego ({c * dx + s * dy:5.2f},{-s * dx + c * dy:5.2f})",
                flush=True,
            )

    run_match(duration, seed, left, right, on_event=lambda text: None, on_cycle=on_cycle)
    return state["moved"], state["fell"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--players", type=int, default=11)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1])
    parser.add_argument("--duration", type=float, default=4.0)
    parser.add_argument("--every", type=float, default=0.1)
    parser.add_argument("--trace", action="store_true")
    add_set_option(parser)
    args = parser.parse_args()
    base = team_with_overrides(DEFAULT_TEAM_FILE, args.set) if args.set else None
    taken = clean = 0
    every = args.every if args.trace else 0.0
    for seed in args.seeds:
        moved, fell = probe(args.players, seed, args.duration, base, every)
        taken += moved is not None
        clean += moved is not None and (fell is None or fell > moved)
        moved_text = "never" if moved is None else f"{moved:.2f} s"
        fell_text = "no" if fell is None else f"{fell:.2f} s"
        print(f"seed {seed}: ball moved {moved_text}, taker fell {fell_text}", flush=True)
    print(f"kickoff_taken: {taken}/{len(args.seeds)}")
    print(f"kickoff_taken_before_any_fall: {clean}/{len(args.seeds)}")


if __name__ == "__main__":
    main()
