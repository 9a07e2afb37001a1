"""Where the time of a k v k match goes: per team, what its active field player does, how long
the ball is contested, and where the falls happen.

A diagnostic, not a benchmark (it reads the simulator's ground truth to classify, never to
act): the match is ``benchmarks.match.play``'s, same seeds and teams, so its score and falls
repeat the benchmark's for a seed on one machine.

Run: ``python scripts/attack/match_probe.py --seed S [--duration 120] [--set KEY=VALUE ...]``;
prints the score, per team the seconds its active player spent per skill, the seconds with the
ball contested (players of both teams within ``CONTEST_M`` of it), ball-lost seconds, per team
the player-seconds its standing players spent with the ball lost to them
(:func:`agent.strategy.ball_lost`: searching instead of playing), and each fall: time, team,
unum, distance to the ball, nearest opponent and nearest teammate (distance and name), skill
before the fall.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from agent.match import run_match
from agent.strategy import ball_lost
from benchmarks.match import (
    DEFAULT_TEAM_FILE,
    _recorded,
    add_set_option,
    small_team,
    team_with_overrides,
)

#: the ball counts as contested with robots of both teams this close (m)
CONTEST_M = 0.7
CYCLE_S = 0.02


def _nearest(places: dict, key: tuple, same_team: bool) -> tuple[float, str]:
    """Distance (m) from the robot ``key`` to the nearest other robot of its own team
    (``same_team``) or of the other, and that robot's name (99 and "-" with none)."""
    return min(
        (
            (math.dist(place, places[key]), f"{other[0]}{other[1]}")
            for other, place in places.items()
            if other != key and (other[0] == key[0]) == same_team
        ),
        default=(99.0, "-"),
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--players", type=int, default=3)
    parser.add_argument("--duration", type=float, default=120.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--config")
    parser.add_argument(
        "--window",
        type=float,
        nargs=2,
        default=None,
        metavar=("T0", "T1"),
        help="print every robot each 0.5 s between these game times",
    )
    add_set_option(parser)
    args = parser.parse_args()
    base = None
    if args.config or args.set:
        base = team_with_overrides(args.config or DEFAULT_TEAM_FILE, args.set)
    left = _recorded(small_team("NaoLeft", args.players, base))
    right = _recorded(small_team("NaoRight", args.players, base))
    active_time = {"L": Counter(), "R": Counter()}
    contested = Counter()
    falls = []
    fallen: set = set()
    last_skill: dict = {}
    zones = Counter()
    lost = Counter()

    def on_cycle(session) -> None:
        if session.referee.play_mode != "PlayOn":
            return
        bx, by, _ = session.ball.position()
        new_falls = []
        agents = {(a.config.team_name[3], a.world.unum): a for a in left.made + right.made}
        places = {}
        for slot in session.agents.values():
            if slot.robot is None:
                continue
            key = (slot.team_name[3], slot.unum)
            places[key] = slot.robot.torso_position()[:2]
            agent = agents.get(key)
            run = None if agent is None else agent.behavior.current
            skill = "-" if run is None else run.name
            is_fallen = slot.robot.has_fallen()
            if is_fallen and key not in fallen:
                new_falls.append((key, last_skill.get(key, "-")))
            (fallen.add if is_fallen else fallen.discard)(key)
            if not is_fallen and skill != "get_up":
                last_skill[key] = skill
                if agent is not None and ball_lost(agent.world):
                    lost[key[0]] += CYCLE_S
            if agent is not None and agent.strategy._was_active:
                st = agent.strategy
                label = skill
                if st._escape is not None:
                    label += "+escape"
                if st._shooting:
                    label += "+shot"
                active_time[key[0]][label] += CYCLE_S
        for key, skill in new_falls:
            opp = _nearest(places, key, same_team=False)
            mate = _nearest(places, key, same_team=True)
            dist = math.dist(places[key], (bx, by))
            falls.append((session.referee.game_time, key, dist, skill, opp, mate))
        near = {
            t: min((math.dist(p, (bx, by)) for k, p in places.items() if k[0] == t), default=99)
            for t in "LR"
        }
        if near["L"] < CONTEST_M and near["R"] < CONTEST_M:
            contested["both"] += CYCLE_S
        elif near["L"] < CONTEST_M:
            contested["L only"] += CYCLE_S
        elif near["R"] < CONTEST_M:
            contested["R only"] += CYCLE_S
        else:
            contested["none"] += CYCLE_S
        zones[round(bx / 5.0) * 5] += CYCLE_S
        now = session.referee.game_time
        if args.window and args.window[0] <= now <= args.window[1] and session.cycle % 25 == 0:
            print(f"t {now:6.1f} ball {bx:6.2f} {by:5.2f}")
            for key, agent in sorted(agents.items()):
                if key not in places:
                    continue
                st, w = agent.strategy, agent.world
                run = agent.behavior.current
                est = w.ball.position
                est_txt = "-" if est is None else f"{est[0]:5.2f} {est[1]:5.2f}"
                sign = 1.0 if key[0] == "L" else -1.0
                px, py = places[key]
                print(
                    f"   {key[0]}{key[1]} at {px:6.2f} {py:5.2f} "
                    f"{'-' if run is None else run.name:14s} "
                    f"act {int(st._was_active)} drib {int(st._dribbling)} "
                    f"esc {int(st._escape is not None)} shot {int(st._shooting)} "
                    f"lost {w.ball.time_since_seen:4.1f} est(team) {est_txt} "
                    f"true(team) {sign * bx:5.2f} {sign * by:5.2f}"
                )

    result = run_match(
        args.duration, args.seed, left, right, on_event=lambda s: None, on_cycle=on_cycle
    )
    print(f"seed {args.seed}: {result.score_left}-{result.score_right}, falls {len(falls)}")
    for team in "LR":
        items = sorted(active_time[team].items(), key=lambda kv: -kv[1])
        print(f"  {team} active: " + ", ".join(f"{k} {v:.0f}" for k, v in items))
    print("  ball near: " + ", ".join(f"{k} {v:.0f}" for k, v in contested.items()))
    print("  ball lost (player-seconds up): " + ", ".join(f"{k} {lost[k]:.0f}" for k in "LR"))
    print("  ball x zone: " + ", ".join(f"{k:+d} {v:.0f}" for k, v in sorted(zones.items())))
    for t, key, dist, skill, opp, mate in falls:
        print(
            f"  fall {t:6.1f} {key[0]}{key[1]} ball {dist:4.2f} opp {opp[0]:4.2f} {opp[1]} "
            f"mate {mate[0]:4.2f} {mate[1]} after {skill}"
        )


if __name__ == "__main__":
    main()
