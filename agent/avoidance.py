"""Walking round robots on the way to a target.

Why: two robots that walk into each other both fall, and both get up facing the same way. In a
3 v 3 match (``python scripts/attack/match_probe.py --seed 2``) the right team's active player
walked to the ball through the left keeper standing 4 m from it, fell with it, got up and
walked into it again: ten falls in ten seconds, the ball untouched. A waypoint beside the robot
in the way breaks that loop; the robots at the target itself (a contest for the ball) are left
to the contest rules (``AttackConfig.yield_*``, the stall watch).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from agent.attack_keeper import detour_point


def avoidance_waypoint(
    origin: tuple[float, float],
    target: tuple[float, float],
    robots: Iterable[tuple[float, float]],
    clear_m: float,
    target_zone_m: float,
    beyond_m: float,
) -> tuple[float, float] | None:
    """Where to walk instead of straight to ``target``: beside the nearest robot that stands
    ahead within ``clear_m`` of the straight path, ``clear_m`` to the side of it away from the
    path (:func:`agent.attack_keeper.detour_point`, the dribble's detour) and ``beyond_m``
    past it along the path, or None when the path is clear.

    Robots behind ``origin``, beyond the target or within ``target_zone_m`` of it are not in
    the way. The waypoint lies past the robot so that, walking to it, the robot falls behind
    the walker before the waypoint is reached and the walk turns back to the target; the side
    is the one away from the robot, which stays the same as the walker moves round it.
    """
    length = math.dist(origin, target)
    if clear_m <= 0.0 or length < 1e-6:
        return None
    ux, uy = (target[0] - origin[0]) / length, (target[1] - origin[1]) / length
    in_the_way = []
    for robot in robots:
        beside = detour_point(origin, target, robot, clear_m, length)
        if beside is not None and math.dist(robot, target) >= target_zone_m:
            along = (robot[0] - origin[0]) * ux + (robot[1] - origin[1]) * uy
            in_the_way.append((along, beside))
    if not in_the_way:
        return None
    _, (x, y) = min(in_the_way)
    return x + beyond_m * ux, y + beyond_m * uy
