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
    path and ``beyond_m`` past it along the path, or None when the path is clear.

    Robots behind ``origin``, beyond the target or within ``target_zone_m`` of it are not in
    the way. The waypoint lies past the robot so that, walking to it, the robot falls behind
    the walker before the waypoint is reached and the walk turns back to the target; the side
    is the one away from the robot, which stays the same as the walker moves round it.
    """
    if clear_m <= 0.0:
        return None
    dx, dy = target[0] - origin[0], target[1] - origin[1]
    length = math.hypot(dx, dy)
    if length < 1e-6:
        return None
    ux, uy = dx / length, dy / length
    in_the_way = []
    for x, y in robots:
        rx, ry = x - origin[0], y - origin[1]
        along, across = rx * ux + ry * uy, -rx * uy + ry * ux
        if along <= 0.0 or abs(across) >= clear_m:
            continue
        if math.dist((x, y), target) < target_zone_m or along >= length:
            continue
        in_the_way.append((along, across, x, y))
    if not in_the_way:
        return None
    _, across, x, y = min(in_the_way)
    side = -1.0 if across > 0.0 else 1.0  # pass on the side away from the robot
    return (
        x + beyond_m * ux - side * clear_m * uy,
        y + beyond_m * uy + side * clear_m * ux,
    )
