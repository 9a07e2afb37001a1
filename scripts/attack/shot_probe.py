"""What becomes of a match's shots: every run of ``basic_kick`` by any player, from the cycle
the strategy starts it to the cycle it stops, with the time it spent in each of the skill's
phases, whether it reached its kick, how near the nearest opponent came, and whether a goal
for the shooter's team followed.

A diagnostic, not a benchmark (it reads the simulator's ground truth to classify, never to
act): the matches are ``benchmarks.match.play``'s (same seeds and teams), so score and falls
repeat the benchmark's for a seed on one machine.

Run: ``python scripts/attack/shot_probe.py --players 3 --matches 4 --seed S [--set KEY=VALUE]``;
prints one line per shot and a summary (shots, kicks, median seconds from the start to the
kick, goals within ``GOAL_AFTER_S`` of a kick, what the shots that never kicked ended in).
Why: the session-32 traces showed attackers in ``basic_kick`` for 10-16 s in range of the goal
while a defender walked up and took the ball.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from agent.match import run_match
from benchmarks.match import probe_parser, probe_teams

#: a goal this soon (s) after a shot's kick counts for the shot
GOAL_AFTER_S = 10.0
CYCLE_S = 0.02


@dataclass
class Shot:
    """One run of ``basic_kick`` by one player."""

    match_seed: int
    player: str
    start_s: float
    ball_to_goal_m: float
    opponent_at_start_m: float
    phases: Counter = field(default_factory=Counter)
    kick_s: float | None = None
    end_s: float | None = None
    ended_in: str = ""
    next_skill: str = ""
    nearest_opponent_m: float = 99.0
    goal: bool = False

    def line(self) -> str:
        kick = "-" if self.kick_s is None else f"{self.kick_s - self.start_s:5.1f}"
        phases = " ".join(f"{k}:{v:.1f}" for k, v in self.phases.items())
        end = f"ended {self.end_s - self.start_s:5.1f} s in {self.ended_in} -> {self.next_skill}"
        return (
            f"seed {self.match_seed} {self.player} t {self.start_s:6.1f} "
            f"goal {self.ball_to_goal_m:4.1f} m "
            f"opp {self.opponent_at_start_m:4.1f} (min {self.nearest_opponent_m:4.1f}) "
            f"kick after {kick} s, {end}{' GOAL' if self.goal else ''} | {phases}"
        )


def probe_match(args: argparse.Namespace, seed: int) -> list[Shot]:
    """The shots of one match (see the module docstring)."""
    left, right = probe_teams(args)
    open_shots: dict[tuple[str, int], Shot] = {}
    shots: list[Shot] = []

    def close(key: tuple[str, int], shot: Shot, now: float, next_skill: str) -> None:
        shot.end_s = now
        shot.next_skill = next_skill
        shots.append(shot)
        del open_shots[key]

    def on_cycle(session) -> None:
        now = session.referee.game_time
        bx, by, _ = session.ball.position()
        places = {
            (slot.team_name[3], slot.unum): slot.robot.torso_position()[:2]
            for slot in session.agents.values()
            if slot.robot is not None
        }
        for agent in left.made + right.made:
            key = (agent.config.team_name[3], agent.world.unum)
            run = agent.behavior.current
            name = "-" if run is None else run.name
            shot = open_shots.get(key)
            if name != "basic_kick" or session.referee.play_mode != "PlayOn":
                if shot is not None:
                    close(key, shot, now, name if name != "basic_kick" else "play stopped")
                continue
            opponent = min(
                (math.dist(p, (bx, by)) for k, p in places.items() if k[0] != key[0]),
                default=99.0,
            )
            if shot is None:
                goal_x = 15.0 if key[0] == "L" else -15.0
                shot = open_shots[key] = Shot(
                    seed, f"{key[0]}{key[1]}", now, math.dist((bx, by), (goal_x, 0.0)), opponent
                )
            phase = agent.behavior.skill("basic_kick").phase
            shot.phases[phase] += CYCLE_S
            shot.ended_in = phase
            shot.nearest_opponent_m = min(shot.nearest_opponent_m, opponent)
            if phase == "kick" and shot.kick_s is None:
                shot.kick_s = now

    def on_event(text: str) -> None:
        if "goal for" not in text:
            return
        now = float(text.split("]")[0].strip("[ "))
        team = "L" if "NaoLeft" in text else "R"
        for shot in shots + list(open_shots.values()):
            kicked = shot.kick_s is not None and 0.0 <= now - shot.kick_s <= GOAL_AFTER_S
            if kicked and shot.player[0] == team:
                shot.goal = True

    result = run_match(args.duration, seed, left, right, on_event=on_event, on_cycle=on_cycle)
    for key, shot in list(open_shots.items()):
        close(key, shot, result.game_time, "match over")
    print(f"# match seed {seed}: {result.score_left}-{result.score_right}", flush=True)
    return shots


def summary(shots: list[Shot]) -> list[str]:
    kicked = [s for s in shots if s.kick_s is not None]
    lines = [
        f"shots: {len(shots)}",
        f"shots_kicked: {len(kicked)}",
        f"shots_goal: {sum(s.goal for s in shots)}",
    ]
    if kicked:
        seconds = [s.kick_s - s.start_s for s in kicked]
        lines.append(f"shot_seconds_to_kick_median: {statistics.median(seconds):.1f}")
    ended = Counter(f"{s.ended_in}->{s.next_skill}" for s in shots if s.kick_s is None)
    lines.append("not kicked, ended in: " + ", ".join(f"{k} {v}" for k, v in ended.most_common()))
    return lines


def main() -> None:
    parser = probe_parser(__doc__.split("\n\n")[0])
    parser.add_argument("--matches", type=int, default=1)
    args = parser.parse_args()
    shots: list[Shot] = []
    for k in range(args.matches):
        new = probe_match(args, args.seed + k)
        for shot in new:
            print(shot.line(), flush=True)
        shots.extend(new)
    for line in summary(shots):
        print(line)


if __name__ == "__main__":
    main()
