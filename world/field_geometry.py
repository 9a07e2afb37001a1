"""Static soccer field geometry known to the server and to every agent.

Values follow rcssserver3d 0.7.2 (naosoccersim.rb, soccer.rsg); see
``shared/reference/nao-model-facts.md``. World frame: origin at the centre spot, x towards the
right team's goal, y to the left seen from the left team, z up.
"""

from __future__ import annotations

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
