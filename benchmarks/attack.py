"""Can a player score? The whole agent (world model, strategy, skills) attacking an empty field.

One agent of the left team (unum 10, the centre forward) joins an in-process session, beams to
its formation place before kick-off and stands; then the referee gives the left team the
kick-off and the game runs until the left team scores or ``--seconds`` of game time pass. The
agent sees only its perceptions and acts only through its effectors, exactly as over TCP (the
same bytes); nothing helps it along. Per trial: scored or not, game seconds from kick-off to the
goal, falls (the attacker's).

``--keeper``: the right team fields its goalkeeper (unum 1, the same strategy and skills), so
the attacker has to beat a keeper that guards its line and comes out for the ball: the
situation in which matches stall near the goal.

Run: ``.venv/bin/python benchmarks/attack.py [--trials 5] [--seconds 120] [--type 0] [--seed 0]
[--keeper] [--start-x X] [--config team.yaml] [--set strategy.attack.KEY=VALUE ...]``;
prints ``attack_goals``, ``attack_goal_rate``, ``attack_time_to_goal_s_median`` and
``attack_falls``.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from agent.agent import Agent, AgentConfig
from agent.strategy import Strategy
from agent.strategy_config import StrategyConfig
from benchmarks.match import DEFAULT_TEAM_FILE, add_set_option, team_with_overrides
from sim.physics import CYCLE_SECONDS
from sim.session import Session, SessionConfig

#: cycles before kick-off: beam, stand up, settle
PREPARE_CYCLES = 100
#: the attacker starts this far behind the ball (m)
START_BEHIND_BALL_M = 0.5
#: the start's y lies within this of the middle (m)
START_MAX_Y_M = 1.5


@dataclass(frozen=True)
class AttackResult:
    scored: bool
    #: game seconds from kick-off to the goal (None: no goal)
    time_to_goal_s: float | None
    falls: int


def run_attack(
    robot_type: int,
    seed: int,
    seconds: float,
    unum: int = 10,
    strategy: StrategyConfig | None = None,
    keeper: bool = False,
    trace_every_s: float = 0.0,
    start_x: float = 0.0,
) -> AttackResult:
    """One trial; see the module docstring. With ``trace_every_s`` it prints, that often, the
    ball's place and each robot's place and current skill (to see where an attack stalls);
    with ``start_x`` > 0 the trial starts at the goal (``--start-x``)."""
    session = Session(SessionConfig(seed=seed))
    try:
        agents = {}
        configs = [AgentConfig("Attackers", unum, robot_type)]
        if keeper:
            configs.append(AgentConfig("Keepers", 1, robot_type))
        for config in configs:  # the attackers join first: they play from the left
            slot = session.add_agent()
            agents[slot] = Agent(config, Strategy(strategy))
            session.handle_message(slot, agents[slot].greeting())
        for _ in range(PREPARE_CYCLES):
            _step(session, agents)
        if start_x > 0.0:
            session.trainer("(playMode PlayOn)" + _start_commands(start_x, seed, unum))
        else:
            session.trainer("(playMode KickOff_Left)")
        robot = session.agents[next(iter(agents))].robot
        falls, was_fallen = 0, False
        for cycle in range(round(seconds / CYCLE_SECONDS)):
            _step(session, agents)
            if trace_every_s and cycle % max(1, round(trace_every_s / CYCLE_SECONDS)) == 0:
                _trace(session, agents)
            fallen = robot.has_fallen()
            falls += fallen and not was_fallen
            was_fallen = fallen
            if session.referee.score_left > 0:
                return AttackResult(True, (cycle + 1) * CYCLE_SECONDS, falls)
        return AttackResult(False, None, falls)
    finally:
        session.close()


def _start_commands(start_x: float, seed: int, unum: int) -> str:
    """Trainer commands placing the ball at (``start_x``, y) and the attacker behind it
    facing +x (the trainer's angle 0 faces +y), y drawn from ``seed``."""
    y = random.Random(seed).uniform(-START_MAX_Y_M, START_MAX_Y_M)
    x = start_x - START_BEHIND_BALL_M
    return (
        f"(ball (pos {start_x} {y:.3f} 0.042) (vel 0 0 0))"
        f"(agent (unum {unum}) (team Left) (move {x} {y:.3f} 0.4 -90))"
    )


def _step(session: Session, agents: dict[int, Agent]) -> None:
    """One server cycle; every agent answers its perception."""
    session.step()
    for slot, agent in agents.items():
        session.handle_message(slot, agent.think(session.perception(slot)))


def _trace(session: Session, agents: dict[int, Agent]) -> None:
    """``# t ... ball x y | A10 x y skill | K1 ...`` (true places, field frame)."""
    x, y, _ = session.ball.position()
    parts = [f"#   t {session.referee.game_time:6.1f} ball {x:6.2f} {y:5.2f}"]
    for slot, agent in agents.items():
        robot = session.agents[slot].robot
        rx, ry = robot.torso_position()[:2]
        run = agent.behavior.current
        skill = run.name if run is not None else "-"
        fallen = " fallen" if robot.has_fallen() else ""
        parts.append(
            f"{agent.config.team_name[0]}{agent.config.unum} {rx:6.2f} {ry:5.2f} {skill}{fallen}"
        )
    print(" | ".join(parts), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=5)
    parser.add_argument("--seconds", type=float, default=120.0, help="game seconds per trial")
    parser.add_argument("--type", type=int, default=0, help="robot type 0-4")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--keeper", action="store_true", help="the right team fields its goalkeeper"
    )
    parser.add_argument(
        "--start-x",
        type=float,
        default=0.0,
        help="start at the goal: ball at this x, attacker behind it, PlayOn (0: kick-off)",
    )
    parser.add_argument(
        "--trace", type=float, default=0.0, help="print the scene every this many seconds"
    )
    parser.add_argument("--config", help="team YAML whose strategy to use (default: built-in)")
    add_set_option(parser)
    args = parser.parse_args()
    strategy = None
    if args.config or args.set:
        strategy = team_with_overrides(args.config or DEFAULT_TEAM_FILE, args.set).strategy
    results = []
    for k in range(args.trials):
        result = run_attack(
            args.type,
            args.seed + k,
            args.seconds,
            strategy=strategy,
            keeper=args.keeper,
            trace_every_s=args.trace,
            start_x=args.start_x,
        )
        results.append(result)
        time_text = f"{result.time_to_goal_s:.1f} s" if result.scored else "no goal"
        print(f"# trial {k}: {time_text}, falls {result.falls}", flush=True)
    times = [r.time_to_goal_s for r in results if r.time_to_goal_s is not None]
    print(f"attack_goals: {len(times)}/{len(results)}")
    print(f"attack_goal_rate: {len(times) / len(results):.2f}")
    median = f"{statistics.median(times):.1f}" if times else "nan"
    print(f"attack_time_to_goal_s_median: {median}")
    print(f"attack_falls: {sum(r.falls for r in results)}")


if __name__ == "__main__":
    main()
