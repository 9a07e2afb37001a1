"""Per-cycle trace of one get-up trial, to see why a trial of ``benchmarks/get_up.py`` fails.

Why: a success rate says how often the get-up fails, not where. The trace prints, every
``--every`` cycles, what the skill believes (attempt, side lying on, sequence and time into it,
perceived tilt) next to the simulator's ground truth (torso pitch and roll, torso height as a
fraction of standing height), so a failed sit-up, a tip-over in the crouch or a roll that does
not turn the body can be told apart.

``--contacts`` adds the pairs of the robot's own parts that touch each other, with their summed
normal force (N), and their impulses over the trial at the end. Why: the real rcssserver3d never
collides a robot's parts with each other (``benchmarks/physics.py --variant noself``), and the
back sit-ups of session 10 stood robots up only while the forearms pressed the rising thighs.

Run (the trial numbers come from ``benchmarks/get_up.py --show-failures``)::

    .venv/bin/python learning/get_up_trace.py --type 1 --direction back --seed 1004
    .venv/bin/python benchmarks/physics.py --variant noself --run learning/get_up_trace.py \\
        --type 1 --direction back --seed 1001
"""

from __future__ import annotations

import argparse
import collections
import math
import sys
from pathlib import Path

import pybullet

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.get_up import GetUpSkill
from behaviors.joint_control import CYCLE_SECONDS
from benchmarks.get_up import run_trial
from learning.local_agent import LocalAgent
from world.nao_model import ROBOT_TYPES


def torso_pitch_roll_deg(agent: LocalAgent) -> tuple[float, float]:
    """Ground truth: forward lean (positive forwards) and sideways lean (positive right), from
    the torso's z axis in the world frame expressed in its own frame."""
    rotation = agent.robot.torso_world_transform()[:3, :3]
    up_x, up_y, up_z = rotation[2, 0], rotation[2, 1], rotation[2, 2]
    return math.degrees(math.atan2(-up_y, up_z)), math.degrees(math.atan2(-up_x, up_z))


def trace_line(agent: LocalAgent, cycle: int) -> str:
    """One line of the trace: the skill's view, then the simulator's."""
    skill = agent.behavior.skill("get_up")
    assert isinstance(skill, GetUpSkill)
    playing = f"{skill.playing[0]} {skill.playing[1]:4.2f}s" if skill.playing else "-"
    pitch, roll = torso_pitch_roll_deg(agent)
    height = float(agent.robot.torso_position()[2]) / agent.robot.spec.sole_height()
    state = agent.state
    return (
        f"t {cycle * 0.02:4.2f} attempt {skill.attempts} on {skill.lying_on} {playing:28s} "
        f"tilt {state.tilt_deg:5.1f} gyro {float(abs(state.gyro_deg_s).max()):4.0f} | "
        f"pitch {pitch:6.1f} roll {roll:6.1f} height {height:4.2f}"
    )


def self_contact_forces(agent: LocalAgent, min_force: float = 1.0) -> dict[str, float]:
    """Summed normal force (N) per pair of the robot's own links now (``a-b``, sorted), pairs
    under ``min_force`` left out."""
    robot = agent.robot
    forces: dict[str, float] = collections.defaultdict(float)
    for point in pybullet.getContactPoints(
        bodyA=robot.body_id, bodyB=robot.body_id, physicsClientId=robot.world.client
    ):
        a, b = sorted((robot.link_name(point[3]), robot.link_name(point[4])))
        forces[f"{a}-{b}"] += point[9] / 2.0  # a self-contact is reported from either side
    return {pair: force for pair, force in forces.items() if force >= min_force}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--type", type=int, choices=ROBOT_TYPES, default=0)
    parser.add_argument("--direction", default="front")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--every", type=int, default=5, help="print every N-th cycle")
    parser.add_argument("--contacts", action="store_true", help="self-contacts (N) too")
    args = parser.parse_args()
    impulses: dict[str, float] = collections.defaultdict(float)

    def observe(agent: LocalAgent, cycle: int) -> None:
        forces = self_contact_forces(agent) if args.contacts else {}
        for pair, force in forces.items():
            impulses[pair] += force * CYCLE_SECONDS
        if cycle % args.every == 0:
            pairs = " ".join(f"{p}:{f:.0f}" for p, f in sorted(forces.items(), key=lambda x: -x[1]))
            print(trace_line(agent, cycle) + (f" | {pairs}" if args.contacts else ""))

    print(run_trial(args.type, args.direction, args.seed, observer=observe))
    for pair, impulse in sorted(impulses.items(), key=lambda x: -x[1]):
        print(f"self-contact impulse {pair}: {impulse:.1f} N s")


if __name__ == "__main__":
    main()
