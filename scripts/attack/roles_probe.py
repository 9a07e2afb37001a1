"""How well a k v k team settles who goes for the ball: per team, the PlayOn seconds with no,
one and two or more active players (``Strategy._was_active``), how long the ball lies free
(no robot within ``FREE_M``) while the team's nearest robot is not the active one, and per
player the seconds it had lost the ball (``agent.strategy.ball_lost``, any play mode).

A diagnostic, not a benchmark (it reads the simulator's ground truth to classify, never to
act): the match is ``benchmarks.match.play``'s, same seeds and teams.

Run: ``python scripts/attack/roles_probe.py --seed S [--duration 120] [--set KEY=VALUE ...]``.
"""

from __future__ import annotations

import math
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from agent.match import run_match
from agent.strategy import ball_lost
from benchmarks.match import probe_parser, probe_teams

#: the ball counts as free with no robot this close (m)
FREE_M = 0.7
CYCLE_S = 0.02


def main() -> None:
    args = probe_parser(__doc__.split("\n\n")[0]).parse_args()
    left, right = probe_teams(args)
    counts = {"L": Counter(), "R": Counter()}
    wrong = Counter()
    switches = Counter()
    idle = {"L": Counter(), "R": Counter()}
    last_active: dict = {}
    lost = Counter()

    def on_cycle(session) -> None:
        for agent in left.made + right.made:
            if agent.world.time is not None and ball_lost(agent.world):
                lost[f"{agent.config.team_name[3]}{agent.config.unum}"] += CYCLE_S
        if session.referee.play_mode != "PlayOn":
            return
        bx, by, _ = session.ball.position()
        agents = {(a.config.team_name[3], a.world.unum): a for a in left.made + right.made}
        places = {}
        for slot in session.agents.values():
            if slot.robot is not None:
                places[(slot.team_name[3], slot.unum)] = slot.robot.torso_position()[:2]
        free = all(math.dist(p, (bx, by)) > FREE_M for p in places.values())
        for team in "LR":
            mine = {k: a for k, a in agents.items() if k[0] == team and k in places}
            active = sorted(k[1] for k, a in mine.items() if a.strategy._was_active)
            counts[team][min(len(active), 2)] += CYCLE_S
            if not active:
                idle[team][_why_idle(mine)] += CYCLE_S
            if len(active) == 1 and last_active.get(team) not in (None, active[0]):
                switches[team] += 1
            if len(active) == 1:
                last_active[team] = active[0]
            if free and mine:
                nearest = min(mine, key=lambda k: math.dist(places[k], (bx, by)))
                if not mine[nearest].strategy._was_active:
                    wrong[team] += CYCLE_S

    result = run_match(
        args.duration, args.seed, left, right, on_event=lambda s: None, on_cycle=on_cycle
    )
    print(f"seed {args.seed}: {result.score_left}-{result.score_right}")
    for team in "LR":
        c = counts[team]
        print(
            f"  {team} active 0: {c[0]:.0f} s, 1: {c[1]:.0f} s, 2+: {c[2]:.0f} s; "
            f"hand-overs {switches[team]}; free ball, nearest not active {wrong[team]:.0f} s"
        )
        print("    none active: " + ", ".join(f"{k} {v:.0f} s" for k, v in idle[team].items()))
    per_player = " ".join(f"{k} {v:.1f}" for k, v in sorted(lost.items()))
    print(f"  ball lost (s): {per_player}; all players {sum(lost.values()):.1f}")


def _why_idle(agents: dict) -> str:
    """Why no player of a team is active: every field player down, the ball lost to all,
    or the claims (someone could go but believes a teammate is closer)."""
    field = [a for a in agents.values() if not a.strategy.is_goalie(a.world)]
    up = [a for a in field if not (a.world.robot.is_fallen or a.strategy._getting_up)]
    if not up:
        return "all down"
    if all(ball_lost(a.world) for a in up):
        return "ball lost"
    return "claims"


if __name__ == "__main__":
    main()
