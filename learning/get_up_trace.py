"""Per-cycle trace of one get-up trial, to see why a trial of ``benchmarks/get_up.py`` fails.

Why: a success rate says how often the get-up fails, not where. The trace prints, every
``--every`` cycles, what the skill believes (attempt, side lying on, sequence and time into it,
perceived tilt) next to the simulator's ground truth (torso pitch and roll, torso height as a
fraction of standing height), so a failed sit-up, a tip-over in the crouch or a roll that does
not turn the body can be told apart.

Run (the trial numbers come from ``benchmarks/get_up.py --show-failures``)::

    .venv/bin/python learning/get_up_trace.py --type 1 --direction back --seed 1004
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.get_up import GetUpSkill
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
        f"tilt {state.tilt_deg:5.1f} | pitch {pitch:6.1f} roll {roll:6.1f} height {height:4.2f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--type", type=int, choices=ROBOT_TYPES, default=0)
    parser.add_argument("--direction", default="front")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--every", type=int, default=5, help="print every N-th cycle")
    args = parser.parse_args()

    def observe(agent: LocalAgent, cycle: int) -> None:
        if cycle % args.every == 0:
            print(trace_line(agent, cycle))

    print(run_trial(args.type, args.direction, args.seed, observer=observe))


if __name__ == "__main__":
    main()
