"""Do matches produce goals? Seeded short matches, k v k, through the real team and strategy.

Each match is ``agent.match.run_match`` (the embedded server and two in-process teams, the same
bytes as TCP), so everything a full 11 v 11 match runs is exercised; only the number of players
is smaller, because an 11 v 11 match runs at about 0.3x real time on a 2-core machine. With
``--players k`` each team fields the first ``k`` places of :data:`LINEUP_ORDER` (the centre
forward first, then the goalkeeper, ...), renumbered 1..k with the formation places and robot
types of the full team, so a 3 v 3 is a goalkeeper, a midfielder and a forward on each side.

Run: ``.venv/bin/python benchmarks/match.py [--players 3] [--matches 4] [--duration 60]
[--seed 0] [--config team.yaml] [--set strategy.attack.dribble_kind=lfdl ...]``
(``--set`` overrides one key of the team file, both teams; the value is read as YAML);
prints one line per match and ``match_goals``, ``match_goals_per_match``,
``match_with_goal``, ``match_right_team_goals`` (the right team plays the same code: a check
that the two sides are symmetric), ``match_falls_per_player_minute``,
``match_realtime_factor``.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import yaml

from agent.match import run_match
from agent.team import DEFAULT_ROBOT_TYPES, TeamConfig
from world.yaml_config import apply_overrides, config_from_mapping

#: The team file played when no ``--config`` is given (it spells out the built-in defaults).
DEFAULT_TEAM_FILE = Path(__file__).resolve().parents[1] / "config" / "team.yaml"

#: Which formation places (unums of the full team) a smaller team fields, in order.
LINEUP_ORDER: tuple[int, ...] = (10, 1, 7, 9, 11, 4, 5, 6, 8, 2, 3)


def small_team(name: str, players: int, base: TeamConfig | None = None) -> TeamConfig:
    """A team of ``players`` taking the first places of :data:`LINEUP_ORDER` of ``base``.

    The chosen places keep their full-team order (the goalkeeper stays unum 1 whenever it
    plays), their formation places and robot types; advancing players
    (``strategy.advance.unums``) and places in play (``strategy.play_places``) move to the new
    numbers, the absent players' dropped.
    """
    base = base or TeamConfig(name)
    if not 1 <= players <= len(LINEUP_ORDER):
        raise ValueError(f"players must be 1-{len(LINEUP_ORDER)}, got {players}")
    places = sorted(LINEUP_ORDER[:players])
    types = base.robot_types if len(base.robot_types) == 11 else DEFAULT_ROBOT_TYPES
    formation = {new: base.strategy.formation[old] for new, old in enumerate(places, start=1)}
    goalie = 1 if 1 in places else None
    renumber = {old: new for new, old in enumerate(places, start=1)}
    advance = replace(
        base.strategy.advance,
        unums=tuple(renumber[u] for u in base.strategy.advance.unums if u in renumber),
    )
    play_places = {
        renumber[old]: place for old, place in base.strategy.play_places.items() if old in renumber
    }
    strategy = replace(
        base.strategy,
        formation=formation,
        goalie_unum=goalie,
        advance=advance,
        play_places=play_places,
    )
    return replace(
        base,
        name=name,
        robot_types=tuple(types[old - 1] for old in places),
        strategy=strategy,
    )


@dataclass(frozen=True)
class RecordedTeam(TeamConfig):
    """A team that keeps the agents it makes, so a trace can say what each player does."""

    made: list = field(default_factory=list, compare=False, repr=False)

    def agents(self) -> list:
        made = super().agents()
        self.made.extend(made)
        return made


@dataclass(frozen=True)
class MatchFigures:
    score_left: int
    score_right: int
    falls: int
    player_minutes: float
    realtime_factor: float


def play(
    players: int,
    seed: int,
    duration_s: float,
    base: TeamConfig | None = None,
    trace_every_s: float = 0.0,
) -> MatchFigures:
    """One seeded match of ``players`` v ``players``; returns its :class:`MatchFigures`.
    With ``trace_every_s`` it prints the referee's events and, that often, the ball's place
    and the play mode (to see where a match got stuck)."""
    falls = {"count": 0, "fallen": set()}
    trace_cycles = round(trace_every_s / 0.02)

    def count_falls(session) -> None:
        if trace_cycles and session.cycle % trace_cycles == 0:
            skills = {
                (agent.config.team_name, agent.config.unum): agent.behavior
                for agent in left.made + right.made
            }
            x, y, _ = session.ball.position()
            near = _players_near(session, (x, y), 1.5, skills)
            print(
                f"#   t {session.referee.game_time:6.1f} ball {x:6.2f} {y:6.2f} "
                f"{session.referee.play_mode} fallen {len(falls['fallen'])} near {' '.join(near)}",
                flush=True,
            )
        for agent_id, slot in session.agents.items():
            if slot.robot is None:
                continue
            fallen = slot.robot.has_fallen()
            if fallen and agent_id not in falls["fallen"]:
                falls["count"] += 1
            (falls["fallen"].add if fallen else falls["fallen"].discard)(agent_id)

    left = _recorded(small_team("NaoLeft", players, base))
    right = _recorded(small_team("NaoRight", players, base))

    def events(text: str) -> None:
        if trace_cycles:
            print(text, flush=True)

    result = run_match(duration_s, seed, left, right, on_event=events, on_cycle=count_falls)
    return MatchFigures(
        result.score_left,
        result.score_right,
        falls["count"],
        2 * players * result.game_time / 60.0,
        result.realtime_factor,
    )


def add_set_option(parser: argparse.ArgumentParser) -> None:
    """``--set KEY=VALUE`` (repeatable): a team-file key overridden for this run."""
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a key of the team file, e.g. strategy.attack.dribble_kind=dfdl",
    )


def team_with_overrides(path: str | Path, overrides: list[str]) -> TeamConfig:
    """The team of the YAML file ``path`` with each ``dotted.key=value`` of ``overrides`` set
    (the value read as YAML), checked as the file itself is: so a comparison of two settings
    is one command line, not a hand-edited copy of the file."""
    data = yaml.safe_load(Path(path).read_text()) or {}
    apply_overrides(data, overrides, str(path))
    return config_from_mapping(TeamConfig, data, source=f"{path} with {overrides}")


def probe_parser(description: str) -> argparse.ArgumentParser:
    """The options of a one-match diagnostic (``scripts/attack/*_probe.py``): players,
    duration, seed, team file and ``--set``, as :func:`probe_teams` reads them."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--players", type=int, default=3)
    parser.add_argument("--duration", type=float, default=120.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--config")
    add_set_option(parser)
    return parser


def probe_teams(args: argparse.Namespace) -> tuple[RecordedTeam, RecordedTeam]:
    """The two recording teams of a diagnostic's match, as :func:`play` fields them."""
    base = None
    if args.config or args.set:
        base = team_with_overrides(args.config or DEFAULT_TEAM_FILE, args.set)
    return (
        _recorded(small_team("NaoLeft", args.players, base)),
        _recorded(small_team("NaoRight", args.players, base)),
    )


def _recorded(team: TeamConfig) -> RecordedTeam:
    return RecordedTeam(team.name, team.robot_types, team.strategy)


def _players_near(
    session, point: tuple[float, float], radius: float, skills: dict | None = None
) -> list[str]:
    """``L7@0.42:dribble``: team initial (of NaoLeft/NaoRight), unum, distance and current
    skill (when ``skills`` maps (team, unum) to the agent's behaviour) of each robot within
    ``radius`` of ``point``."""
    near = []
    for slot in session.agents.values():
        if slot.robot is None:
            continue
        distance = math.dist(slot.robot.torso_position()[:2], point)
        if distance < radius:
            behavior = (skills or {}).get((slot.team_name, slot.unum))
            run = None if behavior is None else behavior.current
            skill = "" if run is None else f":{run.name}"
            near.append(f"{(slot.team_name or '???')[3:4]}{slot.unum}@{distance:.2f}{skill}")
    return near


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--players", type=int, default=3, help="players per team, 1-11")
    parser.add_argument("--matches", type=int, default=4)
    parser.add_argument("--duration", type=float, default=60.0, help="game seconds per match")
    parser.add_argument("--seed", type=int, default=0, help="seed of the first match")
    parser.add_argument("--config", help="team YAML (default: the built-in team)")
    add_set_option(parser)
    parser.add_argument(
        "--trace",
        type=float,
        default=0.0,
        help="print events and the ball's place every this many game seconds (0: off)",
    )
    args = parser.parse_args()
    base = None
    if args.config or args.set:
        base = team_with_overrides(args.config or DEFAULT_TEAM_FILE, args.set)
    figures = []
    for k in range(args.matches):
        f = play(args.players, args.seed + k, args.duration, base, args.trace)
        figures.append(f)
        print(
            f"# match seed {args.seed + k}: {f.score_left}-{f.score_right}, falls {f.falls}, "
            f"{f.realtime_factor:.2f}x real time",
            flush=True,
        )
    goals = sum(f.score_left + f.score_right for f in figures)
    print(f"match_goals: {goals}")
    print(f"match_goals_per_match: {goals / len(figures):.2f}")
    with_goal = sum(1 for f in figures if f.score_left + f.score_right)
    print(f"match_with_goal: {with_goal}/{len(figures)}")
    print(f"match_right_team_goals: {sum(f.score_right for f in figures)}")
    minutes = sum(f.player_minutes for f in figures)
    print(f"match_falls_per_player_minute: {sum(f.falls for f in figures) / minutes:.2f}")
    rtf = sum(f.realtime_factor for f in figures) / len(figures)
    print(f"match_realtime_factor: {rtf:.2f}")


if __name__ == "__main__":
    main()
