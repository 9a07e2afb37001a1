"""Kick trials: a robot stands, the trainer places the ball in front of one foot, ``kick`` runs.

A trial: one robot in an in-process :class:`~sim.session.Session` beamed to (-1, 0) facing +x
rises slowly into ``stand``; the trainer puts the ball (at rest) ``gap`` metres in front of the
toe of the kicking foot and sets PlayOn. From then on the agent side runs alone through
perception bytes (``learning.local_agent.LocalAgent``) with ``execute("kick", foot, strength)``
until the skill finishes, then holds ``stand`` for three seconds while the ball rolls out.
Measured from the simulator: how far the ball went, its direction against the robot's facing,
whether the robot fell at any time, and the time from the first kick cycle to the first cycle
the ball moves (faster than 0.1 m/s).

Run: ``.venv/bin/python benchmarks/kick.py [--seeds 3] [--robot-type 0]``; prints
``kick_distance_m[strength=S]`` (median over seeds and both feet),
``kick_direction_error_deg_median``, ``kick_falls`` (count over all trials), ``kick_time_s``
(median).
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import behaviors.kick  # noqa: F401  (registers the built-in skills and the kick)
from behaviors.joint_control import CYCLE_SECONDS
from learning.local_agent import LocalAgent
from sim.session import Session, SessionConfig
from world.field_geometry import BALL_RADIUS

#: Where the robot stands (world x, y) and which way it faces (degrees, 0 = +x).
START = (-1.0, 0.0, 0.0)
#: Ball distance (m) from the kicking foot's toe, as the kick expects it (see ``kicks.yaml``).
DEFAULT_GAP = 0.03
#: The ball counts as set moving by the kick above this speed (m/s).
MOVING_SPEED = 0.1
#: Cycles to let the ball roll out after the kick (it stops within about 3 s).
ROLL_OUT_CYCLES = 150


@dataclass(frozen=True)
class KickResult:
    foot: str
    strength: float
    #: ball travel (m) from where it was placed to where it rests
    distance_m: float
    #: direction of travel against the robot's facing (deg, positive = to its left)
    direction_deg: float
    fell: bool
    #: seconds from the first kick cycle to the ball moving (None: it never moved)
    time_to_contact_s: float | None
    #: the ball's lateral position relative to the robot's centre line when placed (m, +left)
    ball_side_m: float


def stand_up(session: Session, robot_type: int) -> LocalAgent:
    """Join a robot at :data:`START`, rise slowly into ``stand`` and hold it half a second."""
    return LocalAgent.join(session, "Kickers", 1, robot_type, beam=START).rise_to_stand()


def place_ball_in_front_of(driver: LocalAgent, foot: str, gap: float) -> tuple[float, float]:
    """Trainer placement of the ball at rest ``gap`` m ahead of ``foot``'s toe; returns (x, y)."""
    robot = driver.session.agents[driver.agent].robot
    name = "lfoot" if foot == "left" else "rfoot"
    transform = robot.body_world_transforms()[name]
    centre, forward = transform[:3, 3], transform[:3, 1]  # native y = the foot's forward axis
    reach = robot.spec.body(name).size[1] / 2 + BALL_RADIUS + gap
    x, y = centre[0] + forward[0] * reach, centre[1] + forward[1] * reach
    driver.session.trainer(
        f"(playMode PlayOn)(ball (pos {x:.4f} {y:.4f} {BALL_RADIUS}) (vel 0 0 0))"
    )
    return float(x), float(y)


def run_trial(
    foot: str, strength: float, seed: int = 0, robot_type: int = 0, gap: float = DEFAULT_GAP
) -> KickResult:
    """One kick from a stand; see the module docstring for what is measured."""
    session = Session(SessionConfig(seed=seed, beam_noise=False))
    try:
        driver = stand_up(session, robot_type)
        robot = session.agents[driver.agent].robot
        bx, by = place_ball_in_front_of(driver, foot, gap)
        driver.run_skill("pose", "stand")  # the placement acts on the next cycle
        cycles, contact, fell = 0, None, False
        finished = False
        while not finished:
            finished = driver.run_skill("kick", foot, strength)
            cycles += 1
            if contact is None and session.ball.speed() > MOVING_SPEED:
                contact = cycles
            fell |= robot.has_fallen()
        for _ in range(ROLL_OUT_CYCLES):
            driver.run_skill("pose", "stand")
            fell |= robot.has_fallen()
        x, y, _ = session.ball.position()
        heading = math.radians(START[2])
        travel = math.degrees(math.atan2(y - by, x - bx)) - START[2]
        side = -(bx - START[0]) * math.sin(heading) + (by - START[1]) * math.cos(heading)
        return KickResult(
            foot,
            strength,
            math.hypot(x - bx, y - by),
            (travel + 180.0) % 360.0 - 180.0,
            fell,
            None if contact is None else contact * CYCLE_SECONDS,
            side,
        )
    finally:
        session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--robot-type", type=int, default=0)
    parser.add_argument("--strengths", type=float, nargs="+", default=[0.0, 0.25, 0.5, 0.75, 1.0])
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    results = []
    for strength in args.strengths:
        mine = []
        for seed in range(args.seeds):
            for foot in ("left", "right"):
                gap = DEFAULT_GAP + rng.uniform(-0.01, 0.01)  # placement a little off
                mine.append(run_trial(foot, strength, seed, args.robot_type, gap))
        results += mine
        print(f"kick_distance_m[strength={strength:g}]: "
              f"{statistics.median(r.distance_m for r in mine):.2f}")  # fmt: skip
    moved = [r for r in results if r.time_to_contact_s is not None]
    errors = [abs(r.direction_deg) for r in moved]
    times = [r.time_to_contact_s for r in moved]
    print(
        f"kick_direction_error_deg_median: {statistics.median(errors) if errors else math.nan:.1f}"
    )
    print(f"kick_falls: {sum(r.fell for r in results)} of {len(results)}")
    print(f"kick_time_s: {statistics.median(times) if times else math.nan:.2f}")
    print(f"kick_ball_untouched: {len(results) - len(moved)}")


if __name__ == "__main__":
    main()
