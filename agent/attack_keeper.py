"""Beating a goalkeeper: which side of the goal mouth to aim at, and how to pass a keeper that
has come out of its goal (or any opponent in the way: :func:`free_heading`).

Why a module of its own: against an empty goal the attacker only needs the goal centre, but
against a keeper the aim depends on where the keeper stands as seen from the ball, and the
dribble must not run straight into a keeper that has left its line to meet the ball (both
robots then push the ball against each other and fall at it; see ``benchmarks/attack.py
--keeper --trace 1``). Pure geometry on the world model's estimates, team frame (x towards
the opponent goal), so it is tested without a simulator.
"""

from __future__ import annotations

import math

from world.field_geometry import GOAL_WIDTH, HALF_LENGTH, HALF_WIDTH

Point = tuple[float, float]


def open_side(
    ball: Point, keeper: Point, margin_m: float, current: float | None, switch_deg: float
) -> float:
    """The side of the goal mouth to aim at: +1 (y > 0) or -1, the one whose aim point (``margin_m``
    inside its post) is seen from the ball farthest in bearing from the keeper.

    Why the bearing from the ball and not the keeper's y: from a ball out wide, a keeper in
    the middle of its goal covers the near post, whatever the sign of its y. ``current`` (the
    side aimed at so far) is kept unless the other side is better by ``switch_deg``: a
    keeper shuffling about the middle would otherwise turn the dribble back and forth, and
    every turn slows it down and loses the ball.
    """
    keeper_bearing = _bearing(ball, keeper)
    gaps = {
        side: abs(_wrap(_bearing(ball, aim_point(side, margin_m)) - keeper_bearing))
        for side in (1.0, -1.0)
    }
    best = max(gaps, key=lambda side: gaps[side])
    if current in gaps and gaps[current] + math.radians(switch_deg) >= gaps[best]:
        return current
    return best


def aim_point(side: float, margin_m: float) -> Point:
    """The point on the opponent goal line ``margin_m`` inside the post of ``side``."""
    return (HALF_LENGTH, side * max(0.0, GOAL_WIDTH / 2 - margin_m))


def detour_point(
    ball: Point, aim: Point, keeper: Point, clear_m: float, ahead_m: float
) -> Point | None:
    """Where to dribble instead of ``aim`` to pass a keeper in the way, or None.

    The keeper is in the way when it stands ahead of the ball (less than ``ahead_m`` along
    the line ball -> aim) and less than ``clear_m`` beside that line; the dribble then heads
    for the point level with the keeper and ``clear_m`` to its side, on the side of the line
    away from it (the open side of the goal). Why a point and not a fixed turn: the nearer
    the keeper, the sharper the turn needed to pass it, and past it the line to the aim is
    free again.
    """
    heading = _bearing(ball, aim)
    ux, uy = math.cos(heading), math.sin(heading)
    rx, ry = keeper[0] - ball[0], keeper[1] - ball[1]
    along, across = rx * ux + ry * uy, -rx * uy + ry * ux
    if not 0.0 < along < ahead_m or abs(across) >= clear_m:
        return None
    lateral = across - math.copysign(clear_m, across if across else 1.0)
    return (ball[0] + along * ux - lateral * uy, ball[1] + along * uy + lateral * ux)


def free_heading(
    ball: Point,
    heading_deg: float,
    opponents: list[Point],
    max_turn_deg: float,
    step_deg: float,
    ahead_m: float,
    clear_m: float,
    margin_m: float = 0.5,
) -> float:
    """The dribble heading (deg) into free space: ``heading_deg`` when no opponent stands
    within ``clear_m`` of the path ``ahead_m`` long from the ball that way, else the heading
    off it by the fewest ``step_deg`` steps (at most ``max_turn_deg``) whose path is free,
    the side with the wider gap first; with none free, the one whose path passes the
    opponents widest. Opponents behind the ball (as seen along a path) do not block it, and
    a turned path that ends within ``margin_m`` of a touch line, or beyond the goal line
    outside the posts, is not taken.

    Why: dribbling straight at the goal, the attacker ran into the opponent in its way and
    both fell at the ball (11 v 11, ``scripts/attack/match_probe.py --players 11``: most
    falls are the active players' ``after dribble`` with an opponent within 0.9 m); the
    fixed dodge (``AttackConfig.dodge_deg``) turns away from the nearest opponent only, maybe
    into the next one.
    """
    steps = int(max_turn_deg // step_deg) if step_deg > 0.0 else 0
    best: tuple[float, float, float] | None = None  # (-gap, turn, heading)
    for k in range(steps + 1):
        turns = [0.0] if k == 0 else [k * step_deg, -k * step_deg]
        gaps = {}
        for turn in turns:
            h = math.radians(heading_deg + turn)
            end = (ball[0] + ahead_m * math.cos(h), ball[1] + ahead_m * math.sin(h))
            if turn and not _on_field(end, margin_m):
                continue
            gaps[turn] = _path_gap(ball, end, opponents)
        for turn, gap in sorted(gaps.items(), key=lambda item: -item[1]):
            if gap >= clear_m:
                return heading_deg + turn
            if best is None or (-gap, abs(turn)) < best[:2]:
                best = (-gap, abs(turn), heading_deg + turn)
    return heading_deg if best is None else best[2]


def _on_field(point: Point, margin_m: float) -> bool:
    """Whether ``point`` lies ``margin_m`` inside the touch lines and short of the goal lines,
    or beyond the opponent goal line between the posts."""
    if abs(point[1]) > HALF_WIDTH - margin_m or point[0] < -HALF_LENGTH + margin_m:
        return False
    return point[0] < HALF_LENGTH - margin_m or abs(point[1]) < GOAL_WIDTH / 2


def _path_gap(start: Point, end: Point, opponents: list[Point]) -> float:
    """The least distance from an opponent ahead of ``start`` (along start -> end) to that
    segment (infinite with none)."""
    dx, dy = end[0] - start[0], end[1] - start[1]
    length2 = dx * dx + dy * dy
    gap = math.inf
    for ox, oy in opponents:
        along = (ox - start[0]) * dx + (oy - start[1]) * dy
        if along <= 0.0 or length2 == 0.0:
            continue
        t = min(1.0, along / length2)
        gap = min(gap, math.dist((ox, oy), (start[0] + t * dx, start[1] + t * dy)))
    return gap


def _bearing(origin: Point, point: Point) -> float:
    return math.atan2(point[1] - origin[1], point[0] - origin[0])


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def contested(
    me: Point, ball: Point, opponents: list[Point], opponent_m: float, reach_m: float
) -> bool:
    """Whether an opponent is at the ball from the far side while this player is at it too:
    an opponent within ``opponent_m`` of the ball, on the other side of the ball from this
    player, who is within ``reach_m`` of it.

    Why: two robots walking into the ball from both sides push it against each other's feet
    and both fall over it (``benchmarks/attack.py --keeper --trace 1``); the one that stops
    and stands stays up, and whoever falls loses the ball for the seconds of its get-up.
    """
    if math.dist(me, ball) >= reach_m:
        return False
    tx, ty = ball[0] - me[0], ball[1] - me[1]
    return any(
        math.dist(opponent, ball) < opponent_m
        and (opponent[0] - ball[0]) * tx + (opponent[1] - ball[1]) * ty > 0.0
        for opponent in opponents
    )
