"""The ``naosoccer`` command line.

Subcommands import their heavy parts (PyBullet for the server) only when they run, so that
``import agent`` stays light for a playing agent.
"""

from __future__ import annotations

import argparse
import logging
import signal
import sys
import threading
from collections.abc import Sequence

SERVER_EXAMPLES = """examples:
  naosoccer server                      real-time server on 127.0.0.1:3100 (monitor 3200)
  naosoccer server --sync --seed 7      wait for every agent's (syn), as fast as possible
  naosoccer server --sync --pipeline    the same, physics overlapping the agents' thinking
  naosoccer server --host 0.0.0.0 --port 3100 --monitor-port 3200 --config config/server.yaml
"""

TEAM_EXAMPLES = """examples:
  naosoccer team                                  11 agents against 127.0.0.1:3100
  naosoccer team --name Alpha --host 10.0.0.5     against a real rcssserver3d elsewhere
  naosoccer team --config config/team.yaml
"""

MATCH_EXAMPLES = """examples:
  naosoccer match --duration 20 --seed 1         a short match, events and the score
  naosoccer match --duration 20 --seed 1 --one-process    the same match on one core
  naosoccer match --duration 600 --monitor-port 3200   a full game RoboViz can watch
"""

TRAIN_EXAMPLES = """examples:
  nice -n 5 naosoccer train --config config/train/get_up.yaml --out runs/get_up_1
  naosoccer train --config config/train/get_up.yaml --out runs/short --max-minutes 10
"""

DEMO_EXAMPLES = """examples:
  naosoccer demo                        embedded server + a scripted client for 5 s
  naosoccer demo --cycles 1000          a longer run
"""


def main(argv: Sequence[str] | None = None) -> int:
    parser = _build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=getattr(logging, args.log_level.upper()),
        format="%(asctime)s %(levelname)-7s %(name)s: %(message)s",
    )
    if not hasattr(args, "run"):
        parser.print_help()
        return 2
    try:
        return args.run(args)
    except KeyboardInterrupt:
        return 130
    except (OSError, ValueError, RuntimeError) as exc:
        print(f"naosoccer: error: {exc}", file=sys.stderr)
        return 1


def _build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="naosoccer", description="RoboCup 3D soccer with simulated NAO robots."
    )
    parser.add_argument(
        "--log-level", default="info", choices=["debug", "info", "warning", "error"]
    )
    commands = parser.add_subparsers(title="commands")

    server = commands.add_parser(
        "server",
        help="run the PyBullet stand-in for rcssserver3d",
        description="Run the stand-in server: agents on --port, monitors and trainers on "
        "--monitor-port, the real server's wire protocol on both.",
        epilog=SERVER_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    _add_server_options(server)
    server.set_defaults(run=_run_server)

    team = commands.add_parser(
        "team",
        help="launch a team of 11 agents against a server",
        description="Connect 11 agents (robot types by the rules) to a SimSpark-protocol server: "
        "ours or a real rcssserver3d. One process; agents join one at a time.",
        epilog=TEAM_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    team.add_argument("--host", default="127.0.0.1")
    team.add_argument("--port", type=int, default=3100, help="the server's agent port")
    team.add_argument("--name", default=None, help="team name (default: from --config)")
    team.add_argument("--config", help="team settings (YAML), e.g. config/team.yaml")
    team.set_defaults(run=_run_team)

    match = commands.add_parser(
        "match",
        help="the embedded server plus two teams: play and print the score",
        description="Start the stand-in server in this process with two 11-agent teams, kick "
        "off, print the referee's events and a final 'score:' line.",
        epilog=MATCH_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    match.add_argument("--duration", type=float, default=60.0, help="game seconds to play")
    match.add_argument("--seed", type=int, default=0)
    match.add_argument("--left", default="NaoLeft", help="left team name")
    match.add_argument("--right", default="NaoRight", help="right team name")
    match.add_argument(
        "--left-config",
        help="left team's settings (YAML, e.g. config/team.yaml; its name is "
        "replaced by --left); default: the built-in defaults, which config/team.yaml spells out",
    )
    match.add_argument("--right-config", help="right team's settings (YAML), as --left-config")
    match.add_argument("--monitor-port", type=int, help="open a monitor port (e.g. 3200)")
    match.add_argument("--real-time", action="store_true", help="no faster than 50 cycles/s")
    processes = match.add_mutually_exclusive_group()
    processes.add_argument(
        "--agent-worker",
        action="store_true",
        help="the agents think in a second process while the server simulates (the same game "
        "as in one process, seed for seed; uses a second core): the default on 2+ cores",
    )
    processes.add_argument(
        "--one-process", action="store_true", help="server and agents in this process"
    )
    processes.add_argument(
        "--team-processes",
        action="store_true",
        help="run each team in its own process over TCP (uses a second core; not reproducible)",
    )
    match.set_defaults(run=_run_match)

    render = commands.add_parser(
        "render",
        help="render a short match to a GIF (headless, PyBullet's software renderer)",
        description="Play the embedded match and save every Nth cycle, seen from a camera "
        "that follows the ball, as an animated GIF.",
        epilog="examples:\n  naosoccer render --duration 4 --out match.gif",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    render.add_argument("--duration", type=float, default=4.0, help="game seconds")
    render.add_argument("--seed", type=int, default=0)
    render.add_argument("--every", type=int, default=5, help="render every Nth cycle")
    render.add_argument("--distance", type=float, default=6.0, help="camera distance (m)")
    render.add_argument("--out", default="match.gif", help="output GIF")
    render.set_defaults(run=_run_render)

    train = commands.add_parser(
        "train",
        help="train a policy with PPO from a YAML config and export it for numpy",
        description="Train with stable-baselines3 PPO (learning/train.py): the config names the "
        "environment and PPO's settings; the run directory gets the config, the git commit, "
        "checkpoints, the model and policy.npz (the actor a behaviour runs without torch).",
        epilog=TRAIN_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    train.add_argument("--config", required=True, help="training config (YAML)")
    train.add_argument("--out", required=True, help="run directory (created)")
    train.add_argument("--max-minutes", type=float, help="stop (and export) after this long")
    train.add_argument("--total-timesteps", type=int, help="override train.total_timesteps")
    train.add_argument("--seed", type=int, help="override train.seed")
    train.set_defaults(run=_run_train)

    demo = commands.add_parser(
        "demo",
        help="embedded server plus a short scripted client (the README's main job for now)",
        description="Start the stand-in server in this process and run a scripted client that "
        "connects over TCP, beams in, moves its joints and prints what it perceives.",
        epilog=DEMO_EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    demo.add_argument("--cycles", type=int, default=250, help="cycles to run (0.02 s each)")
    demo.add_argument("--seed", type=int, default=0)
    demo.set_defaults(run=_run_demo)
    return parser


def _run_train(args: argparse.Namespace) -> int:
    from learning.train import main as train_main  # torch: only when training

    argv = ["--config", args.config, "--out", args.out]
    for flag, value in (
        ("--max-minutes", args.max_minutes),
        ("--total-timesteps", args.total_timesteps),
        ("--seed", args.seed),
    ):
        if value is not None:
            argv += [flag, str(value)]
    train_main(argv)
    return 0


def _add_server_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--host", default="127.0.0.1", help="address to listen on")
    parser.add_argument("--port", type=int, default=3100, help="agent port (default 3100)")
    parser.add_argument(
        "--monitor-port", type=int, default=3200, help="monitor/trainer port (default 3200)"
    )
    pacing = parser.add_mutually_exclusive_group()
    pacing.add_argument(
        "--sync", action="store_true", help="wait for every agent's (syn), as fast as possible"
    )
    pacing.add_argument(
        "--real-time", action="store_true", help="50 cycles per second (the default)"
    )
    parser.add_argument(
        "--pipeline",
        action="store_true",
        help="simulate the next cycle while the agents think (the same game; agents in other "
        "processes then use another core; trainer commands act a cycle later)",
    )
    parser.add_argument("--seed", type=int, default=0, help="seed for all simulator noise")
    parser.add_argument("--config", help="server settings (YAML), e.g. config/server.yaml")


def _make_session(seed: int, config_path: str | None = None):
    from dataclasses import replace

    from sim.session import Session, SessionConfig

    config = SessionConfig.from_yaml(config_path) if config_path else SessionConfig()
    return Session(replace(config, seed=seed))


def _run_server(args: argparse.Namespace) -> int:
    from sim.server import SoccerServer

    session = _make_session(args.seed, args.config)
    server = SoccerServer(
        session, args.host, args.port, args.monitor_port, sync=args.sync, pipeline=args.pipeline
    )
    signal.signal(signal.SIGTERM, lambda *_: server.stop())
    mode = "sync" if args.sync else "real-time"
    print(
        f"naosoccer server ({mode}) on {args.host}: agents {server.port}, "
        f"monitor {server.monitor_port}; Ctrl-C stops it",
        flush=True,
    )
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.close()
        session.close()
    return 0


def _run_team(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from agent.team import TeamConfig, run_team_tcp

    config = TeamConfig.from_yaml(args.config) if args.config else TeamConfig()
    if args.name:
        config = replace(config, name=args.name)
    print(f"team {config.name}: 11 agents against {args.host}:{args.port}", flush=True)
    run_team_tcp(config, args.host, args.port)
    print(f"team {config.name}: the server closed the game")
    return 0


def _match_team(name: str, config_path: str | None):
    """A match team: the settings of ``config_path`` (or the defaults) under ``name``."""
    from dataclasses import replace

    from agent.team import TeamConfig

    if config_path is None:
        return TeamConfig(name)
    return replace(TeamConfig.from_yaml(config_path), name=name)


def _default_agent_worker(args: argparse.Namespace) -> bool:
    """Agents in a worker process unless asked otherwise or there is only one core: the game
    is the same either way, only faster with the physics and the thinking on two cores."""
    import os

    return not (args.one_process or args.team_processes) and (os.cpu_count() or 1) >= 2


def _run_match(args: argparse.Namespace) -> int:
    from agent.match import run_match

    agent_worker = args.agent_worker or _default_agent_worker(args)
    result = run_match(
        args.duration,
        seed=args.seed,
        left=_match_team(args.left, args.left_config),
        right=_match_team(args.right, args.right_config),
        monitor_port=args.monitor_port,
        real_time=args.real_time,
        on_event=lambda text: print(text, flush=True),
        team_processes=args.team_processes,
        agent_worker=agent_worker,
    )
    print(
        f"played {result.game_time:.1f} s of game time in {result.wall_seconds:.1f} s "
        f"({result.realtime_factor:.2f}x real time once all players had joined"
        f"{'; agents in a worker process' if agent_worker else ''})"
    )
    print(result.score_line())
    return 0


def _run_render(args: argparse.Namespace) -> int:
    from agent.match import run_match
    from sim.render import Renderer, save_gif

    frames = []
    renderers = {}

    def capture(session) -> None:
        if session.cycle % args.every:
            return
        renderer = renderers.setdefault(id(session), Renderer(session))
        frames.append(renderer.frame(distance=args.distance))

    result = run_match(args.duration, seed=args.seed, on_event=print, on_cycle=capture)
    path = save_gif(frames, args.out, fps=50 / args.every)
    print(f"{len(frames)} frames -> {path}")
    print(result.score_line())
    return 0


def _run_demo(args: argparse.Namespace) -> int:
    from agent.demo import run_demo_client
    from sim.server import SoccerServer

    session = _make_session(args.seed)
    server = SoccerServer(session, "127.0.0.1", 0, 0, sync=True)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    print(f"embedded server (sync mode) on 127.0.0.1:{server.port}, monitor {server.monitor_port}")
    try:
        received = run_demo_client("127.0.0.1", server.port, cycles=args.cycles)
    finally:
        server.stop()
        thread.join(timeout=5)
        server.close()
        session.close()
    print(f"demo finished: {received} perceptions received, simulated {received * 0.02:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
