"""Ball benchmark: rolling against the real server, and missed foot contacts per substep count.

Run: ``.venv/bin/python benchmarks/ball.py``. Prints ``name: value`` lines:

* ``ball_roll_distance_m[v=V]`` - total roll of a ball given V m/s on flat ground (real server:
  2.71 m at 4 m/s, 5.42 m at 8 m/s);
* ``ball_rest_time_s[v=4]`` - time after which the ball stays within 1 mm of its rest point
  (real server: about 6 s);
* ``missed_contacts[substeps=N]`` - of the foot speeds 2, 4, 6, 8, 10 m/s, how many pass (at
  least partly) through a resting ball, for a foot sliding straight or swung on a 0.2 m hinge,
  at the worst of four step phases; per rig in ``missed_contacts_slide`` / ``_swing``;
* ``missed_contacts_foot_ccd[substeps=1]`` - the same with Bullet CCD on the foot link.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sim.field import DEFAULT_SUBSTEPS, Ball, build_field, foot_strike_speed
from sim.physics import CYCLE_SECONDS, PhysicsWorld
from sim.session import default_contacts
from world.field_geometry import BALL_RADIUS

SPEEDS = (2.0, 4.0, 6.0, 8.0, 10.0)
PHASES = (0.0, 0.25, 0.5, 0.75)
#: Below this fraction of the foot's speed the foot has passed (partly) through the ball
#: (clean hits give 1.0-1.2, pass-throughs 0-0.75).
CLEAN_HIT_RATIO = 0.85
ROLL_SECONDS = 10.0


def roll(speed: float, substeps: int = DEFAULT_SUBSTEPS) -> tuple[float, float]:
    """(total roll distance, time after which the ball stays within 1 mm of its rest point), on
    the contacts a default session plays (:func:`sim.session.default_contacts`)."""
    contact = default_contacts()
    world = PhysicsWorld(substeps=substeps, min_bounce_speed=contact.min_bounce_speed)
    try:
        build_field(world, contact.ground, contact.post_restitution)
        ball = Ball.create(world, (0.0, 0.0, BALL_RADIUS), contact.ball)
        ball.place((0.0, 0.0, BALL_RADIUS), (speed, 0.0, 0.0))
        xs = []
        for _ in range(round(ROLL_SECONDS / CYCLE_SECONDS)):
            world.step_cycle()
            xs.append(ball.position()[0])
    finally:
        world.close()
    final = xs[-1]
    moving = [i for i, x in enumerate(xs) if abs(x - final) >= 1e-3]
    rest_cycle = moving[-1] + 2 if moving else 1
    return final, rest_cycle * CYCLE_SECONDS


def hit_ratios(substeps: int, swing: bool, foot_ccd: bool = False) -> list[float]:
    """Per speed in SPEEDS: ball launch speed / foot speed at the worst phase."""
    return [
        min(
            foot_strike_speed(speed, substeps, swing, foot_ccd=foot_ccd, phase=phase)
            for phase in PHASES
        )
        / speed
        for speed in SPEEDS
    ]


def count_missed(ratios: list[float]) -> int:
    return sum(r < CLEAN_HIT_RATIO for r in ratios)


def main() -> None:
    for speed in (4.0, 8.0):
        distance, rest = roll(speed)
        print(f"ball_roll_distance_m[v={speed:g}]: {distance:.3f}")
        if speed == 4.0:
            print(f"ball_rest_time_s[v={speed:g}]: {rest:.2f}")
    for substeps in (1, 2, 3, 4, 5, 6, 8):
        slide, swing = hit_ratios(substeps, False), hit_ratios(substeps, True)
        either = [min(a, b) for a, b in zip(slide, swing, strict=True)]
        print(f"missed_contacts[substeps={substeps}]: {count_missed(either)}")
        print(f"missed_contacts_slide[substeps={substeps}]: {count_missed(slide)}")
        print(f"missed_contacts_swing[substeps={substeps}]: {count_missed(swing)}")
    with_ccd = count_missed(hit_ratios(1, False, True)) + count_missed(hit_ratios(1, True, True))
    without = count_missed(hit_ratios(1, False)) + count_missed(hit_ratios(1, True))
    print(f"missed_contacts_foot_ccd[substeps=1]: {with_ccd}")
    print(f"missed_contacts_no_ccd[substeps=1]: {without}")
    print(f"default_substeps: {DEFAULT_SUBSTEPS}")


if __name__ == "__main__":
    main()
