"""Static soccer field geometry known to the server and to every agent.

Values follow rcssserver3d 0.7.2 (naosoccersim.rb, soccer.rsg); see
``shared/reference/nao-model-facts.md``. World frame: origin at the centre spot, x towards the
right team's goal, y to the left seen from the left team, z up.
"""

from __future__ import annotations

import math

FIELD_LENGTH = 30.0
FIELD_WIDTH = 20.0
HALF_LENGTH = FIELD_LENGTH / 2
HALF_WIDTH = FIELD_WIDTH / 2
GOAL_WIDTH = 2.1
GOAL_DEPTH = 0.6
GOAL_HEIGHT = 0.8
GOAL_POST_RADIUS = 0.02
PENALTY_DEPTH = 1.8
PENALTY_WIDTH = 6.0
CENTER_CIRCLE_RADIUS = 2.0
FREE_KICK_DISTANCE = 2.0
BORDER_SIZE = 10.0

BALL_RADIUS = 0.042
BALL_MASS = 0.026

#: Corner flags (z = 0) and goal-post markers (z = goal height), as the vision perceptor names them.
LANDMARKS: dict[str, tuple[float, float, float]] = {
    "F1L": (-HALF_LENGTH, HALF_WIDTH, 0.0),
    "F2L": (-HALF_LENGTH, -HALF_WIDTH, 0.0),
    "F1R": (HALF_LENGTH, HALF_WIDTH, 0.0),
    "F2R": (HALF_LENGTH, -HALF_WIDTH, 0.0),
    "G1L": (-HALF_LENGTH, GOAL_WIDTH / 2, GOAL_HEIGHT),
    "G2L": (-HALF_LENGTH, -GOAL_WIDTH / 2, GOAL_HEIGHT),
    "G1R": (HALF_LENGTH, GOAL_WIDTH / 2, GOAL_HEIGHT),
    "G2R": (HALF_LENGTH, -GOAL_WIDTH / 2, GOAL_HEIGHT),
}

#: x of the penalty-area front lines (13.2 m): goal line minus the area's depth.
PENALTY_LINE_X = HALF_LENGTH - PENALTY_DEPTH
#: The centre circle is drawn as a regular polygon with this many segments (fieldring.rsg).
CENTER_CIRCLE_SEGMENTS = 10

Point3 = tuple[float, float, float]
Segment3 = tuple[Point3, Point3]


def _center_circle_segments() -> tuple[Segment3, ...]:
    """The ring as the server builds it: vertex k at 36 k degrees, segment k from vertex k to
    vertex k + 1, counter-clockwise from the point (+radius, 0)."""
    vertices = [
        (
            CENTER_CIRCLE_RADIUS * math.cos(2.0 * math.pi * k / CENTER_CIRCLE_SEGMENTS),
            CENTER_CIRCLE_RADIUS * math.sin(2.0 * math.pi * k / CENTER_CIRCLE_SEGMENTS),
            0.0,
        )
        for k in range(CENTER_CIRCLE_SEGMENTS)
    ]
    return tuple(
        (vertices[k], vertices[(k + 1) % CENTER_CIRCLE_SEGMENTS])
        for k in range(CENTER_CIRCLE_SEGMENTS)
    )


#: Every field line segment the vision perceptor reports, world frame, in the server's scene
#: order (the order ``L`` entries appear in a ``See``), each as (begin, end): centre line,
#: right and left goal lines, the two side lines, the right then the left penalty area (front
#: line, then the two lines to the goal line), then the centre circle. The direction matters:
#: the perceptor reports begin before end. Facts: rcssserver3d soccer.rsg/fieldring.rsg, checked
#: against the recorded traces (tests/test_vision.py).
FIELD_LINES: tuple[Segment3, ...] = (
    ((0.0, -HALF_WIDTH, 0.0), (0.0, HALF_WIDTH, 0.0)),
    ((HALF_LENGTH, -HALF_WIDTH, 0.0), (HALF_LENGTH, HALF_WIDTH, 0.0)),
    ((-HALF_LENGTH, -HALF_WIDTH, 0.0), (-HALF_LENGTH, HALF_WIDTH, 0.0)),
    ((HALF_LENGTH, HALF_WIDTH, 0.0), (-HALF_LENGTH, HALF_WIDTH, 0.0)),
    ((HALF_LENGTH, -HALF_WIDTH, 0.0), (-HALF_LENGTH, -HALF_WIDTH, 0.0)),
    ((PENALTY_LINE_X, PENALTY_WIDTH / 2, 0.0), (PENALTY_LINE_X, -PENALTY_WIDTH / 2, 0.0)),
    ((PENALTY_LINE_X, PENALTY_WIDTH / 2, 0.0), (HALF_LENGTH, PENALTY_WIDTH / 2, 0.0)),
    ((PENALTY_LINE_X, -PENALTY_WIDTH / 2, 0.0), (HALF_LENGTH, -PENALTY_WIDTH / 2, 0.0)),
    ((-PENALTY_LINE_X, PENALTY_WIDTH / 2, 0.0), (-PENALTY_LINE_X, -PENALTY_WIDTH / 2, 0.0)),
    ((-PENALTY_LINE_X, PENALTY_WIDTH / 2, 0.0), (-HALF_LENGTH, PENALTY_WIDTH / 2, 0.0)),
    ((-PENALTY_LINE_X, -PENALTY_WIDTH / 2, 0.0), (-HALF_LENGTH, -PENALTY_WIDTH / 2, 0.0)),
    *_center_circle_segments(),
)
