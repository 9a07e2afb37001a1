"""Kick trials: ``kick`` from a stand with the ball placed at the foot, and ``basic_kick``.

Stand kicks: one robot in an in-process :class:`~sim.session.Session` beamed to (-1, 0) facing +x
rises slowly into ``stand``; the trainer puts the ball (at rest) where the kick expects it
(``ball_gap_m`` ahead of the kicking foot's toe, ``ball_side_m`` outwards, from ``kicks.yaml``)
and sets PlayOn. From then on the agent side runs alone through perception bytes
(``learning.local_agent.LocalAgent``) with ``execute("kick", foot, strength)`` until the skill
finishes, then holds ``stand`` for three seconds while the ball rolls out. Measured from the
simulator: how far the ball went, its direction against the robot's facing, whether the robot
fell at any time, and the time from the first kick cycle to the first cycle the ball moves
(faster than 0.1 m/s).

Basic kicks: the same standing robot, the ball 0.5-2 m away at a random bearing, a target
``distance`` m from the ball within 45 deg of the line robot -> ball;
``execute("basic_kick", x, y, distance)`` runs until it finishes (or 20 s). Measured: ball
travel from where it lay when the kick hit it, direction error against the target, falls, and
the time from the first ``basic_kick`` cycle to the ball moving (walking included).

Run: ``.venv/bin/python benchmarks/kick.py [--seeds 3] [--robot-type 0] [--strengths ...]
[--basic-trials 20] [--basic-distance 3|long]``; prints ``kick_distance_m[strength=S]``
(median over seeds and both feet), ``kick_direction_error_deg_median``, ``kick_falls``,
``kick_time_s`` (median), then ``basic_kick_distance_m``, ``basic_kick_direction_error_deg``,
``basic_kick_time_s`` (medians over the trials that kicked), ``basic_kick_falls`` and
``basic_kick_not_kicked``. ``--strengths`` with no value skips the stand kicks,
``--basic-trials 0`` the basic ones.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.joint_control import CYCLE_SECONDS
from behaviors.kick import KickMotion, kick_motion
from learning.local_agent import LocalAgent
from sim.session import Session, SessionConfig
from world.field_geometry import BALL_RADIUS

#: Where the robot stands (world x, y) and which way it faces (degrees, 0 = +x).
START = (-1.0, 0.0, 0.0)
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


def place_ball_in_front_of(
    driver: LocalAgent, foot: str, gap: float, side: float = 0.0
) -> tuple[float, float]:
    """Trainer placement of the ball at rest ``gap`` m ahead of ``foot``'s toe and ``side`` m
    outwards of its centre line; returns (x, y)."""
    robot = driver.session.agents[driver.agent].robot
    name = "lfoot" if foot == "left" else "rfoot"
    transform = robot.body_world_transforms()[name]
    centre, forward = transform[:3, 3], transform[:3, 1]  # native y = the foot's forward axis
    outwards = transform[:3, 0] * (-1.0 if foot == "left" else 1.0)  # native x = right
    reach = robot.spec.body(name).size[1] / 2 + BALL_RADIUS + gap
    x = centre[0] + forward[0] * reach + outwards[0] * side
    y = centre[1] + forward[1] * reach + outwards[1] * side
    driver.session.trainer(
        f"(playMode PlayOn)(ball (pos {x:.4f} {y:.4f} {BALL_RADIUS}) (vel 0 0 0))"
    )
    return float(x), float(y)


def run_trial(
    foot: str,
    strength: float,
    seed: int = 0,
    robot_type: int = 0,
    gap_error: float = 0.0,
    motions: Mapping[str, KickMotion] | None = None,
) -> KickResult:
    """One kick from a stand; see the module docstring for what is measured. The ball lies
    where the kick expects it (its ``ball_gap_m``, ``ball_side_m``) plus ``gap_error`` m
    further ahead; ``motions`` replaces the packaged kicks (searches)."""
    session = Session(SessionConfig(seed=seed, beam_noise=False))
    try:
        driver = stand_up(session, robot_type)
        driver.behavior.skill("kick").motions = motions
        motion = kick_motion(robot_type, motions)
        robot = session.agents[driver.agent].robot
        bx, by = place_ball_in_front_of(
            driver, foot, motion.ball_gap_m + gap_error, motion.ball_side_m
        )
        driver.run("pose", "stand")  # the placement acts on the next cycle
        cycles, contact, fell = 0, None, False
        finished = False
        while not finished:
            finished = driver.run("kick", foot, strength)
            cycles += 1
            if contact is None and session.ball.speed() > MOVING_SPEED:
                contact = cycles
            fell |= robot.has_fallen()
        for _ in range(ROLL_OUT_CYCLES):
            driver.run("pose", "stand")
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


@dataclass(frozen=True)
class BasicKickResult:
    """One ``basic_kick`` trial: walk from a stand to a ball 0.5-2 m away, align, kick."""

    #: the distance asked for (m) or "long"
    asked: float | str
    #: ball travel (m) from where it lay when the kick started to where it rests
    distance_m: float
    #: direction of travel against the direction to the target (deg, + = left of it)
    direction_error_deg: float
    fell: bool
    #: seconds from the first ``basic_kick`` cycle to the ball moving; None: never kicked
    time_to_kick_s: float | None
    #: the foot the skill chose (None if it never got that far)
    foot: str | None


#: Give a basic-kick trial this many cycles to reach the ball and kick (20 s).
BASIC_KICK_TIMEOUT_CYCLES = 1000


def random_basic_layout(rng: np.random.Generator) -> tuple[float, float, float]:
    """Ball distance (0.5-2 m) and bearing (deg, any) from the robot, and the target direction
    (deg, team frame) within 45 deg of the line from the robot to the ball: a kick forwards, as
    a player would choose it, without walking round the ball."""
    distance = rng.uniform(0.5, 2.0)
    bearing = rng.uniform(-180.0, 180.0)
    return distance, bearing, bearing + START[2] + rng.uniform(-45.0, 45.0)


def run_basic_trial(
    asked: float | str,
    seed: int,
    ball_distance: float,
    ball_bearing_deg: float,
    target_direction_deg: float,
    robot_type: int = 0,
) -> BasicKickResult:
    """One basic kick: see :class:`BasicKickResult`. The robot stands at :data:`START`; the
    ball lies at ``ball_distance`` m and ``ball_bearing_deg`` from its facing; the target is
    ``asked`` m (10 m for "long") from the ball in ``target_direction_deg``."""
    session = Session(SessionConfig(seed=seed, beam_noise=False))
    try:
        driver = stand_up(session, robot_type)
        robot = driver.robot
        angle = math.radians(START[2] + ball_bearing_deg)
        bx = START[0] + ball_distance * math.cos(angle)
        by = START[1] + ball_distance * math.sin(angle)
        driver.trainer(f"(playMode PlayOn)(ball (pos {bx:.4f} {by:.4f} {BALL_RADIUS}) (vel 0 0 0))")
        driver.run("pose", "stand")
        reach = 10.0 if isinstance(asked, str) else asked
        direction = math.radians(target_direction_deg)
        tx, ty = bx + reach * math.cos(direction), by + reach * math.sin(direction)
        cycles, contact, fell, finished = 0, None, False, False
        start = (bx, by)
        while not finished and cycles < BASIC_KICK_TIMEOUT_CYCLES:
            before = session.ball.position()
            finished = driver.run("basic_kick", tx, ty, asked)
            cycles += 1
            if contact is None and session.ball.speed() > MOVING_SPEED:
                contact, start = cycles, (before[0], before[1])
            fell |= robot.has_fallen()
        for _ in range(ROLL_OUT_CYCLES):
            driver.run("pose", "stand")
            fell |= robot.has_fallen()
        x, y, _ = session.ball.position()
        travel = math.degrees(math.atan2(y - start[1], x - start[0]))
        return BasicKickResult(
            asked,
            math.hypot(x - start[0], y - start[1]),
            (travel - target_direction_deg + 180.0) % 360.0 - 180.0,
            fell,
            None if contact is None else contact * CYCLE_SECONDS,
            driver.behavior.skill("basic_kick").foot,
        )
    finally:
        session.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--robot-type", type=int, default=0)
    parser.add_argument("--strengths", type=float, nargs="*", default=[0.0, 0.25, 0.5, 0.75, 1.0])
    parser.add_argument("--basic-trials", type=int, default=20)
    parser.add_argument(
        "--basic-distance", default="3", help='metres asked of basic_kick, or "long"'
    )
    args = parser.parse_args()
    if args.strengths:
        stand_kicks(args.seeds, args.robot_type, args.strengths)
    if args.basic_trials:
        asked = args.basic_distance if args.basic_distance == "long" else float(args.basic_distance)
        basic_kicks(args.basic_trials, args.robot_type, asked)


def basic_kicks(trials: int, robot_type: int, asked: float | str) -> None:
    """``basic_kick`` from a stand, the ball 0.5-2 m away at random bearings; medians."""
    rng = np.random.default_rng(1)
    results = []
    for seed in range(trials):
        layout = random_basic_layout(rng)
        results.append(run_basic_trial(asked, seed, *layout, robot_type=robot_type))
        r = results[-1]
        print(f"# trial {seed}: {r}", flush=True)
    kicked = [r for r in results if r.time_to_kick_s is not None]
    label = f"[asked={asked}]"

    def median(values: list[float]) -> float:
        return statistics.median(values) if values else math.nan

    print(f"basic_kick_distance_m{label}: {median([r.distance_m for r in kicked]):.2f}")
    errors = [abs(r.direction_error_deg) for r in kicked]
    print(f"basic_kick_direction_error_deg{label}: {median(errors):.1f}")
    print(f"basic_kick_time_s{label}: {median([r.time_to_kick_s for r in kicked]):.2f}")
    print(f"basic_kick_falls{label}: {sum(r.fell for r in results)} of {len(results)}")
    print(f"basic_kick_not_kicked{label}: {len(results) - len(kicked)} of {len(results)}")


def stand_kicks(seeds: int, robot_type: int, strengths: list[float]) -> None:
    """``kick`` from a stand with the ball placed at the foot: distance per strength."""
    rng = np.random.default_rng(0)
    results = []
    for strength in strengths:
        mine = []
        for seed in range(seeds):
            for foot in ("left", "right"):
                error = rng.uniform(-0.01, 0.01)  # placement a little off
                mine.append(run_trial(foot, strength, seed, robot_type, error))
        results += mine
        print(f"kick_distance_m[strength={strength:g}]: "
              f"{statistics.median(r.distance_m for r in mine):.2f}")  # fmt: skip
        print(f"kick_falls[strength={strength:g}]: {sum(r.fell for r in mine)} of {len(mine)}")
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
