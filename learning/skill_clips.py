"""Short headless GIF clips of single skills, so a reader can see the gaits (README).

Each clip is a scenario: a robot joins an in-process session, a setup places it (and the ball)
with the trainer commands the real server also has, then the skill runs through the same
perception and effector bytes as in a match (:class:`~learning.local_agent.LocalAgent`), and
PyBullet's software renderer takes every ``every``-th cycle from a camera that follows the robot.

    python -m learning.skill_clips walk kick --out-dir docs/skills
    python -m learning.skill_clips --list
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from benchmarks.kick import place_ball
from learning.falls import knock_over
from learning.local_agent import LocalAgent
from sim.render import Renderer, save_gif
from sim.session import Session, SessionConfig

#: One clip's behaviour: runs the session one cycle per ``next()``.
Scenario = Callable[[LocalAgent], Iterator[None]]


@dataclass(frozen=True)
class Clip:
    """A named scenario with its camera settings."""

    scenario: Scenario
    seconds: float
    description: str
    camera_distance: float = 1.6
    #: seen from ahead and to the left of a robot walking along +x: robot and ball both show
    camera_yaw_deg: float = 40.0
    camera_pitch_deg: float = -30.0


def _place_ball(agent: LocalAgent, forward: float, left: float = 0.0) -> None:
    """Trainer placement of the ball at rest ``forward``/``left`` m from the torso (through
    the kick trials' :func:`~benchmarks.kick.place_ball`, play mode left as it is)."""
    x, y, _ = agent.robot.torso_position()
    yaw = math.radians(agent.robot.torso_yaw_deg())
    bx = x + forward * math.cos(yaw) - left * math.sin(yaw)
    by = y + forward * math.sin(yaw) + left * math.cos(yaw)
    place_ball(agent, bx, by, play_on=False)


def _repeat(agent: LocalAgent, name: str, *args: object) -> Iterator[None]:
    while True:
        agent.run(name, *args)
        yield


def walk_clip(agent: LocalAgent) -> Iterator[None]:
    """Forward at full speed, then a turn, then sideways."""
    for command, cycles in (((1.0, 0.0, 0.0), 100), ((0.3, 0.0, 60.0), 60), ((0.0, 0.4, 0.0), 60)):
        for _ in range(cycles):
            agent.run("walk_velocity", *command)
            yield


def kick_clip(agent: LocalAgent) -> Iterator[None]:
    """The keyframe kick with the left foot from a stand, ball placed before the foot."""
    _place_ball(agent, 0.16, 0.05)
    agent.run("pose", "stand")
    yield
    while not agent.run("kick", "left", 1.0):
        yield
    yield from _repeat(agent, "pose", "stand")


def basic_kick_clip(agent: LocalAgent) -> Iterator[None]:
    """Approach, align and kick a ball 1 m away towards the opponent goal."""
    _place_ball(agent, 1.0, 0.3)
    while not agent.run("basic_kick", 15.0, 0.0, "long"):
        yield
    yield from _repeat(agent, "pose", "stand")


def _dribble_clip(kind: str, foot: str) -> Scenario:
    def clip(agent: LocalAgent) -> Iterator[None]:
        _place_ball(agent, 0.3)
        yield from _repeat(agent, "dribble", kind, 0.0, foot)

    clip.__doc__ = f"{kind.upper()} with the {foot} foot towards the opponent goal."
    return clip


def get_up_clip(agent: LocalAgent) -> Iterator[None]:
    """Pushed over backwards by its own joints (most falls end on the back), then the get-up."""
    knock_over(agent, "back", np.random.default_rng(3))
    for _ in range(10):
        agent.send({})
        yield
    while not agent.run("get_up"):
        yield
    yield from _repeat(agent, "pose", "stand")


CLIPS: dict[str, Clip] = {
    "walk": Clip(walk_clip, 4.4, "omnidirectional walk", camera_distance=2.2),
    "kick": Clip(kick_clip, 2.5, "keyframe kick, left foot"),
    "basic_kick": Clip(basic_kick_clip, 17.0, "approach, align, kick", camera_distance=2.2),
    "dfdl": Clip(_dribble_clip("dfdl", "left"), 4.0, "double-footed dribble", 2.2),
    "lfdl": Clip(_dribble_clip("lfdl", "left"), 4.0, "left-footed dribble", 2.2),
    "lfdl_right": Clip(_dribble_clip("lfdl", "right"), 4.0, "LFDL mirrored", 2.2),
    "get_up": Clip(get_up_clip, 6.0, "fall onto the back, get up"),
}


def render_clip(
    name: str,
    path: str | Path,
    robot_type: int = 0,
    every: int = 3,
    seed: int = 0,
    seconds: float | None = None,
) -> Path:
    """Run clip ``name`` (for ``seconds``, default the clip's own length) and write its GIF."""
    clip = CLIPS[name]
    session = Session(SessionConfig(seed=seed, beam_noise=False))
    try:
        agent = LocalAgent.join(session, "Clip", 1, robot_type, beam=(-3.0, 0.0, 0.0))
        agent.trainer("(playMode PlayOn)")
        agent.rise_to_stand()
        renderer = Renderer(session, width=360, height=240)
        frames = []
        scenario = clip.scenario(agent)
        for cycle in range(round((seconds or clip.seconds) / 0.02)):
            next(scenario)
            if cycle % every == 0:
                x, y, _ = agent.robot.torso_position()
                frames.append(
                    renderer.frame(
                        target=(x, y, 0.2),
                        distance=clip.camera_distance,
                        yaw_deg=clip.camera_yaw_deg,
                        pitch_deg=clip.camera_pitch_deg,
                    )
                )
        return save_gif(frames, path, fps=50.0 / every)
    finally:
        session.close()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("clips", nargs="*", help=f"clip names ({', '.join(CLIPS)})")
    parser.add_argument("--out-dir", default="docs/skills")
    parser.add_argument("--type", type=int, default=0, help="robot type 0-4")
    parser.add_argument("--every", type=int, default=3, help="render every Nth cycle")
    parser.add_argument("--list", action="store_true", help="list the clips and exit")
    args = parser.parse_args(argv)
    if args.list or not args.clips:
        for name, clip in CLIPS.items():
            print(f"{name}: {clip.description}")
        return 0
    unknown = [name for name in args.clips if name not in CLIPS]
    if unknown:
        parser.error(f"unknown clip(s) {unknown}; known: {', '.join(CLIPS)}")
    for name in args.clips:
        path = render_clip(name, Path(args.out_dir) / f"{name}.gif", args.type, args.every)
        print(f"{name}: {path}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
