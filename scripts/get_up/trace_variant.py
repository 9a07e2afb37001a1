"""Trace benchmark trials played with a screen variant: ``learning/get_up_trace.py``'s lines
(the skill's view next to the simulator's torso pitch, roll and height) for a variant of
``scripts/get_up/screen_sequences.py`` (edited or added sequences, ``knob:`` constants).

Why: a screen says how many trials a candidate motion stands up, not what the motion does;
designing a new one (a roll from the front onto the back) needs to see where the body goes.

Run::

    nice -n 5 .venv/bin/python scripts/get_up/trace_variant.py --trial 3:front:3000 \\
        --variant "roll_front_to_back=roll_front_to_back_candidate" --every 5
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import behaviors.get_up as get_up
from behaviors.get_up import GetUpSkill
from benchmarks.get_up import fall, play_get_up
from learning.get_up_trace import trace_line
from learning.local_agent import LocalAgent
from scripts.get_up.screen_sequences import variant_balances, variant_knobs, variant_sequences


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--trial", action="append", required=True, help="TYPE:DIRECTION:SEED")
    parser.add_argument("--variant", default="base")
    parser.add_argument("--every", type=int, default=5, help="print every N-th cycle")
    parser.add_argument("--time-limit", type=float, default=4.0)
    args = parser.parse_args()
    for name, value in variant_knobs(args.variant).items():
        setattr(get_up, name, value)
    sequences = variant_sequences(args.variant)
    balances = variant_balances(args.variant)
    for trial in args.trial:
        robot_type, direction, seed = trial.split(":")
        spec = (int(robot_type), direction, int(seed))
        session, driver, lying_on = fall(*spec)
        try:
            skill = driver.behavior.skill("get_up")
            assert isinstance(skill, GetUpSkill)
            skill.sequences = sequences

            def observe(agent: LocalAgent, cycle: int) -> None:
                if cycle % args.every == 0:
                    up = agent.robot.torso_world_transform()[2, :3]
                    print(f"{trace_line(agent, cycle)} up {up[0]:5.2f} {up[1]:5.2f} {up[2]:5.2f}")

            print(trial, lying_on)
            print(play_get_up(driver, *spec, lying_on, args.time_limit, observe, balances))
        finally:
            session.close()


if __name__ == "__main__":
    main()
